//! `headlamp bench --pan`: how steady the GI is. The camera turns right by a small angle each
//! frame about a fixed eye; the GI's linear indirect light and the exact reference are rendered
//! for every frame, and `flicker` is how far the GI's error moves from one frame to the next
//! (4×4-block means, relative to the reference's mean norm). The GI frames are rendered in
//! sequence by one renderer, as play would; the reference by another, so it never disturbs
//! anything the GI keeps between frames.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{anyhow, Context};
use engine::frame::ViewState;
use engine::glam::Quat;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::scene::Level;
use engine::start_view::{initial_view, ViewOverrides};
use plugin_gi::metrics;
use serde::Serialize;

use crate::cli::BenchArgs;

/// Block size of the flicker figure (the definition).
const FLICKER_BLOCK: u32 = 4;

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
    pub gi: plugin_gi::GiSettings,
    /// mean_t ‖e(t+1) − e(t)‖ / mean_t ‖ref(t)‖, e = indirect − reference on 4×4-block means.
    pub flicker: f64,
    /// The same for the reference alone: how much the picture itself changes per frame.
    pub reference_change: f64,
    /// The GI's change per frame, the same way.
    pub indirect_change: f64,
    /// Per frame: relative L2 error of 8×8-block means against the reference (as `bench`).
    pub error_per_frame: Vec<f64>,
    /// With `--reference-senders K`: the same figures against the reference lit by K² as many
    /// senders.
    pub finer: Option<FinerReport>,
}

/// The pan against a reference of the same receivers lit by `senders`² as many senders.
#[derive(Serialize, Debug)]
pub struct FinerReport {
    pub senders: u32,
    /// The GI's flicker against it.
    pub flicker: f64,
    /// The frame-size reference's own flicker against it: how far that reference's sampling
    /// moves it from frame to frame.
    pub reference_flicker: f64,
    /// Per frame: the GI's error against it (8×8 blocks).
    pub error_per_frame: Vec<f64>,
}

pub fn pan(gpu: &Gpu, level: &Level, args: &BenchArgs, gi: plugin_gi::GiSettings) -> anyhow::Result<PanReport> {
    let mut on = gi;
    on.enabled = true;
    let (plugins, handle) = crate::plugins(on.clone());
    let mut renderer = Renderer::new(gpu, &level.scene, plugins)?;
    renderer.set_view("indirect").map_err(|e| anyhow!(e))?;
    let (reference_plugins, _) = crate::plugins(on);
    let mut reference = Renderer::new(gpu, &level.scene, reference_plugins)?;
    reference.set_view("reference").map_err(|e| anyhow!(e))?;
    if let Some(dir) = &args.out_dir {
        std::fs::create_dir_all(dir).with_context(|| format!("--out-dir {}", dir.display()))?;
    }

    let overrides = ViewOverrides { look: args.camera, fov_y: args.fov.map(f32::to_radians) };
    let start: ViewState = initial_view(level, &overrides);
    let (w, h) = args.size();
    let n = args.frames() as usize;
    let target = HeadlessTarget::new(gpu, w, h, ImageKind::Linear);
    let mut finer = args.reference_senders.map(|k| FinerReference::new(gpu, level, &handle, k, (w, h))).transpose()?;
    let (mut finer_refs, mut finer_errors) = (Vec::new(), Vec::new());
    let (mut tests, mut references, mut errors) = (Vec::new(), Vec::new(), Vec::new());
    for t in 0..n {
        let mut view = start.clone();
        // Turning right is a negative turn about +Y, about the eye.
        let turn = Quat::from_rotation_y(-(args.pan_deg * t as f32).to_radians());
        view.camera.rotation = (turn * start.camera.rotation).normalize();
        let indirect = linear(target.render(gpu, &mut renderer, &view)?)?;
        let exact = linear(target.render(gpu, &mut reference, &view)?)?;
        if let Some(dir) = &args.out_dir {
            save(&indirect, &dir.join(format!("indirect_{t:03}.exr")))?;
            save(&exact, &dir.join(format!("reference_{t:03}.exr")))?;
        }
        if let Some(finer) = &mut finer {
            let fine = finer.render(gpu, &view)?;
            if let Some(dir) = &args.out_dir {
                save(&fine, &dir.join(format!("reference_finer_{t:03}.exr")))?;
            }
            finer_errors.push(metrics::block_error(&indirect, &fine));
            finer_refs.push(metrics::block_means(&fine, FLICKER_BLOCK));
        }
        errors.push(metrics::block_error(&indirect, &exact));
        tests.push(metrics::block_means(&indirect, FLICKER_BLOCK));
        references.push(metrics::block_means(&exact, FLICKER_BLOCK));
    }
    let finer = finer.map(|f| FinerReport {
        senders: f.senders,
        flicker: metrics::flicker(&tests, &finer_refs),
        reference_flicker: metrics::flicker(&references, &finer_refs),
        error_per_frame: finer_errors,
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
        gi: handle.settings(),
        flicker: metrics::flicker(&tests, &references),
        reference_change: metrics::change(&references),
        indirect_change: metrics::change(&tests),
        error_per_frame: errors,
        finer,
    })
}

/// The reference of a frame's receivers lit by k² as many senders: rendered at k times the
/// frame's size, evaluating only the centre pixel of each k×k block (`set_reference_stride`),
/// which looks along the ray of the frame's pixel.
struct FinerReference {
    senders: u32,
    renderer: Renderer,
    target: HeadlessTarget,
}

impl FinerReference {
    fn new(gpu: &Gpu, level: &Level, handle: &plugin_gi::GiHandle, k: u32, (w, h): (u32, u32)) -> anyhow::Result<Self> {
        let limit = gpu.device.limits().max_texture_dimension_2d;
        if w.saturating_mul(k) > limit || h.saturating_mul(k) > limit {
            return Err(anyhow!(
                "--reference-senders {k}: the finer reference of a {w}x{h} pan is {}x{} pixels, more than this \
                 device's {limit}",
                w * k,
                h * k
            ));
        }
        let (plugins, finer) = crate::plugins(handle.settings());
        finer.set_reference_stride(k);
        let mut renderer = Renderer::new(gpu, &level.scene, plugins)?;
        renderer.set_view("reference").map_err(|e| anyhow!(e))?;
        Ok(Self { senders: k, renderer, target: HeadlessTarget::new(gpu, w * k, h * k, ImageKind::Linear) })
    }

    fn render(&mut self, gpu: &Gpu, view: &ViewState) -> anyhow::Result<image::Rgba32FImage> {
        let full = linear(self.target.render(gpu, &mut self.renderer, view)?)?;
        let k = self.senders;
        let (w, h) = (full.width() / k, full.height() / k);
        Ok(image::Rgba32FImage::from_fn(w, h, |x, y| *full.get_pixel(x * k + k / 2, y * k + k / 2)))
    }
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
        "headlamp bench --pan: {}, {}x{}, {} frames turning right {}° a frame, on {}",
        r.level, r.size[0], r.size[1], r.frames, r.pan_deg, r.adapter
    );
    let [x, y, z] = r.eye;
    let [fx, fy, fz] = r.forward;
    let _ = writeln!(s, "eye {x:.2},{y:.2},{z:.2} looking {fx:.2},{fy:.2},{fz:.2}, fov {:.1}°", r.fov_y_deg);
    let _ = writeln!(
        s,
        "GI: split ratio {}, indirect target at {} of the view, {} bounce(s)",
        r.gi.split_ratio, r.gi.resolution_scale, r.gi.bounces
    );
    let _ = writeln!(s);
    let _ = writeln!(s, "| figure (4x4-block means) | value |");
    let _ = writeln!(s, "| --- | ---: |");
    let _ = writeln!(s, "| flicker: mean ‖e(t+1) − e(t)‖ / mean ‖ref‖ | {:.2} % |", 100.0 * r.flicker);
    let _ = writeln!(s, "| the reference's own change per frame | {:.2} % |", 100.0 * r.reference_change);
    let _ = writeln!(s, "| the GI's change per frame | {:.2} % |", 100.0 * r.indirect_change);
    let (median, worst) = median_and_worst(&r.error_per_frame);
    let _ = writeln!(
        s,
        "| error vs reference (8x8 blocks), median / worst frame | {:.2} % / {:.2} % |",
        100.0 * median,
        100.0 * worst
    );
    if let Some(f) = &r.finer {
        let k = f.senders;
        let (median, _) = median_and_worst(&f.error_per_frame);
        let _ =
            writeln!(s, "| against the reference with {k}x{k} as many senders: flicker | {:.2} % |", 100.0 * f.flicker);
        let _ = writeln!(
            s,
            "| the {}x{} reference's own flicker against it | {:.2} % |",
            r.size[0],
            r.size[1],
            100.0 * f.reference_flicker
        );
        let _ = writeln!(s, "| error vs it (8x8 blocks), median frame | {:.2} % |", 100.0 * median);
    }
    s
}

/// The median (the upper one of an even count) and the largest of per-frame figures; NaN when
/// there are none.
fn median_and_worst(figures: &[f64]) -> (f64, f64) {
    let mut sorted = figures.to_vec();
    sorted.sort_by(f64::total_cmp);
    let median = sorted.get(sorted.len() / 2).copied().unwrap_or(f64::NAN);
    (median, sorted.last().copied().unwrap_or(f64::NAN))
}
