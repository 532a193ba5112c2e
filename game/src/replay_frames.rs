//! A replay's frames rendered headless: what `replay --headless --snapshots` writes and
//! `replay --goldens` compares.

use anyhow::{bail, Context};
use engine::frame::ViewState;
use engine::gpu::{Gpu, GpuError};
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;

use crate::recording::LoadedReplay;
use crate::sim::{Simulation, WorldState};
use crate::view::WorldView;

/// Re-simulates a replay without a window, checking every tick's hash, and hands `frame` the
/// picture after each of `ticks` (0 = the start; in tick order, each once), rendered on the
/// device `open` gives when there is a picture to take ([`Gpu::lavapipe`] where the pictures
/// meet goldens, [`Gpu::headless`] otherwise).
pub fn frames(
    loaded: &LoadedReplay,
    ticks: &[u32],
    size: (u32, u32),
    open: fn() -> Result<Gpu, GpuError>,
    frame: impl FnMut(u32, &image::RgbaImage) -> anyhow::Result<()>,
) -> anyhow::Result<WorldState> {
    frames_edited(loaded, ticks, size, open, |_, _| {}, frame)
}

/// [`frames`], each picture's view handed to `edit` first with the world it shows: a thing
/// taken out or dimmed, to show what a golden comparison sees.
pub fn frames_edited(
    loaded: &LoadedReplay,
    ticks: &[u32],
    size: (u32, u32),
    open: fn() -> Result<Gpu, GpuError>,
    mut edit: impl FnMut(&WorldState, &mut ViewState),
    mut frame: impl FnMut(u32, &image::RgbaImage) -> anyhow::Result<()>,
) -> anyhow::Result<WorldState> {
    let end = loaded.commands.len() as u32;
    if let Some(&late) = ticks.iter().find(|&&t| t > end) {
        bail!("--snapshots: tick {late} is past the end of {} ({end} ticks)", loaded.path.display());
    }
    let mut ticks = ticks.to_vec();
    ticks.sort_unstable();
    ticks.dedup();
    let mut shooter = if ticks.is_empty() { None } else { Some(SnapshotRenderer::new(loaded, size, open()?)?) };
    let mut sim = loaded.simulation()?;
    let mut wanted = ticks.iter().peekable();
    for i in 0..=loaded.commands.len() {
        while wanted.next_if_eq(&&(i as u32)).is_some() {
            if let Some(s) = &mut shooter {
                frame(i as u32, &s.shoot(&sim, &mut edit)?)?;
            }
        }
        if i < loaded.commands.len() {
            loaded.step_checked(&mut sim, i).with_context(|| loaded.path.display().to_string())?;
        }
    }
    Ok(sim.state)
}

/// Renders the game's view of a simulation, headless.
struct SnapshotRenderer {
    gpu: Gpu,
    renderer: Renderer,
    target: HeadlessTarget,
    view: WorldView,
}

impl SnapshotRenderer {
    fn new(loaded: &LoadedReplay, size: (u32, u32), gpu: Gpu) -> anyhow::Result<Self> {
        let (plugins, _) = crate::plugins(loaded.gi.clone());
        let mut renderer = Renderer::new(&gpu, &loaded.level.scene, plugins)?;
        let target = HeadlessTarget::new(&gpu, size.0, size.1, ImageKind::Display);
        let mut view = WorldView::new(&loaded.level);
        view.add_meshes(&mut renderer, &gpu);
        Ok(Self { gpu, renderer, target, view })
    }

    fn shoot(
        &mut self,
        sim: &Simulation,
        edit: &mut impl FnMut(&WorldState, &mut ViewState),
    ) -> anyhow::Result<image::RgbaImage> {
        self.view.at(sim.entities(), &sim.state);
        edit(&sim.state, &mut self.view.view);
        // Snapshots are far apart in time: each is a cut for the renderer's history.
        self.renderer.reset_history();
        match self.target.render(&self.gpu, &mut self.renderer, &self.view.view)? {
            RenderedImage::Display(image) => Ok(image),
            RenderedImage::Linear(_) => bail!("a display target rendered linear values"),
        }
    }
}

/// The file name `replay --headless --snapshots` gives the frame after `tick` ticks.
pub fn snapshot_name(tick: u32) -> String {
    format!("tick_{tick:06}.png")
}
