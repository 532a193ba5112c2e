// GI lights view: the tonemapped frame with every reflection light drawn as a dot, coloured by
// the mip level it came from (white: one texel … red: coarsest).
#include "common.wgsl"
#include "gi_common.wgsl"

@group(1) @binding(0) var<storage, read> reflection_lights: array<ReflectionLight>;
@group(1) @binding(1) var frame: texture_2d<f32>;

struct DotOut {
    @builtin(position) clip: vec4f,
    @location(0) color: vec3f,
};

const LEVEL_COLORS = array<vec3f, 8>(
    vec3f(1.0, 1.0, 1.0), vec3f(0.3, 0.6, 1.0), vec3f(0.2, 1.0, 1.0), vec3f(0.2, 1.0, 0.3),
    vec3f(1.0, 1.0, 0.2), vec3f(1.0, 0.6, 0.1), vec3f(1.0, 0.2, 0.2), vec3f(1.0, 0.2, 1.0),
);

@vertex
fn vs_dot(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> DotOut {
    let light = reflection_lights[i];
    var clip = globals.view_proj * vec4f(light.position, 1.0);
    // A 3×3-pixel square around the projected light (two triangles).
    let corners = array<vec2f, 6>(vec2f(-1.0, -1.0), vec2f(1.0, -1.0), vec2f(1.0, 1.0), vec2f(-1.0, -1.0), vec2f(1.0, 1.0), vec2f(-1.0, 1.0));
    clip = vec4f(clip.xy + corners[v % 6u] * 1.5 * globals.viewport.zw * 2.0 * clip.w, clip.zw);
    var out: DotOut;
    // Only the first six vertices of each instance make the square; lights behind the camera
    // and the remaining vertices collapse to nothing.
    out.clip = select(vec4f(0.0), clip, v < 6u && clip.w > 0.0);
    out.color = LEVEL_COLORS[min(light.level, 7u)];
    return out;
}

@fragment
fn fs_dot(in: DotOut) -> @location(0) vec4f {
    return vec4f(in.color, 1.0);
}

@vertex
fn vs_frame(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

// The frame underneath, tonemapped as the present pass does (kept linear: the output is sRGB).
@fragment
fn fs_frame(in: FullscreenOut) -> @location(0) vec4f {
    let c = textureLoad(frame, vec2i(in.position.xy), 0).rgb;
    return vec4f(aces(c * globals.params.x) * 0.6, 1.0);
}
