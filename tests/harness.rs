//! Golden-image comparison for frame regression tests, by the metric and tolerances of
//! [`game::golden`], which `headlamp replay --goldens` uses too.
//!
//! On failure the actual frame and a FLIP error map (magma colours) are written beside the
//! golden as `NAME.actual.png` and `NAME.diff.png` (git-ignored). The goldens and the test
//! replays are re-made by one command, never by the tests:
//! `cargo run --release -p headlamp-tests --bin update-goldens` (see `update_goldens.rs`).

use std::path::PathBuf;

pub use engine;

pub mod frames;
pub mod fuzz_bounds;
pub mod fuzz_targets;
pub mod module_graph;
pub mod replay_files;

pub use game::golden::Difference;

/// The command that re-makes the goldens and the test replays.
pub const UPDATE_COMMAND: &str = "cargo run --release -p headlamp-tests --bin update-goldens";

/// The folder of the shipped level `id` (`cellar`, `gallery`, `hall`).
pub fn level_path(id: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../levels")).join(id)
}

/// The shipped level `id`, loaded.
pub fn load_level(id: &str) -> engine::scene::Level {
    engine::scene::load_level(&level_path(id)).unwrap_or_else(|e| panic!("{e}"))
}

pub fn cellar_path() -> PathBuf {
    level_path("cellar")
}

/// The default shipped level, loaded.
pub fn cellar() -> engine::scene::Level {
    load_level("cellar")
}

pub fn goldens_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/goldens"))
}

/// `goldens/NAME.png`.
pub fn golden_path(name: &str) -> PathBuf {
    goldens_dir().join(format!("{name}.png"))
}

/// Compares `actual` with `goldens/NAME.png`. Returns a message describing the failure, with the
/// paths of the images written.
pub fn check_golden(name: &str, actual: &image::RgbaImage) -> Result<Difference, String> {
    game::golden::compare(&golden_path(name), actual)
        .map_err(|e| format!("{name}: {e}; if the change is intended, look at the frame, then run {UPDATE_COMMAND}"))
}
