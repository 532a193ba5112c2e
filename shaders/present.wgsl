// Present pass: turns the chosen view into the output image — tonemapped for display and PNG,
// or raw linear values for EXR.
#include "common.wgsl"

struct PresentParams {
    // x: view (0 radiance, 1 albedo, 2 normal, 3 depth); y: 1 = write linear values;
    // z: 1 = encode sRGB in the shader (output format is not an sRGB format).
    mode: vec4u,
};

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

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    // Sources of another size than the output (the fixed-size lamp maps) are scaled to fit,
    // nearest texel; same-sized ones map texel to pixel.
    let scale = vec2f(textureDimensions(source)) * globals.viewport.zw;
    let value = textureLoad(source, vec2i(in.position.xy * scale), 0);
    let view = params.mode.x;
    if params.mode.y == 1u {
        // Linear: radiance, albedo, the unit normal, or depth in metres as stored.
        if view == 3u {
            return vec4f(vec3f(value.w), 1.0);
        }
        return vec4f(value.rgb, 1.0);
    }
    var c: vec3f;
    switch view {
        case 0u: { c = aces(value.rgb * globals.params.x); }
        case 1u: { c = value.rgb; }
        case 2u: { c = select(vec3f(0.0), value.xyz * 0.5 + 0.5, value.w > 0.0); }
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
