//! Golden-image comparison: the metric and tolerance of the project's own frame tests, shared
//! with `headlamp replay --goldens` so that anyone's level gets the same regression tests.
//!
//! Metric: NVIDIA FLIP (perceptual, 0 = identical … 1 = maximal difference) at the default
//! viewing condition (67 pixels per degree). A frame passes when its mean FLIP error against
//! the golden is at most [`MEAN_FLIP_TOLERANCE`]. Lavapipe's output varies slightly with the
//! CPU's SIMD width, so exact bytes are never compared.

use std::path::{Path, PathBuf};

/// Mean FLIP error above which a frame is judged different from its golden.
pub const MEAN_FLIP_TOLERANCE: f32 = 0.02;

/// Mean FLIP error between two equally sized images, and the error map (magma colours).
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

/// Compares `actual` with the PNG at `golden` and returns the mean FLIP error. On a failure
/// (unreadable golden, other size, error over the tolerance) the frame is written beside the
/// golden as `NAME.actual.png` (and the error map as `NAME.diff.png`), and the message names them.
pub fn compare(golden: &Path, actual: &image::RgbaImage) -> Result<f32, String> {
    let expected = match image::open(golden) {
        Ok(img) => img.to_rgba8(),
        Err(e) => {
            let actual_path = write_beside(golden, "actual", actual);
            return Err(format!(
                "{}: cannot read the golden ({e}); the frame is in {}",
                golden.display(),
                actual_path.display()
            ));
        }
    };
    if expected.dimensions() != actual.dimensions() {
        let actual_path = write_beside(golden, "actual", actual);
        return Err(format!(
            "{}: the frame is {:?}, the golden {:?}; the frame is in {}",
            golden.display(),
            actual.dimensions(),
            expected.dimensions(),
            actual_path.display()
        ));
    }
    let (mean, diff) = flip_error(&expected, actual);
    if mean > MEAN_FLIP_TOLERANCE {
        let actual_path = write_beside(golden, "actual", actual);
        let diff_path = beside(golden, "diff");
        let _ = diff.save(&diff_path);
        return Err(format!(
            "{}: mean FLIP error {mean:.4} exceeds {MEAN_FLIP_TOLERANCE}; frame: {}, difference: {}",
            golden.display(),
            actual_path.display(),
            diff_path.display()
        ));
    }
    Ok(mean)
}

/// `dir/NAME.png` → `dir/NAME.SUFFIX.png`.
fn beside(golden: &Path, suffix: &str) -> PathBuf {
    let stem = golden.file_stem().and_then(|s| s.to_str()).unwrap_or("frame");
    golden.with_file_name(format!("{stem}.{suffix}.png"))
}

fn write_beside(golden: &Path, suffix: &str, img: &image::RgbaImage) -> PathBuf {
    let path = beside(golden, suffix);
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

    #[test]
    fn a_failure_writes_the_frame_and_the_difference_beside_the_golden() {
        let dir = std::env::temp_dir().join(format!("headlamp-golden-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let golden = dir.join("tick_000010.png");
        let grey = image::RgbaImage::from_pixel(32, 32, image::Rgba([90, 90, 90, 255]));
        grey.save(&golden).unwrap();
        assert_eq!(compare(&golden, &grey), Ok(0.0));
        let white = image::RgbaImage::from_pixel(32, 32, image::Rgba([255, 255, 255, 255]));
        let e = compare(&golden, &white).unwrap_err();
        assert!(e.contains("exceeds") && e.contains("tick_000010.diff.png"), "{e}");
        assert!(dir.join("tick_000010.actual.png").exists() && dir.join("tick_000010.diff.png").exists());
        let e = compare(&golden, &image::RgbaImage::new(16, 16)).unwrap_err();
        assert!(e.contains("(16, 16)"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
