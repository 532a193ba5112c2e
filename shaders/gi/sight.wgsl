// GI sight: which of each tile's lights nine of its receivers see (its corners, the middles
// of its edges and its centre), so the sum can stop light that a surface between would stop
// (no light through walls). One workgroup a tile, after the cuts: every light of the cut (its
// classes' slots and its near list) is tested along the segments to those receivers
// (visibility.wgsl) and gets nine bits. The sum weighs a light's irradiance at each receiver
// by them, bilinearly within the quarter of the tile it lies in: at most nine marches a light
// and tile instead of one for every receiver that evaluates it.
#include "common.wgsl"
#include "gi_common.wgsl"

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var<uniform> table: Levels;
@group(1) @binding(2) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(3) var gbuffer_position: texture_2d<f32>;
// The cuts, and after them the sight bits this pass writes (`sight_start`): which of the nine
// receivers see the light in each slot (`points_seeing`).
@group(1) @binding(4) var<storage, read_write> cuts: array<vec4u>;
@group(1) @binding(5) var<storage, read> receiver_texels: array<u32>;
// The view depth to march, at half the G-buffer's size (sight_depth.wgsl).
@group(1) @binding(6) var sight_depth: texture_2d<f32>;

#include "visibility.wgsl"

// The corners among them (point i = x + 3y, bit i of `points_seeing`), and the points
// between them.
const CORNER_POINTS = array<u32, 4>(0u, 2u, 6u, 8u);
const CORNERS: u32 = 0x145u;
const BETWEEN_POINTS = array<u32, 5>(1u, 3u, 4u, 5u, 7u);
const BETWEEN: u32 = 0x0bau;

// Those receivers in clip space (`globals.view_proj`), w 0 where there is no surface.
var<workgroup> points: array<vec4f, 9>;

// Point i's answer for a light at `light` (clip space): its bit where it sees it (x) and
// where it has a surface to be asked (y).
fn point_sees(i: u32, light: vec4f) -> vec2u {
    let c = points[i];
    if c.w <= 0.0 {
        return vec2u(0u);
    }
    return vec2u(u32(clip_segment_seen(c, light)), 1u) << vec2u(i);
}

// Which of the points see the light at p (bit i for point i): the corners first, the others
// only where the corners disagree (where they agree, a surface between would be narrower
// than the tile: the others take their answer). A point without a surface sees it where
// another point does (or where none has a surface).
fn points_seeing(p: vec3f) -> u32 {
    let light = globals.view_proj * vec4f(p, 1.0);
    var answer = vec2u(0u);
    for (var k = 0u; k < 4u; k++) {
        answer |= point_sees(CORNER_POINTS[k], light);
    }
    var seen = answer.x;
    var valid = answer.y;
    let corners = seen & valid & CORNERS;
    if corners == 0u || corners == (valid & CORNERS) {
        valid |= BETWEEN;
        seen |= select(0u, BETWEEN, corners != 0u);
    } else {
        for (var k = 0u; k < 5u; k++) {
            answer |= point_sees(BETWEEN_POINTS[k], light);
        }
        seen = answer.x;
        valid = answer.y;
    }
    let others = select(0u, 511u, seen != 0u || valid == 0u);
    return seen | (others & ~valid & 511u);
}

@compute @workgroup_size(64)
fn main(@builtin(local_invocation_index) i: u32, @builtin(workgroup_id) group: vec3u) {
    if i < 9u {
        let at = vec2u(SIGHT_AT[i % 3u], SIGHT_AT[i / 3u]);
        let q = min(group.xy * CUT_TILE + at, params.indirect_size - 1u);
        let g = unpack_texel(receiver_texels[q.y * params.indirect_size.x + q.x]);
        let valid = textureLoad(gbuffer_normal, g, 0).w > 0.0;
        let clip = globals.view_proj * vec4f(textureLoad(gbuffer_position, g, 0).xyz, 1.0);
        points[i] = select(vec4f(0.0), clip, valid);
    }
    workgroupBarrier();
    let top_level = table.levels[PYRAMID_LEVELS - 1u];
    let cut = tile_cut(group.xy, params.indirect_size, top_level);
    let start = sight_start(params.indirect_size, top_level);
    let base = cut.x;
    let stride = cut.y;
    let counts = cuts[base].xz;
    let centre = bitcast<vec3f>(cuts[base + 1u].xyz);
    for (var k = i; k < counts.x; k += 64u) {
        let slot = base + 2u + k;
        let word = start + slot;
        cuts[word / 4u][word % 4u] = points_seeing(unpack_cut_light(cuts[slot], centre).position);
    }
    for (var k = i; k < counts.y; k += 64u) {
        let slot = near_slot(base, stride, k);
        let word = start + slot;
        cuts[word / 4u][word % 4u] = points_seeing(unpack_cut_light(cuts[slot], centre).position);
    }
}
