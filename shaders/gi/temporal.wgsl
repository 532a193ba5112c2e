// GI temporal pass: this frame's irradiance blended with last frame's, reprojected. The gather's
// lights live in screen space (the pyramid's quadtree and the tiles' cuts are laid over the
// view), so as the view moves its small errors move with it; averaging each receiver's world
// point over frames holds them still. Last frame's sample is taken where the receiver's world
// point was (bilinear over the four samples about it, each kept only if it lay on the same
// surface: depth within DEPTH_TOLERANCE, normal within NORMAL_COS); where none was (a
// disocclusion) the frame starts afresh. History whose lighting changed is pulled into the
// range this frame's 3×3 neighbourhood on the same surface spans, widened by
// `temporal.slack`: a light switched off or an object moved out of the beam leaves no trail.
#include "common.wgsl"
#include "gi_common.wgsl"

struct TemporalParams {
    // Last frame's view-projection: where a world point was on screen.
    previous_view_proj: mat4x4f,
    // Last frame's GiParams.receiver_offset: where last frame's samples lay.
    previous_offset: vec2f,
    // The weight of this frame's irradiance (1: none of the history's).
    current_weight: f32,
    // How far history may lie outside this frame's neighbourhood, relative.
    slack: f32,
    // 1 when `history` holds last frame's irradiance.
    has_history: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
};

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var<uniform> temporal: TemporalParams;
@group(1) @binding(2) var current: texture_2d<f32>;
@group(1) @binding(3) var history: texture_2d<f32>;
@group(1) @binding(4) var gbuffer_position: texture_2d<f32>;
@group(1) @binding(5) var blended: texture_storage_2d<rgba32float, write>;
// Where each receiver was evaluated, as the cuts pass found it (receivers.wgsl).
@group(1) @binding(6) var<storage, read> receiver_texels: array<u32>;

// Relative view-depth difference within which a sample lies on the same surface.
const DEPTH_TOLERANCE: f32 = 0.05;
// cos 25°: normals closer than this belong to one surface.
const NORMAL_COS: f32 = 0.9;

fn same_surface(packed: f32, depth: f32, n: vec3f) -> bool {
    return bitcast<u32>(packed) != 0u
        && abs(receiver_depth(packed) - depth) < DEPTH_TOLERANCE * depth
        && dot(receiver_normal(packed), n) > NORMAL_COS;
}

// Last frame's irradiance at world point x (normal n), or w = 0 where it had none there. The
// receiver was evaluated `offset` pixels from its cell's centre (receivers.wgsl): its history
// is looked up as far from where x was, so a still view lands on its own sample.
fn reprojected(x: vec3f, n: vec3f, full: vec2f, low: vec2i, offset: vec2f) -> vec4f {
    let clip = temporal.previous_view_proj * vec4f(x, 1.0);
    if clip.w <= 1e-4 {
        return vec4f(0.0);
    }
    let ndc = clip.xy / clip.w;
    let pixel = vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * full - offset;
    // The samples about it, and its place between them, as the composite finds them, so a
    // still view takes each sample's own history.
    let place = sample_place(pixel, vec2u(full), vec2u(low), temporal.previous_offset);
    let base = place.base;
    var f = place.f;
    // On a sample to rounding (a still view): that sample alone, so nothing drifts.
    f = select(f, round(f), abs(f - round(f)) < vec2f(1e-3));
    if any(f < vec2f(-0.5)) || any(f > vec2f(1.5)) {
        return vec4f(0.0);
    }
    var sum = vec3f(0.0);
    var total = 0.0;
    for (var i = 0; i < 4; i++) {
        let o = vec2i(i & 1, i >> 1u);
        let s = base + o;
        if any(s < vec2i(0)) || any(s >= low) {
            continue;
        }
        let h = textureLoad(history, s, 0);
        // For a perspective projection clip.w is the point's view depth last frame.
        if !same_surface(h.w, clip.w, n) {
            continue;
        }
        let fc = clamp(f, vec2f(0.0), vec2f(1.0));
        let w = select(1.0 - fc.x, fc.x, o.x == 1) * select(1.0 - fc.y, fc.y, o.y == 1);
        sum += h.rgb * w;
        total += w;
    }
    // Less than a quarter of the bilinear weight on the surface: too little to trust.
    if total < 0.25 {
        return vec4f(0.0);
    }
    return vec4f(sum / total, 1.0);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let low = vec2i(params.indirect_size);
    let q = vec2i(id.xy);
    if any(q >= low) {
        return;
    }
    let c = textureLoad(current, q, 0);
    if bitcast<u32>(c.w) == 0u || temporal.has_history == 0u || temporal.current_weight >= 1.0 {
        textureStore(blended, q, c);
        return;
    }
    let full = vec2f(textureDimensions(gbuffer_position));
    let at = unpack_texel(receiver_texels[u32(q.y * low.x + q.x)]);
    let x = textureLoad(gbuffer_position, at, 0).xyz;
    let depth = receiver_depth(c.w);
    let n = receiver_normal(c.w);
    let previous = reprojected(x, n, full, low, vec2f(at - receiver_texel(vec2u(q), vec2u(full), vec2u(low), params.receiver_offset)));
    if previous.w == 0.0 {
        textureStore(blended, q, c);
        return;
    }
    // This frame's range on the receiver's surface.
    var lo = c.rgb;
    var hi = c.rgb;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let s = q + vec2i(dx, dy);
            if any(s < vec2i(0)) || any(s >= low) {
                continue;
            }
            let v = textureLoad(current, s, 0);
            if same_surface(v.w, depth, n) {
                lo = min(lo, v.rgb);
                hi = max(hi, v.rgb);
            }
        }
    }
    let slack = temporal.slack;
    let kept = clamp(previous.rgb, lo * (1.0 - slack), hi * (1.0 + slack));
    // (Not mix(): history equal to this frame must give this frame exactly.)
    textureStore(blended, q, vec4f(kept + (c.rgb - kept) * temporal.current_weight, c.w));
}
