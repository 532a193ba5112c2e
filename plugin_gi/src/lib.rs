//! Deferred rendered radiosity from first-person perspective: the global-illumination plugin.
//!
//! Per frame: the lamp-view G-buffer becomes reflected flux per texel (Φ = ρ·I(ω)·Ω_texel),
//! merged up a quadtree with the article's filter into a pyramid of reflection lights of every
//! size; each 8×8 tile of a reduced-resolution irradiance target takes its own cut through the
//! pyramid (fine lights near it, coarse ones far away) and gathers their irradiance, which is
//! upsampled with geometry-aware weights, turned into radiance and added to the frame. With
//! `gi.method = article` the article's own pipeline makes that irradiance instead: its
//! distribution table's lights of the same pyramid, drawn as light volumes (`passes/article/`).
//! It depends on the engine's public API only and registers everything in [`GiPlugin::build`].

mod cuts_layout;
pub mod distribution_table;
mod frame;
pub mod gpu_types;
mod grids;
pub mod metrics;
mod passes;
mod pipelines;
pub mod quadtree;
pub mod readback;
mod resources;
mod schedule;
mod settings;
mod shader;
mod shared;
pub mod shared_constants;
mod world_grid;

use engine::graph::{PassOrder, Stage};
use engine::passes::OutputView;
use engine::plugin::{Plugin, PluginContext};

pub use gpu_types::{names, ReflectionLight};
pub use passes::{bindings, SumLanes, SHADERS};
pub use settings::{FieldInfo, GiSettings, Method, RETIRED};
pub use shader::INCLUDES as SHADER_INCLUDES;
pub use shared::{GiHandle, GiStats};

use passes::*;
use schedule::{GiPass, Scheduled, When};

pub struct GiPlugin {
    handle: GiHandle,
}

impl GiPlugin {
    pub fn new(settings: GiSettings) -> Self {
        let handle = GiHandle::default();
        handle.set_settings(settings);
        Self { handle }
    }

    /// Live access to the settings and the last frame's figures.
    pub fn handle(&self) -> GiHandle {
        self.handle.clone()
    }
}

impl Plugin for GiPlugin {
    fn name(&self) -> &str {
        "gi"
    }

    fn build(&mut self, ctx: &mut PluginContext<'_>) {
        let (device, globals) = (&ctx.gpu.device.clone(), &ctx.layouts.globals.clone());
        let bounces = GiSettings::FIELDS.iter().find(|f| f.name == "bounces").map_or(1, |f| f.max as u32);
        let (core, gi, handle) = (*ctx.core(), resources::GiResources::register(ctx, bounces), self.handle.clone());
        let lanes = SumLanes::for_device(ctx.gpu);
        let world = std::rc::Rc::new(world_grid::WorldGrid::new(device, ctx.scene));
        let h = &handle;
        add(ctx, h, When::ALWAYS, GiParamsPass::first(gi.params()));
        add(ctx, h, When::ALWAYS, PyramidPass::new(device, globals, 1, core, gi.clone()));
        add(ctx, h, When::ALWAYS.with_visibility(), SightDepthPass::new(device, globals, core, gi.clone()));
        // The first bounce: each tile's cut of the pyramid, which of its lights its receivers
        // see, and their sum …
        let cuts = When::method(Method::Cuts);
        add(ctx, h, cuts, CutsPass::new(device, globals, 1, core, gi.clone()));
        add(ctx, h, cuts.with_visibility(), SightPass::new(device, globals, 1, core, gi.clone(), world.clone()));
        add(ctx, h, cuts, GatherPass::new(device, globals, 1, lanes, core, gi.clone()));
        // … or the article's light volumes, which make the same irradiance.
        let article = ArticlePass::new(ctx.gpu, globals, core, gi.clone(), world.clone());
        add(ctx, h, When::method(Method::Article), article);
        let view_models = ViewModelIrradiancePass::new(device, globals, gi.clone(), core.view_model_irradiance);
        add(ctx, h, When::ENABLED, view_models);
        // Further bounces: the camera's view lit by the bounce before, the same stages again.
        if bounces > 1 {
            add(ctx, h, When::bounce(2), GiParamsPass::further(gi.bounce(2).params));
        }
        for k in 2..=bounces {
            add(ctx, h, When::bounce(k), PyramidPass::new(device, globals, k, core, gi.clone()));
            add(ctx, h, When::bounce(k), CutsPass::new(device, globals, k, core, gi.clone()));
            add(
                ctx,
                h,
                When::bounce(k).with_visibility(),
                SightPass::new(device, globals, k, core, gi.clone(), world.clone()),
            );
            add(ctx, h, When::bounce(k), GatherPass::new(device, globals, k, lanes, core, gi.clone()));
        }
        // The total of every bounce, blended over frames.
        add(ctx, h, When::ALWAYS, TemporalPass::new(device, globals, core, gi.clone()));
        add(ctx, h, When::ALWAYS, ReferencePass::new(device, globals, handle.clone(), core, gi.clone()));
        let upsample = || Gi { handle: handle.clone(), core, resources: gi.clone() };
        let composite = IndirectCompositePass::new(ctx.gpu, ctx.layouts, upsample());
        ctx.replace_pass("composite", composite);
        ctx.add_pass(Stage::Composite, IndirectViewPass::new(device, globals, upsample()));
        // It draws over the finished frame, view models included, so it comes with the present.
        ctx.add_pass(Stage::Present, LightsViewPass::new(device, globals, gi.clone(), core.hdr));
        ctx.add_view("indirect", gi.indirect, OutputView::Radiance);
        ctx.add_view("flux", gi.flux_view, OutputView::Color);
        ctx.add_view("lights", gi.lights_view, OutputView::Color);
        // The GPU reference, every texel of the lamp view a sender; `reference` is the world-fixed
        // one the game computes on the CPU (the gi-reference crate).
        ctx.add_view("reference_screen", gi.reference, OutputView::Radiance);
    }
}

/// Adds a GI pass to the indirect stage, run on the frames `when` holds.
fn add<'c, P: GiPass>(ctx: &'c mut PluginContext<'_>, handle: &GiHandle, when: When, pass: P) -> PassOrder<'c> {
    ctx.add_pass(Stage::Indirect, Scheduled { pass, when, handle: handle.clone() })
}
