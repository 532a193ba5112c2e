//! Renders a level with the depth fog, headless: `cargo run --release -p depth-fog-example --
//! levels/cellar/level.toml fog.png`.

use anyhow::Context;
use depth_fog_example::DepthFogPlugin;
use engine::headless::{HeadlessTarget, ImageKind};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [level, out] = args.as_slice() else {
        anyhow::bail!("usage: depth-fog-example LEVEL OUTPUT.png");
    };
    let level = engine::scene::load_level(level.as_ref()).with_context(|| format!("loading {level}"))?;
    let gpu = engine::gpu::Gpu::headless()?;
    let fog = DepthFogPlugin { radiance: [0.02, 0.025, 0.03], density: 0.15 };
    let mut renderer = engine::renderer::Renderer::new(&gpu, &level.scene, vec![Box::new(fog)])?;
    let view = engine::start_view::initial_view(&level, &Default::default());
    let image = HeadlessTarget::new(&gpu, 640, 360, ImageKind::Display).render(&gpu, &mut renderer, &view)?;
    engine::output::save(&image, out.as_ref())
}
