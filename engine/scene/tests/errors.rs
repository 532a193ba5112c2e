//! Every kind of bad input is an `Err` whose one-line message names the file and the problem,
//! and no input panics.

mod common;

use std::path::Path;

use common::*;
use scene::{load_gltf, load_level, load_obj, load_scene_file, load_texture, LoadError};
use serde_json::{json, Value};

/// Mutations per input in the two fuzz tests below: fixed, so every run checks the same inputs
/// (the longer, coverage-guided runs are `tests/fuzz/`'s, see docs/testing.md).
const ROUNDS: usize = 300;

/// Asserts the error is one line, names `file`, and contains every word in `words`.
fn expect_err<T: std::fmt::Debug>(result: Result<T, LoadError>, file: &str, words: &[&str]) -> String {
    let msg = result.expect_err("expected an error").to_string();
    assert!(!msg.contains('\n'), "not one line: {msg}");
    assert!(msg.contains(file), "'{msg}' does not name {file}");
    for w in words {
        assert!(msg.contains(w), "'{msg}' does not contain '{w}'");
    }
    msg
}

fn tri_doc(indices: Option<&[u16]>) -> (Bin, Value) {
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let mut prim = json!({"attributes": {"POSITION": pos}});
    if let Some(i) = indices {
        prim["indices"] = json!(bin.u16s(i));
    }
    let doc = single_primitive(&bin, prim);
    (bin, doc)
}

#[test]
fn missing_file() {
    let dir = TempDir::new("missing");
    let p = dir.path().join("nope.gltf");
    let msg = expect_err(load_gltf(&p), "nope.gltf", &["file not found"]);
    assert!(msg.starts_with(&p.display().to_string()), "path first: {msg}");
    expect_err(load_obj(&dir.path().join("nope.obj")), "nope.obj", &["not found"]);
    expect_err(load_level(&dir.path().join("nope")), "nope", &["not found"]);
    expect_err(load_texture(&dir.path().join("nope.png")), "nope.png", &["not found"]);
}

#[test]
fn not_json() {
    let dir = TempDir::new("notjson");
    let p = dir.write("x.gltf", "this is not json");
    expect_err(load_gltf(&p), "x.gltf", &["corrupt glTF", "JSON"]);
    let p = dir.write("y.gltf", "[1, 2, 3]");
    expect_err(load_gltf(&p), "y.gltf", &["corrupt glTF"]);
}

#[test]
fn truncated_glb() {
    let dir = TempDir::new("trunc");
    let (bin, _) = tri_doc(None);
    let doc = bin.gltf_with_buffer(
        json!({"scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]}),
        json!({"byteLength": bin.data.len()}),
    );
    let full = glb(&doc, &bin.data);
    load_gltf(&dir.write("ok.glb", &full)).unwrap();
    expect_err(load_gltf(&dir.write("cut.glb", &full[..full.len() - 10])), "cut.glb", &["truncated"]);
    // Every prefix is an error, never a panic.
    for n in 0..full.len() {
        assert!(load_gltf(&dir.write("prefix.glb", &full[..n])).is_err(), "prefix {n}");
    }
}

#[test]
fn index_out_of_range() {
    let dir = TempDir::new("oob");
    let (_, doc) = tri_doc(Some(&[0, 1, 7]));
    expect_err(load_gltf(&write_json(&dir, "bad.gltf", &doc)), "bad.gltf", &["index 7 out of range", "3 vertices"]);
}

#[test]
fn unknown_extension() {
    let dir = TempDir::new("ext");
    let p = dir.write("bar.xyz", "whatever");
    expect_err(load_scene_file(&p), "bar.xyz", &["unknown scene file extension 'xyz'", ".gltf, .glb or .obj"]);
    expect_err(load_level(&p), "bar.xyz", &["unknown scene file extension"]);
}

#[test]
fn accessor_problems() {
    let dir = TempDir::new("acc");
    // NORMAL pointing at a VEC2 accessor.
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let uv = bin.vec2(&[[0.0, 0.0]; 3]);
    let doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos, "NORMAL": uv}}));
    expect_err(load_gltf(&write_json(&dir, "vec2.gltf", &doc)), "vec2.gltf", &["NORMAL", "3-component"]);
    // POSITION naming an accessor that does not exist (gltf-json's validator would panic).
    let doc = single_primitive(&bin, json!({"attributes": {"POSITION": 9}}));
    expect_err(load_gltf(&write_json(&dir, "noacc.gltf", &doc)), "noacc.gltf", &["accessor 9 does not exist"]);

    // Accessor count larger than its view.
    let (_, mut doc) = tri_doc(None);
    doc["accessors"][0]["count"] = json!(100);
    expect_err(load_gltf(&write_json(&dir, "count.gltf", &doc)), "count.gltf", &["overruns"]);

    // View larger than its buffer.
    let (_, mut doc) = tri_doc(None);
    doc["bufferViews"][0]["byteLength"] = json!(4096);
    expect_err(load_gltf(&write_json(&dir, "view.gltf", &doc)), "view.gltf", &["bufferView 0"]);

    // Buffer shorter than its byteLength.
    let (_, mut doc) = tri_doc(None);
    doc["buffers"][0]["byteLength"] = json!(1000);
    expect_err(load_gltf(&write_json(&dir, "short.gltf", &doc)), "short.gltf", &["byteLength"]);

    // Index accessor of floats.
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos}, "indices": pos}));
    expect_err(load_gltf(&write_json(&dir, "fidx.gltf", &doc)), "fidx.gltf", &["index accessor"]);

    // Stride smaller than the element.
    let (_, mut doc) = tri_doc(None);
    doc["bufferViews"][0]["byteStride"] = json!(4);
    expect_err(load_gltf(&write_json(&dir, "stride.gltf", &doc)), "stride.gltf", &["corrupt glTF"]);

    // Zero-count accessor: empty, not a panic.
    let (_, mut doc) = tri_doc(None);
    doc["accessors"][0]["count"] = json!(0);
    let _ = load_gltf(&write_json(&dir, "zero.gltf", &doc));

    // Absurd count.
    let (_, mut doc) = tri_doc(None);
    doc["accessors"][0]["count"] = json!(4_000_000_000u64);
    expect_err(load_gltf(&write_json(&dir, "huge.gltf", &doc)), "huge.gltf", &["too large"]);
}

#[test]
fn bad_references_and_structure() {
    let dir = TempDir::new("refs");
    let (_, mut doc) = tri_doc(None);
    doc["nodes"][0]["mesh"] = json!(5);
    expect_err(load_gltf(&write_json(&dir, "ref.gltf", &doc)), "ref.gltf", &["corrupt glTF", "mesh"]);

    // A node cycle.
    let (_, mut doc) = tri_doc(None);
    doc["nodes"] = json!([{"mesh": 0, "children": [1]}, {"children": [0]}]);
    expect_err(load_gltf(&write_json(&dir, "cycle.gltf", &doc)), "cycle.gltf", &["node"]);

    // A missing external buffer names the .bin.
    let (bin, _) = tri_doc(None);
    let doc = bin.gltf_with_buffer(
        json!({"scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]}),
        json!({"byteLength": bin.data.len(), "uri": "geometry.bin"}),
    );
    expect_err(load_gltf(&write_json(&dir, "nobin.gltf", &doc)), "geometry.bin", &["not found"]);

    // Bad base64.
    let (_, mut doc) = tri_doc(None);
    doc["buffers"][0]["uri"] = json!("data:application/octet-stream;base64,@@@@");
    expect_err(load_gltf(&write_json(&dir, "b64.gltf", &doc)), "b64.gltf", &["base64"]);

    // Images the gltf crate would unwrap: no source at all, a bufferView without a mimeType.
    for (tag, image, needle) in [
        ("nosource", json!({}), "images[0] has neither a uri nor a bufferView"),
        ("nomime", json!({"bufferView": 0}), "images[0] is in a bufferView but has no mimeType"),
    ] {
        let (_, mut doc) = tri_doc(None);
        doc["images"] = json!([image]);
        doc["textures"] = json!([{"source": 0}]);
        doc["materials"] = json!([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]);
        doc["meshes"][0]["primitives"][0]["material"] = json!(0);
        let file = format!("{tag}.gltf");
        expect_err(load_gltf(&write_json(&dir, &file, &doc)), &file, &["corrupt glTF", needle]);
    }

    // Unsupported required extension.
    let (_, mut doc) = tri_doc(None);
    doc["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    doc["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    expect_err(load_gltf(&write_json(&dir, "draco.gltf", &doc)), "draco.gltf", &["KHR_draco_mesh_compression"]);

    // A zero quaternion.
    let (_, mut doc) = tri_doc(None);
    doc["nodes"][0]["rotation"] = json!([0.0, 0.0, 0.0, 0.0]);
    expect_err(load_gltf(&write_json(&dir, "quat.gltf", &doc)), "quat.gltf", &["rotation"]);

    // A spot light without its cone, a camera with yfov 0.
    let (_, mut doc) = tri_doc(None);
    doc["extensions"] = json!({"KHR_lights_punctual": {"lights": [{"type": "spot"}]}});
    doc["nodes"][0]["extensions"] = json!({"KHR_lights_punctual": {"light": 0}});
    expect_err(load_gltf(&write_json(&dir, "spot.gltf", &doc)), "spot.gltf", &["spot"]);
    let (_, mut doc) = tri_doc(None);
    doc["cameras"] = json!([{"type": "perspective", "perspective": {"yfov": 0.0, "znear": 0.1}}]);
    doc["nodes"][0]["camera"] = json!(0);
    expect_err(load_gltf(&write_json(&dir, "cam.gltf", &doc)), "cam.gltf", &["yfov"]);
}

#[test]
fn nan_positions() {
    let dir = TempDir::new("nan");
    let mut bin = Bin::default();
    let pos = bin.vec3(&[[0.0, 0.0, 0.0], [f32::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let mut doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos}}));
    doc["accessors"][0]["min"] = json!([0.0, 0.0, 0.0]); // NaN would serialise as null
    doc["accessors"][0]["max"] = json!([1.0, 1.0, 0.0]);
    expect_err(load_gltf(&write_json(&dir, "nan.gltf", &doc)), "nan.gltf", &["non-finite"]);
    let p = dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_err(load_obj(&p), "nan.obj", &["non-finite"]);
}

#[test]
fn bad_images() {
    let dir = TempDir::new("img");
    let p = dir.write("junk.png", "not a png at all");
    expect_err(load_texture(&p), "junk.png", &["image"]);
    // A PNG header claiming 100000 x 1 pixels is refused before decoding.
    let mut big = png(1, 1, &[0, 0, 0, 255]);
    big[16..20].copy_from_slice(&100_000u32.to_be_bytes());
    let crc = crc32(&big[12..29]); // IHDR type + data
    big[29..33].copy_from_slice(&crc.to_be_bytes());
    expect_err(load_texture(&dir.write("big.png", &big)), "big.png", &["too large"]);
}

#[test]
fn obj_errors() {
    let dir = TempDir::new("objerr");
    let p = dir.write("oob.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    expect_err(load_obj(&p), "oob.obj", &["line 3", "out of range"]);
    let p = dir.write("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/-5 2 3\n");
    expect_err(load_obj(&p), "neg.obj", &["out of range"]);

    // A texture the .mtl names but that does not exist.
    dir.write("m.mtl", "newmtl a\nmap_Kd missing.png\n");
    let p = dir.write("tex.obj", "mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_err(load_obj(&p), "missing.png", &["not found"]);

    // A malformed .mtl.
    dir.write("bad.mtl", "newmtl a\nKd 0.5 0.5\n");
    let p = dir.write("badmtl.obj", "mtllib bad.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_err(load_obj(&p), "bad.mtl", &["corrupt MTL", "line 2"]);
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xffff_ffffu32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xedb8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

fn level_dir(tag: &str, toml: &str) -> TempDir {
    let dir = TempDir::new(tag);
    dir.write("scene.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    dir.write("level.toml", toml);
    dir
}

#[test]
fn level_toml_errors() {
    let base = "name = \"L\"\nscene = \"scene.obj\"\n";
    let cases: &[(&str, &str, &[&str])] = &[
        ("syntax", "name = \"L\"\nscene = \"scene.obj\"\npower = = 3\n", &["level.toml:3:9: invalid TOML"]),
        ("unknown", &format!("{base}[headlamp]\npowr = 2.0\n"), &["level.toml:4:1: invalid level: unknown field `powr`"]),
        ("unknown-top", &format!("{base}exposre = 2.0\n"), &["unknown field `exposre`"]),
        ("missing-name", "scene = \"scene.obj\"\n", &["missing field `name`"]),
        ("escape", "name = \"L\"\nscene = \"../../etc/passwd\"\n", &["path '../../etc/passwd' escapes the level folder"]),
        ("absolute", "name = \"L\"\nscene = \"/etc/passwd\"\n", &["escapes the level folder"]),
        ("cone", &format!("{base}[headlamp]\nprofile = \"spot\"\ninner_deg = 30.0\nouter_deg = 30.0\n"), &["level.toml:6:1:", "outer_deg", "greater than inner_deg"]),
        ("light-cone", &format!("{base}[[lights]]\nkind = \"spot\"\nposition = [0,0,0]\ndirection = [0,-1,0]\ninner_deg = 40.0\nouter_deg = 35.0\n"), &["level.toml:8:1:", "lights[0].outer_deg"]),
        ("power", &format!("{base}[headlamp]\npower = -1.0\n"), &["level.toml:4:1:", "headlamp.power", ">= 0"]),
        ("fov", &format!("{base}[headlamp]\nfov_deg = 180.0\n"), &["headlamp.fov_deg"]),
        ("exposure", &format!("{base}exposure = 0.0\n"), &["exposure"]),
        ("zero-dir", &format!("{base}[[lights]]\nkind = \"directional\"\ndirection = [0,0,0]\n"), &["lights[0].direction", "non-zero"]),
        ("no-pos", &format!("{base}[[lights]]\nkind = \"point\"\n"), &["level.toml:3:1:", "lights[0]", "needs a position"]),
        ("kind", &format!("{base}[[lights]]\nkind = \"area\"\nposition = [0,0,0]\n"), &["area"]),
        ("type", &format!("{base}exposure = \"bright\"\n"), &["exposure"]),
        ("pitch", &format!("{base}[spawn]\nposition = [0,0,0]\npitch_deg = 95.0\n"), &["level.toml:5:1:", "spawn.pitch_deg"]),
        ("empty-name", "name = \"  \"\nscene = \"scene.obj\"\n", &["name"]),
    ];
    for (tag, toml, words) in cases {
        let dir = level_dir(tag, toml);
        let msg = expect_err(load_level(dir.path()), "level.toml", words);
        assert!(msg.contains(&dir.path().join("level.toml").display().to_string()), "{tag}: {msg}");
    }

    // The scene file named in level.toml is missing: the message names it.
    let dir = level_dir("noscene", "name = \"L\"\nscene = \"cellar.gltf\"\n");
    expect_err(load_level(dir.path()), "cellar.gltf", &["not found"]);

    // A headlamp profile texture that is missing.
    let dir = level_dir("noprofile", &format!("{base}[headlamp]\nprofile = \"lamp.png\"\n"));
    expect_err(load_level(dir.path()), "lamp.png", &["not found"]);

    // A folder without level.toml.
    let dir = TempDir::new("empty");
    expect_err(load_level(dir.path()), "level.toml", &["not found"]);
}

#[test]
fn files_referenced_by_the_scene_may_not_leave_the_level_folder() {
    let outer = TempDir::new("confine");
    let (bin, _) = tri_doc(None);
    outer.write("secret.bin", &bin.data);
    let doc = bin.gltf_with_buffer(
        json!({"scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]}),
        json!({"byteLength": bin.data.len(), "uri": "../secret.bin"}),
    );
    write_json(&outer, "level/scene.gltf", &doc);
    outer.write("level/level.toml", "name = \"L\"\nscene = \"scene.gltf\"\n");
    expect_err(load_level(&outer.path().join("level")), "scene.gltf", &["'../secret.bin' escapes the level folder"]);
    // The same file loaded bare is trusted like any file the user opens.
    load_gltf(&outer.path().join("level/scene.gltf")).unwrap();
}

/// Deterministic byte mutations of valid files: every result is Ok or Err, never a panic.
#[test]
fn mutated_inputs_never_panic() {
    let dir = TempDir::new("fuzz");
    let mut bin = Bin::default();
    let pos = bin.vec3(&QUAD);
    let nrm = bin.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let uv = bin.vec2(&[[0.0, 0.0]; 4]);
    let idx = bin.u16s(&[0, 1, 2, 0, 2, 3]);
    let doc = bin.gltf_with_buffer(
        json!({"scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "children": [1]}, {"camera": 0, "extras": {"a": 1}}],
               "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
               "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}, "indices": idx, "mode": 4}]}]}),
        json!({"byteLength": bin.data.len()}),
    );
    let glb_bytes = glb(&doc, &bin.data);
    let json_bytes =
        serde_json::to_vec(&single_primitive(&bin, json!({"attributes": {"POSITION": pos}, "indices": idx}))).unwrap();
    let obj = b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nusemtl a\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf -1 -2 -3\n".to_vec();
    dir.write("m.mtl", "newmtl a\nKd 1 0 0\nKe 0 0 0\nd 1\n");

    let mut rng = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        rng
    };
    for round in 0..ROUNDS {
        for (name, original) in [("f.glb", &glb_bytes), ("f.gltf", &json_bytes), ("f.obj", &obj)] {
            let mut bytes = original.clone();
            for _ in 0..1 + next() % 4 {
                let at = (next() as usize) % bytes.len();
                bytes[at] = match next() % 4 {
                    0 => next() as u8,
                    1 => b"0123456789-.e"[(next() % 13) as usize],
                    2 => 0xff,
                    _ => bytes[at].wrapping_add(1),
                };
            }
            let path = dir.write(name, &bytes);
            let _ = load_scene_file(Path::new(&path))
                .map_err(|e| assert!(!e.to_string().contains('\n'), "round {round}: {e}"));
        }
    }
}

/// Structured mutations: valid JSON whose numbers (offsets, counts, strides, component types,
/// indices, modes...) are replaced by awkward values. Exercises the byte-level checks.
#[test]
fn mutated_gltf_values_never_panic() {
    let dir = TempDir::new("fuzz-values");
    let mut bin = Bin::default();
    let pos = bin.vec3(&QUAD);
    let nrm = bin.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let uv = bin.vec2(&[[0.0, 0.0]; 4]);
    let idx = bin.u16s(&[0, 1, 2, 0, 2, 3]);
    let img = bin.view(&png(1, 1, &[1, 2, 3, 4]));
    let doc = bin.gltf(json!({
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.2}}]}},
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "children": [1], "scale": [1.0, 2.0, 3.0]},
                  {"camera": 0, "children": [2], "rotation": [0.0, 0.0, 0.0, 1.0]},
                  {"extensions": {"KHR_lights_punctual": {"light": 0}}, "matrix": [1.0,0.0,0.0,0.0, 0.0,1.0,0.0,0.0, 0.0,0.0,1.0,0.0, 0.0,0.0,0.0,1.0]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}, "indices": idx, "mode": 4, "material": 0},
            {"attributes": {"POSITION": pos}, "mode": 5}
        ]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}],
        "images": [{"bufferView": img, "mimeType": "image/png"}],
    }));

    fn numbers(v: &Value, path: String, out: &mut Vec<String>) {
        match v {
            Value::Number(_) => out.push(path),
            Value::Array(a) => a.iter().enumerate().for_each(|(i, x)| numbers(x, format!("{path}/{i}"), out)),
            Value::Object(o) => {
                o.iter().filter(|(k, _)| *k != "uri").for_each(|(k, x)| numbers(x, format!("{path}/{k}"), out))
            }
            _ => {}
        }
    }
    let mut leaves = Vec::new();
    numbers(&doc, String::new(), &mut leaves);
    let awkward: [f64; 14] =
        [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 7.0, 255.0, 5121.0, 5123.0, 5125.0, 65536.0, 4294967295.0, 1e12];

    let mut rng = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        rng
    };
    for _ in 0..ROUNDS {
        let mut d = doc.clone();
        for _ in 0..1 + next() % 3 {
            let leaf = &leaves[(next() as usize) % leaves.len()];
            let value = awkward[(next() as usize) % awkward.len()];
            *d.pointer_mut(leaf).unwrap() = json!(value as u64);
        }
        for (name, bytes) in [
            ("v.gltf", serde_json::to_vec(&d).unwrap()),
            (
                "v.glb",
                glb(
                    &{
                        let mut g = d.clone();
                        g["buffers"][0] = json!({"byteLength": bin.data.len()});
                        g
                    },
                    &bin.data,
                ),
            ),
        ] {
            let path = dir.write(name, bytes);
            if let Err(e) = load_gltf(&path) {
                assert!(!e.to_string().contains('\n'), "{e}");
            }
        }
    }
}
