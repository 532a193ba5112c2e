//! The GI's render-graph passes, in frame order.

mod bounces;
mod composite;
mod lights;
mod lights_view;
mod reference;
mod shade;

pub use bounces::BouncePass;
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

pub const FLUX_SHADER: &str = include_str!("../../../shaders/gi/flux.wgsl");
pub const REDUCE_SHADER: &str = include_str!("../../../shaders/gi/reduce.wgsl");
pub const BUILD_SHADER: &str = include_str!("../../../shaders/gi/build_lights.wgsl");

/// Every WGSL file of the plugin, for validation tests.
pub const SHADERS: &[(&str, &str)] = &[
    ("gi/flux.wgsl", FLUX_SHADER),
    ("gi/reduce.wgsl", REDUCE_SHADER),
    ("gi/build_lights.wgsl", BUILD_SHADER),
    ("gi/add.wgsl", bounces::ADD_SHADER),
    ("gi/shade.wgsl", shade::SHADER),
    ("gi/composite.wgsl", composite::SHADER),
    ("gi/lights_view.wgsl", lights_view::SHADER),
    ("gi/reference.wgsl", reference::SHADER),
];
