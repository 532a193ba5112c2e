// Composite pass: the frame's linear radiance before plugins add to it, direct + emissive.
#include "common.wgsl"

@group(1) @binding(0) var direct_radiance: texture_2d<f32>;
@group(1) @binding(1) var gbuffer_emissive: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    let texel = vec2i(in.position.xy);
    let direct = textureLoad(direct_radiance, texel, 0).rgb;
    let emissive = textureLoad(gbuffer_emissive, texel, 0).rgb;
    return vec4f(direct + emissive, 1.0);
}
