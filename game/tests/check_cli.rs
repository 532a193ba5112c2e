//! `headlamp check` as a modder runs it: the shipped level passes, and each kind of mistake is
//! one `FILE:LINE:COL: error|warning: …` line (and the same in `--json`), exit 1 on errors.

use std::path::Path;
use std::process::Output;

use serde_json::{json, Value};

mod common;

use common::{cellar, headlamp, scratch};

fn printed(out: &Output) -> Vec<String> {
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    String::from_utf8_lossy(&out.stdout).lines().map(str::to_owned).collect()
}

fn has(lines: &[String], needles: &[&str]) {
    assert!(lines.iter().any(|l| needles.iter().all(|n| l.contains(n))), "no line with {needles:?} in {lines:#?}");
}

/// Two 5 × 6 m rooms side by side (x from 0 to 10), split by a wall at x = 5 with no door; a
/// floor, no ceiling. `markers` are glTF nodes placed in them.
fn two_rooms(dir: &Path, markers: &[Value], level_toml: &str, material: Value) {
    let quads: [[[f32; 3]; 4]; 2] = [
        [[0.0, 0.0, 0.0], [0.0, 0.0, 6.0], [10.0, 0.0, 6.0], [10.0, 0.0, 0.0]],
        [[5.0, 0.0, 0.0], [5.0, 3.0, 0.0], [5.0, 3.0, 6.0], [5.0, 0.0, 6.0]],
    ];
    let positions: Vec<f32> = quads.iter().flatten().flatten().copied().collect();
    let indices: Vec<u16> = [0u16, 4].iter().flat_map(|&b| [b, b + 1, b + 2, b, b + 2, b + 3]).collect();
    let mut bin: Vec<u8> = positions.iter().flat_map(|v| v.to_le_bytes()).collect();
    let index_offset = bin.len();
    bin.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    std::fs::write(dir.join("scene.bin"), &bin).unwrap();
    let mut nodes = vec![json!({"mesh": 0})];
    nodes.extend(markers.iter().cloned());
    let doc = json!({
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": (0..nodes.len()).collect::<Vec<_>>()}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [material],
        "buffers": [{"byteLength": bin.len(), "uri": "scene.bin"}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": index_offset},
            {"buffer": 0, "byteOffset": index_offset, "byteLength": indices.len() * 2},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [10.0, 3.0, 6.0]},
            {"bufferView": 1, "componentType": 5123, "count": indices.len(), "type": "SCALAR"},
        ],
    });
    std::fs::write(dir.join("scene.gltf"), serde_json::to_vec_pretty(&doc).unwrap()).unwrap();
    std::fs::write(dir.join("level.toml"), level_toml).unwrap();
}

fn marker(name: &str, at: [f32; 3], extras: Value) -> Value {
    json!({"name": name, "translation": at, "extras": extras})
}

const LEVEL: &str = "name = \"Two rooms\"\nscene = \"scene.gltf\"\n\n[spawn]\nposition = [2.0, 0.0, 3.0]\n";

#[test]
fn the_shipped_level_passes() {
    let out = headlamp(&["check", &cellar()]);
    let lines = printed(&out);
    assert_eq!(out.status.code(), Some(0), "{lines:#?}");
    has(&lines, &["ok (0 errors"]);
}

#[test]
fn a_level_too_large_for_the_gis_occupancy_grid_is_reported_not_refused() {
    // A floor 600 m across fits only with coarser voxels; a triangle a million metres across
    // fits no grid at all. Neither keeps the level from being played.
    let dir = scratch("grid_size");
    let obj = |path: &Path, far: f32| {
        let text = format!("v 0 0 0\nv {far} 0 0\nv 0 0 {far}\nv 0 100 0\nv 1 100 0\nv 0 100 1\nf 1 2 3\nf 4 5 6\n");
        std::fs::write(path, text).unwrap();
    };
    let (wide, huge) = (dir.join("wide.obj"), dir.join("huge.obj"));
    obj(&wide, 600.0);
    obj(&huge, 1.0e6);
    let lines = printed(&headlamp(&["check", wide.to_str().unwrap()]));
    has(&lines, &["wide.obj: warning: the GI's occupancy grid takes", "cm voxels to fit 64 MiB (the finest is 5 cm)"]);
    let out = headlamp(&["check", huge.to_str().unwrap()]);
    let lines = printed(&out);
    has(&lines, &["huge.obj: warning: the GI cannot see this level's walls where the camera does not", "1000000"]);
    // (Its spawn floats over nothing: that error is the level's, not the grid's.)
    assert!(!lines.iter().any(|l| l.contains(": error: the GI")), "{lines:#?}");
}

#[test]
fn a_level_toml_typo_is_placed_at_its_line_and_column() {
    let dir = scratch("typo");
    two_rooms(&dir, &[], &format!("{LEVEL}\n[headlamp]\n  powr = 3.0\n"), json!({}));
    let out = headlamp(&["check", dir.to_str().unwrap()]);
    let lines = printed(&out);
    assert_eq!(out.status.code(), Some(1), "{lines:#?}");
    has(&lines, &["level.toml:8:3: error: invalid level: unknown field `powr`"]);
}

#[test]
fn unreachable_things_a_stuck_spawn_and_ignored_features_are_reported() {
    let dir = scratch("rooms");
    let markers = [
        marker("ammo_near", [3.0, 0.3, 3.0], json!({"pickup": "ammo"})),
        marker("ammo_far", [8.0, 0.3, 3.0], json!({"pickup": "ammo"})),
        marker("way_out", [8.0, 0.0, 5.0], json!({"exit": true})),
        marker("crawler", [8.0, 0.0, 1.0], json!({"enemy": "crawler"})),
    ];
    two_rooms(&dir, &markers, LEVEL, json!({"name": "leaves", "alphaMode": "BLEND"}));
    let path = dir.to_str().unwrap();
    let out = headlamp(&["check", path]);
    let lines = printed(&out);
    assert_eq!(out.status.code(), Some(1), "{lines:#?}");
    has(&lines, &["scene.gltf: error: node 'ammo_far': the ammo pickup", "cannot be walked to from the spawn"]);
    has(&lines, &["scene.gltf: error: the exit at (8.00, 0.00, 5.00) cannot be walked to"]);
    has(&lines, &["scene.gltf: warning: node 'crawler': this crawler", "cannot walk to the player's spawn"]);
    has(
        &lines,
        &["scene.gltf: warning: material 0 ('leaves'): alphaMode BLEND (partial transparency) is not supported"],
    );
    assert!(!lines.iter().any(|l| l.contains("ammo_near")), "the near pickup is reachable: {lines:#?}");

    // The same findings for tools.
    let out = headlamp(&["check", path, "--json"]);
    assert_eq!(out.status.code(), Some(1));
    let report: Value = serde_json::from_slice(&out.stdout).expect("--json prints one JSON document");
    assert_eq!(
        (report["ok"].as_bool(), report["errors"].as_u64(), report["warnings"].as_u64()),
        (Some(false), Some(2), Some(2))
    );
    let first = &report["diagnostics"].as_array().unwrap()[0];
    assert_eq!((first["severity"].as_str(), first["line"].as_u64()), (Some("warning"), None));

    // The spawn moved into the wall: stuck, placed at the spawn's line in level.toml.
    std::fs::write(dir.join("level.toml"), LEVEL.replace("[2.0, 0.0, 3.0]", "[5.0, 0.0, 3.0]")).unwrap();
    let lines = printed(&headlamp(&["check", path]));
    has(&lines, &["level.toml:5:1: error: the spawn (5.00, 0.00, 3.00) is inside the level's geometry"]);

    // Won by the exit once it is in the spawn's room; warnings alone exit 0.
    let markers = [marker("way_out", [3.0, 0.0, 5.0], json!({"exit": true}))];
    two_rooms(&dir, &markers, LEVEL, json!({"name": "leaves", "alphaMode": "BLEND"}));
    let out = headlamp(&["check", path]);
    let lines = printed(&out);
    assert_eq!(out.status.code(), Some(0), "{lines:#?}");
    has(&lines, &["ok (0 errors, 1 warning)"]);
}

#[test]
fn what_check_refuses_the_game_refuses_too() {
    let dir = scratch("broken");
    two_rooms(&dir, &[marker("p", [3.0, 0.0, 3.0], json!({"pickup": "gold"}))], LEVEL, json!({}));
    let lines = printed(&headlamp(&["check", dir.to_str().unwrap()]));
    has(&lines, &["scene.gltf: error: node 'p': unknown pickup \"gold\""]);
    // `script` builds the level's world as the game does, and stops on the same line.
    let steps = dir.join("walk.txt");
    std::fs::write(&steps, "10 forward\n").unwrap();
    let replay = dir.join("walk.replay");
    let out = headlamp(&[
        "script",
        steps.to_str().unwrap(),
        "--level",
        dir.to_str().unwrap(),
        "--out",
        replay.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("node 'p': unknown pickup \"gold\""), "{err}");
}

#[test]
fn modding_md_carries_the_level_toml_reference_as_check_prints_it() {
    let out = headlamp(&["check", "--reference"]);
    assert_eq!(out.status.code(), Some(0));
    let reference = String::from_utf8(out.stdout).unwrap();
    assert!(
        reference.contains("| [headlamp] `profile` |") && reference.contains("| [game] `objective` |"),
        "{reference}"
    );
    let modding = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../MODDING.md")).unwrap();
    let block = modding
        .split_once("<!-- level.toml reference: begin")
        .and_then(|(_, rest)| rest.split_once("-->\n"))
        .and_then(|(_, rest)| rest.split_once("<!-- level.toml reference: end -->"))
        .map(|(block, _)| block)
        .expect("MODDING.md has the reference markers");
    assert_eq!(
        block, reference,
        "MODDING.md's reference is stale: paste `headlamp check --reference` between its markers"
    );
}
