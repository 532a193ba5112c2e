//! How far the GI is from the brute-force reference, the same way in tests and in `bench`.

/// Relative L2 error of 8×8-block means (all three channels) of `test` against `reference`:
/// ‖B(test) − B(reference)‖ / ‖B(reference)‖ over the blocks B that fit whole. Block means keep
/// the figure about the light's distribution rather than per-pixel noise. 0 is a perfect match;
/// NaN when the reference is black.
pub fn block_error(test: &image::Rgba32FImage, reference: &image::Rgba32FImage) -> f64 {
    block_error_where(test, reference, 8, |_, _| true)
}

/// [`block_error`] with blocks of `block`×`block` pixels.
pub fn block_error_sized(test: &image::Rgba32FImage, reference: &image::Rgba32FImage, block: u32) -> f64 {
    block_error_where(test, reference, block, |_, _| true)
}

/// Σ test / Σ reference − 1 over the three channels: how much light the test has too much.
pub fn energy(test: &image::Rgba32FImage, reference: &image::Rgba32FImage) -> f64 {
    energy_where(test, reference, |_| true)
}

/// `image` shrunk by a whole `factor` each way, each pixel the mean of the `factor`² it covers
/// (a frame compared with a reference computed at fewer receivers).
pub fn shrink(image: &image::Rgba32FImage, factor: u32) -> image::Rgba32FImage {
    let (w, h) = (image.width() / factor, image.height() / factor);
    let n = (factor * factor) as f32;
    image::Rgba32FImage::from_fn(w, h, |x, y| {
        let mut sum = [0.0f32; 4];
        for v in y * factor..(y + 1) * factor {
            for u in x * factor..(x + 1) * factor {
                for (s, c) in sum.iter_mut().zip(image.get_pixel(u, v).0) {
                    *s += c;
                }
            }
        }
        image::Rgba(sum.map(|s| s / n))
    })
}

/// [`block_error`] over the 8×8 blocks that lie wholly inside `mask` (one flag a pixel, row by
/// row): a reference evaluated at some pixels only is compared where it was evaluated. NaN when
/// no block is.
pub fn block_error_masked(test: &image::Rgba32FImage, reference: &image::Rgba32FImage, mask: &[bool]) -> f64 {
    block_error_masked_sized(test, reference, mask, 8)
}

/// [`block_error_masked`] with blocks of `block`×`block` pixels.
pub fn block_error_masked_sized(
    test: &image::Rgba32FImage,
    reference: &image::Rgba32FImage,
    mask: &[bool],
    block: u32,
) -> f64 {
    let (w, _) = reference.dimensions();
    assert_eq!(mask.len(), reference.pixels().len(), "one mask flag a pixel");
    block_error_where(test, reference, block, |bx, by| block_inside(mask, w, block, bx, by))
}

/// [`energy`] over the pixels of `mask`.
pub fn energy_masked(test: &image::Rgba32FImage, reference: &image::Rgba32FImage, mask: &[bool]) -> f64 {
    assert_eq!(mask.len(), reference.pixels().len(), "one mask flag a pixel");
    energy_where(test, reference, |i| mask[i])
}

/// [`energy`] over the pixels (row by row) that `counts` keeps.
fn energy_where(test: &image::Rgba32FImage, reference: &image::Rgba32FImage, counts: impl Fn(usize) -> bool) -> f64 {
    let sum = |img: &image::Rgba32FImage| {
        img.pixels()
            .enumerate()
            .filter(|(i, _)| counts(*i))
            .map(|(_, p)| p[0] as f64 + p[1] as f64 + p[2] as f64)
            .sum::<f64>()
    };
    sum(test) / sum(reference) - 1.0
}

fn block_error_where(
    test: &image::Rgba32FImage,
    reference: &image::Rgba32FImage,
    block: u32,
    counts: impl Fn(u32, u32) -> bool,
) -> f64 {
    assert_eq!(test.dimensions(), reference.dimensions(), "block_error compares images of one size");
    let (w, h) = reference.dimensions();
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for by in 0..h / block {
        for bx in (0..w / block).filter(|&bx| counts(bx, by)) {
            for c in 0..3 {
                let (mut t, mut r) = (0.0f64, 0.0f64);
                for y in by * block..(by + 1) * block {
                    for x in bx * block..(bx + 1) * block {
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

/// Whether block (`bx`, `by`) of `block`×`block` pixels lies wholly inside `mask`.
fn block_inside(mask: &[bool], width: u32, block: u32, bx: u32, by: u32) -> bool {
    (by * block..(by + 1) * block).all(|y| (bx * block..(bx + 1) * block).all(|x| mask[(y * width + x) as usize]))
}

/// Means of `block`×`block` blocks of the three colour channels, row by row (the blocks that fit
/// whole): the scale at which the flicker figure compares frames.
pub fn block_means(image: &image::Rgba32FImage, block: u32) -> Vec<f64> {
    block_means_where(image, block, |_, _| true)
}

/// [`block_means`] of the blocks that lie wholly inside `mask` (one flag a pixel, row by row).
pub fn block_means_masked(image: &image::Rgba32FImage, block: u32, mask: &[bool]) -> Vec<f64> {
    let (w, _) = image.dimensions();
    assert_eq!(mask.len(), image.pixels().len(), "one mask flag a pixel");
    block_means_where(image, block, |bx, by| block_inside(mask, w, block, bx, by))
}

fn block_means_where(image: &image::Rgba32FImage, block: u32, counts: impl Fn(u32, u32) -> bool) -> Vec<f64> {
    let (w, h) = image.dimensions();
    let mut out = Vec::with_capacity(((w / block) * (h / block) * 3) as usize);
    let n = f64::from(block * block);
    for by in 0..h / block {
        for bx in (0..w / block).filter(|&bx| counts(bx, by)) {
            for c in 0..3 {
                let mut sum = 0.0f64;
                for y in by * block..(by + 1) * block {
                    for x in bx * block..(bx + 1) * block {
                        sum += f64::from(image.get_pixel(x, y)[c]);
                    }
                }
                out.push(sum / n);
            }
        }
    }
    out
}

/// The pixels of every `every`-th `block`×`block` block across and down (those that fit
/// whole), as a mask for the `_masked` figures: the blocks a costly reference is evaluated on.
pub fn block_mask(width: u32, height: u32, block: u32, every: u32) -> Vec<bool> {
    assert!(block != 0 && every != 0, "blocks and strides are at least 1");
    let (bw, bh) = (width / block, height / block);
    let mut mask = vec![false; (width * height) as usize];
    for y in 0..bh * block {
        for x in 0..bw * block {
            mask[(y * width + x) as usize] = (x / block).is_multiple_of(every) && (y / block).is_multiple_of(every);
        }
    }
    mask
}

fn norm(v: impl Iterator<Item = f64>) -> f64 {
    v.map(|x| x * x).sum::<f64>().sqrt()
}

/// How much the GI's error moves from frame to frame of a sequence:
/// mean over t of ‖e(t+1) − e(t)‖ / mean over t of ‖ref(t)‖, with e(t) = test(t) − ref(t), all
/// on block means. A steady error (a bias that holds still) gives 0; an error that jumps
/// around as the view moves is shimmer. NaN with fewer than two frames or a black reference.
/// (`bench --pan` takes blocks 1/40 of the frame's width: 4×4 at 160 wide.)
pub fn flicker(tests: &[Vec<f64>], references: &[Vec<f64>]) -> f64 {
    assert_eq!(tests.len(), references.len(), "flicker compares one test frame per reference frame");
    if tests.len() < 2 {
        return f64::NAN;
    }
    let error = |t: usize| -> Vec<f64> { tests[t].iter().zip(&references[t]).map(|(a, b)| a - b).collect() };
    let mut steps = 0.0;
    for t in 0..tests.len() - 1 {
        let (a, b) = (error(t), error(t + 1));
        steps += norm(a.iter().zip(&b).map(|(x, y)| y - x));
    }
    let steps = steps / (tests.len() - 1) as f64;
    let signal = references.iter().map(|r| norm(r.iter().copied())).sum::<f64>() / references.len() as f64;
    steps / signal
}

/// How much a sequence itself changes from frame to frame, relative to its mean norm: the
/// reference's own motion, to read the flicker figure against.
pub fn change(frames: &[Vec<f64>]) -> f64 {
    if frames.len() < 2 {
        return f64::NAN;
    }
    let steps: f64 = frames.windows(2).map(|w| norm(w[0].iter().zip(&w[1]).map(|(a, b)| b - a))).sum::<f64>()
        / (frames.len() - 1) as f64;
    steps / (frames.iter().map(|f| norm(f.iter().copied())).sum::<f64>() / frames.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Asserts that `figure` is `value` within `within`, NaN failing.
    fn near(figure: &str, value: f64, expected: f64, within: f64) {
        bounds::assert(bounds::magnitude_at_most(figure, value - expected, within));
    }

    fn flat(w: u32, h: u32, v: f32) -> image::Rgba32FImage {
        image::Rgba32FImage::from_pixel(w, h, image::Rgba([v, v, v, 1.0]))
    }

    #[test]
    fn block_error_is_zero_for_equal_images_and_relative_otherwise() {
        assert_eq!(block_error(&flat(16, 16, 0.5), &flat(16, 16, 0.5)), 0.0);
        near("10 % more light", block_error(&flat(16, 16, 1.1), &flat(16, 16, 1.0)), 0.1, 1e-6);
        // Noise within a block averages out.
        let mut noisy = flat(8, 8, 1.0);
        noisy.put_pixel(0, 0, image::Rgba([2.0, 2.0, 2.0, 1.0]));
        noisy.put_pixel(1, 0, image::Rgba([0.0, 0.0, 0.0, 1.0]));
        near("noise inside a block", block_error(&noisy, &flat(8, 8, 1.0)), 0.0, 1e-9);
    }

    #[test]
    fn block_means_average_each_block_and_channel() {
        let mut img = flat(8, 4, 1.0);
        img.put_pixel(7, 3, image::Rgba([17.0, 1.0, 1.0, 1.0]));
        assert_eq!(block_means(&img, 4), vec![1.0, 1.0, 1.0, 2.0, 1.0, 1.0]);
    }

    #[test]
    fn masked_figures_take_only_the_blocks_wholly_inside_the_mask() {
        // Three 8×8 blocks across; the middle one differs, and the mask leaves it out.
        let reference = flat(24, 8, 1.0);
        let mut test = flat(24, 8, 1.0);
        for y in 0..8 {
            for x in 8..16 {
                test.put_pixel(x, y, image::Rgba([2.0, 2.0, 2.0, 1.0]));
            }
        }
        let mask = block_mask(24, 8, 8, 2);
        assert_eq!(mask.iter().filter(|&&m| m).count(), 128, "blocks 0 and 2");
        assert_eq!(block_error_masked(&test, &reference, &mask), 0.0);
        near("one block of three doubled", block_error(&test, &reference), 1.0 / 3f64.sqrt(), 1e-12);
        near(
            "masked by all against unmasked",
            block_error_masked(&test, &reference, &[true; 24 * 8]),
            block_error(&test, &reference),
            1e-15,
        );
        // A block partly outside the mask does not count; none at all gives NaN.
        let mut partial = vec![true; 24 * 8];
        partial[0] = false;
        assert_eq!(block_means_masked(&test, 8, &partial), vec![2.0, 2.0, 2.0, 1.0, 1.0, 1.0]);
        assert!(block_error_masked(&test, &reference, &[false; 24 * 8]).is_nan());
        // 4×4 means of every other block across and down: (0, 0), (2, 0), (4, 0) of a 24×8 frame.
        let mask = block_mask(24, 8, 4, 2);
        assert_eq!(block_means_masked(&test, 4, &mask), vec![1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 1.0, 1.0, 1.0]);
        assert_eq!(block_means_masked(&test, 4, &[true; 24 * 8]), block_means(&test, 4));
        // Blocks that do not fit whole are never in it.
        assert!(!block_mask(10, 10, 4, 1)[(9 * 10 + 9) as usize] && block_mask(10, 10, 4, 1)[0]);
    }

    /// A GI that writes NaN or ∞ in a single pixel fails every figure's check, by name; so does
    /// a black reference (nothing to compare with).
    #[test]
    fn nan_and_infinity_in_any_pixel_fail_every_figure_by_name() {
        let reference = flat(16, 16, 1.0);
        let mask = block_mask(16, 16, 4, 2);
        for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            let mut test = flat(16, 16, 1.0);
            test.put_pixel(5, 9, image::Rgba([bad, 1.0, 1.0, 1.0]));
            let mut masked = flat(16, 16, 1.0);
            masked.put_pixel(1, 1, image::Rgba([1.0, bad, 1.0, 1.0]));
            let means = |img: &image::Rgba32FImage| block_means(img, 4);
            let figures = [
                ("block error", block_error(&test, &reference)),
                ("4x4 block error", block_error_sized(&test, &reference, 4)),
                ("masked block error", block_error_masked_sized(&masked, &reference, &mask, 4)),
                ("energy", energy(&test, &reference)),
                ("masked energy", energy_masked(&masked, &reference, &mask)),
                ("flicker", flicker(&[means(&reference), means(&test)], &[means(&reference), means(&reference)])),
                ("change", change(&[means(&reference), means(&test)])),
                ("the error of the worst frame", bounds::worst([0.01, block_error(&test, &reference), 0.02])),
            ];
            for (name, value) in figures {
                let e = bounds::at_most(name, value, 0.05).expect_err(name);
                assert!(e.starts_with(name) && e.contains("not a finite number"), "{e}");
            }
        }
        let black = flat(16, 16, 0.0);
        for (name, value) in [("block error", block_error(&reference, &black)), ("energy", energy(&reference, &black))]
        {
            assert!(bounds::magnitude_at_most(name, value, 0.05).is_err(), "{name} against black: {value}");
        }
    }

    #[test]
    fn flicker_sees_an_error_that_moves_but_not_one_that_holds_still() {
        let reference = vec![vec![1.0, 1.0], vec![1.0, 1.0], vec![1.0, 1.0]];
        // A constant bias does not flicker.
        let biased = vec![vec![1.1, 0.9], vec![1.1, 0.9], vec![1.1, 0.9]];
        near("a steady bias", flicker(&biased, &reference), 0.0, 1e-12);
        // An error that swaps sides every frame does: ‖(−0.2, 0.2)‖ / ‖(1, 1)‖ = 0.2.
        let jumping = vec![vec![1.1, 0.9], vec![0.9, 1.1], vec![1.1, 0.9]];
        near("an error swapping sides", flicker(&jumping, &reference), 0.2, 1e-12);
        // The same motion in the reference and the test is no error at all.
        let moving = vec![vec![1.0, 2.0], vec![2.0, 1.0], vec![1.0, 2.0]];
        near("the same motion", flicker(&moving, &moving), 0.0, 1e-12);
        near("the change", change(&moving), 2f64.sqrt() / 5f64.sqrt(), 1e-12);
        assert!(flicker(&biased[..1], &reference[..1]).is_nan());
    }
}
