//! How far the GI is from the brute-force reference, the same way in tests and in `bench`.

/// Relative L2 error of 8×8-block means (all three channels) of `test` against `reference`:
/// ‖B(test) − B(reference)‖ / ‖B(reference)‖ over the blocks B that fit whole. Block means keep
/// the figure about the light's distribution rather than per-pixel noise. 0 is a perfect match;
/// NaN when the reference is black.
pub fn block_error(test: &image::Rgba32FImage, reference: &image::Rgba32FImage) -> f64 {
    assert_eq!(test.dimensions(), reference.dimensions(), "block_error compares images of one size");
    let (w, h) = reference.dimensions();
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for by in 0..h / 8 {
        for bx in 0..w / 8 {
            for c in 0..3 {
                let (mut t, mut r) = (0.0f64, 0.0f64);
                for y in by * 8..by * 8 + 8 {
                    for x in bx * 8..bx * 8 + 8 {
                        t += test.get_pixel(x, y)[c] as f64;
                        r += reference.get_pixel(x, y)[c] as f64;
                    }
                }
                num += (t - r).powi(2);
                den += r.powi(2);
            }
        }
    }
    (num / den).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(w: u32, h: u32, v: f32) -> image::Rgba32FImage {
        image::Rgba32FImage::from_pixel(w, h, image::Rgba([v, v, v, 1.0]))
    }

    #[test]
    fn block_error_is_zero_for_equal_images_and_relative_otherwise() {
        assert_eq!(block_error(&flat(16, 16, 0.5), &flat(16, 16, 0.5)), 0.0);
        assert!((block_error(&flat(16, 16, 1.1), &flat(16, 16, 1.0)) - 0.1).abs() < 1e-6);
        // Noise within a block averages out.
        let mut noisy = flat(8, 8, 1.0);
        noisy.put_pixel(0, 0, image::Rgba([2.0, 2.0, 2.0, 1.0]));
        noisy.put_pixel(1, 0, image::Rgba([0.0, 0.0, 0.0, 1.0]));
        assert!(block_error(&noisy, &flat(8, 8, 1.0)) < 1e-9);
    }
}
