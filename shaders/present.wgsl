// Present pass: turns the chosen view into the output image — tonemapped for display and PNG,
// or raw linear values for EXR.
#include "common.wgsl"

struct PresentParams {
    // x: view (VIEW_*: radiance, albedo, normal, depth); y: 1 = write linear values; z: 1 =
    // encode sRGB in the shader (output format is not an sRGB format); w: 1 = upsample
    // bilinearly (a view rendered at a reduced render scale).
    mode: vec4u,
    // Output width, height, 1/width, 1/height.
    output: vec4f,
};

// PresentParams.mode.x: the view shown.
const VIEW_RADIANCE: u32 = 0u;
const VIEW_COLOR: u32 = 1u;
const VIEW_NORMAL: u32 = 2u;
const VIEW_DEPTH: u32 = 3u;

@group(1) @binding(0) var source: texture_2d<f32>;
@group(1) @binding(1) var<uniform> params: PresentParams;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

fn linear_to_srgb(c: vec3f) -> vec3f {
    let lo = c * 12.92;
    let hi = 1.055 * pow(c, vec3f(1.0 / 2.4)) - 0.055;
    return select(hi, lo, c <= vec3f(0.0031308));
}

// The source at `p` (texels, centres at +0.5) interpolated between its four nearest texels,
// edges clamped. By hand: sources may be unfilterable (Rgba32Float).
fn bilinear(p: vec2f) -> vec4f {
    let last = vec2i(textureDimensions(source)) - 1;
    let q = p - 0.5;
    let base = vec2i(floor(q));
    let f = q - floor(q);
    let t00 = textureLoad(source, clamp(base, vec2i(0), last), 0);
    let t10 = textureLoad(source, clamp(base + vec2i(1, 0), vec2i(0), last), 0);
    let t01 = textureLoad(source, clamp(base + vec2i(0, 1), vec2i(0), last), 0);
    let t11 = textureLoad(source, clamp(base + vec2i(1, 1), vec2i(0), last), 0);
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y);
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    // Sources of another size than the output (the fixed-size lamp maps, views rendered at a
    // reduced scale) are scaled to fit, nearest texel unless upsampling; same-sized ones map
    // texel to pixel.
    let scale = vec2f(textureDimensions(source)) * params.output.zw;
    var value: vec4f;
    if params.mode.w == 1u {
        value = bilinear(in.position.xy * scale);
    } else {
        value = textureLoad(source, vec2i(in.position.xy * scale), 0);
    }
    return shown(value);
}

// A view rendered at a reduced scale in a filterable format, upsampled by the sampler: the
// same bilinear weights as `bilinear`, in one sample (the layout binds `source` filterable).
@fragment
fn fs_upsample(in: FullscreenOut) -> @location(0) vec4f {
    return shown(textureSampleLevel(source, linear_clamp, in.position.xy * params.output.zw, 0.0));
}

// What the output holds for a source value: linear, or a picture of the view.
fn shown(value: vec4f) -> vec4f {
    let view = params.mode.x;
    if params.mode.y == 1u {
        // Linear: radiance, albedo, the unit normal, or depth in metres as stored.
        if view == VIEW_DEPTH {
            return vec4f(vec3f(value.w), 1.0);
        }
        return vec4f(value.rgb, 1.0);
    }
    var c: vec3f;
    switch view {
        case VIEW_RADIANCE: { c = aces(value.rgb * globals.params.x); }
        case VIEW_COLOR: { c = value.rgb; }
        case VIEW_NORMAL: { c = select(vec3f(0.0), value.xyz * 0.5 + 0.5, value.w > 0.0); }
        default: {
            // Depth: near is white, fading with distance (1 at 0 m, 0.5 at 5 m); sky black.
            c = select(vec3f(0.0), vec3f(1.0 / (1.0 + value.w / 5.0)), value.w > 0.0);
        }
    }
    if params.mode.z == 1u {
        c = linear_to_srgb(c);
    }
    return vec4f(c, 1.0);
}
