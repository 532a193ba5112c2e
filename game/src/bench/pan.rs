//! `headlamp bench --pan`: how steady the GI is. The camera turns right by a small angle each
//! frame about a fixed eye; the GI's linear indirect light and the exact reference are computed
//! for every frame, and `flicker` is how far the GI's error moves from one frame to the next
//! (means of blocks 1/40 of the frame's width, relative to the reference's mean norm). The
//! reference is the world-fixed one (`gi-reference`): its senders are patches of the level, so
//! it does not move where the picture does not. The GI frames are rendered in sequence by one
//! renderer, as play would; the reference's receivers by another, so it never disturbs anything
//! the GI keeps between frames.
//!
//! The reference costs O(receivers × lit patches) on the CPU, so it may be evaluated on every
//! k-th flicker block only (the same blocks every frame); every figure is then taken over those
//! blocks, for the GI and the reference alike.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{anyhow, Context};
use engine::frame::ViewState;
use engine::glam::{Quat, Vec3};
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::scene::Level;
use engine::start_view::{initial_view, ViewOverrides};
use plugin_gi::metrics;
use serde::Serialize;

use crate::cli::BenchArgs;
use crate::world_reference::WorldReference;

/// The flicker figure's blocks are this fraction of the frame's width: 4×4 at 160 wide.
const FLICKER_BLOCKS_ACROSS: u32 = 40;
/// Frames up to this many pixels get the reference on every block without `--reference-every`.
const WHOLE_FRAME_PIXELS: u32 = 640 * 480;

#[derive(Serialize, Debug)]
pub struct PanReport {
    pub level: String,
    pub size: [u32; 2],
    pub frames: usize,
    pub adapter: String,
    pub eye: [f32; 3],
    pub forward: [f32; 3],
    pub fov_y_deg: f32,
    pub pan_deg: f32,
    /// Frames rendered along the path before the first measured one (the history's warm-up).
    pub warmup_frames: u32,
    /// Centimetres walked forward a frame.
    pub walk_cm: f32,
    /// Where the lamp was set down (eye, target), or None: on the camera.
    pub lamp: Option<[[f32; 3]; 2]>,
    pub gi: plugin_gi::GiSettings,
    /// Side of the flicker figure's blocks, pixels (1/40 of the width).
    pub flicker_block: u32,
    /// What the reference evaluated, and what it cost.
    pub reference: ReferenceFigures,
    /// mean_t ‖e(t+1) − e(t)‖ / mean_t ‖ref(t)‖, e = indirect − reference on flicker-block means.
    pub flicker: f64,
    /// The same for the reference alone: how much the picture itself changes per frame.
    pub reference_change: f64,
    /// The GI's change per frame, the same way.
    pub indirect_change: f64,
    /// Per frame: relative L2 error of 8×8-block means against the reference (as `bench`),
    /// of smaller blocks where the flicker blocks are ([`error_block`]).
    pub error_per_frame: Vec<f64>,
    /// With `--converge`: the reference against one with patches of half the size.
    pub converge: Option<ConvergeReport>,
}

/// The world reference of a pan.
#[derive(Serialize, Debug)]
pub struct ReferenceFigures {
    /// The longest patch edge, metres.
    pub patch_size_m: f32,
    /// Every `every`-th flicker block across and down is evaluated.
    pub every: u32,
    /// Whether each sender–receiver pair is tested for what stands between them: so when the
    /// GI is (`gi.visibility`), so that its shadows are measured and not counted as error.
    pub visibility: bool,
    /// Pixels evaluated per frame (those blocks' pixels), and how many of them had a surface.
    pub pixels: usize,
    pub receivers_per_frame: Vec<usize>,
    /// Per frame: the patches the lamp lit, and the seconds (wall clock) spent finding them
    /// and summing their light at the receivers.
    pub lit_patches_per_frame: Vec<usize>,
    pub patch_seconds_per_frame: Vec<f64>,
    pub sum_seconds_per_frame: Vec<f64>,
}

/// The pan's reference against one with patches of half the size.
#[derive(Serialize, Debug)]
pub struct ConvergeReport {
    pub patch_size_m: f32,
    /// Per frame: the reference's 8×8-block error against it.
    pub error_per_frame: Vec<f64>,
    /// The reference's own flicker against it: how much finer patches would move it.
    pub reference_flicker: f64,
    /// The GI's flicker against it.
    pub flicker: f64,
    pub lit_patches_per_frame: Vec<usize>,
    pub patch_seconds_per_frame: Vec<f64>,
    pub sum_seconds_per_frame: Vec<f64>,
}

/// The flicker figure's block side for a frame `width` pixels wide.
pub fn flicker_block(width: u32) -> u32 {
    (width / FLICKER_BLOCKS_ACROSS).max(1)
}

/// The error's block side with flicker blocks of `flicker_block` pixels: 8, as `bench`'s, or
/// the flicker block's where that is smaller (frames under 320 pixels wide), so that whole
/// blocks lie inside the flicker blocks the reference is evaluated on.
pub fn error_block(flicker_block: u32) -> u32 {
    flicker_block.min(8)
}

/// Every how many flicker blocks the reference is evaluated, unless told: every block of a
/// frame up to 640×480, every other block across and down (a quarter of them) above. The
/// flicker and the error live in a few blocks along folds and contacts, so a lattice reads
/// them by where it falls: on the face-on Cornell pan at 640×480 every 4th block read
/// 0.85–1.45 % by its offset against 1.16 % over the whole frame, every other block
/// 1.09–1.21 %; on the Cellar's spawn pan at 640×360 every 3rd read 1.01 %, every other one
/// 1.59 %, the whole frame 1.29 %.
pub fn default_every(size: (u32, u32)) -> u32 {
    if size.0 * size.1 <= WHOLE_FRAME_PIXELS {
        1
    } else {
        2
    }
}

/// Frames a pan renders before its first measured one, unless told: until the first frame's
/// share of the history (`history`ᵏ) falls under 1 %, so the measured frames see the history
/// of a camera that was already moving, as in play, and not its build-up from nothing.
pub fn warmup_frames(history: f32) -> u32 {
    if history <= 0.0 {
        return 0;
    }
    (0.01f64.ln() / f64::from(history).ln()).ceil() as u32
}

pub fn pan(gpu: &Gpu, level: &Level, args: &BenchArgs, gi: plugin_gi::GiSettings) -> anyhow::Result<PanReport> {
    let mut on = gi;
    on.enabled = true;
    let (plugins, handle) = crate::plugins(on);
    let mut renderer = Renderer::new(gpu, &level.scene, plugins)?;
    renderer.set_view("indirect").map_err(|e| anyhow!(e))?;
    let visibility = handle.settings().visibility == 1;
    let mut reference = WorldReference::new(gpu, &level.scene)?;
    if visibility {
        reference = reference.with_visibility();
    }
    if let Some(dir) = &args.out_dir {
        std::fs::create_dir_all(dir).with_context(|| format!("--out-dir {}", dir.display()))?;
    }

    let overrides = ViewOverrides { look: args.camera, fov_y: args.fov.map(f32::to_radians) };
    let start: ViewState = initial_view(level, &overrides);
    let (w, h) = args.size();
    let n = args.frames() as usize;
    let block = flicker_block(w);
    let every = args.reference_every.unwrap_or_else(|| default_every((w, h)));
    let mask = metrics::block_mask(w, h, block, every);
    let (patch, half) = (args.patch_size(), args.patch_size() / 2.0);
    let target = HeadlessTarget::new(gpu, w, h, ImageKind::Linear);
    let (mut tests, mut references, mut errors) = (Vec::new(), Vec::new(), Vec::new());
    let (mut receivers_per_frame, mut lit, mut seconds) = (Vec::new(), Vec::new(), (Vec::new(), Vec::new()));
    let (mut halves, mut half_errors, mut half_lit) = (Vec::new(), Vec::new(), Vec::new());
    let mut half_seconds = (Vec::new(), Vec::new());
    // Forward along the first frame's view, level.
    let walk = (start.camera.forward() * Vec3::new(1.0, 0.0, 1.0)).normalize_or_zero();
    let warmup = args.warmup.unwrap_or_else(|| warmup_frames(handle.settings().history));
    for t in -i64::from(warmup)..n as i64 {
        let mut view = start.clone();
        // Turning right is a negative turn about +Y, about the eye.
        let turn = Quat::from_rotation_y(-(args.pan_deg * t as f32).to_radians());
        view.camera.rotation = (turn * start.camera.rotation).normalize();
        view.camera.position += walk * (0.01 * args.walk_cm * t as f32);
        if let Some((eye, target)) = args.pan_lamp {
            view.headlamp.detach_looking_at(eye, target);
        }
        let indirect = linear(target.render(gpu, &mut renderer, &view)?)?;
        if t < 0 {
            continue;
        }
        let receivers = reference.receivers(gpu, &view, (w, h))?;
        let exact = reference.evaluate(&view, (w, h), &receivers, Some(&mask), patch);
        if let Some(dir) = &args.out_dir {
            save(&indirect, &dir.join(format!("indirect_{t:03}.exr")))?;
            save(&exact.image, &dir.join(format!("reference_{t:03}.exr")))?;
        }
        if args.converge {
            let fine = reference.evaluate(&view, (w, h), &receivers, Some(&mask), half);
            if let Some(dir) = &args.out_dir {
                save(&fine.image, &dir.join(format!("reference_half_{t:03}.exr")))?;
            }
            half_errors.push(metrics::block_error_masked_sized(&exact.image, &fine.image, &mask, error_block(block)));
            halves.push(metrics::block_means_masked(&fine.image, block, &mask));
            half_lit.push(fine.lit_patches);
            half_seconds.0.push(fine.patch_seconds);
            half_seconds.1.push(fine.sum_seconds);
        }
        errors.push(metrics::block_error_masked_sized(&indirect, &exact.image, &mask, error_block(block)));
        tests.push(metrics::block_means_masked(&indirect, block, &mask));
        references.push(metrics::block_means_masked(&exact.image, block, &mask));
        receivers_per_frame.push(exact.receivers);
        lit.push(exact.lit_patches);
        seconds.0.push(exact.patch_seconds);
        seconds.1.push(exact.sum_seconds);
    }
    let converge = args.converge.then(|| ConvergeReport {
        patch_size_m: half,
        error_per_frame: half_errors,
        reference_flicker: metrics::flicker(&references, &halves),
        flicker: metrics::flicker(&tests, &halves),
        lit_patches_per_frame: half_lit,
        patch_seconds_per_frame: half_seconds.0,
        sum_seconds_per_frame: half_seconds.1,
    });
    Ok(PanReport {
        level: args.level.display().to_string(),
        size: [w, h],
        frames: n,
        adapter: gpu.adapter.get_info().name,
        eye: start.camera.position.to_array(),
        forward: start.camera.forward().to_array(),
        fov_y_deg: start.camera.fov_y().unwrap_or(0.0).to_degrees(),
        pan_deg: args.pan_deg,
        warmup_frames: warmup,
        walk_cm: args.walk_cm,
        lamp: args.pan_lamp.map(|(eye, target)| [eye.to_array(), target.to_array()]),
        gi: handle.settings(),
        flicker_block: block,
        reference: ReferenceFigures {
            patch_size_m: patch,
            every,
            visibility,
            pixels: mask.iter().filter(|&&m| m).count(),
            receivers_per_frame,
            lit_patches_per_frame: lit,
            patch_seconds_per_frame: seconds.0,
            sum_seconds_per_frame: seconds.1,
        },
        flicker: metrics::flicker(&tests, &references),
        reference_change: metrics::change(&references),
        indirect_change: metrics::change(&tests),
        error_per_frame: errors,
        converge,
    })
}

fn linear(image: RenderedImage) -> anyhow::Result<image::Rgba32FImage> {
    match image {
        RenderedImage::Linear(img) => Ok(img),
        RenderedImage::Display(_) => Err(anyhow!("the pan renders linear images")),
    }
}

fn save(image: &image::Rgba32FImage, path: &Path) -> anyhow::Result<()> {
    engine::output::save(&RenderedImage::Linear(image.clone()), path)
}

pub fn table(r: &PanReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "headlamp bench --pan: {}, {}x{}, {} frames turning right {}° a frame (after {} on the same path \
         for the history), on {}",
        r.level, r.size[0], r.size[1], r.frames, r.pan_deg, r.warmup_frames, r.adapter
    );
    if r.walk_cm != 0.0 {
        let _ = writeln!(s, "walking forward {} cm a frame", r.walk_cm);
    }
    match r.lamp {
        Some([[x, y, z], [tx, ty, tz]]) => {
            let _ = writeln!(s, "lamp set down at {x:.2},{y:.2},{z:.2} pointing at {tx:.2},{ty:.2},{tz:.2}");
        }
        None => {
            let _ = writeln!(s, "lamp on the camera");
        }
    }
    let [x, y, z] = r.eye;
    let [fx, fy, fz] = r.forward;
    let _ = writeln!(s, "eye {x:.2},{y:.2},{z:.2} looking {fx:.2},{fy:.2},{fz:.2}, fov {:.1}°", r.fov_y_deg);
    let _ = writeln!(
        s,
        "GI: split ratio {}, indirect target at {} of the view, {} bounce(s), history {}",
        r.gi.split_ratio, r.gi.resolution_scale, r.gi.bounces, r.gi.history
    );
    let f = &r.reference;
    let (median_lit, _) = median_and_worst(&f.lit_patches_per_frame.iter().map(|&v| v as f64).collect::<Vec<_>>());
    let (median_s, worst_s) = median_and_worst(&frame_seconds(&f.patch_seconds_per_frame, &f.sum_seconds_per_frame));
    let (median_patches, _) = median_and_worst(&f.patch_seconds_per_frame);
    let b = r.flicker_block;
    let e = error_block(b);
    let blocks = match f.every {
        1 => format!("on every {b}x{b} flicker block"),
        k => format!("on every {} {b}x{b} flicker block across and down", ordinal(k)),
    };
    let _ = writeln!(
        s,
        "reference: world-fixed patches of at most {} cm, {}, {blocks} ({} pixels); median {:.0} lit patches, \
         {:.2} s a frame (worst {:.2} s; finding the lit patches {:.2} s)",
        100.0 * f.patch_size_m,
        if f.visibility { "each pair tested for what stands between (as gi.visibility)" } else { "no visibility" },
        f.pixels,
        median_lit,
        median_s,
        worst_s,
        median_patches
    );
    let _ = writeln!(s);
    let _ = writeln!(s, "| figure ({b}x{b}-block means) | value |");
    let _ = writeln!(s, "| --- | ---: |");
    let _ = writeln!(s, "| flicker: mean ‖e(t+1) − e(t)‖ / mean ‖ref‖ | {:.2} % |", 100.0 * r.flicker);
    let _ = writeln!(s, "| the reference's own change per frame | {:.2} % |", 100.0 * r.reference_change);
    let _ = writeln!(s, "| the GI's change per frame | {:.2} % |", 100.0 * r.indirect_change);
    let (median, worst) = median_and_worst(&r.error_per_frame);
    let _ = writeln!(
        s,
        "| error vs reference ({e}x{e} blocks), median / worst frame | {:.2} % / {:.2} % |",
        100.0 * median,
        100.0 * worst
    );
    if let Some(c) = &r.converge {
        let cm = 100.0 * c.patch_size_m;
        let (median, worst) = median_and_worst(&c.error_per_frame);
        let _ = writeln!(
            s,
            "| the reference vs its {cm} cm patches ({e}x{e} blocks), median / worst frame | {:.2} % / {:.2} % |",
            100.0 * median,
            100.0 * worst
        );
        let _ = writeln!(
            s,
            "| the reference's own flicker against its {cm} cm patches | {:.2} % |",
            100.0 * c.reference_flicker
        );
        let _ = writeln!(s, "| the GI's flicker against the {cm} cm reference | {:.2} % |", 100.0 * c.flicker);
        let (lit, _) = median_and_worst(&c.lit_patches_per_frame.iter().map(|&v| v as f64).collect::<Vec<_>>());
        let (median_s, _) = median_and_worst(&frame_seconds(&c.patch_seconds_per_frame, &c.sum_seconds_per_frame));
        let _ = writeln!(s, "| {cm} cm patches: median lit patches, s a frame | {lit:.0}, {median_s:.2} s |");
    }
    s
}

fn frame_seconds(patches: &[f64], sums: &[f64]) -> Vec<f64> {
    patches.iter().zip(sums).map(|(a, b)| a + b).collect()
}

/// "2nd", "3rd", "4th", "11th", "21st" …
fn ordinal(k: u32) -> String {
    let suffix = match (k % 10, k % 100) {
        (_, 11..=13) => "th",
        (1, _) => "st",
        (2, _) => "nd",
        (3, _) => "rd",
        _ => "th",
    };
    format!("{k}{suffix}")
}

/// The median (the upper one of an even count) and the largest of per-frame figures; NaN when
/// there are none.
fn median_and_worst(figures: &[f64]) -> (f64, f64) {
    let mut sorted = figures.to_vec();
    sorted.sort_by(f64::total_cmp);
    let median = sorted.get(sorted.len() / 2).copied().unwrap_or(f64::NAN);
    (median, sorted.last().copied().unwrap_or(f64::NAN))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flicker_blocks_are_a_fortieth_of_the_width_and_the_reference_covers_all_or_a_quarter_of_them() {
        assert_eq!([160, 640, 1280, 20].map(flicker_block), [4, 16, 32, 1]);
        assert_eq!([0.0, 0.5, 0.8].map(warmup_frames), [0, 7, 21], "0.5⁷ < 1 % < 0.5⁶");
        assert_eq!([2, 3, 4, 11, 21, 22].map(ordinal), ["2nd", "3rd", "4th", "11th", "21st", "22nd"]);
        assert_eq!([(160, 120), (640, 360), (640, 480)].map(default_every), [1, 1, 1], "the whole frame");
        for size in [(1280, 720), (1920, 1080)] {
            let every = default_every(size);
            assert_eq!(every, 2);
            let mask = metrics::block_mask(size.0, size.1, flicker_block(size.0), every);
            let pixels = mask.iter().filter(|&&m| m).count() as f64;
            let share = pixels / f64::from(size.0 * size.1);
            assert!((0.22..=0.26).contains(&share), "{size:?}: {share} of the pixels");
        }
    }
}
