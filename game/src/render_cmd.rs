//! `headlamp render`: one headless frame of a level to PNG or EXR.

use anyhow::anyhow;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::start_view::{initial_view, ViewOverrides};

use crate::cli::RenderArgs;
use crate::world_reference::{tonemap, WorldReference};

/// The view name of the world-fixed reference, computed on the CPU rather than drawn by a pass.
pub const WORLD_REFERENCE_VIEW: &str = "reference";
/// The same with every sender–receiver pair tested for occlusion: no light through walls.
pub const WORLD_REFERENCE_VIS_VIEW: &str = "reference_vis";

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    let kind = engine::output::kind_for_path(&args.out)?;
    let gi = args.gi_settings().map_err(|e| anyhow!("--set {e}"))?;
    let level = engine::scene::load_level(&args.level)?;
    let gpu = Gpu::headless()?;
    let overrides = ViewOverrides { look: args.camera, fov_y: args.fov.map(f32::to_radians) };
    let mut view = initial_view(&level, &overrides);
    if let Some((eye, target)) = args.lamp {
        view.headlamp.detach_looking_at(eye, target);
    }
    let image = if args.view == WORLD_REFERENCE_VIEW || args.view == WORLD_REFERENCE_VIS_VIEW {
        let mut reference = WorldReference::new(&gpu, &level.scene)?;
        if args.view == WORLD_REFERENCE_VIS_VIEW {
            reference = reference.with_visibility();
        }
        let frame = reference.render(&gpu, &view, args.size, args.patch_size())?;
        println!(
            "reference: {} lit patches of at most {} cm ({:.2} s), {} receivers ({:.2} s)",
            frame.lit_patches,
            100.0 * args.patch_size(),
            frame.patch_seconds,
            frame.receivers,
            frame.sum_seconds
        );
        match kind {
            ImageKind::Linear => RenderedImage::Linear(frame.image),
            ImageKind::Display => RenderedImage::Display(tonemap(&frame.image, view.exposure)),
        }
    } else {
        let (plugins, _gi) = crate::plugins(gi);
        let mut renderer = Renderer::new(&gpu, &level.scene, plugins)?;
        renderer
            .set_view(&args.view)
            .map_err(|e| {
                anyhow!(
                    "--view: {e}, or {WORLD_REFERENCE_VIEW} (the world-fixed reference), or {WORLD_REFERENCE_VIS_VIEW} (the same with visibility)"
                )
            })?;
        let target = HeadlessTarget::new(&gpu, args.size.0, args.size.1, kind);
        target.render(&gpu, &mut renderer, &view)?
    };
    engine::output::save(&image, &args.out)?;
    println!("wrote {} ({}x{}, view {})", args.out.display(), args.size.0, args.size.1, args.view);
    Ok(())
}
