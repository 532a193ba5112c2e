//! Deferred rendered radiosity from first-person perspective: the global-illumination plugin.
//!
//! Per frame: the lamp-view G-buffer becomes reflected flux per texel (Φ = ρ·I(ω)·Ω_texel);
//! a mip chain merges similar texels; a precomputed distribution table picks the quadtree
//! slots that become reflection lights, built on the GPU into an instance buffer with indirect
//! draw arguments; instanced light volumes shade the camera G-buffer into an irradiance target,
//! which is upsampled, turned into radiance and added to the frame. It depends on the
//! engine's public API only and registers everything in [`GiPlugin::build`].

mod bindings;
pub mod distribution_table;
mod gpu_types;
mod light_builder;
pub mod metrics;
mod passes;
pub mod quadtree;
pub mod readback;
mod settings;
mod shared;

use std::rc::Rc;

use engine::passes::OutputView;
use engine::plugin::{Plugin, PluginContext};

pub use gpu_types::{names, ReflectionLight};
pub use passes::{INCLUDES as SHADER_INCLUDES, SHADERS};
pub use settings::{FieldInfo, GiSettings};
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
        ctx.add_pass(passes::LightsPass::new(device, globals, self.handle.clone(), gpu.clone()));
        ctx.add_pass(passes::ShadePass::new(ctx.gpu, globals, self.handle.clone(), gpu.clone()));
        ctx.add_pass(passes::BouncePass::new(ctx.gpu, globals, self.handle.clone()));
        ctx.add_pass(passes::CompositePass::new(device, globals, self.handle.clone(), gpu.clone()));
        ctx.add_pass(passes::LightsViewPass::new(device, globals));
        ctx.add_pass(passes::ReferencePass::new(device, globals, gpu));
        ctx.add_view("indirect", names::INDIRECT, OutputView::Radiance);
        ctx.add_view("flux", names::FLUX_VIEW, OutputView::Color);
        ctx.add_view("lights", names::LIGHTS_VIEW, OutputView::Color);
        ctx.add_view("reference", names::REFERENCE, OutputView::Radiance);
    }

    fn stats(&self) -> Vec<(String, f64)> {
        let s = self.handle.stats();
        vec![
            ("gi_slots".into(), s.slots as f64),
            ("gi_light_capacity".into(), s.light_capacity as f64),
            ("gi_dispatches".into(), s.dispatches as f64),
            ("gi_draws".into(), s.draws as f64),
        ]
    }
}
