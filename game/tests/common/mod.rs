//! What the command-line tests share: running the binary, the shipped level, scratch folders.
// Each test file is its own crate and uses only some of these.
#![allow(dead_code)]

pub mod cornell;

use std::path::PathBuf;
use std::process::{Command, Output};

pub fn headlamp(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_headlamp")).args(args).output().expect("run headlamp")
}

pub fn cellar() -> String {
    format!("{}/../levels/cellar", env!("CARGO_MANIFEST_DIR"))
}

/// An empty folder of its own for one test (named after the test file, the process and `name`).
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("headlamp-{}-{}-{name}", env!("CARGO_CRATE_NAME"), std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
