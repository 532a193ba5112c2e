//! level.toml: the full schema, bare files as levels, the content hash.

mod common;

use common::*;
use glam::Vec3;
use scene::{load_level, HeadlampProfile, IntensityDistribution, LightKind, DEFAULT_EYE_HEIGHT};
use serde_json::json;

const FULL_TOML: &str = r#"
name = "The Cellar"
scene = "scene.gltf"
exposure = 8

[spawn]
position = [1.0, 0.0, 4.0]
yaw_deg = 90.0
pitch_deg = -10.0

[headlamp]
power = 2.5
fov_deg = 70.0
profile = "spot"
inner_deg = 15.0
outer_deg = 25.0
color = [1.0, 0.9, 0.8]

[[lights]]
kind = "point"
position = [0.0, 2.5, 0.0]
color = [1.0, 0.6, 0.3]
intensity = 2.0
range = 8.0

[[lights]]
name = "moon"
kind = "directional"
direction = [0.0, -2.0, 0.0]
intensity = 0.5

[[lights]]
kind = "spot"
position = [0.0, 3.0, 0.0]
direction = [0.0, 0.0, -1.0]
inner_deg = 20.0
outer_deg = 35.0

[game]
enemies = 3
music = "drips.ogg"
[game.difficulty]
hard = true
"#;

/// A level folder whose glTF has an external .bin and one light of its own.
fn write_level(dir: &TempDir, toml: &str) {
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    dir.write("scene.bin", &bin.data);
    let doc = bin.gltf_with_buffer(
        json!({
            "extensionsUsed": ["KHR_lights_punctual"],
            "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 7.0}]}},
            "scenes": [{"nodes": [0, 1]}],
            "nodes": [{"mesh": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos}}]}],
        }),
        json!({"byteLength": bin.data.len(), "uri": "scene.bin"}),
    );
    write_json(dir, "scene.gltf", &doc);
    dir.write("level.toml", toml);
}

#[test]
fn full_level_round_trip() {
    let dir = TempDir::new("full");
    write_level(&dir, FULL_TOML);
    let level = load_level(dir.path()).unwrap();
    assert_eq!(level.name, "The Cellar");
    assert_eq!(level.root.as_deref(), Some(dir.path()));
    assert_eq!(level.scene_path, dir.path().join("scene.gltf"));
    assert_eq!(level.exposure, Some(8.0));

    let spawn = level.spawn.unwrap();
    close(spawn.position, [1.0, 0.0, 4.0]);
    close(spawn.eye(), [1.0, DEFAULT_EYE_HEIGHT, 4.0]);
    assert!((spawn.yaw - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
    assert!((spawn.pitch + 10f32.to_radians()).abs() < 1e-6);
    // Yaw +90° turns left from -Z, i.e. towards -X.
    assert!(spawn.forward().x < -0.9);

    let h = &level.headlamp;
    assert_eq!(h.power, 2.5);
    assert!((h.fov_y - 70f32.to_radians()).abs() < 1e-6);
    assert_eq!(h.color, [1.0, 0.9, 0.8]);
    assert_eq!(h.distribution, IntensityDistribution::Spot { inner: 15f32.to_radians(), outer: 25f32.to_radians() });

    // The scene's own light first, then level.toml's three.
    let lights = &level.scene.lights;
    assert_eq!(lights.len(), 4);
    assert_eq!(lights[0].intensity, 7.0);
    assert_eq!(lights[1].kind, LightKind::Point);
    close(lights[1].position, [0.0, 2.5, 0.0]);
    assert_eq!(lights[1].color, [1.0, 0.6, 0.3]);
    assert_eq!(lights[1].range, Some(8.0));
    assert_eq!(lights[2].name, "moon");
    assert_eq!(lights[2].kind, LightKind::Directional);
    close(lights[2].direction, Vec3::NEG_Y);
    assert_eq!(lights[2].intensity, 0.5);
    assert_eq!(lights[3].kind, LightKind::Spot { inner_cone: 20f32.to_radians(), outer_cone: 35f32.to_radians() });
    assert_eq!(lights[3].color, [1.0; 3]);
    assert_eq!(lights[3].intensity, 1.0);

    assert_eq!(level.game.get("enemies").and_then(|v| v.as_integer()), Some(3));
    assert_eq!(level.game.get("music").and_then(|v| v.as_str()), Some("drips.ogg"));
    assert_eq!(level.game["difficulty"]["hard"].as_bool(), Some(true));

    // The level.toml path itself works too, and gives the same level.
    assert_eq!(load_level(&dir.path().join("level.toml")).unwrap(), level);
}

#[test]
fn minimal_level_has_defaults() {
    let dir = TempDir::new("min");
    write_level(&dir, "name = \"Min\"\nscene = \"scene.gltf\"\n");
    let level = load_level(dir.path()).unwrap();
    assert_eq!(level.exposure, None);
    assert_eq!(level.spawn, None);
    assert_eq!(level.headlamp, HeadlampProfile::default());
    assert!(level.game.is_empty());
    assert_eq!(level.scene.lights.len(), 1);
}

#[test]
fn headlamp_profile_texture_is_linear() {
    let dir = TempDir::new("profile");
    write_level(&dir, "name = \"P\"\nscene = \"scene.gltf\"\n[headlamp]\nprofile = \"lamp/ies.png\"\n");
    dir.write("lamp/ies.png", png(2, 1, &[255, 255, 255, 255, 51, 102, 0, 255]));
    let level = load_level(dir.path()).unwrap();
    let IntensityDistribution::Image(img) = &level.headlamp.distribution else { panic!("expected an image profile") };
    assert_eq!((img.width, img.height), (2, 1));
    assert_eq!(img.values[0], [1.0, 1.0, 1.0]);
    assert!((img.values[1][0] - 0.2).abs() < 1e-6, "v/255, no sRGB decoding");
    assert!((img.values[1][1] - 0.4).abs() < 1e-6);
}

#[test]
fn bare_obj_file_is_a_level_with_defaults() {
    let dir = TempDir::new("bare");
    let path = dir.write("crate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let level = load_level(&path).unwrap();
    assert_eq!(level.name, "crate");
    assert_eq!(level.root, None);
    assert_eq!(level.scene_path, path);
    assert_eq!(level.spawn, None);
    assert_eq!(level.headlamp, HeadlampProfile::default());
    assert_eq!(level.scene.triangle_count(), 1);
    assert_ne!(level.content_hash, 0);
}

#[test]
fn content_hash_is_stable_and_sees_every_file() {
    let a = TempDir::new("hash-a");
    let b = TempDir::new("hash-b");
    write_level(&a, FULL_TOML);
    write_level(&b, FULL_TOML);
    let ha = load_level(a.path()).unwrap().content_hash;
    assert_eq!(ha, load_level(a.path()).unwrap().content_hash, "same inputs, same hash");
    assert_eq!(ha, load_level(b.path()).unwrap().content_hash, "the folder's location does not matter");

    // One byte of the external buffer changes: the first float of vertex 1 (1.0 → 1.0000001).
    let mut bin = std::fs::read(b.path().join("scene.bin")).unwrap();
    bin[12] ^= 1;
    std::fs::write(b.path().join("scene.bin"), &bin).unwrap();
    let hb = load_level(b.path()).unwrap().content_hash;
    assert_ne!(ha, hb, "a changed .bin changes the hash");

    // A changed level.toml (even just whitespace) changes it too.
    std::fs::write(a.path().join("level.toml"), format!("{FULL_TOML}\n")).unwrap();
    assert_ne!(ha, load_level(a.path()).unwrap().content_hash);

    // So does a change in the scene file itself.
    let c = TempDir::new("hash-c");
    write_level(&c, FULL_TOML);
    let gltf = std::fs::read_to_string(c.path().join("scene.gltf")).unwrap();
    std::fs::write(c.path().join("scene.gltf"), gltf.replace("7.0", "7.5")).unwrap();
    assert_ne!(ha, load_level(c.path()).unwrap().content_hash);
}

#[test]
fn scene_in_a_sub_folder_with_dot_dot_that_stays_inside() {
    let dir = TempDir::new("sub");
    dir.write("models/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    dir.write("level.toml", "name = \"Sub\"\nscene = \"models/../models/tri.obj\"\n");
    let level = load_level(dir.path()).unwrap();
    assert_eq!(level.scene.triangle_count(), 1);
}
