//! The GI's WGSL: its shared include, and modules built with it.

use engine::wgpu;

/// The GI's shared WGSL include.
pub const INCLUDES: &[(&str, &str)] = &[
    ("gi_common.wgsl", include_str!("../../shaders/gi/gi_common.wgsl")),
    ("receivers.wgsl", include_str!("../../shaders/gi/receivers.wgsl")),
    ("visibility.wgsl", include_str!("../../shaders/gi/visibility.wgsl")),
    ("sub_image_layout.wgsl", include_str!("../../shaders/gi/sub_image_layout.wgsl")),
    // The gather's body, included by its two entry points (see crate::gather).
    ("gather.wgsl", include_str!("../../shaders/gi/gather.wgsl")),
];

pub fn module(device: &wgpu::Device, label: &str, source: &str) -> wgpu::ShaderModule {
    engine::shader::module(device, label, source, INCLUDES)
}
