// GI composite pass: upsamples the irradiance target to full resolution with weights that
// respect geometry (depth and normal), turns it into indirect radiance L_i = ρ/π · E, writes
// it as the `indirect` view and adds it to the frame's HDR radiance.
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

struct CompositeOut {
    @location(0) indirect: vec4f,
    @location(1) hdr: vec4f,
};

@fragment
fn fs_main(in: FullscreenOut) -> CompositeOut {
    let p = vec2i(in.position.xy);
    var out: CompositeOut;
    let normal = textureLoad(gbuffer_normal, p, 0);
    if normal.w == 0.0 {
        return out;
    }
    let depth = textureLoad(gbuffer_position, p, 0).w;
    let full = vec2f(textureDimensions(gbuffer_normal));
    let low = vec2f(params.indirect_size);
    let scale = full / low;
    // Position in the low-resolution grid, and its four nearest samples.
    let q = in.position.xy / scale - 0.5;
    let base = vec2i(floor(q));
    let f = q - floor(q);
    var sum = vec3f(0.0);
    var total = 0.0;
    var nearest = vec3f(0.0);
    var nearest_err = 1e30;
    for (var i = 0; i < 4; i++) {
        let o = vec2i(i & 1, i >> 1u);
        let s = clamp(base + o, vec2i(0), vec2i(low) - 1);
        // The G-buffer texel the shading pass evaluated for sample s.
        let g = vec2i((vec2f(s) + 0.5) * scale);
        let sn = textureLoad(gbuffer_normal, g, 0);
        let sd = textureLoad(gbuffer_position, g, 0).w;
        let e = textureLoad(irradiance, s, 0).rgb;
        let bilinear = select(1.0 - f.x, f.x, o.x == 1) * select(1.0 - f.y, f.y, o.y == 1);
        let depth_err = abs(sd - depth) / max(depth, 1e-3);
        let geometric = select(0.0, pow(max(0.0, dot(sn.xyz, normal.xyz)), 8.0), sn.w > 0.0)
            * exp(-depth_err * 20.0);
        sum += e * bilinear * geometric;
        total += bilinear * geometric;
        let err = depth_err + (1.0 - dot(sn.xyz, normal.xyz));
        if sn.w > 0.0 && err < nearest_err {
            nearest_err = err;
            nearest = e;
        }
    }
    // Where no sample shares this surface, take the most similar one rather than bleed.
    let e = select(nearest, sum / total, total > 1e-4);
    let rho = textureLoad(gbuffer_albedo, p, 0).rgb;
    let radiance = rho / PI * e;
    out.indirect = vec4f(radiance, 1.0);
    out.hdr = vec4f(radiance, 1.0);
    return out;
}
