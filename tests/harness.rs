//! Golden-image comparison for frame regression tests.
//!
//! Metric: NVIDIA FLIP (perceptual, 0 = identical … 1 = maximal difference) at the default
//! viewing condition (67 pixels per degree). A frame passes when its mean FLIP error against
//! the golden is at most [`MEAN_FLIP_TOLERANCE`]. Lavapipe's output varies slightly with the
//! CPU's SIMD width, so exact bytes are never compared.
//!
//! On failure the actual frame and a FLIP error map (magma colours) are written beside the
//! golden as `NAME.actual.png` and `NAME.diff.png` (git-ignored).
//! Set `HEADLAMP_UPDATE_GOLDENS=1` to (re)write the goldens from the current renderer instead
//! (and the test replays from their scripts, see [`replay_files`]).

use std::path::{Path, PathBuf};

pub use engine;

pub mod replay_files;

/// Mean FLIP error above which a frame is judged different from its golden.
pub const MEAN_FLIP_TOLERANCE: f32 = 0.02;
pub const UPDATE_ENV: &str = "HEADLAMP_UPDATE_GOLDENS";

pub fn cellar_path() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../levels/cellar"))
}

/// The shipped level, loaded.
pub fn cellar() -> engine::scene::Level {
    engine::scene::load_level(&cellar_path()).unwrap_or_else(|e| panic!("{e}"))
}

pub fn goldens_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/goldens"))
}

/// `HEADLAMP_UPDATE_GOLDENS` is set (and not 0): goldens and test replays are being re-made.
pub fn updating_goldens() -> bool {
    std::env::var_os(UPDATE_ENV).is_some_and(|v| v != "0")
}

/// Mean FLIP error between two equally sized images, and the error map.
pub fn flip_error(reference: &image::RgbaImage, test: &image::RgbaImage) -> (f32, image::RgbImage) {
    let rgb = |img: &image::RgbaImage| {
        let data: Vec<u8> = img.pixels().flat_map(|p| [p[0], p[1], p[2]]).collect();
        nv_flip::FlipImageRgb8::with_data(img.width(), img.height(), &data)
    };
    let map = nv_flip::flip(rgb(reference), rgb(test), nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let mean = nv_flip::FlipPool::from_image(&map).mean();
    let colours = map.apply_color_lut(&nv_flip::magma_lut());
    let diff = image::RgbImage::from_raw(map.width(), map.height(), colours.to_vec()).expect("flip map size");
    (mean, diff)
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
    let golden = match image::open(&golden_path) {
        Ok(img) => img.to_rgba8(),
        Err(e) => {
            let actual_path = write_beside(&golden_path, "actual", actual);
            return Err(format!(
                "golden {} could not be read ({e}); actual frame written to {}; run with {UPDATE_ENV}=1 to create it",
                golden_path.display(),
                actual_path.display()
            ));
        }
    };
    if golden.dimensions() != actual.dimensions() {
        let actual_path = write_beside(&golden_path, "actual", actual);
        return Err(format!(
            "{name}: size {:?} differs from the golden's {:?}; actual written to {}",
            actual.dimensions(),
            golden.dimensions(),
            actual_path.display()
        ));
    }
    let (mean, diff) = flip_error(&golden, actual);
    if mean > MEAN_FLIP_TOLERANCE {
        let actual_path = write_beside(&golden_path, "actual", actual);
        let diff_path = golden_path.with_file_name(format!("{name}.diff.png"));
        let _ = diff.save(&diff_path);
        return Err(format!(
            "{name}: mean FLIP error {mean:.4} exceeds {MEAN_FLIP_TOLERANCE}; actual: {}, difference: {}; \
             if the change is intended, rerun with {UPDATE_ENV}=1",
            actual_path.display(),
            diff_path.display()
        ));
    }
    Ok(mean)
}

fn write_beside(golden: &Path, suffix: &str, img: &image::RgbaImage) -> PathBuf {
    let stem = golden.file_stem().and_then(|s| s.to_str()).unwrap_or("frame");
    let path = golden.with_file_name(format!("{stem}.{suffix}.png"));
    let _ = img.save(&path);
    path
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_images_have_zero_error_and_different_ones_do_not() {
        let a = image::RgbaImage::from_fn(64, 64, |x, y| image::Rgba([(x * 4) as u8, (y * 4) as u8, 128, 255]));
        assert_eq!(flip_error(&a, &a).0, 0.0);
        let mut b = a.clone();
        for y in 16..48 {
            for x in 16..48 {
                b.put_pixel(x, y, image::Rgba([255, 255, 255, 255]));
            }
        }
        let (mean, diff) = flip_error(&a, &b);
        assert!(mean > MEAN_FLIP_TOLERANCE, "a white square must fail the tolerance, got {mean}");
        assert_eq!(diff.dimensions(), (64, 64));
    }
}
