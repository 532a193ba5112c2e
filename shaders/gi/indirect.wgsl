// GI composite: the indirect radiance of each full-resolution pixel from the irradiance
// target: geometry-aware upsampling of E (depth and normal weights against the four nearest
// samples), then L_i = ρ/π · E. Two passes draw it: `gi_composite` adds it to the frame's HDR
// radiance (additive blending) and `gi_indirect_view` writes it alone for the `indirect` view,
// only when something shows that. The target's alpha holds each sample's depth and normal
// (`pack_receiver`), so nothing else is looked up for it.
#include "common.wgsl"
#include "gi_common.wgsl"

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var irradiance: texture_2d<f32>;
@group(1) @binding(2) var gbuffer_albedo: texture_2d<f32>;
@group(1) @binding(3) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(4) var gbuffer_position: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

// L_i at pixel p; w = 0 where there is no geometry.
fn indirect_radiance(p: vec2i) -> vec4f {
    let normal = textureLoad(gbuffer_normal, p, 0);
    if normal.w == 0.0 {
        return vec4f(0.0);
    }
    let depth = textureLoad(gbuffer_position, p, 0).w;
    let full = textureDimensions(gbuffer_normal);
    let low = vec2f(params.indirect_size);
    // The two samples on either side of p along each axis, and p's place between them.
    let place = sample_place(vec2f(p) + 0.5, full, params.indirect_size);
    let base = place.base;
    let f = clamp(place.f, vec2f(0.0), vec2f(1.0));
    var sum = vec3f(0.0);
    var total = 0.0;
    var nearest = vec3f(0.0);
    var nearest_err = 1e30;
    for (var i = 0; i < 4; i++) {
        let o = vec2i(i & 1, i >> 1u);
        let s = clamp(base + o, vec2i(0), vec2i(low) - 1);
        let sample = textureLoad(irradiance, s, 0);
        // The depth and normal of the G-buffer texel the gather evaluated for sample s.
        let surface = bitcast<u32>(sample.w) != 0u;
        let sn = receiver_normal(sample.w);
        let bilinear = select(1.0 - f.x, f.x, o.x == 1) * select(1.0 - f.y, f.y, o.y == 1);
        let depth_err = abs(receiver_depth(sample.w) - depth) / max(depth, 1e-3);
        let facing = max(0.0, dot(sn, normal.xyz));
        let facing2 = facing * facing;
        let facing4 = facing2 * facing2;
        let geometric = select(0.0, facing4 * facing4, surface) * exp(-depth_err * 20.0);
        sum += sample.rgb * bilinear * geometric;
        total += bilinear * geometric;
        let err = depth_err + (1.0 - dot(sn, normal.xyz));
        if surface && err < nearest_err {
            nearest_err = err;
            nearest = sample.rgb;
        }
    }
    // Where no sample shares this surface, take the most similar one rather than bleed.
    let e = select(nearest, sum / total, total > 1e-4);
    let rho = textureLoad(gbuffer_albedo, p, 0).rgb;
    return vec4f(rho / PI * e, 1.0);
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    return indirect_radiance(vec2i(in.position.xy));
}
