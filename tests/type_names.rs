//! One name per type across the workspace's crates: a public struct, enum or trait named in
//! two crates (two `CompositePass`es, two `ConfigError`s) makes a reader ask which one is
//! meant. Read from the sources' text; test code is left out.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the workspace root").to_path_buf()
}

/// Every `.rs` file under `dir` (recursively).
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let path = entry.path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") && !path.ends_with("tests.rs") {
            out.push(path);
        }
    }
}

/// The public types a source declares at the start of a line, until its `#[cfg(test)]`.
fn public_types(text: &str) -> Vec<String> {
    let code = text.split("#[cfg(test)]").next().unwrap_or(text);
    code.lines()
        .filter_map(|line| {
            let rest = ["pub struct ", "pub enum ", "pub trait "].iter().find_map(|k| line.strip_prefix(k))?;
            let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            (!name.is_empty()).then_some(name)
        })
        .collect()
}

/// Type name → the crates (by their `src` folder) declaring it, where there are two or more.
fn names_in_two_crates(crates: &[(String, Vec<String>)]) -> Vec<(String, Vec<String>)> {
    let mut owners: BTreeMap<&str, Vec<String>> = BTreeMap::new();
    for (krate, types) in crates {
        for t in types {
            let list = owners.entry(t).or_default();
            if !list.contains(krate) {
                list.push(krate.clone());
            }
        }
    }
    owners.into_iter().filter(|(_, c)| c.len() > 1).map(|(t, c)| (t.to_owned(), c)).collect()
}

#[test]
fn no_public_type_name_is_declared_in_two_crates() {
    let root = root();
    let dirs = [
        "engine",
        "engine/scene",
        "engine/physics",
        "engine/audio",
        "engine/bounds",
        "plugin_gi",
        "game",
        "game/ui",
        "examples/depth_fog",
    ];
    let crates: Vec<(String, Vec<String>)> = dirs
        .iter()
        .map(|d| {
            let mut files = Vec::new();
            sources(&root.join(d).join("src"), &mut files);
            let types = files.iter().flat_map(|f| public_types(&std::fs::read_to_string(f).unwrap_or_default()));
            (d.to_string(), types.collect())
        })
        .collect();
    assert!(crates.iter().all(|(_, t)| !t.is_empty()), "every crate declares some public type");
    let twice = names_in_two_crates(&crates);
    assert!(twice.is_empty(), "public types named in two crates: {twice:?}");
}

#[test]
fn the_check_finds_a_name_declared_twice() {
    let a = public_types("pub struct CompositePass;\npub enum Stage {}\n#[cfg(test)]\npub struct Hidden;");
    assert_eq!(a, ["CompositePass", "Stage"]);
    let crates = [("engine".to_owned(), a), ("plugin_gi".to_owned(), vec!["CompositePass".to_owned()])];
    assert_eq!(names_in_two_crates(&crates), [("CompositePass".to_owned(), vec!["engine".into(), "plugin_gi".into()])]);
}
