//! The GI's indirect light as the accuracy tests compare it with a reference.

use engine::frame::ViewState;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::scene::Scene;
use plugin_gi::metrics::shrink;
use plugin_gi::{GiSettings, GiStats};

/// The indirect light of `view` rendered at `frame` with `settings`, after four frames (the
/// temporal pass starts from nothing, and a few frames settle it), shrunk `by` times each way
/// to the reference's receivers; and the GI's calls in the last frame.
pub fn settled_indirect(
    gpu: &Gpu,
    scene: &Scene,
    view: &ViewState,
    settings: GiSettings,
    frame: (u32, u32),
    by: u32,
) -> (image::Rgba32FImage, GiStats) {
    let (plugins, _) = game::plugins(settings);
    let mut renderer = Renderer::new(gpu, scene, plugins).unwrap();
    renderer.set_view("indirect").unwrap();
    let target = HeadlessTarget::new(gpu, frame.0, frame.1, ImageKind::Linear);
    let mut last = None;
    for _ in 0..4 {
        last = Some(target.render(gpu, &mut renderer, view).unwrap());
    }
    let stats = GiStats::of(&renderer);
    match last.unwrap() {
        RenderedImage::Linear(img) => (shrink(&img, by), stats),
        RenderedImage::Display(_) => unreachable!("a linear target"),
    }
}
