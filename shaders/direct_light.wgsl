// Direct light pass: L_d = ρ/π · I(ω) · max(0, n·l) / d² from the headlamp, the camera flash
// and every punctual light.
#include "common.wgsl"
#include "lights.wgsl"

@group(1) @binding(0) var gbuffer_albedo: texture_2d<f32>;
@group(1) @binding(1) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(2) var gbuffer_position: texture_2d<f32>;
// The detached headlamp's shadow map (reversed Z) and a bilinear GreaterEqual comparison.
@group(1) @binding(3) var lamp_depth: texture_depth_2d;
@group(1) @binding(4) var lamp_shadow: sampler_comparison;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    let texel = vec2i(in.position.xy);
    let normal = textureLoad(gbuffer_normal, texel, 0);
    if normal.w == 0.0 {
        return vec4f(0.0, 0.0, 0.0, 1.0);
    }
    let n = normal.xyz;
    let x = textureLoad(gbuffer_position, texel, 0).xyz;
    let rho = textureLoad(gbuffer_albedo, texel, 0).rgb;
    let e = headlamp_irradiance(lamp_depth, lamp_shadow, x, n) + flash_irradiance(x, n) + punctual_irradiance(x, n);
    return vec4f(rho / PI * e, 1.0);
}
