// GI world sight: whether the segment between two points crosses a surface of the level,
// wherever it runs, seen by the camera or not: a march through the level's surfaces as voxels
// (the occupancy crate, whose `Occupancy::segment_clear` is this march on the CPU). Through
// blocks of 4×4×4 voxels that hold nothing it moves a cube of them at a time, as far as the
// block's distance to the nearest block with a surface says is empty; through the others a
// voxel at a time. Every voxel a triangle touches is marked, so a segment that crosses a wall
// of any thickness meets one. Included by the sight pass, which declares `world` (WorldGrid),
// `world_bits` and `world_distances`.

// A level's grid: its lowest corner and voxel side (metres), its size in blocks.
struct WorldGrid {
    origin: vec3f,
    voxel: f32,
    blocks: vec3u,
    pad: u32,
};

// Voxels along a block's side (occupancy::BLOCK).
const WORLD_BLOCK: u32 = 4u;
// Most steps of one march (occupancy::MAX_STEPS); a segment that needs more counts as clear.
const WORLD_MAX_STEPS: u32 = 256u;
// How far past a boundary a step lands, in voxels.
const WORLD_NUDGE: f32 = 1e-3;

fn world_block_index(block: vec3u) -> u32 {
    return block.x + world.blocks.x * (block.y + world.blocks.y * block.z);
}

// Whether voxel v holds a surface.
fn world_solid(v: vec3u) -> bool {
    let local = v % WORLD_BLOCK;
    let bit = local.x + WORLD_BLOCK * (local.y + WORLD_BLOCK * local.z);
    let index = world_block_index(v / WORLD_BLOCK) * 2u + bit / 32u;
    return ((world_bits[index] >> (bit % 32u)) & 1u) == 1u;
}

// The Chebyshev distance in blocks from `block` to the nearest block with a surface (0: it
// has one), four to a word.
fn world_block_distance(block: vec3u) -> u32 {
    let index = world_block_index(block);
    return (world_distances[index / 4u] >> (8u * (index % 4u))) & 255u;
}

// When the line a + d·t leaves the box [lo, hi] it is in (along no axis where d is 0).
fn world_box_exit(a: vec3f, d: vec3f, lo: vec3f, hi: vec3f) -> f32 {
    let still = d == vec3f(0.0);
    let bound = select(lo, hi, d > vec3f(0.0));
    let t = select((bound - a) / select(d, vec3f(1.0), still), vec3f(3.4e38), still);
    return min(t.x, min(t.y, t.z));
}

// Whether the part `span` (fractions of the way from a to b) of the segment from a to b
// (world space, metres) crosses no surface, leaving out the first and last `skip` metres of
// the whole (the surfaces its ends lie on). (It returns at its end only: lavapipe's compiler
// fails on a return from within this function as the sight pass inlines it.)
fn world_segment_clear(a_world: vec3f, b_world: vec3f, skip_world: f32, span: vec2f) -> bool {
    let a = (a_world - world.origin) / world.voxel;
    let d = (b_world - world.origin) / world.voxel - a;
    let length = length(d);
    let skip = skip_world / world.voxel;
    let size = vec3f(world.blocks * WORLD_BLOCK);
    // The part of the segment inside the grid, less the skipped ends; a segment parallel to
    // a side and outside the grid misses it.
    let still = d == vec3f(0.0);
    let safe = select(d, vec3f(1.0), still);
    let t0 = (vec3f(0.0) - a) / safe;
    let t1 = (size - a) / safe;
    let enter = select(min(t0, t1), vec3f(-3.4e38), still);
    let leave = select(max(t0, t1), vec3f(3.4e38), still);
    var t = max(max(skip / length, span.x), max(enter.x, max(enter.y, enter.z)));
    var end = min(min(1.0 - skip / length, span.y), min(leave.x, min(leave.y, leave.z)));
    if length <= 2.0 * skip || any(still & ((a < vec3f(0.0)) | (a >= size))) {
        end = t;
    }
    let nudge = WORLD_NUDGE / length;
    var hit = false;
    for (var step = 0u; step < WORLD_MAX_STEPS && t < end && !hit; step++) {
        let p = clamp(a + d * t, vec3f(0.0), size - WORLD_NUDGE);
        let block = floor(p / f32(WORLD_BLOCK));
        let distance = world_block_distance(vec3u(block));
        var lo: vec3f;
        var hi: vec3f;
        if distance > 0u {
            // The cube of blocks around this one that holds nothing.
            let r = f32(distance);
            lo = (block - (r - 1.0)) * f32(WORLD_BLOCK);
            hi = (block + r) * f32(WORLD_BLOCK);
        } else {
            let voxel = floor(p);
            hit = world_solid(vec3u(voxel));
            lo = voxel;
            hi = voxel + 1.0;
        }
        t = world_box_exit(a, d, lo, hi) + nudge;
    }
    return !hit;
}
