//! No module imports another that imports it back, in any crate of the workspace: one test per
//! crate, so each crate's status reads on its own. What counts as an import (an edge) is set out
//! in `module_graph.rs`.

use std::path::{Path, PathBuf};

use headlamp_tests::module_graph::{tangles, ModuleGraph};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the workspace root").to_path_buf()
}

/// The quoted strings of a TOML value (`members = ["a", "b"]`, `path = "x.rs"`).
fn quoted(value: &str) -> Vec<String> {
    value.split('"').skip(1).step_by(2).map(String::from).collect()
}

/// The workspace's members, as the root manifest lists them (on one line).
fn members() -> Vec<String> {
    let manifest = std::fs::read_to_string(root().join("Cargo.toml")).expect("the workspace manifest");
    let line = manifest.lines().find(|l| l.starts_with("members")).expect("a members line");
    quoted(line)
}

/// The root files of package `dir`'s library and binaries, relative to the workspace root.
fn crate_roots(dir: &str) -> Vec<String> {
    let manifest = std::fs::read_to_string(root().join(dir).join("Cargo.toml")).expect("a manifest");
    let mut roots = Vec::new();
    let mut section = "";
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            section = line;
        } else if (section == "[lib]" || section == "[[bin]]") && line.starts_with("path") {
            roots.extend(quoted(line).into_iter().map(|path| format!("{dir}/{path}")));
        }
    }
    for default in ["src/lib.rs", "src/main.rs"].map(|f| format!("{dir}/{f}")) {
        if root().join(&default).exists() && !roots.contains(&default) {
            roots.push(default);
        }
    }
    assert!(!root().join(dir).join("src/bin").exists(), "{dir}/src/bin: its binaries are not read yet");
    roots
}

fn graph_of(dir: &str) -> ModuleGraph {
    let root = root();
    ModuleGraph::read(&crate_roots(dir), |file| std::fs::read_to_string(root.join(file)).ok())
        .unwrap_or_else(|e| panic!("{e}"))
}

fn assert_no_circle(dir: &str) {
    let graph = graph_of(dir);
    // A reader that saw nothing would find no circle either; a crate of single-file roots
    // (a small example) has no modules to import between.
    let single_files = graph.modules.len() == crate_roots(dir).len();
    assert!(
        single_files || !graph.edges.is_empty(),
        "{dir}: no imports found between its {} modules",
        graph.modules.len()
    );
    let found = tangles(&graph);
    let list: Vec<String> = found.iter().map(|t| t.describe(&graph)).collect();
    assert!(
        found.is_empty(),
        "{dir}: modules import each other in circles; move what both sides need where only one imports it:\n{}",
        list.join("\n")
    );
}

/// One test per workspace member, and the list they cover.
macro_rules! each_member {
    ($($test:ident: $dir:literal,)*) => {
        $(
            #[test]
            fn $test() {
                assert_no_circle($dir);
            }
        )*
        const CHECKED: &[&str] = &[$($dir),*];
    };
}

each_member! {
    engine_has_no_import_circle: "engine",
    scene_has_no_import_circle: "engine/scene",
    gltf_conformance_has_no_import_circle: "engine/scene/conformance",
    physics_has_no_import_circle: "engine/physics",
    audio_has_no_import_circle: "engine/audio",
    bounds_has_no_import_circle: "engine/bounds",
    occupancy_has_no_import_circle: "engine/occupancy",
    plugin_gi_has_no_import_circle: "plugin_gi",
    gi_reference_has_no_import_circle: "plugin_gi/reference",
    game_has_no_import_circle: "game",
    game_ui_has_no_import_circle: "game/ui",
    headlamp_tests_has_no_import_circle: "tests",
    level_generator_has_no_import_circle: "levels/generator",
    depth_fog_example_has_no_import_circle: "examples/depth_fog",
}

#[test]
fn every_workspace_member_is_checked() {
    let mut members = members();
    let mut checked: Vec<String> = CHECKED.iter().map(|d| d.to_string()).collect();
    members.sort();
    checked.sort();
    assert_eq!(members, checked, "a test per member of the workspace");
}

/// The graph of a made-up crate whose root is `src/lib.rs`.
fn graph(files: &[(&str, &str)]) -> ModuleGraph {
    let source = |file: &str| files.iter().find(|(f, _)| *f == file).map(|(_, text)| text.to_string());
    ModuleGraph::read(&["src/lib.rs".to_string()], source).unwrap_or_else(|e| panic!("{e}"))
}

/// The edges as `from → to`, by module name, sorted.
fn edges(graph: &ModuleGraph) -> Vec<String> {
    let mut edges: Vec<String> =
        graph.edges.iter().map(|e| format!("{} → {}", graph.name(e.from), graph.name(e.to))).collect();
    edges.sort();
    edges
}

#[test]
fn a_planted_circle_is_found_with_its_places() {
    let graph = graph(&[
        ("src/lib.rs", "mod a;\nmod b;\nmod c;\nmod d;"),
        ("src/a.rs", "use crate::b::B;\npub struct A;"),
        ("src/b.rs", "pub struct B;\nfn f() -> crate::c::C { todo!() }"),
        ("src/c.rs", "pub struct C;\n\nfn g() { let _ = super::a::A; }"),
        ("src/d.rs", "use crate::a::A;"),
    ]);
    let found = tangles(&graph);
    assert_eq!(found.len(), 1);
    assert_eq!(
        found[0].describe(&graph),
        "3 modules in a tangle: crate::a, crate::b, crate::c\n  \
         crate::a → crate::b → crate::c → crate::a\n      \
         src/a.rs:1 names crate::b (crate::b::B)\n      \
         src/b.rs:2 names crate::c (crate::c::C)\n      \
         src/c.rs:3 names crate::a (super::a::A)"
    );
}

#[test]
fn every_edge_of_a_tangle_is_in_some_circle_listed() {
    // a ⇄ b and a ⇄ c: one tangle, two circles.
    let graph = graph(&[
        ("src/lib.rs", "mod a;\nmod b;\nmod c;"),
        ("src/a.rs", "use crate::{b::B, c::C};\npub struct A;"),
        ("src/b.rs", "use crate::a::A;\npub struct B;"),
        ("src/c.rs", "use crate::a::A;\npub struct C;"),
    ]);
    let found = tangles(&graph);
    assert_eq!(found.len(), 1);
    let listed: Vec<String> = found[0].circles.iter().map(|c| c.describe(&graph)).collect();
    assert_eq!(listed.len(), 2, "{listed:?}");
    assert!(listed[0].starts_with("  crate::a → crate::b → crate::a\n"), "{listed:?}");
    assert!(listed[1].starts_with("  crate::a → crate::c → crate::a\n"), "{listed:?}");
}

#[test]
fn the_module_tree_is_not_a_circle() {
    // The parent declares and re-exports its child; the child uses the parent's constant.
    let graph = graph(&[
        ("src/lib.rs", "pub mod passes;\nmod user;"),
        ("src/passes/mod.rs", "mod x;\npub use x::Pass;\npub const SIZE: u32 = 4;"),
        ("src/passes/x.rs", "use super::SIZE;\npub struct Pass([u8; SIZE as usize]);"),
        ("src/user.rs", "use crate::passes::Pass;\nfn f(_: Pass, _: [u8; crate::passes::SIZE as usize]) {}"),
    ]);
    assert!(tangles(&graph).is_empty());
    // The re-export is followed to the file that defines the item.
    assert_eq!(
        edges(&graph),
        ["crate::passes::x → crate::passes", "crate::user → crate::passes", "crate::user → crate::passes::x"]
    );
}

#[test]
fn a_re_export_the_file_uses_itself_is_an_edge() {
    let graph = graph(&[
        ("src/lib.rs", "pub mod passes;"),
        ("src/passes/mod.rs", "mod x;\npub use x::Pass;\npub const SIZE: u32 = 4;\npub fn make() -> Pass { todo!() }"),
        ("src/passes/x.rs", "pub struct Pass([u8; super::SIZE as usize]);"),
    ]);
    assert_eq!(tangles(&graph).len(), 1);
    assert_eq!(graph.edges[0].line, 4);
}

#[test]
fn globs_aliases_and_child_paths_are_followed() {
    let graph = graph(&[
        ("src/lib.rs", "mod types;\nmod level;\npub use types::*;\nfn f() { level::load(); }"),
        ("src/types.rs", "pub struct Scene;"),
        ("src/level.rs", "use crate::Scene;\nuse crate::types as t;\npub fn load() -> t::Scene { Scene }"),
    ]);
    assert_eq!(edges(&graph), ["crate → crate::level", "crate::level → crate::types"]);
}

#[test]
fn test_code_comments_and_strings_are_not_read() {
    let graph = graph(&[
        ("src/lib.rs", "mod a;\nmod b;"),
        ("src/a.rs", "pub struct A;\n#[cfg(test)]\nmod tests;\n#[cfg(test)]\nmod more { use crate::b::B; }"),
        ("src/b.rs", "use crate::a::A;\npub struct B;\n// crate::a::A\nconst S: &str = \"crate::a::A\";"),
    ]);
    assert_eq!(edges(&graph), ["crate::b → crate::a"]);
    assert_eq!(graph.edges[0].line, 1);
}

#[test]
fn a_missing_module_file_is_an_error() {
    let files = [("src/lib.rs", "mod gone;")];
    let source = |file: &str| files.iter().find(|(f, _)| *f == file).map(|(_, text)| text.to_string());
    let error = ModuleGraph::read(&["src/lib.rs".to_string()], source).err().expect("an error");
    assert_eq!(error, "src/lib.rs:1: `mod gone;` has no file");
}
