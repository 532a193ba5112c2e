//! `headlamp bench`: a headless timedemo. The camera follows a fixed, deterministic path; every
//! frame renders `final` into an offscreen target and waits for the GPU, and the figures are the
//! GPU time of each render-graph pass (timestamp queries), the whole frame's GPU and CPU time,
//! and what the GI did: reflection lights, draw and dispatch calls, and its error against the
//! brute-force reference.

use std::fmt::Write as _;
use std::io::Write as _;
use std::time::Instant;

use anyhow::{anyhow, Context};
use engine::dynamic_resolution::DynamicResolution;
use engine::frame::ViewState;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::scene::Level;
use engine::start_view::{initial_view, ViewOverrides};
use serde::Serialize;

use crate::cli::BenchArgs;
use crate::world_reference::WorldReference;
use plugin_gi::Method;
use timing::WARMUP_FRAMES;

mod camera_path;
mod compare;
mod pan;
mod timing;

pub use camera_path::CameraPath;
pub use pan::{pan, PanReport};
pub use timing::Spread;

/// The GI-vs-reference comparison is rendered at this size: the reference costs
/// O(pixels × lit patches) on the CPU.
pub const ERROR_SIZE: (u32, u32) = (160, 90);
/// At most this many frames are re-rendered, untimed, to read the reflection lights back.
const LIGHT_SAMPLES: usize = 5;

#[derive(Serialize, Debug)]
pub struct PassFigure {
    pub name: String,
    /// GPU milliseconds over the timed frames.
    pub gpu_ms: Spread,
}

#[derive(Serialize, Debug)]
pub struct FrameFigure {
    /// CPU wall time of recording, submitting and waiting for the frame.
    pub cpu_ms: f64,
    /// Σ of the pass times, when the device has timestamps.
    pub gpu_ms: Option<f64>,
    pub passes: Vec<(String, f64)>,
    /// The render scale the frame was drawn at.
    pub render_scale: f32,
}

#[derive(Serialize, Debug)]
pub struct LightFigure {
    /// What is counted: "per_tile", the reflection lights per 8×8 tile of the indirect target
    /// (each tile's cut through the pyramid), or with `gi.method = article` "volumes", the
    /// light volumes drawn.
    pub counted: &'static str,
    /// Median over the sampled frames of that count.
    pub median: f64,
    /// Which frames were re-rendered (untimed) to read the figures back, their count, and how
    /// many tiles filled their cut (the article's method: the distribution table's slots).
    pub frames: Vec<usize>,
    pub per_tile: Vec<f64>,
    pub full_tiles: Vec<u32>,
}

#[derive(Serialize, Debug)]
pub struct ErrorFigure {
    /// The size both were computed at (smaller than the benchmark: the reference's cost).
    pub size: [u32; 2],
    /// Which frame's camera.
    pub frame: usize,
    /// The world reference's longest patch edge (metres).
    pub patch_size_m: f32,
    /// Relative L2 error of 8×8 block means of `indirect` against the world-fixed reference
    /// (linear radiance; the reference without visibility, whatever `gi.visibility` says).
    pub relative_l2_block8: f64,
}

#[derive(Serialize, Debug)]
pub struct DynamicFigure {
    pub target_fps: f32,
    /// The render scales of the timed frames.
    pub render_scale: Spread,
    /// Their least and greatest, as the frames record them (f32, so they compare exactly
    /// with `per_frame`; the spread's are f64).
    pub lowest: f32,
    pub highest: f32,
}

#[derive(Serialize, Debug)]
pub struct Report {
    pub level: String,
    pub size: [u32; 2],
    /// Rendered at this fraction of `size`, then scaled up (as `play`'s render scale).
    pub render_scale: f32,
    /// With `--target-fps`: the frame rate dynamic resolution held, and the scales it chose
    /// over the timed frames.
    pub dynamic_resolution: Option<DynamicFigure>,
    pub frames: usize,
    pub warmup_frames: usize,
    pub adapter: String,
    pub backend: String,
    pub gpu_timestamps: bool,
    pub camera_path: String,
    pub gi: plugin_gi::GiSettings,
    /// Per pass, in execution order (empty without timestamps).
    pub passes: Vec<PassFigure>,
    pub gpu_frame_ms: Option<Spread>,
    pub cpu_frame_ms: Spread,
    /// 1000 / median CPU frame time.
    pub fps: f64,
    pub reflection_lights: Option<LightFigure>,
    pub gi_dispatches: u32,
    pub gi_draws: u32,
    pub error_vs_reference: ErrorFigure,
    pub per_frame: Vec<FrameFigure>,
}

pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    let gi = crate::cli::gi_settings(&args.settings, args.gi).map_err(|e| anyhow!("--set {e}"))?;
    // Opened first so that a bad path fails now, not after the benchmark.
    let json = match &args.json {
        Some(path) => Some((path, std::fs::File::create(path).with_context(|| format!("--json {}", path.display()))?)),
        None => None,
    };
    let level = engine::scene::load_level(&args.level)?;
    let gpu = Gpu::headless()?;
    let text = if args.pan {
        let report = pan::pan(&gpu, &level, args, gi)?;
        print!("{}", pan::table(&report));
        serde_json::to_string_pretty(&report)?
    } else if args.compare {
        let report = compare::compare(&gpu, &level, args, gi)?;
        print!("{}", compare::table(&report));
        serde_json::to_string_pretty(&report)?
    } else {
        let report = bench(&gpu, &level, args, gi)?;
        print!("{}", table(&report));
        serde_json::to_string_pretty(&report)?
    };
    if let Some((path, mut file)) = json {
        file.write_all(text.as_bytes())
            .and_then(|_| file.write_all(b"\n"))
            .with_context(|| format!("--json {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

fn bench(gpu: &Gpu, level: &Level, args: &BenchArgs, gi: plugin_gi::GiSettings) -> anyhow::Result<Report> {
    let method = gi.method;
    let (plugins, handle) = crate::plugins(gi);
    let mut renderer = Renderer::new(gpu, &level.scene, plugins)?;
    renderer.set_view("final").map_err(|e| anyhow!(e))?;
    renderer.set_render_scale(args.render_scale);
    let path = CameraPath::for_level(level);
    let mut view: ViewState = initial_view(level, &ViewOverrides::default());
    let n = args.frames() as usize;
    let (w, h) = args.size();
    let target = HeadlessTarget::new(gpu, w, h, ImageKind::Display);

    renderer.set_timing(true);
    for _ in 0..WARMUP_FRAMES {
        view.camera = path.camera(0, n);
        renderer.render(gpu, &view, &target.texture, &target.view)?;
        gpu.wait_idle();
    }
    let mut dynamic = args.target_fps.map(|fps| DynamicResolution::new(fps, args.render_scale));
    // With dynamic resolution the path runs once untimed first: the scale settles as in a
    // player's first seconds.
    let untimed = if dynamic.is_some() { n } else { 0 };
    let mut per_frame = Vec::with_capacity(n);
    for k in 0..untimed + n {
        view.camera = path.camera(k % n, n);
        let render_scale = renderer.render_scale();
        let start = Instant::now();
        renderer.render(gpu, &view, &target.texture, &target.view)?;
        gpu.wait_idle();
        let cpu_ms = start.elapsed().as_secs_f64() * 1e3;
        if let Some(scale) = dynamic.as_mut().and_then(|d| d.push((cpu_ms / 1e3) as f32)) {
            renderer.set_render_scale(scale);
        }
        if k < untimed {
            continue;
        }
        // Read after the timed window: the readback's map and wait are not part of the frame.
        let passes = renderer.last_pass_times(gpu).unwrap_or_default();
        let gpu_ms = (!passes.is_empty()).then(|| passes.iter().map(|(_, ms)| ms).sum());
        per_frame.push(FrameFigure { cpu_ms, gpu_ms, passes, render_scale });
    }
    let dynamic_resolution = dynamic.map(|d| {
        let scales: Vec<f64> = per_frame.iter().map(|f| f.render_scale as f64).collect();
        DynamicFigure {
            target_fps: d.target_fps(),
            render_scale: Spread::of(&scales),
            lowest: per_frame.iter().map(|f| f.render_scale).fold(f32::INFINITY, f32::min),
            highest: per_frame.iter().map(|f| f.render_scale).fold(0.0, f32::max),
        }
    });
    renderer.set_timing(false);
    let stats = plugin_gi::GiStats::of(&renderer);

    // Reflection lights, on a few frames rendered again untimed (the readback stalls).
    let samples: Vec<usize> = if n <= LIGHT_SAMPLES {
        (0..n).collect()
    } else {
        (0..LIGHT_SAMPLES).map(|k| k * (n - 1) / (LIGHT_SAMPLES - 1)).collect()
    };
    let (mut per_tile, mut full_tiles) = (Vec::new(), Vec::new());
    for &i in &samples {
        view.camera = path.camera(i, n);
        renderer.render(gpu, &view, &target.texture, &target.view)?;
        let figures = match method {
            Method::Cuts => plugin_gi::readback::cut_stats(gpu, &renderer).map(|c| (c.lights_per_tile(), c.full_tiles)),
            Method::Article => plugin_gi::readback::volume_stats(gpu, &renderer).map(|v| (f64::from(v.drawn), v.slots)),
        };
        match figures {
            Some((count, other)) => {
                per_tile.push(count);
                full_tiles.push(other);
            }
            None => break, // the GI is off: its passes are not scheduled
        }
    }
    let counted = match method {
        Method::Cuts => "per_tile",
        Method::Article => "volumes",
    };
    let reflection_lights = (per_tile.len() == samples.len()).then(|| LightFigure {
        counted,
        median: Spread::of(&per_tile).median,
        frames: samples,
        per_tile,
        full_tiles,
    });

    // The GI against brute force, on the first frame's camera at a small size, unscaled.
    renderer.set_render_scale(1.0);
    view.camera = path.camera(0, n);
    renderer.set_view("indirect").map_err(|e| anyhow!(e))?;
    let target = HeadlessTarget::new(gpu, ERROR_SIZE.0, ERROR_SIZE.1, ImageKind::Linear);
    let indirect = match target.render(gpu, &mut renderer, &view)? {
        RenderedImage::Linear(img) => img,
        RenderedImage::Display(_) => unreachable!("asked for a linear target"),
    };
    let reference = WorldReference::new(gpu, &level.scene)?.render(gpu, &view, ERROR_SIZE, args.patch_size())?.image;
    let error = plugin_gi::metrics::block_error(&indirect, &reference);

    let mut passes: Vec<(String, Vec<f64>)> = Vec::new();
    for (name, ms) in per_frame.iter().flat_map(|f| &f.passes) {
        match passes.iter_mut().find(|(n, _)| n == name) {
            Some((_, v)) => v.push(*ms),
            None => passes.push((name.clone(), vec![*ms])),
        }
    }
    let gpu_totals: Vec<f64> = per_frame.iter().filter_map(|f| f.gpu_ms).collect();
    let cpu_frame_ms = Spread::of(&per_frame.iter().map(|f| f.cpu_ms).collect::<Vec<_>>());
    let info = gpu.adapter.get_info();
    let settings = handle.settings();
    Ok(Report {
        level: args.level.display().to_string(),
        size: [w, h],
        render_scale: args.render_scale,
        dynamic_resolution,
        frames: n,
        warmup_frames: WARMUP_FRAMES,
        adapter: info.name,
        backend: format!("{:?}", info.backend),
        gpu_timestamps: gpu.timestamps,
        camera_path: path.describe(),
        passes: passes.into_iter().map(|(name, v)| PassFigure { name, gpu_ms: Spread::of(&v) }).collect(),
        gpu_frame_ms: (!gpu_totals.is_empty()).then(|| Spread::of(&gpu_totals)),
        fps: 1e3 / cpu_frame_ms.median,
        cpu_frame_ms,
        reflection_lights,
        gi_dispatches: stats.dispatches,
        gi_draws: stats.draws,
        error_vs_reference: ErrorFigure {
            size: [ERROR_SIZE.0, ERROR_SIZE.1],
            frame: 0,
            patch_size_m: args.patch_size(),
            relative_l2_block8: error,
        },
        gi: settings,
        per_frame,
    })
}

/// The report as the table `bench` prints.
pub fn table(r: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "headlamp bench: {}, {}x{} (render scale {}), {} frames (+{} warm-up, not counted), on {} ({})",
        r.level, r.size[0], r.size[1], r.render_scale, r.frames, r.warmup_frames, r.adapter, r.backend
    );
    let _ = writeln!(s, "camera: {}", r.camera_path);
    if let Some(d) = &r.dynamic_resolution {
        let _ = writeln!(
            s,
            "dynamic resolution holding {:.0} fps (render scale at most {}): the timed frames at render scale median {:.0} % ({:.0} to {:.0} %), after one untimed pass of the path",
            d.target_fps,
            r.render_scale,
            d.render_scale.median * 100.0,
            d.lowest * 100.0,
            d.highest * 100.0
        );
    }
    let _ = writeln!(
        s,
        "GI: {}, split ratio {}, indirect target at {} of the view, {} bounce(s)",
        if r.gi.enabled { "on" } else { "off" },
        r.gi.split_ratio,
        r.gi.resolution_scale,
        r.gi.bounces
    );
    let _ = writeln!(s);
    let _ = writeln!(s, "| pass | GPU median ms | GPU p90 ms | share |");
    let _ = writeln!(s, "| --- | ---: | ---: | ---: |");
    if r.passes.is_empty() {
        let _ = writeln!(s, "| (no GPU timestamps on this device) | | | |");
    }
    let total = r.gpu_frame_ms.map_or(f64::NAN, |g| g.median);
    let sum_of_medians: f64 = r.passes.iter().map(|p| p.gpu_ms.median).sum();
    for p in &r.passes {
        let share = 100.0 * p.gpu_ms.median / sum_of_medians;
        let _ = writeln!(s, "| {} | {:.3} | {:.3} | {share:.1} % |", p.name, p.gpu_ms.median, p.gpu_ms.p90);
    }
    if let Some(g) = r.gpu_frame_ms {
        let _ = writeln!(s, "| **frame, GPU (Σ passes)** | {total:.3} | {:.3} | |", g.p90);
    }
    let c = r.cpu_frame_ms;
    let _ =
        writeln!(s, "| **frame, CPU wall (render + wait)** | {:.3} | {:.3} | **{:.1} fps** |", c.median, c.p90, r.fps);
    let _ = writeln!(s);
    match &r.reflection_lights {
        Some(l) if l.counted == "volumes" => {
            let drawn: Vec<String> = l.per_tile.iter().map(|v| format!("{v:.0}")).collect();
            let _ = writeln!(
                s,
                "light volumes drawn (the article's method): median {:.0} (frames {:?}: [{}]; distribution table slots: {:?})",
                l.median,
                l.frames,
                drawn.join(", "),
                l.full_tiles.first().copied().unwrap_or(0)
            );
        }
        Some(l) => {
            let per_tile: Vec<String> = l.per_tile.iter().map(|v| format!("{v:.0}")).collect();
            let _ = writeln!(
                s,
                "reflection lights per 8x8 tile: median {:.0} (frames {:?}: [{}]; tiles with a full cut: {:?})",
                l.median,
                l.frames,
                per_tile.join(", "),
                l.full_tiles
            );
        }
        None => {
            let _ = writeln!(s, "reflection lights: none (GI off)");
        }
    }
    let _ = writeln!(
        s,
        "GI calls per frame: {} draws + {} dispatches = {}",
        r.gi_draws,
        r.gi_dispatches,
        r.gi_draws + r.gi_dispatches
    );
    let e = &r.error_vs_reference;
    let _ = writeln!(
        s,
        "error vs brute-force reference: {:.4} (relative L2 of 8x8 block means, `indirect` vs the world-fixed `reference` \
         of {} cm patches, {}x{}, frame {}'s camera)",
        e.relative_l2_block8,
        100.0 * e.patch_size_m,
        e.size[0],
        e.size[1],
        e.frame
    );
    if r.gi.visibility == 1 {
        // Evaluated with visibility the reference costs minutes a frame: `bench --pan` has it.
        let _ = writeln!(
            s,
            "  (that reference has no visibility, so with gi.visibility on the GI's correct shadows count as error \
             here; bench --pan compares with the visibility-correct one)"
        );
    }
    s
}
