//! Golden-image comparison: the metric and tolerances of the project's own frame tests, shared
//! with `headlamp replay --goldens` so that anyone's level gets the same regression tests.
//!
//! A frame passes when all four bounds hold against its golden:
//! - the mean NVIDIA FLIP error (perceptual, 0 = identical … 1 = maximal difference, at the
//!   default viewing condition of 67 pixels per degree) is at most [`MEAN_FLIP_TOLERANCE`];
//! - the 99th percentile of the per-pixel FLIP error is at most [`P99_FLIP_TOLERANCE`]: a
//!   change over a few percent of the frame (a shadow moved) that the mean dilutes;
//! - the mean FLIP error of the worst 8×8 window, at every position, is at most
//!   [`WINDOW_FLIP_TOLERANCE`]: a change smaller than the percentile ignores (576 pixels at
//!   320×180), such as a pickup gone or a crawler's eyes dimmed;
//! - the mean luminance is within [`LUMINANCE_TOLERANCE`] of the golden's: a frame dimmer or
//!   brighter all over, which FLIP reads as small in a dark frame (10 % less light: mean FLIP
//!   0.009 on the Cellar's hall).
//!
//! Lavapipe's output varies slightly with the CPU's SIMD width, so exact bytes are never compared.

use std::path::{Path, PathBuf};

/// Mean FLIP error above which a frame is judged different from its golden.
pub const MEAN_FLIP_TOLERANCE: f64 = 0.02;
/// 99th percentile of the per-pixel FLIP error above which a frame is judged different.
pub const P99_FLIP_TOLERANCE: f64 = 0.1;
/// Mean FLIP error of the worst [`WINDOW`]×[`WINDOW`] window above which a frame is judged
/// different. Today's frames against their goldens reach 0.17 at worst (the Gallery's blue room
/// lit by the lamp set down); a crawler's eyes across a dark room dimmed by half read 0.33, a
/// 12×12 patch of a frame's brightest area turned to its mean colour 0.57 or more
/// (docs/testing.md, `tests/golden_bounds.rs`).
pub const WINDOW_FLIP_TOLERANCE: f64 = 0.24;
/// The side of the windows of [`WINDOW_FLIP_TOLERANCE`], pixels.
pub const WINDOW: u32 = 8;
/// Relative difference of the mean luminance above which a frame is judged different.
pub const LUMINANCE_TOLERANCE: f64 = 0.03;

/// How a frame differs from its golden, by the three measures the bounds apply to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Difference {
    pub mean_flip: f32,
    pub p99_flip: f32,
    /// The mean FLIP error of the worst [`WINDOW`]×[`WINDOW`] window.
    pub window_flip: f32,
    /// The frame's mean luminance over the golden's, minus 1.
    pub luminance: f64,
}

impl Difference {
    /// The difference between two equally sized images, and the FLIP error map (magma colours).
    pub fn between(golden: &image::RgbaImage, frame: &image::RgbaImage) -> (Difference, image::RgbImage) {
        let rgb = |img: &image::RgbaImage| {
            let data: Vec<u8> = img.pixels().flat_map(|p| [p[0], p[1], p[2]]).collect();
            nv_flip::FlipImageRgb8::with_data(img.width(), img.height(), &data)
        };
        let map = nv_flip::flip(rgb(golden), rgb(frame), nv_flip::DEFAULT_PIXELS_PER_DEGREE);
        let mean_flip = nv_flip::FlipPool::from_image(&map).mean();
        let errors = map.to_vec();
        let window_flip = worst_window_mean(&errors, map.width(), WINDOW);
        let p99_flip = percentile(errors, 0.99);
        let (g, f) = (mean_luminance(golden), mean_luminance(frame));
        let luminance = if g > 0.0 {
            f / g - 1.0
        } else if f > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        let colours = map.apply_color_lut(&nv_flip::magma_lut());
        let diff = image::RgbImage::from_raw(map.width(), map.height(), colours.to_vec()).expect("flip map size");
        (Difference { mean_flip, p99_flip, window_flip, luminance }, diff)
    }

    /// Each bound this difference exceeds (or a figure that is not a number), in words; empty
    /// when the frame passes.
    pub fn exceeded(&self) -> Vec<String> {
        [
            bounds::at_most("the mean FLIP error", f64::from(self.mean_flip), MEAN_FLIP_TOLERANCE),
            bounds::at_most("the 99th-percentile FLIP error", f64::from(self.p99_flip), P99_FLIP_TOLERANCE),
            bounds::at_most(
                format!("the worst {WINDOW}x{WINDOW} window's mean FLIP error"),
                f64::from(self.window_flip),
                WINDOW_FLIP_TOLERANCE,
            ),
            bounds::magnitude_at_most("the mean luminance's change", self.luminance, LUMINANCE_TOLERANCE),
        ]
        .into_iter()
        .filter_map(Result::err)
        .collect()
    }
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "mean FLIP {:.4}, 99th percentile {:.3}, worst {WINDOW}x{WINDOW} window {:.3}, luminance {:+.2} %",
            self.mean_flip,
            self.p99_flip,
            self.window_flip,
            100.0 * self.luminance
        )
    }
}

/// The `p` quantile (0…1) of `values` (the nearest rank below).
fn percentile(mut values: Vec<f32>, p: f64) -> f32 {
    if values.is_empty() {
        return 0.0;
    }
    let rank = ((values.len() - 1) as f64 * p).floor() as usize;
    *values.select_nth_unstable_by(rank, f32::total_cmp).1
}

/// The largest mean of `values` (a `width`-wide image, row by row) over the `side`×`side`
/// windows at every position, by a summed-area table; a NaN anywhere gives NaN, and an image
/// smaller than a window is one window.
fn worst_window_mean(values: &[f32], width: u32, side: u32) -> f32 {
    let w = width as usize;
    let h = values.len().checked_div(w).unwrap_or(0);
    if w == 0 || h == 0 {
        return 0.0;
    }
    // sums[(y) * (w + 1) + x]: the sum over the rectangle above and left of (x, y).
    let mut sums = vec![0.0f64; (w + 1) * (h + 1)];
    for y in 0..h {
        let mut row = 0.0f64;
        for x in 0..w {
            row += f64::from(values[y * w + x]);
            sums[(y + 1) * (w + 1) + x + 1] = sums[y * (w + 1) + x + 1] + row;
        }
    }
    let (sw, sh) = ((side as usize).min(w), (side as usize).min(h));
    let mut means = Vec::with_capacity((w - sw + 1) * (h - sh + 1));
    for y in 0..=h - sh {
        for x in 0..=w - sw {
            let at = |x: usize, y: usize| sums[y * (w + 1) + x];
            let sum = at(x + sw, y + sh) - at(x, y + sh) - at(x + sw, y) + at(x, y);
            means.push(sum / (sw * sh) as f64);
        }
    }
    bounds::worst(means) as f32
}

/// An 8-bit sRGB-encoded value decoded to linear, 0…1.
pub fn srgb_to_linear(c: u8) -> f64 {
    let c = c as f64 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Mean relative luminance (Rec. 709, linear: the sRGB-encoded pixels decoded), 0…1.
pub fn mean_luminance(img: &image::RgbaImage) -> f64 {
    let sum: f64 = img
        .pixels()
        .map(|p| 0.2126 * srgb_to_linear(p[0]) + 0.7152 * srgb_to_linear(p[1]) + 0.0722 * srgb_to_linear(p[2]))
        .sum();
    sum / (img.width() as f64 * img.height() as f64).max(1.0)
}

/// Compares `actual` with the PNG at `golden`. On a failure (unreadable golden, other size, a
/// bound exceeded) the frame is written beside the golden as `NAME.actual.png` (and the FLIP
/// error map as `NAME.diff.png`), and the message names them.
pub fn compare(golden: &Path, actual: &image::RgbaImage) -> Result<Difference, String> {
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
    let (difference, diff) = Difference::between(&expected, actual);
    let exceeded = difference.exceeded();
    if !exceeded.is_empty() {
        let actual_path = write_beside(golden, "actual", actual);
        let diff_path = beside(golden, "diff");
        let _ = diff.save(&diff_path);
        return Err(format!(
            "{}: {}; frame: {}, difference: {}",
            golden.display(),
            exceeded.join(", "),
            actual_path.display(),
            diff_path.display()
        ));
    }
    Ok(difference)
}

/// Writes `image` as the golden at `path`, and removes what an earlier failure left beside it.
pub fn write(path: &Path, image: &image::RgbaImage) -> Result<(), String> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    image.save(path).map_err(|e| format!("{}: {e}", path.display()))?;
    for stale in ["actual", "diff"] {
        let _ = std::fs::remove_file(beside(path, stale));
    }
    Ok(())
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

    fn gradient() -> image::RgbaImage {
        image::RgbaImage::from_fn(64, 64, |x, y| image::Rgba([(x * 4) as u8, (y * 4) as u8, 128, 255]))
    }

    #[test]
    fn identical_images_do_not_differ_and_a_white_square_exceeds_every_bound() {
        let a = gradient();
        let (same, _) = Difference::between(&a, &a);
        assert_eq!(same, Difference { mean_flip: 0.0, p99_flip: 0.0, window_flip: 0.0, luminance: 0.0 });
        assert!(same.exceeded().is_empty());
        let mut b = a.clone();
        for y in 16..48 {
            for x in 16..48 {
                b.put_pixel(x, y, image::Rgba([255, 255, 255, 255]));
            }
        }
        let (d, diff) = Difference::between(&a, &b);
        assert_eq!(d.exceeded().len(), 4, "{d}");
        assert_eq!(diff.dimensions(), (64, 64));
    }

    #[test]
    fn a_small_local_change_fails_the_percentile_and_a_uniform_dimming_the_luminance() {
        let a = gradient();
        // A 28×28 square of a 256×256 frame (1.2 %) turned white: the mean barely moves, the
        // percentile does.
        let big = image::RgbaImage::from_fn(256, 256, |x, y| image::Rgba([x as u8, y as u8, 128, 255]));
        let mut local = big.clone();
        for y in 100..128 {
            for x in 100..128 {
                local.put_pixel(x, y, image::Rgba([255, 255, 255, 255]));
            }
        }
        let (d, _) = Difference::between(&big, &local);
        let exceeded = d.exceeded();
        assert!(exceeded.iter().any(|e| e.contains("99th-percentile")), "{d}");
        assert!(!exceeded.iter().any(|e| e.contains("the mean FLIP")), "{d}");
        // 8 % less light everywhere (each channel's linear value × 0.92).
        let dim = image::RgbaImage::from_fn(64, 64, |x, y| {
            let p = a.get_pixel(x, y);
            let scale = |c: u8| ((c as f64 / 255.0).powf(2.2) * 0.92).powf(1.0 / 2.2) * 255.0;
            image::Rgba([scale(p[0]).round() as u8, scale(p[1]).round() as u8, scale(p[2]).round() as u8, 255])
        });
        let (d, _) = Difference::between(&a, &dim);
        assert!(d.exceeded().iter().any(|e| e.contains("luminance")), "{d}");
    }

    #[test]
    fn a_change_of_a_few_pixels_fails_the_window_alone() {
        // Four pixels of a 320×180 frame turned white: the mean and the percentile cannot see it.
        let frame = image::RgbaImage::from_fn(320, 180, |x, y| image::Rgba([(x / 2) as u8, (y / 2) as u8, 60, 255]));
        let mut spot = frame.clone();
        for (x, y) in [(100, 90), (101, 90), (100, 91), (101, 91)] {
            spot.put_pixel(x, y, image::Rgba([255, 255, 255, 255]));
        }
        let (d, _) = Difference::between(&frame, &spot);
        let exceeded = d.exceeded();
        assert_eq!(exceeded.len(), 1, "{d}");
        assert!(exceeded[0].contains("8x8 window"), "{exceeded:?}");
    }

    #[test]
    fn the_worst_window_is_found_anywhere_and_a_nan_is_kept() {
        // A 3×3 image: windows of 2 at four positions, the largest mean at the bottom right.
        let values = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 3.0, 6.0];
        assert_eq!(worst_window_mean(&values, 3, 2), 3.0);
        assert_eq!(worst_window_mean(&values, 3, 1), 6.0);
        assert_eq!(worst_window_mean(&values, 3, 8), 12.0 / 9.0, "a window larger than the image is the image");
        let mut with_nan = values;
        with_nan[0] = f32::NAN;
        assert!(worst_window_mean(&with_nan, 3, 2).is_nan());
    }

    #[test]
    fn a_figure_that_is_not_a_number_fails_naming_it() {
        let fine = Difference { mean_flip: 0.001, p99_flip: 0.01, window_flip: 0.02, luminance: 0.0 };
        assert!(fine.exceeded().is_empty());
        let cases = [
            (Difference { mean_flip: f32::NAN, ..fine }, "the mean FLIP error"),
            (Difference { p99_flip: f32::NAN, ..fine }, "the 99th-percentile FLIP error"),
            (Difference { window_flip: f32::INFINITY, ..fine }, "the worst 8x8 window's mean FLIP error"),
            (Difference { luminance: f64::NAN, ..fine }, "the mean luminance's change"),
        ];
        for (d, figure) in cases {
            let exceeded = d.exceeded();
            assert_eq!(exceeded.len(), 1, "{exceeded:?}");
            assert!(exceeded[0].starts_with(figure) && exceeded[0].contains("not a finite number"), "{exceeded:?}");
        }
    }

    #[test]
    fn the_luminance_of_black_white_and_mid_grey() {
        let grey = |v: u8| image::RgbaImage::from_pixel(4, 4, image::Rgba([v, v, v, 255]));
        assert_eq!(mean_luminance(&grey(0)), 0.0);
        bounds::assert(bounds::magnitude_at_most("white's luminance less 1", mean_luminance(&grey(255)) - 1.0, 1e-9));
        // sRGB 188 encodes linear 0.5.
        bounds::assert(bounds::magnitude_at_most(
            "sRGB 188's luminance less 0.5",
            mean_luminance(&grey(188)) - 0.5,
            0.003,
        ));
    }

    #[test]
    fn a_failure_writes_the_frame_and_the_difference_beside_the_golden_and_write_clears_them() {
        let dir = std::env::temp_dir().join(format!("headlamp-golden-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let golden = dir.join("tick_000010.png");
        let grey = image::RgbaImage::from_pixel(32, 32, image::Rgba([90, 90, 90, 255]));
        write(&golden, &grey).unwrap();
        assert!(compare(&golden, &grey).unwrap().exceeded().is_empty());
        let white = image::RgbaImage::from_pixel(32, 32, image::Rgba([255, 255, 255, 255]));
        let e = compare(&golden, &white).unwrap_err();
        assert!(e.contains("past its limit") && e.contains("tick_000010.diff.png"), "{e}");
        assert!(dir.join("tick_000010.actual.png").exists() && dir.join("tick_000010.diff.png").exists());
        let e = compare(&golden, &image::RgbaImage::new(16, 16)).unwrap_err();
        assert!(e.contains("(16, 16)"), "{e}");
        write(&golden, &white).unwrap();
        assert!(!dir.join("tick_000010.actual.png").exists() && !dir.join("tick_000010.diff.png").exists());
        assert!(compare(&golden, &white).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
