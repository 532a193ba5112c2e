//! What a load accepts but ignores is a warning on the level, naming the file and what is
//! ignored (and in level.toml, where), never silence.

mod common;

use common::*;
use scene::{load_level, TextPos};
use serde_json::json;

#[test]
fn ignored_gltf_features_and_keys_are_warnings() {
    let dir = TempDir::new("warnings");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let colours = bin.vec3(&[[1.0, 0.0, 0.0]; 3]);
    let mut doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos, "COLOR_0": colours}, "material": 0}));
    // What is read (vertex colours, MASK, samplers, texture transforms, emissive strength) is
    // not warned about; what is not (BLEND's partial transparency, normal maps) is.
    doc["materials"] = json!([{
        "name": "leaves",
        "alphaMode": "BLEND",
        "normalTexture": {"index": 0},
        "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [2.0, 2.0]}}}},
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2.0}}
    }, {"name": "twigs", "alphaMode": "MASK", "doubleSided": true}]);
    doc["textures"] = json!([{"source": 0, "sampler": 0}]);
    doc["samplers"] = json!([{"wrapS": 33071, "wrapT": 33648, "magFilter": 9728, "minFilter": 9984}]);
    doc["images"] = json!([{"uri": format!("data:image/png;base64,{}", base64(&png(1, 1, &[255; 4])))}]);
    doc["extensionsUsed"] = json!(["KHR_materials_sheen", "KHR_texture_transform", "KHR_materials_emissive_strength"]);
    write_json(&dir, "scene.gltf", &doc);
    dir.write(
        "level.toml",
        "name = \"W\"\nscene = \"scene.gltf\"\n\n[[lights]]\nkind = \"point\"\nposition = [0, 2, 0]\ndirection = [0, -1, 0]\n\n[headlamp]\ninner_deg = 10\n",
    );
    let level = load_level(dir.path()).unwrap();
    let lines: Vec<String> = level.warnings.iter().map(ToString::to_string).collect();
    for needle in [
        "scene.gltf: extension KHR_materials_sheen is not supported",
        "scene.gltf: material 0 ('leaves'): alphaMode BLEND (partial transparency) is not supported; drawn as MASK with alphaCutoff 0.5",
        "scene.gltf: material 0 ('leaves'): normal maps are not supported",
        "level.toml:7:1: lights[0].direction is ignored",
        "level.toml:10:1: headlamp.inner_deg is ignored: it only applies to profile = \"spot\"",
    ] {
        assert!(lines.iter().any(|l| l.contains(needle)), "no '{needle}' in {lines:#?}");
    }
    for supported in
        ["COLOR_0", "alphaMode MASK", "twigs", "KHR_texture_transform", "emissive", "wrap", "filter", "sampler"]
    {
        assert!(!lines.iter().any(|l| l.contains(supported)), "a warning about '{supported}' in {lines:#?}");
    }
    assert_eq!(lines.iter().filter(|l| l.contains("scene.gltf")).count(), 3, "{lines:#?}");
    let direction = level.warnings.iter().find(|w| w.message.contains("direction")).unwrap();
    assert_eq!(direction.at, Some(TextPos { line: 7, column: 1 }));
}

#[test]
fn a_plain_level_has_no_warnings() {
    let dir = TempDir::new("no-warnings");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    write_json(&dir, "scene.gltf", &single_primitive(&bin, json!({"attributes": {"POSITION": pos}})));
    dir.write("level.toml", "name = \"W\"\nscene = \"scene.gltf\"\n");
    assert_eq!(load_level(dir.path()).unwrap().warnings, vec![]);
}
