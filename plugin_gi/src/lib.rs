//! Deferred rendered radiosity from first-person perspective: the global-illumination plugin.
//!
//! Per frame: the lamp-view G-buffer becomes reflected flux per texel (Φ = ρ·I(ω)·Ω_texel),
//! merged up a quadtree with the article's filter into a pyramid of reflection lights of every
//! size; each 8×8 tile of a reduced-resolution irradiance target takes its own cut through the
//! pyramid (fine lights near it, coarse ones far away) and gathers their irradiance, which is
//! upsampled with geometry-aware weights, turned into radiance and added to the frame. With
//! `gi.method = article` the article's own pipeline makes that irradiance instead: its
//! distribution table's lights of the same pyramid, drawn as light volumes (`light_volumes.rs`).
//! It depends on the engine's public API only and registers everything in [`GiPlugin::build`].

pub mod distribution_table;
mod frame;
mod gather;
pub mod gpu_types;
mod grids;
mod light_volumes;
pub mod metrics;
mod passes;
mod pipelines;
mod pyramid;
pub mod quadtree;
pub mod readback;
mod resources;
mod settings;
mod shader;
mod shared;
pub mod shared_constants;
mod sight_depth;

use engine::graph::Stage;
use engine::passes::OutputView;
use engine::plugin::{Plugin, PluginContext};

pub use gather::SumLanes;
pub use gpu_types::{names, ReflectionLight};
pub use passes::{bindings, SHADERS};
pub use settings::{FieldInfo, GiSettings, Method, RETIRED};
pub use shader::INCLUDES as SHADER_INCLUDES;
pub use shared::{GiHandle, GiStats};

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
        let (core, gi, handle) = (*ctx.core(), resources::GiResources::register(ctx), self.handle.clone());
        let shared = (handle.clone(), core, gi);
        let (params, irradiance) = (gi.params, core.view_model_irradiance);
        ctx.add_pass(Stage::Indirect, passes::GiParamsPass { handle: handle.clone(), params });
        ctx.add_pass(Stage::Indirect, passes::FluxPass::new(device, globals, handle.clone(), core, gi));
        let lanes = gather::SumLanes::for_device(ctx.gpu);
        ctx.add_pass(Stage::Indirect, passes::GatherPass::new(device, globals, handle.clone(), core, gi, lanes));
        // `gi.method = article`: the same irradiance by the article's light volumes instead.
        ctx.add_pass(Stage::Indirect, passes::ArticlePass::new(ctx.gpu, globals, handle.clone(), core, gi));
        let probe = passes::ViewModelIrradiancePass::new(device, globals, handle.clone(), gi, irradiance);
        ctx.add_pass(Stage::Indirect, probe);
        ctx.add_pass(Stage::Indirect, passes::BouncePass::new(device, globals, handle.clone(), core, gi, lanes));
        // The total of every bounce, blended over frames.
        ctx.add_pass(Stage::Indirect, passes::TemporalPass::new(device, globals, handle.clone(), core, gi))
            .after("gi_bounces");
        ctx.add_pass(Stage::Indirect, passes::ReferencePass::new(device, globals, handle, core, gi));
        let composite = passes::IndirectCompositePass::new(ctx.gpu, ctx.layouts, shared.clone());
        ctx.replace_pass("composite", composite);
        ctx.add_pass(Stage::Composite, passes::IndirectViewPass::new(device, globals, shared));
        // It draws over the finished frame, view models included, so it comes with the present.
        ctx.add_pass(Stage::Present, passes::LightsViewPass::new(device, globals, gi, core.hdr));
        ctx.add_view("indirect", gi.indirect, OutputView::Radiance);
        ctx.add_view("flux", gi.flux_view, OutputView::Color);
        ctx.add_view("lights", gi.lights_view, OutputView::Color);
        // The GPU reference, every texel of the lamp view a sender; `reference` is the world-fixed
        // one the game computes on the CPU (the gi-reference crate).
        ctx.add_view("reference_screen", gi.reference, OutputView::Radiance);
    }
}
