//! The GI's render-graph passes, in frame order.

mod composite;
mod lights;
mod lights_view;
mod reference;
mod shade;

pub use composite::CompositePass;
pub use lights::LightsPass;
pub use lights_view::LightsViewPass;
pub use reference::ReferencePass;
pub use shade::ShadePass;

use engine::wgpu;

/// The GI's shared WGSL include.
pub const INCLUDES: &[(&str, &str)] = &[("gi_common.wgsl", include_str!("../../../shaders/gi/gi_common.wgsl"))];

pub fn module(device: &wgpu::Device, label: &str, source: &str) -> wgpu::ShaderModule {
    engine::shader::module(device, label, source, INCLUDES)
}

/// Every WGSL file of the plugin, for validation tests.
pub const SHADERS: &[(&str, &str)] = &[
    ("gi/flux.wgsl", lights::FLUX_SHADER),
    ("gi/reduce.wgsl", lights::REDUCE_SHADER),
    ("gi/build_lights.wgsl", lights::BUILD_SHADER),
    ("gi/shade.wgsl", shade::SHADER),
    ("gi/composite.wgsl", composite::SHADER),
    ("gi/lights_view.wgsl", lights_view::SHADER),
    ("gi/reference.wgsl", reference::SHADER),
];
