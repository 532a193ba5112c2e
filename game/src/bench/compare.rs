//! `headlamp bench --compare`: what the GI costs, as the ratio of frame times with it on and
//! off, measured side by side in one process: two renderers, one with the GI and one without,
//! render each camera of the path in turn (alternating which goes first), so a shared, noisy
//! machine slows both alike. Only the ratio is meant to be compared across machines.

use std::fmt::Write as _;
use std::time::Instant;

use anyhow::anyhow;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind};
use engine::renderer::Renderer;
use engine::scene::Level;
use engine::start_view::{initial_view, ViewOverrides};
use serde::Serialize;

use super::{CameraPath, Spread, WARMUP_FRAMES};
use crate::cli::BenchArgs;

#[derive(Serialize, Debug)]
pub struct CompareReport {
    pub level: String,
    pub size: [u32; 2],
    pub frames: usize,
    pub adapter: String,
    pub camera_path: String,
    pub gi: plugin_gi::GiSettings,
    /// CPU wall time of each frame (record + submit + wait), without and with the GI.
    pub off_ms: Spread,
    pub on_ms: Spread,
    /// Median over frames of (frame with GI) / (the same camera's frame without).
    pub ratio: f64,
    /// 1 − off/on at the medians: the GI's share of a frame that has it.
    pub gi_share: f64,
    pub gi_draws: u32,
    pub gi_dispatches: u32,
}

pub fn compare(gpu: &Gpu, level: &Level, args: &BenchArgs, gi: plugin_gi::GiSettings) -> anyhow::Result<CompareReport> {
    let mut on_settings = gi.clone();
    on_settings.enabled = true;
    let off_settings = plugin_gi::GiSettings { enabled: false, ..gi };
    let (on_plugins, on_handle) = crate::plugins(on_settings);
    let (off_plugins, _) = crate::plugins(off_settings);
    let mut on = Renderer::new(gpu, &level.scene, on_plugins)?;
    let mut off = Renderer::new(gpu, &level.scene, off_plugins)?;
    for r in [&mut on, &mut off] {
        r.set_view("final").map_err(|e| anyhow!(e))?;
        r.set_render_scale(args.render_scale);
    }
    let path = CameraPath::for_level(level);
    let mut view = initial_view(level, &ViewOverrides::default());
    let n = args.frames() as usize;
    let target = HeadlessTarget::new(gpu, args.size().0, args.size().1, ImageKind::Display);
    let time = |r: &mut Renderer, view: &engine::frame::ViewState| -> anyhow::Result<f64> {
        let start = Instant::now();
        r.render(gpu, view, &target.texture, &target.view)?;
        gpu.wait_idle();
        Ok(start.elapsed().as_secs_f64() * 1e3)
    };
    view.camera = path.camera(0, n);
    for _ in 0..WARMUP_FRAMES {
        time(&mut on, &view)?;
        time(&mut off, &view)?;
    }
    let (mut on_ms, mut off_ms, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..n {
        view.camera = path.camera(i, n);
        let (a, b) = if i % 2 == 0 {
            let a = time(&mut off, &view)?;
            (a, time(&mut on, &view)?)
        } else {
            let b = time(&mut on, &view)?;
            (time(&mut off, &view)?, b)
        };
        off_ms.push(a);
        on_ms.push(b);
        ratios.push(b / a);
    }
    let stats = plugin_gi::GiStats::of(&on);
    let (off_ms, on_ms) = (Spread::of(&off_ms), Spread::of(&on_ms));
    Ok(CompareReport {
        level: args.level.display().to_string(),
        size: [args.size().0, args.size().1],
        frames: n,
        adapter: gpu.adapter.get_info().name,
        camera_path: path.describe(),
        gi: on_handle.settings(),
        ratio: Spread::of(&ratios).median,
        gi_share: 1.0 - off_ms.median / on_ms.median,
        off_ms,
        on_ms,
        gi_draws: stats.draws,
        gi_dispatches: stats.dispatches,
    })
}

pub fn table(r: &CompareReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "headlamp bench --compare: {}, {}x{}, {} frames each, GI off and on alternating, on {}",
        r.level, r.size[0], r.size[1], r.frames, r.adapter
    );
    let _ = writeln!(s, "camera: {}", r.camera_path);
    let _ = writeln!(s);
    let _ = writeln!(s, "| frame, CPU wall (render + wait) | GI off | GI on |");
    let _ = writeln!(s, "| --- | ---: | ---: |");
    let _ = writeln!(s, "| median ms | {:.3} | {:.3} |", r.off_ms.median, r.on_ms.median);
    let _ = writeln!(s, "| p90 ms | {:.3} | {:.3} |", r.off_ms.p90, r.on_ms.p90);
    let _ = writeln!(s);
    let _ = writeln!(s, "ratio (GI on / GI off, median of per-camera ratios): {:.2}", r.ratio);
    let _ = writeln!(s, "GI share of a frame with GI: {:.1} %", 100.0 * r.gi_share);
    let _ = writeln!(
        s,
        "GI calls per frame: {} draws + {} dispatches = {}",
        r.gi_draws,
        r.gi_dispatches,
        r.gi_draws + r.gi_dispatches
    );
    s
}
