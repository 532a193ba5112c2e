//! What the command-line tests share: running the binary, the shipped level, scratch folders.
// Each test file is its own crate and uses only some of these.
#![allow(dead_code)]

pub mod cornell;
pub mod settled;

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs the `headlamp` binary with a private runtime folder: without one Mesa's window-system
/// layer prints a warning on every device it creates, which would break the one-line errors
/// the tests expect.
pub fn headlamp(args: &[&str]) -> Output {
    let runtime = std::env::temp_dir().join(format!("headlamp-runtime-{}", std::process::id()));
    std::fs::create_dir_all(&runtime).unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&runtime, std::fs::Permissions::from_mode(0o700)).unwrap();
    }
    Command::new(env!("CARGO_BIN_EXE_headlamp"))
        .args(args)
        .env("XDG_RUNTIME_DIR", runtime)
        .output()
        .expect("run headlamp")
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

/// The sum of the three channels over the pixels of `img` that `mask` marks (one flag a pixel,
/// row by row): a region's light, to hold against the reference's over the same pixels.
pub fn masked_sum(img: &image::Rgba32FImage, mask: &[bool]) -> f64 {
    img.pixels().zip(mask).filter(|(_, &m)| m).map(|(p, _)| f64::from(p[0] + p[1] + p[2])).sum()
}
