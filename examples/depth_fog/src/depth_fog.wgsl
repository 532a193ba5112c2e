// Depth fog: L = L_surface·T + L_fog·(1 − T), T = exp(−density · depth), blended over `hdr`
// (colour: src + dst·(1 − src.a), with src = (L_fog·(1 − T), 1 − T)).
#include "common.wgsl"

// rgb: the fog's radiance (W·sr⁻¹·m⁻²); a: its density, per metre.
@group(1) @binding(0) var<uniform> fog: vec4f;
// World position; w = view depth in metres, 0 where nothing was drawn (the sky).
@group(1) @binding(1) var gbuffer_position: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    let depth = textureLoad(gbuffer_position, vec2i(in.position.xy), 0).w;
    // Nothing drawn: fog all the way.
    let transmittance = select(0.0, exp(-fog.a * depth), depth > 0.0);
    return vec4f(fog.rgb * (1.0 - transmittance), 1.0 - transmittance);
}
