//! The GI's WGSL: its shared include, and modules built with it.

use engine::wgpu;

/// The GI's shared WGSL include.
pub const INCLUDES: &[(&str, &str)] = &[
    ("gi_common.wgsl", include_str!("../../shaders/gi/gi_common.wgsl")),
    ("receivers.wgsl", include_str!("../../shaders/gi/receivers.wgsl")),
    ("visibility.wgsl", include_str!("../../shaders/gi/visibility.wgsl")),
    ("world_sight.wgsl", include_str!("../../shaders/gi/world_sight.wgsl")),
    ("article_sub_image_layout.wgsl", include_str!("../../shaders/gi/article_sub_image_layout.wgsl")),
    // The bodies of the pyramid and the sum, each included by the files of its entry points
    // (crate::passes::pyramid, crate::passes::gather).
    ("pyramid.wgsl", include_str!("../../shaders/gi/pyramid.wgsl")),
    ("gather.wgsl", include_str!("../../shaders/gi/gather.wgsl")),
];

pub fn module(device: &wgpu::Device, label: &str, source: &str) -> wgpu::ShaderModule {
    engine::shader::module(device, label, source, INCLUDES)
}
