// GI gather pass: the irradiance of each receiver (a pixel of the indirect target) from the
// reflection lights of the flux pyramid. An 8×8 tile of receivers shares one cut through the
// pyramid, built in workgroup memory: a light is split into its four children while it is
// large against its distance to the tile (extent > split_ratio × gap), so near light comes
// from fine lights and far light from coarse ones. Every light carries all the flux of the
// texels below it and the cut covers each lit texel once, so no energy is lost; a light whose
// plane faces away from every receiver of the tile is left out, as it gives them nothing.
// Then the receivers sum E = Φ/π · cos · cos / (d² + A/π) over the cut, interleaved: the cut's
// lights fall into four classes (index mod 4) and each receiver of a 2×2 pattern evaluates one
// class itself and takes the other three from its neighbours with that class (a tent filter
// over its 3×3 neighbourhood) where they lie on its surface. A receiver with no such neighbour
// for a class, at an edge or a corner, evaluates that class itself. Every light is counted
// once per receiver either way; smooth surfaces cost a quarter.
#include "common.wgsl"
#include "gi_common.wgsl"

struct Stats {
    // Draw arguments of the `lights` view: the cut of the tile at the centre of the view.
    vertex_count: u32,
    instance_count: u32,
    first_vertex: u32,
    first_instance: u32,
    // Σ cut sizes over the tiles, the tiles with receivers, the tiles whose cut filled up.
    lights: atomic<u32>,
    tiles: atomic<u32>,
    full: atomic<u32>,
    pad: u32,
};

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var<uniform> table: Levels;
@group(1) @binding(2) var<storage, read> nodes: array<Node>;
@group(1) @binding(3) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(4) var gbuffer_position: texture_2d<f32>;
@group(1) @binding(5) var irradiance_out: texture_storage_2d<rgba32float, write>;
@group(1) @binding(6) var<storage, read_write> stats: Stats;
@group(1) @binding(7) var<storage, read_write> centre_lights: array<ReflectionLight>;
// Further bounces (params.source == 1): the total so far, added to the output, and this
// bounce's irradiance alone, for the next bounce's flux.
@group(1) @binding(8) var accumulate: texture_2d<f32>;
@group(1) @binding(9) var bounce_out: texture_storage_2d<rgba32float, write>;

const TILE: u32 = 8u;
// Lights one tile's cut may hold (and pending splits); top-level lights are taken in chunks.
// Sized to the device's workgroup memory by gather.rs (this is the most; 832 fit 16 KiB).
const CUT_MAX: u32 = 1536u;
const CHUNK: u32 = 256u;
const LEVEL_SHIFT: u32 = 28u;
// Marks a light of the cut that faces away from every receiver of the tile: kept in the cut
// (so the cut still accounts for all the flux) but not evaluated.
const FACES_AWAY: u32 = 0x08000000u;
const INDEX_MASK: u32 = 0x07ffffffu;
// A blank in a front: the child a node at a level's edge does not have.
const NO_CHILD: u32 = 0xffffffffu;

var<workgroup> cut: array<u32, CUT_MAX>;
var<workgroup> fronts: array<array<u32, CUT_MAX>, 2>;
var<workgroup> cut_count: atomic<u32>;
// Lights that face away from the whole tile fill the cut from its far end: they are kept (the
// cut accounts for all the flux) but never evaluated.
var<workgroup> away_count: atomic<u32>;
var<workgroup> away_total: u32;
// Set when a split found the cut full (the light was taken coarser than split_ratio asked).
var<workgroup> cut_filled: u32;
var<workgroup> next_count: atomic<u32>;
// Cut entries plus pending ones: a split reserves its three extra entries first.
var<workgroup> reserved: atomic<u32>;
var<workgroup> front_count: u32;
var<workgroup> cut_total: u32;
// The cut's lights, 64 at a time, for every receiver to read.
var<workgroup> batch: array<Node, 64>;
var<workgroup> receivers: array<vec4f, 64>;
var<workgroup> receiver_normals: array<vec4f, 64>;
// Each receiver's irradiance from its own class of lights, for its neighbours.
var<workgroup> partials: array<vec3f, 64>;
// The tile's receivers: centre and radius of a bounding sphere, mean normal and the largest
// distance from the mean plane; w of `tile_valid` > 0 when the tile has any.
var<workgroup> tile_sphere: vec4f;
var<workgroup> tile_plane: vec4f;
var<workgroup> tile_valid: u32;

fn tile_bounds() {
    var centre = vec3f(0.0);
    var normal = vec3f(0.0);
    var count = 0u;
    for (var i = 0u; i < 64u; i++) {
        if receivers[i].w > 0.0 {
            centre += receivers[i].xyz;
            normal += receiver_normals[i].xyz;
            count++;
        }
    }
    tile_valid = count;
    if count == 0u {
        return;
    }
    centre /= f32(count);
    normal = select(vec3f(0.0, 0.0, 1.0), normalize(normal), length(normal) > 1e-6);
    var radius = 0.0;
    var thickness = 0.0;
    for (var i = 0u; i < 64u; i++) {
        if receivers[i].w > 0.0 {
            let v = receivers[i].xyz - centre;
            radius = max(radius, length(v));
            thickness = max(thickness, abs(dot(v, normal)));
        }
    }
    tile_sphere = vec4f(centre, radius);
    tile_plane = vec4f(normal, thickness);
}

// Whether receiver b (a neighbour of a, both in the tile) lies on a's surface: near, on its
// plane, facing the same way. Its irradiance from a class of lights then stands for a's.
fn same_surface(a: u32, b: u32) -> bool {
    if receivers[b].w <= 0.0 {
        return false;
    }
    let v = receivers[b].xyz - receivers[a].xyz;
    let d = length(receivers[a].xyz - globals.camera_pos.xyz);
    return length(v) < 0.1 * d && abs(dot(receiver_normals[a].xyz, v)) < 0.02 * d
        && dot(receiver_normals[a].xyz, receiver_normals[b].xyz) > 0.9;
}

// The class of lights the receiver at tile position p evaluates itself.
fn light_class(p: vec2i) -> u32 {
    return u32(p.x & 1) + 2u * u32(p.y & 1);
}

// Neighbour k of p's 3×3 (k = (dy + 1) * 3 + dx + 1; 4 is p itself).
fn neighbour(p: vec2i, k: u32) -> vec2i {
    return p + vec2i(i32(k % 3u) - 1, i32(k / 3u) - 1);
}

// Which of p's 3×3 neighbours (bit (dy + 1) * 3 + dx + 1) lie on p's surface.
fn same_surface_mask(p: vec2i) -> u32 {
    var mask = 0u;
    let a = u32(p.y * 8 + p.x);
    for (var k = 0u; k < 9u; k++) {
        let q = neighbour(p, k);
        if k != 4u && all(q >= vec2i(0)) && all(q <= vec2i(7)) && same_surface(a, u32(q.y * 8 + q.x)) {
            mask |= 1u << k;
        }
    }
    return mask;
}

// The tent weight of neighbour k of the 3×3 (½ along each axis it is off the centre).
fn tent(k: u32) -> f32 {
    return select(1.0, 0.5, k % 3u != 1u) * select(1.0, 0.5, k / 3u != 1u);
}

fn accept(entry: u32) {
    if (entry & FACES_AWAY) != 0u {
        let c = atomicAdd(&away_count, 1u);
        cut[CUT_MAX - 1u - c] = entry;
    } else {
        let c = atomicAdd(&cut_count, 1u);
        cut[c] = entry;
    }
}

// Decides one light of the cut: leave it out, take it, or split it into its children.
fn consider(entry: u32, parity: u32) {
    if entry == NO_CHILD {
        return;
    }
    let level = entry >> LEVEL_SHIFT;
    let index = entry & INDEX_MASK;
    let node = nodes[index];
    if luminance(node.flux) <= 0.0 {
        return;
    }
    let v = tile_sphere.xyz - node.position;
    let dist = length(v);
    let radius = tile_sphere.w;
    if node.merged == 1u {
        // The most any receiver rises above the light's plane: on or below it, it gets nothing.
        let ct = dot(node.normal, tile_plane.xyz);
        let rise = dot(node.normal, v) + abs(ct) * tile_plane.w + sqrt(max(0.0, 1.0 - ct * ct)) * radius;
        if rise <= 1e-3 * (dist + radius) {
            accept(entry | FACES_AWAY);
            return;
        }
    }
    let gap = max(dist - radius, 0.0);
    // A light that spans a fold or a depth step is split sooner.
    let ratio = select(0.5 * params.split_ratio, params.split_ratio, node.merged == 1u);
    if level > params.min_level && node.extent > ratio * gap {
        if atomicAdd(&reserved, 3u) + 3u <= CUT_MAX {
            let below = table.levels[level - 1u];
            let here = table.levels[level];
            let t = vec2u((index - here.x) % here.y, (index - here.x) / here.y);
            // One atomic for the four slots; a child past the level's edge is a blank.
            let slot = atomicAdd(&next_count, 4u);
            for (var i = 0u; i < 4u; i++) {
                let c = t * 2u + vec2u(i & 1u, i >> 1u);
                var child = NO_CHILD;
                if c.x < below.y && c.y < below.z {
                    child = ((level - 1u) << LEVEL_SHIFT) | (below.x + c.y * below.y + c.x);
                }
                fronts[1u - parity][slot + i] = child;
            }
            return;
        }
        atomicSub(&reserved, 3u);
        cut_filled = 1u;
    }
    accept(entry);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(local_invocation_id) local: vec3u, @builtin(local_invocation_index) li: u32,
    @builtin(workgroup_id) group: vec3u) {
    let q = group.xy * TILE + local.xy;
    let in_view = all(q < params.indirect_size);
    var x = vec3f(0.0);
    var n = vec4f(0.0);
    var depth = 0.0;
    if in_view {
        let g = receiver_texel(q, textureDimensions(gbuffer_normal), params.indirect_size);
        n = textureLoad(gbuffer_normal, g, 0);
        let position = textureLoad(gbuffer_position, g, 0);
        x = position.xyz;
        depth = position.w;
    }
    let valid = in_view && n.w > 0.0;
    receivers[li] = vec4f(x, select(0.0, 1.0, valid));
    receiver_normals[li] = vec4f(n.xyz, 0.0);
    workgroupBarrier();
    if li == 0u {
        tile_bounds();
        cut_filled = 0u;
    }
    let count = workgroupUniformLoad(&tile_valid);
    var e = vec3f(0.0);
    // Interleaving: this receiver's own class, and the classes it must evaluate itself too
    // (bit c) because no neighbour on its surface has them.
    let p = vec2i(local.xy);
    let interleaved = params.interleave == 2u;
    let own_class = select(0u, light_class(p), interleaved);
    let stride = select(1u, 4u, interleaved);
    var weights = vec4f(0.0);
    var similar = 0u;
    var lacking = 0u;
    if valid && interleaved {
        similar = same_surface_mask(p);
        for (var k = 0u; k < 9u; k++) {
            if ((similar >> k) & 1u) != 0u {
                weights[light_class(neighbour(p, k))] += tent(k);
            }
        }
        for (var c = 0u; c < 4u; c++) {
            if c != own_class && weights[c] <= 0.0 {
                lacking |= 1u << c;
            }
        }
    }
    var own = vec3f(0.0);
    let centre_tile = all(group.xy == params.indirect_size / 2u / TILE);
    var shown = 0u;
    if count > 0u {
        let top = PYRAMID_LEVELS - 1u;
        let top_level = table.levels[top];
        let n_top = top_level.y * top_level.z;
        for (var start = 0u; start < n_top; start += CHUNK) {
            // Seed the cut with a chunk of the top level.
            let seeds = min(CHUNK, n_top - start);
            for (var i = li; i < seeds; i += 64u) {
                fronts[0][i] = (top << LEVEL_SHIFT) | (top_level.x + start + i);
            }
            if li == 0u {
                front_count = seeds;
                atomicStore(&reserved, seeds);
                atomicStore(&cut_count, 0u);
                atomicStore(&away_count, 0u);
                atomicStore(&next_count, 0u);
            }
            var parity = 0u;
            loop {
                let pending = workgroupUniformLoad(&front_count);
                if pending == 0u {
                    break;
                }
                for (var i = li; i < pending; i += 64u) {
                    consider(fronts[parity][i], parity);
                }
                workgroupBarrier();
                if li == 0u {
                    front_count = atomicLoad(&next_count);
                    atomicStore(&next_count, 0u);
                    cut_total = atomicLoad(&cut_count);
                    away_total = atomicLoad(&away_count);
                }
                parity = 1u - parity;
            }
            let lights = workgroupUniformLoad(&cut_total);
            let away = workgroupUniformLoad(&away_total);
            for (var first = 0u; first < lights; first += 64u) {
                // Past the cut's end, lights without flux: they add nothing, so every
                // receiver's loop below runs the same count without a test (cheaper on a CPU).
                var light: Node;
                if first + li < lights {
                    light = nodes[cut[first + li] & INDEX_MASK];
                }
                batch[li] = light;
                workgroupBarrier();
                let in_batch = min(64u, lights - first);
                if valid {
                    for (var j = 0u; j < in_batch; j += stride) {
                        let node = batch[j + own_class];
                        own += patch_irradiance(node.flux, node.area, node.position, node.normal, x, n.xyz);
                    }
                    if lacking != 0u {
                        for (var i = 0u; i < in_batch; i++) {
                            if ((lacking >> (i & 3u)) & 1u) != 0u {
                                let node = batch[i];
                                e += patch_irradiance(node.flux, node.area, node.position, node.normal, x, n.xyz);
                            }
                        }
                    }
                }
                workgroupBarrier();
            }
            if li == 0u {
                atomicAdd(&stats.lights, lights + away);
            }
            if centre_tile {
                // The evaluated lights, then those facing away (from the cut's far end).
                let all = lights + away;
                for (var i = li; i < all && shown + i < arrayLength(&centre_lights); i += 64u) {
                    let entry = cut[select(CUT_MAX - 1u - (i - lights), i, i < lights)];
                    let node = nodes[entry & INDEX_MASK];
                    let faces_away = select(0.0, 1.0, (entry & FACES_AWAY) != 0u);
                    centre_lights[shown + i] =
                        ReflectionLight(node.position, node.area, node.normal, entry >> LEVEL_SHIFT, node.flux, faces_away);
                }
                shown = min(shown + all, arrayLength(&centre_lights));
            }
            workgroupBarrier();
        }
        if li == 0u {
            atomicAdd(&stats.tiles, 1u);
            if cut_filled == 1u {
                atomicAdd(&stats.full, 1u);
            }
        }
        // The other classes from the neighbours on this surface, tent-weighted per class.
        partials[li] = own;
        workgroupBarrier();
        if valid && interleaved {
            var borrowed = array<vec3f, 4>(vec3f(0.0), vec3f(0.0), vec3f(0.0), vec3f(0.0));
            for (var k = 0u; k < 9u; k++) {
                if ((similar >> k) & 1u) != 0u {
                    let q = neighbour(p, k);
                    borrowed[light_class(q)] += partials[u32(q.y * 8 + q.x)] * tent(k);
                }
            }
            for (var c = 0u; c < 4u; c++) {
                if c != own_class && weights[c] > 0.0 {
                    e += borrowed[c] / weights[c];
                }
            }
        }
        e += own;
    }
    if centre_tile && li == 0u {
        stats.vertex_count = 6u;
        stats.instance_count = shown;
    }
    if in_view {
        var total = e;
        if params.source == 1u {
            textureStore(bounce_out, vec2i(q), vec4f(e, 1.0));
            total += textureLoad(accumulate, vec2i(q), 0).rgb;
        }
        // The receiver's depth rides along for the composite's upsampling.
        textureStore(irradiance_out, vec2i(q), vec4f(total, depth));
    }
}
