// GI cuts pass: for each 8×8 tile of receivers, the cut through the flux pyramid that the
// gather sums. A light is split into its four children while it is large against its distance
// to the tile (extent > split_ratio × gap), so near light comes from fine lights and far light
// from coarse ones; every light carries all the flux of the texels below it and the cut covers
// each lit texel once, so no energy is lost. A light whose plane faces away from every
// receiver of the tile belongs to the cut (it is counted, and the `lights` view shows it) but
// is not stored for the sum, as it gives them nothing.
//
// One invocation builds one tile's cut, walking the quadtree depth first without a stack (the
// tree is implicit: a node's children and siblings follow from its level and place). On a CPU
// device a SIMD row of invocations then walks eight neighbouring tiles in step, with no
// barriers, and the order is deterministic. Each light's interleaved class (for the gather)
// follows from its place in the tree (see `walk`). The few tiles whose cut fills up are listed
// and walked again by a second, indirect dispatch (`retry_full_tiles`), packed side by side.
//
// Per tile, `cuts` holds the counts (class slots, facing away, near), the tile's centre
// (the stored positions are relative to it), then the evaluated lights, one vec4 each (see
// gi_common.wgsl): the interleaved classes from the start, the near list from the end. The
// tile at the centre of the view also writes its whole cut, those facing away included, to
// `centre_lights` for the `lights` view.
#include "common.wgsl"
#include "gi_common.wgsl"
#include "receivers.wgsl"

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var<uniform> table: Levels;
@group(1) @binding(2) var<storage, read> nodes: array<Node>;
@group(1) @binding(3) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(4) var gbuffer_position: texture_2d<f32>;
@group(1) @binding(5) var<storage, read_write> cuts: array<vec4u>;
@group(1) @binding(6) var<storage, read_write> stats: Stats;
@group(1) @binding(7) var<storage, read_write> centre_lights: array<ReflectionLight>;

// A tile's bounds: centre and radius of a sphere holding its receivers, their mean normal and
// the largest distance from the mean plane; `count` = 0 when the tile has none.
struct TileBounds {
    sphere: vec4f,
    plane: vec4f,
    count: u32,
    // The same sphere for each 4×4 quarter of the tile (radius < 0 where it has none), for
    // the near list, which a sphere around the whole tile would fill with lights that lie
    // between its surfaces (across a fold or a depth step) but near none of them.
    quarters: array<vec4f, 4>,
    // The receivers in LAYERS slices of view depth (equal steps of log depth between the
    // tile's nearest and farthest), each as a sphere (radius < 0 where a slice has none),
    // for the distance from a light to the tile (`layer_gap`). Across a doorway or along a
    // wall receding from the view the tile's sphere is metres wide and mostly empty: every
    // light in it counted as touching a receiver and was split to the finest level, the cut
    // overflowed, and the retry made the whole cut coarse, the lights next to the receivers
    // too (a lintel's underside by the jamb went 30 % dark in the frames its tile overflowed,
    // and that tile changed as the pan slid the door across the tiles).
    layers: array<vec4f, LAYERS>,
};

const LAYERS: u32 = 4u;
// Tiles whose farthest receiver is less than this many times as far as the nearest keep one
// slice (their sphere): there the slices gain nothing and would only make the cut coarser.
const DEPTH_STEP: f32 = 1.5;

// The depth slice of a receiver at view depth `depth` (see TileBounds.layers).
fn layer_of(depth: f32, nearest: f32, scale: f32) -> u32 {
    return min(u32(max(log(depth / max(nearest, 1e-6)) * scale, 0.0)), LAYERS - 1u);
}

fn quarter(i: u32) -> u32 {
    return u32((i % CUT_TILE) >= CUT_TILE / 2u) + 2u * u32((i / CUT_TILE) >= CUT_TILE / 2u);
}

// (`recorded`: the tile's receivers as `main` recorded them in `receiver_texels`; otherwise
// found and recorded.)
fn tile_bounds(origin: vec2u, recorded: bool) -> TileBounds {
    var b: TileBounds;
    let view = textureDimensions(gbuffer_normal);
    // The tile's receivers where the gather evaluates them: position and view depth (w < 0
    // where there is none).
    var points: array<vec4f, 64>;
    var centre = vec3f(0.0);
    var normal = vec3f(0.0);
    var count = 0u;
    var quarters: array<vec4f, 4>;
    var depths = vec2f(1e30, 0.0);
    for (var i = 0u; i < CUT_TILE * CUT_TILE; i++) {
        points[i] = vec4f(0.0, 0.0, 0.0, -1.0);
        let q = origin + vec2u(i % CUT_TILE, i / CUT_TILE);
        if all(q < params.indirect_size) {
            let slot = q.y * params.indirect_size.x + q.x;
            var s: SurfacePoint;
            if recorded {
                s = surface_point(unpack_texel(receiver_texels[slot]));
            } else {
                // (What it found the texel by is what the G-buffer holds there.)
                let r = receiver_at(q, view, params.indirect_size);
                receiver_texels[slot] = pack_texel(r.texel);
                s = r.surface;
            }
            if s.valid {
                let x = vec4f(s.x, s.depth);
                points[i] = x;
                centre += x.xyz;
                normal += s.n;
                count++;
                quarters[quarter(i)] += vec4f(x.xyz, 1.0);
                depths = vec2f(min(depths.x, x.w), max(depths.y, x.w));
            }
        }
    }
    let span = depths.y / max(depths.x, 1e-6);
    let depth_scale = select(0.0, f32(LAYERS) / log(span), span > DEPTH_STEP);
    var layers: array<vec4f, LAYERS>;
    for (var i = 0u; i < CUT_TILE * CUT_TILE; i++) {
        if points[i].w >= 0.0 {
            layers[layer_of(points[i].w, depths.x, depth_scale)] += vec4f(points[i].xyz, 1.0);
        }
    }
    for (var k = 0u; k < 4u; k++) {
        b.quarters[k] = vec4f(quarters[k].xyz / max(quarters[k].w, 1.0), select(-1.0, 0.0, quarters[k].w > 0.0));
    }
    for (var k = 0u; k < LAYERS; k++) {
        b.layers[k] = vec4f(layers[k].xyz / max(layers[k].w, 1.0), select(-1.0, 0.0, layers[k].w > 0.0));
    }
    b.count = count;
    if count == 0u {
        return b;
    }
    centre /= f32(count);
    normal = select(vec3f(0.0, 0.0, 1.0), normalize(normal), length(normal) > 1e-6);
    var radius = 0.0;
    var thickness = 0.0;
    for (var i = 0u; i < CUT_TILE * CUT_TILE; i++) {
        if points[i].w >= 0.0 {
            let x = points[i].xyz;
            let v = x - centre;
            radius = max(radius, length(v));
            let k = quarter(i);
            b.quarters[k].w = max(b.quarters[k].w, length(x - b.quarters[k].xyz));
            let layer = layer_of(points[i].w, depths.x, depth_scale);
            b.layers[layer].w = max(b.layers[layer].w, length(x - b.layers[layer].xyz));
            thickness = max(thickness, abs(dot(v, normal)));
        }
    }
    b.sphere = vec4f(centre, radius);
    b.plane = vec4f(normal, thickness);
    return b;
}

// What the walk does with one node.
const SKIP: u32 = 0u;
const TAKE: u32 = 1u;
const TAKE_AWAY: u32 = 2u;
const SPLIT: u32 = 3u;
// Taken although it is large against its distance, since it is of the finest level the cut
// may take, at an angle to the tile's surface (or spanning a fold), and all but touching one
// of the tile's quarters: a light of the tile's near list (see `walk`).
const TAKE_NEAR: u32 = 4u;
// Lights within this cosine of the tile's plane stay in the interleaved classes however close:
// next to a receiver on (nearly) their own plane they give it (nearly) nothing, and a tile's
// own surface would otherwise fill its near list.
const NEAR_PLANE_COS: f32 = 0.9;

fn decide(node: Node, level: u32, floor: u32, split_ratio: f32, b: TileBounds) -> u32 {
    if luminance(node.flux) <= 0.0 {
        return SKIP;
    }
    let v = b.sphere.xyz - node.position;
    let dist = length(v);
    let radius = b.sphere.w;
    if node.merged == 1u {
        // The most any receiver rises above the light's plane: on or below it, it gets nothing.
        let ct = dot(node.normal, b.plane.xyz);
        let rise = dot(node.normal, v) + abs(ct) * b.plane.w + sqrt(max(0.0, 1.0 - ct * ct)) * radius;
        if rise <= 1e-3 * (dist + radius) {
            return TAKE_AWAY;
        }
    }
    // A light that spans a fold or a depth step is split sooner.
    let ratio = select(0.5 * split_ratio, split_ratio, node.merged == 1u);
    // The sphere's and the depth slices' gaps both bound the distance to the nearest receiver,
    // and the larger is the closer. The slices can only spare a light from splitting, so they
    // are measured only for one the sphere would split (most lights are taken at once).
    let sphere_gap = max(dist - radius, 0.0);
    if node.extent <= ratio * sphere_gap {
        return TAKE;
    }
    if node.extent > ratio * max(sphere_gap, layer_gap(node.position, b)) {
        if level > floor {
            return SPLIT;
        }
        // (Twice the ratio: the lights within about one radius of a quarter. Those a little
        // farther off measured no better in the near list, at 40 % more of them.)
        let at_angle = node.merged == 0u || dot(node.normal, b.plane.xyz) < NEAR_PLANE_COS;
        return select(TAKE, TAKE_NEAR, at_angle && near_a_quarter(node, 2.0 * ratio, b));
    }
    return TAKE;
}

// The distance from x to the nearest of the tile's depth slices' spheres (0 inside one): a
// bound on its distance to the nearest receiver, as the tile's sphere's is.
fn layer_gap(x: vec3f, b: TileBounds) -> f32 {
    var gap = 1e30;
    for (var k = 0u; k < LAYERS; k++) {
        let l = b.layers[k];
        if l.w >= 0.0 {
            gap = min(gap, max(length(l.xyz - x) - l.w, 0.0));
        }
    }
    return gap;
}

// Whether the light is as large against its distance to one of the tile's quarters as a
// light the cut would split at `ratio`.
fn near_a_quarter(node: Node, ratio: f32, b: TileBounds) -> bool {
    var near = false;
    for (var k = 0u; k < 4u; k++) {
        let q = b.quarters[k];
        near = near || (q.w >= 0.0 && node.extent > ratio * max(length(q.xyz - node.position) - q.w, 0.0));
    }
    return near;
}

// The two sides of a base block (flux G-buffer texel) that spans a fold, as pyramid.wgsl stored
// them; the second has no area where the node is not such a block.
struct Halves {
    first: Node,
    second: Node,
};

fn fold_halves(node: Node, level: u32, place: vec2u, near: bool) -> Halves {
    var h = Halves(node, Node());
    if near && level == 0u && node.merged == 0u && params.flux_block > 1u {
        let at = table.levels[PYRAMID_LEVELS];
        let i = at.x + place.y * at.y + place.x;
        h = Halves(nodes[i], nodes[i + at.y * at.z]);
    }
    return h;
}

// The counts of one walk: lights taken, taken facing away, and 1 when a light asked to be
// split with the cut already full (the walk then stops: see `main`).
struct Walk {
    taken: u32,
    away: u32,
    filled: u32,
    // Lights stored per interleaved class (see `walk`).
    classes: vec4u,
    // When filled: the share of the tree walked by then (see `walked_share`).
    share: f32,
    // Lights stored in the near list.
    near: u32,
};

// The share of the quadtree a depth-first walk has passed when it is at `place` of `level`:
// the top-level lights before it in raster order, plus its own place in depth-first order
// within its top-level light (children go (0,0), (1,0), (0,1), (1,1)).
fn walked_share(level: u32, place: vec2u) -> f32 {
    let top = PYRAMID_LEVELS - 1u;
    let top_level = table.levels[top];
    var within = 0.0;
    var p = place;
    for (var l = level; l < top; l++) {
        within = (within + f32((p.x & 1u) + 2u * (p.y & 1u))) * 0.25;
        p /= 2u;
    }
    return (f32(p.y * top_level.y + p.x) + within) / f32(top_level.y * top_level.z);
}

// Walks the quadtree depth first from the top level, splitting lights by `split_ratio` down to
// `floor` at the finest, and writes the evaluated lights of the cut from `base` + 2 (and every
// light of it to `centre_lights` when `centre`). A light's interleaved class is its place
// among its siblings (x and y parity), so the four children of a split fall into the four
// classes and a light keeps its class from frame to frame whatever else the cut gains or
// loses; it is stored where index mod 4 names its class (`class_slot`). A class that has had
// its share of the room already (not seen in practice) takes the next light of another.
//
// The lights it takes that are still large against their distance to the tile (of the finest
// level it may take, see TAKE_NEAR) go to the tile's near list instead, stored from the far
// end of its room down: every receiver sums those itself (gather.wgsl), since next to a light
// its irradiance changes faster across the 2×2 interleave than a neighbour's value can stand
// for. When the room between the two runs short, which it does not in practice, a near light
// joins its class.
fn walk(b: TileBounds, floor: u32, split_ratio: f32, base: u32, centre: bool) -> Walk {
    var w = Walk(0u, 0u, 0u, vec4u(0u), 1.0, 0u);
    // The vec4s for lights: the classes fill them from the start, the near list from the end.
    let stride = tile_stride();
    let room = stride - 2u;
    let top = PYRAMID_LEVELS - 1u;
    let top_level = table.levels[top];
    // The cut's size if nothing more were split: a split adds three.
    var planned = top_level.y * top_level.z;
    var level = top;
    var place = vec2u(0u);
    loop {
        let here = table.levels[level];
        var descend = false;
        if place.x < here.y && place.y < here.z {
            let index = here.x + place.y * here.y + place.x;
            let node = nodes[index];
            let action = decide(node, level, floor, split_ratio, b);
            if action == SPLIT {
                if planned + 3u > CUT_MAX {
                    w.filled = 1u;
                    break;
                }
                planned += 3u;
                descend = true;
            } else if action != SKIP {
                if centre && w.taken + w.away < arrayLength(&centre_lights) {
                    centre_lights[w.taken + w.away] = ReflectionLight(node.position, node.area, node.normal, level,
                        node.flux, select(0.0, 1.0, action == TAKE_AWAY));
                }
                if action == TAKE_AWAY {
                    w.away++;
                } else {
                    let classes = 4u * max(max(w.classes.x, w.classes.y), max(w.classes.z, w.classes.w));
                    // One place packs and stores the light whichever list takes it: a CPU
                    // device runs every branch of the loop's body for its whole SIMD row.
                    var light = node;
                    var slot: u32;
                    let halves = fold_halves(node, level, place, action == TAKE_NEAR);
                    if action == TAKE_NEAR && halves.second.area > 0.0 && classes + w.near + 2u <= room {
                        // A base block across a fold: its two sides, each on its own plane.
                        cuts[near_slot(base, stride, w.near + 1u)] = pack_cut_light(halves.second, b.sphere.xyz);
                        light = halves.first;
                        slot = near_slot(base, stride, w.near);
                        w.near += 2u;
                    } else if action == TAKE_NEAR && classes + w.near + 1u <= room {
                        slot = near_slot(base, stride, w.near);
                        w.near++;
                    } else {
                        var kind = (place.x & 1u) + 2u * (place.y & 1u);
                        if w.classes[kind] >= (room - w.near) / 4u {
                            kind = fewest(w.classes);
                        }
                        slot = class_slot(base, kind, w.classes[kind]);
                        w.classes[kind] += 1u;
                    }
                    cuts[slot] = pack_cut_light(light, b.sphere.xyz);
                    w.taken++;
                }
            } else {
                planned -= 1u;
            }
        } else {
            // A child past the level's edge.
            planned -= 1u;
        }
        if descend {
            level -= 1u;
            place *= 2u;
            continue;
        }
        // Up past every last child (the fourth of its parent), then on to the next sibling,
        // or to the next light of the top level in raster order.
        while level < top && all((place & vec2u(1u)) == vec2u(1u)) {
            place /= 2u;
            level += 1u;
        }
        if level == top {
            place.x += 1u;
            if place.x >= top_level.y {
                place = vec2u(0u, place.y + 1u);
            }
            if place.y >= top_level.z {
                break;
            }
        } else if (place.x & 1u) == 0u {
            place.x += 1u;
        } else {
            place = vec2u(place.x - 1u, place.y + 1u);
        }
    }
    if w.filled == 1u {
        w.share = walked_share(level, place);
    }
    return w;
}

// Where the k-th light of interleaved class c of the cut at `base` is stored.
fn class_slot(base: u32, c: u32, k: u32) -> u32 {
    return base + 2u + 4u * k + c;
}

fn fewest(classes: vec4u) -> u32 {
    var c = 0u;
    for (var i = 1u; i < 4u; i++) {
        if classes[i] < classes[c] {
            c = i;
        }
    }
    return c;
}

// Where tile `slot` lies, and whether there is such a tile.
fn slot_tile(slot: u32) -> vec3u {
    let tiles = (params.indirect_size + CUT_TILE - 1u) / CUT_TILE;
    let tile = vec2u(slot % tiles.x, slot / tiles.x);
    return vec3u(tile, u32(tile.y < tiles.y));
}

// vec4s per tile in `cuts`.
fn tile_stride() -> u32 {
    let top_level = table.levels[PYRAMID_LEVELS - 1u];
    return cut_stride(top_level.y * top_level.z);
}

fn is_centre_tile(tile: vec2u) -> bool {
    return all(tile == params.indirect_size / 2u / CUT_TILE);
}

// The split ratio a full tile's next walk takes: the one at which the whole cut would fit,
// were the rest of the tree like the part walked (a cut's size goes about as 1/ratio²), at
// least 1.25× and at most 2× the last, and never past three times `split_ratio`.
fn next_ratio(w: Walk, ratio: f32) -> f32 {
    let projected = f32(w.taken + w.away) / max(w.share, 1e-3);
    let step = clamp(sqrt(projected / (0.85 * f32(CUT_MAX))), 1.25, 2.0);
    return min(ratio * step, 3.0 * params.split_ratio);
}

// Writes the cut's counts and pads its classes to one length with lights that carry no flux,
// so the sum's loop over every fourth slot meets only its own class.
fn finish_cut(base: u32, w: Walk, tile: vec2u) {
    let per_class = max(max(w.classes.x, w.classes.y), max(w.classes.z, w.classes.w));
    for (var c = 0u; c < 4u; c++) {
        for (var k = w.classes[c]; k < per_class; k++) {
            cuts[class_slot(base, c, k)] = vec4u(0u);
        }
    }
    cuts[base] = vec4u(4u * per_class, w.away, w.near, 0u);
    if is_centre_tile(tile) {
        stats.vertex_count = 6u;
        stats.instance_count = min(w.taken + w.away, arrayLength(&centre_lights));
    }
}

fn count_cut(w: Walk) {
    atomicAdd(&stats.lights, w.taken + w.away);
    atomicAdd(&stats.tiles, 1u);
}

// Tiles whose first walk filled the cut, for `retry_full_tiles`: `main` appends them.
struct RetryList {
    count: atomic<u32>,
    pad0: u32,
    pad1: u32,
    pad2: u32,
    // Per full tile: its slot, and the split ratio its next walk takes (f32 bits).
    tiles: array<vec2u>,
};
@group(1) @binding(8) var<storage, read_write> retry: RetryList;
// The G-buffer texel each receiver is evaluated on (`receiver_at`, which costs a dozen texel
// loads): found here once a frame, for the gather and temporal passes.
@group(1) @binding(9) var<storage, read_write> receiver_texels: array<u32>;

// The arguments of the indirect dispatch of `retry_full_tiles`: a workgroup per CUTS_GROUP
// full tiles. Only `main` binds it (the retry dispatch reads it as its arguments).
struct DispatchArgs {
    x: atomic<u32>,
    y: u32,
    z: u32,
};
@group(2) @binding(0) var<storage, read_write> retry_dispatch: DispatchArgs;

const CUTS_GROUP: u32 = 8u;

// Each tile's cut, walked once at `split_ratio`. A cut that would outgrow CUT_MAX is left to
// `retry_full_tiles`, so that the few full tiles are walked again side by side rather than
// each holding up the seven tiles that share its SIMD row.
@compute @workgroup_size(CUTS_GROUP)
fn main(@builtin(global_invocation_id) id: vec3u) {
    if id.x == 0u {
        retry_dispatch.y = 1u;
        retry_dispatch.z = 1u;
    }
    let slot = id.x;
    let place = slot_tile(slot);
    if place.z == 0u {
        return;
    }
    let tile = place.xy;
    let base = slot * tile_stride();
    let b = tile_bounds(tile * CUT_TILE, false);
    cuts[base + 1u] = vec4u(bitcast<vec3u>(b.sphere.xyz), 0u);
    var w = Walk(0u, 0u, 0u, vec4u(0u), 1.0, 0u);
    if b.count > 0u {
        w = walk(b, params.min_level, params.split_ratio, base, is_centre_tile(tile));
        // (The top level alone always fits.)
        if w.filled == 1u && params.min_level < PYRAMID_LEVELS - 1u {
            let i = atomicAdd(&retry.count, 1u);
            if i % CUTS_GROUP == 0u {
                atomicAdd(&retry_dispatch.x, 1u);
            }
            retry.tiles[i] = vec2u(slot, bitcast<u32>(next_ratio(w, params.split_ratio)));
            return;
        }
        count_cut(w);
    }
    finish_cut(base, w, tile);
}

// The full tiles' cuts, walked again with a larger split ratio, so a full tile's lights stay
// as even in size across it as the ratio makes them rather than fine where the walk began and
// coarse where it ran out; past three times `split_ratio` (the lights next to the tile are
// split whatever the ratio), with its finest level one coarser each time.
@compute @workgroup_size(CUTS_GROUP)
fn retry_full_tiles(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= atomicLoad(&retry.count) {
        return;
    }
    let entry = retry.tiles[id.x];
    let slot = entry.x;
    let tile = slot_tile(slot).xy;
    let base = slot * tile_stride();
    let b = tile_bounds(tile * CUT_TILE, true);
    let top = PYRAMID_LEVELS - 1u;
    var floor = params.min_level;
    var ratio = bitcast<f32>(entry.y);
    var w: Walk;
    loop {
        w = walk(b, floor, ratio, base, is_centre_tile(tile));
        if w.filled == 0u || floor >= top {
            break;
        }
        if ratio < 3.0 * params.split_ratio {
            ratio = next_ratio(w, ratio);
        } else {
            floor++;
        }
    }
    count_cut(w);
    atomicAdd(&stats.full, 1u);
    finish_cut(base, w, tile);
}
