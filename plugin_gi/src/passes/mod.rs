//! The GI's render-graph passes, in frame order.

mod bounces;
mod composite;
mod flux;
mod gather;
mod lights_view;
mod reference;
mod view_model;

pub use bounces::BouncePass;
pub use composite::{CompositePass, IndirectViewPass};
pub use flux::FluxPass;
pub use gather::GatherPass;
pub use lights_view::LightsViewPass;
pub use reference::ReferencePass;
pub use view_model::ViewModelProbePass;

use engine::wgpu;

/// The GI's shared WGSL include.
pub const INCLUDES: &[(&str, &str)] = &[("gi_common.wgsl", include_str!("../../../shaders/gi/gi_common.wgsl"))];

pub fn module(device: &wgpu::Device, label: &str, source: &str) -> wgpu::ShaderModule {
    engine::shader::module(device, label, source, INCLUDES)
}

pub const PYRAMID_SHADER: &str = include_str!("../../../shaders/gi/pyramid.wgsl");
pub const CUTS_SHADER: &str = include_str!("../../../shaders/gi/cuts.wgsl");
pub const GATHER_SHADER: &str = include_str!("../../../shaders/gi/gather.wgsl");
pub const VIEW_MODEL_PROBE_SHADER: &str = include_str!("../../../shaders/gi/view_model_probe.wgsl");

/// Every WGSL file of the plugin, for validation tests.
pub const SHADERS: &[(&str, &str)] = &[
    ("gi/pyramid.wgsl", PYRAMID_SHADER),
    ("gi/cuts.wgsl", CUTS_SHADER),
    ("gi/gather.wgsl", GATHER_SHADER),
    ("gi/composite.wgsl", composite::SHADER),
    ("gi/lights_view.wgsl", lights_view::SHADER),
    ("gi/reference.wgsl", reference::SHADER),
    ("gi/view_model_probe.wgsl", VIEW_MODEL_PROBE_SHADER),
];
