// GI bounce accumulation: adds one bounce's irradiance into the total (additive blending).
#include "common.wgsl"

@group(1) @binding(0) var bounce_irradiance: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    return vec4f(textureLoad(bounce_irradiance, vec2i(in.position.xy), 0).rgb, 1.0);
}
