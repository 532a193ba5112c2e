// GI composite: the indirect radiance of each full-resolution pixel from the irradiance
// target: geometry-aware upsampling of E (depth and normal weights against the four nearest
// samples), then L_i = ρ/π · E. Two passes draw it: `gi_composite` (fs_frame) makes the frame's
// HDR radiance, direct + emissive + L_i, in place of the engine's composite, and
// `gi_indirect_view` (fs_indirect) writes L_i alone for the `indirect` view, only when
// something shows that. The target's alpha holds each sample's depth and normal
// (`pack_receiver`), so nothing else is looked up for it.
#include "common.wgsl"
#include "gi_common.wgsl"

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var irradiance: texture_2d<f32>;
@group(1) @binding(2) var gbuffer_albedo: texture_2d<f32>;
@group(1) @binding(3) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(4) var gbuffer_position: texture_2d<f32>;
// fs_frame only: the engine composite's inputs.
@group(1) @binding(5) var direct_radiance: texture_2d<f32>;
@group(1) @binding(6) var gbuffer_emissive: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

// Sample s of the irradiance target (of `low` samples), clamped to its edge.
fn sample_at(s: vec2i, low: vec2i) -> vec4f {
    return textureLoad(irradiance, clamp(s, vec2i(0), low - 1), 0);
}

// A sample's irradiance (rgb) and how much it shares the surface of a pixel with normal n at
// view depth `depth` (w: normal and depth weights, 0 where it has no surface).
fn on_surface(sample: vec4f, n: vec3f, depth: f32) -> vec4f {
    let depth_err = abs(receiver_depth(sample.w) - depth) / max(depth, 1e-3);
    let facing = max(0.0, dot(receiver_normal(sample.w), n));
    let facing2 = facing * facing;
    let facing4 = facing2 * facing2;
    let surface = bitcast<u32>(sample.w) != 0u;
    return vec4f(sample.rgb, select(0.0, facing4 * facing4, surface) * exp(-depth_err * 20.0));
}

// L_i at pixel p; w = 0 where there is no geometry.
fn indirect_radiance(p: vec2i) -> vec4f {
    let normal = textureLoad(gbuffer_normal, p, 0);
    if normal.w == 0.0 {
        return vec4f(0.0);
    }
    let depth = textureLoad(gbuffer_position, p, 0).w;
    let full = textureDimensions(gbuffer_normal);
    let low = vec2i(params.indirect_size);
    // The two samples on either side of p along each axis, and p's place between them.
    let place = sample_place(vec2f(p) + 0.5, full, params.indirect_size, params.receiver_offset);
    let base = place.base;
    let f = clamp(place.f, vec2f(0.0), vec2f(1.0));
    var sum = vec3f(0.0);
    var total = 0.0;
    // (Kept for the last resort below, which a CPU device runs for every pixel of a SIMD row
    // that has one needing it: loading them again cost a tenth of the pass.)
    var four: array<vec4f, 4>;
    for (var i = 0; i < 4; i++) {
        let o = vec2i(i & 1, i >> 1u);
        let bilinear = select(1.0 - f.x, f.x, o.x == 1) * select(1.0 - f.y, f.y, o.y == 1);
        four[i] = sample_at(base + o, low);
        let s = on_surface(four[i], normal.xyz, depth);
        sum += s.rgb * bilinear * s.w;
        total += bilinear * s.w;
    }
    // Where none of the four shares this surface (a strip narrower than the samples' spacing,
    // the near side of a depth step), the ring of twelve around them, tent-weighted by
    // distance, rather than a sample of another surface, which pulled the wall's light onto
    // a door's jamb in the frames where no sample fell on the jamb.
    if total <= 1e-4 {
        for (var i = 0; i < 16; i++) {
            let o = vec2i(i & 3, i >> 2u) - 1;
            if all(o >= vec2i(0)) && all(o <= vec2i(1)) {
                continue;
            }
            let t = max(vec2f(0.0), 1.0 - abs(vec2f(o) - f) * 0.5);
            let s = on_surface(sample_at(base + o, low), normal.xyz, depth);
            sum += s.rgb * t.x * t.y * s.w;
            total += t.x * t.y * s.w;
        }
    }
    var e = sum / max(total, 1e-30);
    if total <= 1e-6 {
        // Nothing near on this surface: the most similar of the four.
        var nearest_err = 1e30;
        for (var i = 0; i < 4; i++) {
            let sample = four[i];
            if bitcast<u32>(sample.w) != 0u {
                let err = abs(receiver_depth(sample.w) - depth) / max(depth, 1e-3) + (1.0 - dot(receiver_normal(sample.w), normal.xyz));
                if err < nearest_err {
                    nearest_err = err;
                    e = sample.rgb;
                }
            }
        }
    }
    let rho = textureLoad(gbuffer_albedo, p, 0).rgb;
    return vec4f(rho / PI * e, 1.0);
}

@fragment
fn fs_frame(in: FullscreenOut) -> @location(0) vec4f {
    let p = vec2i(in.position.xy);
    let frame = textureLoad(direct_radiance, p, 0).rgb + textureLoad(gbuffer_emissive, p, 0).rgb;
    return vec4f(frame + indirect_radiance(p).rgb, 1.0);
}

@fragment
fn fs_indirect(in: FullscreenOut) -> @location(0) vec4f {
    return indirect_radiance(vec2i(in.position.xy));
}
