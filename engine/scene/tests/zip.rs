//! A level zipped whole loads from the archive in place, as its folder does, and the archive is
//! a sandbox like the folder: nothing outside it is read.

mod common;

use std::io::Write;

use common::*;
use scene::{load_level, LoadErrorKind};
use serde_json::json;

const TOML: &str =
    "name = \"Zipped\"\ndescription = \"in an archive\"\nscene = \"scene.gltf\"\n\n[headlamp]\npower = 3.0\n";

/// A zip of `files` (name, bytes), deflated.
fn zip(files: &[(&str, &[u8])]) -> Vec<u8> {
    let mut out = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    for (name, bytes) in files {
        out.start_file(*name, options).unwrap();
        out.write_all(bytes).unwrap();
    }
    out.finish().unwrap().into_inner()
}

/// A one-triangle scene whose buffer is the external file `uri`.
fn scene_with_buffer(uri: &str) -> (Vec<u8>, Vec<u8>) {
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let doc = bin.gltf_with_buffer(
        json!({"scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": pos}}]}]}),
        json!({"byteLength": bin.data.len(), "uri": uri}),
    );
    (serde_json::to_vec(&doc).unwrap(), bin.data.clone())
}

#[test]
fn a_zipped_level_loads_like_its_folder() {
    let dir = TempDir::new("zip-ok");
    let (gltf, bin) = scene_with_buffer("data/scene.bin");
    dir.write("folder/level.toml", TOML);
    dir.write("folder/scene.gltf", &gltf);
    dir.write("folder/data/scene.bin", &bin);
    let from_folder = load_level(&dir.path().join("folder")).unwrap();
    for (tag, archive) in [
        ("at its root", zip(&[("level.toml", TOML.as_bytes()), ("scene.gltf", &gltf), ("data/scene.bin", &bin)])),
        (
            "under one top folder",
            zip(&[("lvl/level.toml", TOML.as_bytes()), ("lvl/scene.gltf", &gltf), ("lvl/data/scene.bin", &bin)]),
        ),
    ] {
        let path = dir.write("level.zip", &archive);
        let level = load_level(&path).unwrap_or_else(|e| panic!("{tag}: {e}"));
        assert_eq!((level.name.as_str(), level.description.as_str()), ("Zipped", "in an archive"), "{tag}");
        assert_eq!(level.scene.meshes, from_folder.scene.meshes, "{tag}");
        assert_eq!(level.headlamp, from_folder.headlamp, "{tag}");
        assert_eq!(level.root.as_deref(), Some(path.as_path()), "{tag}");
        assert_eq!(level.scene_path, path.join("scene.gltf"), "{tag}: members are named under the archive");
        assert_eq!(level.files, vec![path.clone()], "{tag}: the archive is what to watch");
        assert_eq!(load_level(&path).unwrap().content_hash, level.content_hash, "{tag}");
    }
    // Another archive, another hash: replays notice.
    let path = dir.write(
        "level.zip",
        zip(&[("level.toml", TOML.replace("3.0", "4.0").as_bytes()), ("scene.gltf", &gltf), ("data/scene.bin", &bin)]),
    );
    assert_ne!(load_level(&path).unwrap().content_hash, from_folder.content_hash);
}

#[test]
fn a_zipped_level_is_a_sandbox_and_its_errors_name_the_member() {
    let dir = TempDir::new("zip-bad");
    let (gltf_out, bin) = scene_with_buffer("../secret.bin");
    dir.write("secret.bin", &bin);
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "escape",
            zip(&[("level.toml", TOML.as_bytes()), ("scene.gltf", &gltf_out)]),
            "scene.gltf: path '../secret.bin' escapes the level folder",
        ),
        (
            "absolute",
            zip(&[("level.toml", TOML.replace("scene.gltf", "/etc/passwd").as_bytes())]),
            "level.toml: path '/etc/passwd' escapes the level folder",
        ),
        (
            "typo",
            zip(&[("level.toml", b"name = \"Z\"\nscene = \"s.gltf\"\npowr = 1\n")]),
            "level.zip/level.toml:3:1: invalid level: unknown field `powr`",
        ),
        ("missing member", zip(&[("level.toml", TOML.as_bytes())]), "level.zip/scene.gltf: file not found"),
        ("no level", zip(&[("readme.txt", b"hi")]), "level.zip/level.toml: file not found"),
        ("two levels", zip(&[("a/level.toml", TOML.as_bytes()), ("b/level.toml", TOML.as_bytes())]), "several levels"),
        ("not a zip", b"PK but not really".to_vec(), "not a readable zip archive"),
    ];
    for (tag, bytes, needle) in cases {
        let path = dir.write("level.zip", &bytes);
        let e = load_level(&path).expect_err(tag);
        let msg = e.to_string();
        assert!(msg.contains(needle), "{tag}: {msg}");
        assert!(!msg.contains('\n'), "{tag}: one line: {msg}");
        if tag == "escape" {
            assert!(matches!(e.kind, LoadErrorKind::EscapesFolder(_)), "{tag}: {e:?}");
        }
    }
}
