//! Golden-image comparison for frame regression tests, by the metric and tolerance of
//! [`game::golden`] (mean FLIP error at most 0.02), which `headlamp replay --goldens` uses too.
//!
//! On failure the actual frame and a FLIP error map (magma colours) are written beside the
//! golden as `NAME.actual.png` and `NAME.diff.png` (git-ignored).
//! Set `HEADLAMP_UPDATE_GOLDENS=1` to (re)write the goldens from the current renderer instead
//! (and the test replays from their scripts, see [`replay_files`]).

use std::path::PathBuf;

pub use engine;

pub mod fuzz_targets;
pub mod replay_files;

pub use game::golden::{flip_error, MEAN_FLIP_TOLERANCE};
pub const UPDATE_ENV: &str = "HEADLAMP_UPDATE_GOLDENS";

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

/// `HEADLAMP_UPDATE_GOLDENS` is set (and not 0): goldens and test replays are being re-made.
pub fn updating_goldens() -> bool {
    std::env::var_os(UPDATE_ENV).is_some_and(|v| v != "0")
}

/// Compares `actual` with `goldens/NAME.png` (or writes it when updating goldens).
/// Returns a message describing the failure, with the paths of the images written.
pub fn check_golden(name: &str, actual: &image::RgbaImage) -> Result<f32, String> {
    let dir = goldens_dir();
    let golden_path = dir.join(format!("{name}.png"));
    if updating_goldens() {
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        actual.save(&golden_path).map_err(|e| format!("{}: {e}", golden_path.display()))?;
        return Ok(0.0);
    }
    game::golden::compare(&golden_path, actual)
        .map_err(|e| format!("{name}: {e}; if the change is intended, rerun with {UPDATE_ENV}=1"))
}
