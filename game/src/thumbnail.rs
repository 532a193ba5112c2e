//! A level's picture for the level menu: the view from its spawn, rendered once and cached on
//! disk by the level's content hash (an edited level gets a new one).

use std::path::Path;

use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;

use crate::level_list::ListedLevel;
use crate::sim::Simulation;
use crate::view::WorldView;

/// Pixels: twice the menu's 160 × 90 points, for high-DPI screens.
pub const SIZE: (u32, u32) = (320, 180);

/// The cached picture, or a new one rendered with `gpu` (and then cached in `cache`).
pub fn thumbnail(
    gpu: &Gpu,
    listed: &ListedLevel,
    gi: &plugin_gi::GiSettings,
    cache: Option<&Path>,
) -> anyhow::Result<image::RgbaImage> {
    let file = cache.map(|dir| dir.join(format!("{:016x}.png", listed.content_hash)));
    if let Some(img) = file.as_ref().and_then(|f| image::open(f).ok()) {
        return Ok(img.to_rgba8());
    }
    let img = render(gpu, &listed.path, gi)?;
    if let Some(file) = &file {
        // A cache that cannot be written only costs a render next time.
        let written = file.parent().is_some_and(|dir| std::fs::create_dir_all(dir).is_ok()) && img.save(file).is_ok();
        if !written {
            log::warn!("cannot cache the thumbnail {}", file.display());
        }
    }
    Ok(img)
}

/// The game's view at the level's start, headless.
fn render(gpu: &Gpu, path: &Path, gi: &plugin_gi::GiSettings) -> anyhow::Result<image::RgbaImage> {
    let level = engine::scene::load_level(path)?;
    let sim =
        Simulation::new(&level, crate::sim::level_world(&level)?, engine::clock::FixedClock::DEFAULT_TICK_RATE, 1);
    let (plugins, _) = crate::plugins(gi.clone());
    let mut renderer = Renderer::new(gpu, &level.scene, plugins)?;
    let mut view = WorldView::new(&level);
    view.add_meshes(&mut renderer, gpu);
    view.at(sim.entities(), &sim.state);
    let target = HeadlessTarget::new(gpu, SIZE.0, SIZE.1, ImageKind::Display);
    match target.render(gpu, &mut renderer, &view.view)? {
        RenderedImage::Display(img) => Ok(img),
        RenderedImage::Linear(_) => anyhow::bail!("a display target rendered linear values"),
    }
}
