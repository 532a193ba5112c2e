//! `headlamp render`: one headless frame of a level to PNG or EXR.

use anyhow::anyhow;
use engine::gpu::Gpu;
use engine::headless::HeadlessTarget;
use engine::renderer::Renderer;
use engine::start_view::{initial_view, ViewOverrides};

use crate::cli::RenderArgs;

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    let kind = engine::output::kind_for_path(&args.out)?;
    let gi = args.gi_settings().map_err(|e| anyhow!("--set {e}"))?;
    let level = engine::scene::load_level(&args.level)?;
    let gpu = Gpu::headless()?;
    let (plugins, _gi) = crate::plugins(gi);
    let mut renderer = Renderer::new(&gpu, &level.scene, plugins)?;
    renderer.set_view(&args.view).map_err(|e| anyhow!("--view: {e}"))?;
    let overrides = ViewOverrides { look: args.camera, fov_y: args.fov.map(f32::to_radians) };
    let mut view = initial_view(&level, &overrides);
    if let Some((eye, target)) = args.lamp {
        view.headlamp.detach_looking_at(eye, target);
    }
    let target = HeadlessTarget::new(&gpu, args.size.0, args.size.1, kind);
    let image = target.render(&gpu, &mut renderer, &view)?;
    engine::output::save(&image, &args.out)?;
    println!("wrote {} ({}x{}, view {})", args.out.display(), args.size.0, args.size.1, args.view);
    Ok(())
}
