// GI sight: which of each tile's lights nine of its receivers see (its corners, the middles
// of its edges and its centre), so the sum can stop light that a surface between would stop
// (no light through walls). One workgroup a tile, after the cuts: every light of the cut (its
// classes' slots and its near list) is tested along the segments to those receivers
// (visibility.wgsl) and gets nine bits. The sum weighs a light's irradiance at each receiver
// by them, bilinearly within the quarter of the tile it lies in: at most nine marches a light
// and tile instead of one for every receiver that evaluates it. With WORLD (`gi.world_sight`
// 1) a segment the screen cannot vouch for (off the screen, or behind what the camera sees)
// is marched through the level's surfaces as voxels (world_sight.wgsl), which sees walls the
// camera does not; what moves (crawlers, the thrown lamp) is in the screen's depth only.
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
// The level's surfaces as voxels (plugin_gi/src/world_grid.rs).
@group(2) @binding(0) var<uniform> world: WorldGrid;
@group(2) @binding(1) var<storage, read> world_bits: array<u32>;
@group(2) @binding(2) var<storage, read> world_distances: array<u32>;

#include "visibility.wgsl"
#include "world_sight.wgsl"

// Whether segments are also marched through the level's voxels (`gi.visibility` 2).
override WORLD: bool = false;
// A segment's ends leave their surfaces along their normals by this many voxels, and the
// march leaves out as many at each end: the voxels of the surfaces they lie on.
const WORLD_LIFT: f32 = 1.5;

// Point i = x + 3y, bit i of `points_seeing`: the corners, and the points between them.
const CORNERS: u32 = 0x145u;
const BETWEEN: u32 = 0x0bau;

// Those receivers in clip space (`globals.view_proj`), w 0 where there is no surface, and in
// the world, lifted off their surfaces (WORLD_LIFT).
var<workgroup> points: array<vec4f, 9>;
var<workgroup> world_points: array<vec3f, 9>;

// Point i's answer for a light at `light` (clip space; lifted off its surface in the world,
// `lifted`): its bit where it sees it (x) and where it has a surface to be asked (y).
fn point_sees(i: u32, light: vec4f, lifted: vec3f) -> vec2u {
    let c = points[i];
    if c.w <= 0.0 {
        return vec2u(0u);
    }
    // Where the screen cannot tell, the level's voxels do.
    let screen = clip_segment_sight(c, light);
    var seen = screen.sight != SIGHT_BLOCKED;
    if WORLD && screen.sight == SIGHT_UNKNOWN {
        seen = world_segment_clear(world_points[i], lifted, WORLD_LIFT * world.voxel, screen.unknown);
    }
    return vec2u(u32(seen), 1u) << vec2u(i);
}

// The points between two corners (bits of point 1, 3, 5 and 7), each with its corners.
const EDGES = array<vec3u, 4>(vec3u(1u, 0u, 2u), vec3u(3u, 0u, 6u), vec3u(5u, 2u, 8u), vec3u(7u, 6u, 8u));
const CENTRE: u32 = 4u;

// Which of the points see the light at p (bit i for point i): the corners first. Where they
// agree, a surface between would be narrower than the tile: the others take their answer.
// Where they disagree, the centre is asked, and each point between two corners that do not
// agree (or do not both have a surface); the others take their corners' answer. A point
// without a surface sees it where another point does (or where none has a surface). (One
// loop, whose length is known only once the corners have answered, so that a CPU device's
// compiler makes one copy of the marches, not one for each point.)
fn points_seeing(l: CutLight) -> u32 {
    let light = globals.view_proj * vec4f(l.position, 1.0);
    let lifted = l.position + l.normal * (WORLD_LIFT * world.voxel);
    var answer = vec2u(0u);
    var pending = CORNERS;
    var corners_asked = false;
    loop {
        if pending == 0u {
            if corners_asked {
                break;
            }
            corners_asked = true;
            let valid = answer.y & CORNERS;
            let seen = answer.x & valid;
            if seen == 0u || seen == valid {
                // They agree: the points between take their answer.
                answer.y |= BETWEEN;
                answer.x |= select(0u, BETWEEN, seen != 0u);
                break;
            }
            pending = 1u << CENTRE;
            for (var e = 0u; e < 4u; e++) {
                let edge = EDGES[e];
                let ends = (1u << edge.y) | (1u << edge.z);
                let agree = (valid & ends) == ends && ((seen & ends) == 0u || (seen & ends) == ends);
                if agree {
                    answer.y |= 1u << edge.x;
                    answer.x |= select(0u, 1u << edge.x, (seen & ends) != 0u);
                } else {
                    pending |= 1u << edge.x;
                }
            }
        }
        let p = firstTrailingBit(pending);
        pending &= pending - 1u;
        answer |= point_sees(p, light, lifted);
    }
    let seen = answer.x;
    let valid = answer.y;
    let others = select(0u, 511u, seen != 0u || valid == 0u);
    return seen | (others & ~valid & 511u);
}

@compute @workgroup_size(64)
fn main(@builtin(local_invocation_index) i: u32, @builtin(workgroup_id) group: vec3u) {
    if i < 9u {
        let at = vec2u(SIGHT_AT[i % 3u], SIGHT_AT[i / 3u]);
        let q = min(group.xy * CUT_TILE + at, params.indirect_size - 1u);
        let g = unpack_texel(receiver_texels[q.y * params.indirect_size.x + q.x]);
        let normal = textureLoad(gbuffer_normal, g, 0);
        let valid = normal.w > 0.0;
        let x = textureLoad(gbuffer_position, g, 0).xyz;
        points[i] = select(vec4f(0.0), globals.view_proj * vec4f(x, 1.0), valid);
        world_points[i] = x + normal.xyz * (WORLD_LIFT * world.voxel);
    }
    workgroupBarrier();
    let top_level = table.levels[PYRAMID_LEVELS - 1u];
    let cut = tile_cut(group.xy, params.indirect_size, top_level);
    let start = sight_start(params.indirect_size, top_level);
    let base = cut.x;
    let stride = cut.y;
    let counts = cuts[base].xz;
    let centre = bitcast<vec3f>(cuts[base + 1u].xyz);
    // The classes' slots, then the near list.
    for (var k = i; k < counts.x + counts.y; k += 64u) {
        let slot = select(near_slot(base, stride, k - counts.x), base + 2u + k, k < counts.x);
        let word = start + slot;
        cuts[word / 4u][word % 4u] = points_seeing(unpack_cut_light(cuts[slot], centre));
    }
}
