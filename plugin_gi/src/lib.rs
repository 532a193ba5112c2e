//! Deferred rendered radiosity from first-person perspective: the global-illumination plugin.
//!
//! Per frame: the lamp-view G-buffer becomes reflected flux per texel (Φ = ρ·I(ω)·Ω_texel),
//! merged up a quadtree with the article's filter into a pyramid of reflection lights of every
//! size; each 8×8 tile of a reduced-resolution irradiance target takes its own cut through the
//! pyramid (fine lights near it, coarse ones far away) and gathers their irradiance, which is
//! upsampled with geometry-aware weights, turned into radiance and added to the frame. It
//! depends on the engine's public API only and registers everything in [`GiPlugin::build`].

mod bindings;
mod gather;
pub mod gpu_types;
pub mod metrics;
mod passes;
mod pyramid;
pub mod quadtree;
pub mod readback;
mod settings;
mod shared;

use std::cell::RefCell;
use std::rc::Rc;

use engine::passes::OutputView;
use engine::plugin::{Plugin, PluginContext};

pub use gpu_types::{names, ReflectionLight};
pub use passes::{INCLUDES as SHADER_INCLUDES, SHADERS};
pub use settings::{FieldInfo, GiSettings, RETIRED};
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
        let device = &ctx.gpu.device;
        let globals = &ctx.layouts.globals;
        let gpu = Rc::new(shared::GpuShared {
            params: bindings::uniform_buffer(device, "gi params", std::mem::size_of::<gpu_types::GiParams>() as u64),
        });
        let pyramid = Rc::new(RefCell::new(pyramid::FluxPyramid::new(device, globals, gpu.params.clone())));
        let handle = &self.handle;
        ctx.add_pass(passes::FluxPass::new(handle.clone(), gpu.clone(), pyramid.clone()));
        ctx.add_pass(passes::GatherPass::new(device, globals, handle.clone(), gpu.clone(), pyramid.clone()));
        ctx.add_pass(passes::ViewModelProbePass::new(device, globals, handle.clone(), pyramid));
        ctx.add_pass(passes::BouncePass::new(device, globals, handle.clone()));
        ctx.add_pass(passes::CompositePass::new(device, globals, handle.clone(), gpu.clone()));
        ctx.add_pass(passes::IndirectViewPass::new(device, globals, handle.clone(), gpu.clone()));
        ctx.add_pass(passes::LightsViewPass::new(device, globals));
        ctx.add_pass(passes::ReferencePass::new(device, globals, handle.clone(), gpu));
        ctx.add_view("indirect", names::INDIRECT, OutputView::Radiance);
        ctx.add_view("flux", names::FLUX_VIEW, OutputView::Color);
        ctx.add_view("lights", names::LIGHTS_VIEW, OutputView::Color);
        ctx.add_view("reference", names::REFERENCE, OutputView::Radiance);
    }

    fn stats(&self) -> Vec<(String, f64)> {
        let s = self.handle.stats();
        vec![("gi_dispatches".into(), s.dispatches as f64), ("gi_draws".into(), s.draws as f64)]
    }
}
