// The article's "render to vertex buffer": the distribution table's slots of the flux pyramid
// become the instance stream of the light volumes (article_volumes.wgsl) and its indirect draw
// arguments, on the GPU. A coherent slot is one reflection light; an incoherent one is
// refined up to two levels, and what is still incoherent there is drawn as it is (a base
// block spanning a fold as its two sides), with all of its flux, so the lights carry every
// lit texel's flux once (none is dropped, as the article's filter dropped all but a
// discontinuous texel's "most significant contributor").
//
// The table has two tiers (plugin_gi/src/distribution_table.rs). A coarse light reaches every
// receiver. A fine light's volume is the sphere of `gi.volume_reach` times the size of the
// coarse light it lies in, around that light's centre; inside it the fine light adds its own irradiance less
// its share (its flux) of the coarse light's, faded out over the sphere's outer half. Every
// fine light of one coarse light shares that sphere and fade, so together they turn the
// coarse light's irradiance into theirs inside it, and beyond it the coarse light carries
// their flux: the volume ends, the light beyond it does not.
//
// One workgroup walks the table in order, 64 entries at a time, and places each entry's
// lights after those of the entries before it (a prefix sum over the workgroup): the stream
// is the same every frame for the same pyramid, so the additive draw sums in the same order.
#include "common.wgsl"
#include "gi_common.wgsl"

struct DrawArgs {
    vertex_count: u32,
    instance_count: u32,
    first_vertex: u32,
    first_instance: u32,
};


@group(1) @binding(0) var<uniform> table: Levels;
@group(1) @binding(1) var<storage, read> nodes: array<Node>;
// Per entry: x = level | kind << 8, y = its texel (x | y << 16), and for a fine entry z, w
// the same of the coarse slot it lies in.
@group(1) @binding(2) var<storage, read> entries: array<vec4u>;
@group(1) @binding(3) var<storage, read_write> stream: array<VolumeLight>;
@group(1) @binding(4) var<storage, read_write> args: DrawArgs;
@group(1) @binding(5) var<storage, read_write> stats: Stats;
// The fine lights as the `lights` view and readback see them (the centre tile's cut, in cuts
// mode).
@group(1) @binding(6) var<storage, read_write> shown: array<ReflectionLight>;

const ENTRY_COARSE: u32 = 0u;
const ENTRY_FINE: u32 = 1u;
// Vertices of one light volume: an icosahedron's 20 triangles (article_volumes.wgsl).
const VOLUME_VERTICES: u32 = 60u;
const VOLUME_EVERYWHERE: f32 = -1.0;
const GROUP: u32 = 64u;
// The most lights a slot is drawn as (see is_drawn): one bit each of a u32 mask.
const LIGHTS_PER_SLOT: u32 = 32u;

var<workgroup> counts: array<u32, GROUP>;

// Over the workgroup's invocations (each passing its own `count`): the sum of the counts of
// those before this one, and of all. Every invocation calls it, in step.
fn exclusive_prefix(i: u32, count: u32) -> vec2u {
    workgroupBarrier();
    counts[i] = count;
    // Inclusive prefix sum (Hillis–Steele).
    for (var step = 1u; step < GROUP; step *= 2u) {
        workgroupBarrier();
        let add = select(0u, counts[i - step], i >= step);
        workgroupBarrier();
        counts[i] += add;
    }
    workgroupBarrier();
    return vec2u(counts[i] - count, counts[GROUP - 1u]);
}

struct Place {
    level: u32,
    t: vec2u,
};

fn node_at(p: Place) -> Node {
    let l = table.levels[p.level];
    return nodes[l.x + p.t.y * l.y + p.t.x];
}

fn in_level(p: Place) -> bool {
    let l = table.levels[p.level];
    return all(p.t < l.yz);
}

// The k-th of the up to 16 places a slot is drawn from (k = child * 4 + grandchild), and
// whether it is one: the slot itself where it is coherent or of the finest level built
// (k = 0), else its coherent children, else their children.
fn child_place(slot: Place, k: u32) -> Place {
    return Place(slot.level - 1u, slot.t * 2u + vec2u((k / 4u) & 1u, k / 8u));
}

fn drawn_place(slot: Place, k: u32) -> Place {
    let child = child_place(slot, k);
    return Place(slot.level - 2u, child.t * 2u + vec2u(k & 1u, (k / 2u) & 1u));
}

// Whether a node is drawn as it is rather than refined: coherent, or of the finest level.
fn whole(p: Place) -> bool {
    return node_at(p).merged == 1u || p.level <= params.min_level;
}

fn is_drawn_place(slot: Place, k: u32) -> bool {
    if luminance(node_at(slot).flux) <= 0.0 {
        return false;
    }
    if whole(slot) {
        return k == 0u;
    }
    let child = child_place(slot, k);
    if !in_level(child) || luminance(node_at(child).flux) <= 0.0 {
        return false;
    }
    if whole(child) {
        return k % 4u == 0u;
    }
    let grandchild = drawn_place(slot, k);
    return in_level(grandchild) && luminance(node_at(grandchild).flux) > 0.0;
}

// Where the slot's k-th light is taken from (see is_drawn_place).
fn place_of(slot: Place, k: u32) -> Place {
    if whole(slot) {
        return slot;
    }
    let child = child_place(slot, k);
    if whole(child) {
        return child;
    }
    return drawn_place(slot, k);
}

// Whether the node at `p` is drawn as its two sides: a base block of lamp-view texels that
// spans a fold (pyramid.wgsl stores its halves, each a light on its own plane), where the
// tilted light between the planes would light the receivers beside the fold from behind.
fn in_halves(p: Place) -> bool {
    return p.level == 0u && table.levels[PYRAMID_LEVELS].y > 0u && node_at(p).merged == 0u;
}

fn half_node(p: Place, second: bool) -> Node {
    let h = table.levels[PYRAMID_LEVELS];
    return nodes[h.x + select(0u, h.y * h.z, second) + p.t.y * h.y + p.t.x];
}

// A slot's lights: j = 2 × its place's index (see drawn_place) + the side of a block drawn
// as its halves (0 for any other node).
fn is_drawn(slot: Place, j: u32) -> bool {
    if !is_drawn_place(slot, j / 2u) {
        return false;
    }
    let p = place_of(slot, j / 2u);
    if !in_halves(p) {
        return j % 2u == 0u;
    }
    return luminance(half_node(p, j % 2u == 1u).flux) > 0.0;
}

fn light_node(slot: Place, j: u32) -> Node {
    let p = place_of(slot, j / 2u);
    if in_halves(p) {
        return half_node(p, j % 2u == 1u);
    }
    return node_at(p);
}

// The coarse light that the light at `p` lies in: the coarse slot's light holding it (the
// same place, where the two tiers draw the same light).
fn proxy_of(coarse: Place, p: Place) -> Place {
    if whole(coarse) || p.level >= coarse.level {
        return coarse;
    }
    let child = Place(coarse.level - 1u, p.t >> vec2u(coarse.level - 1u - p.level));
    if whole(child) || p.level >= child.level {
        return child;
    }
    return Place(coarse.level - 2u, p.t >> vec2u(coarse.level - 2u - p.level));
}

fn unpack_place(level: u32, texel: u32) -> Place {
    return Place(level & 0xffu, vec2u(texel & 0xffffu, texel >> 16u));
}

fn is_fine(e: vec4u) -> bool {
    return ((e.x >> 8u) & 0xffu) == ENTRY_FINE;
}

// Entry `e`'s lights (bit j: see is_drawn): x, those the slot has; y, those drawn as light
// volumes (a fine light drawn the same as its coarse one, the two tiers splitting alike
// there, adds nothing).
fn light_masks(e: vec4u) -> vec2u {
    let slot = unpack_place(e.x, e.y);
    var masks = vec2u(0u);
    for (var j = 0u; j < LIGHTS_PER_SLOT; j++) {
        if is_drawn(slot, j) {
            masks.x |= 1u << j;
            let p = place_of(slot, j / 2u);
            if !(is_fine(e) && same(p, proxy_of(unpack_place(e.z, e.w), p))) {
                masks.y |= 1u << j;
            }
        }
    }
    return masks;
}

fn same(a: Place, b: Place) -> bool {
    return a.level == b.level && all(a.t == b.t);
}

fn write_light(e: vec4u, j: u32, at: u32) {
    let slot = unpack_place(e.x, e.y);
    let p = place_of(slot, j / 2u);
    let node = light_node(slot, j);
    var light: VolumeLight;
    light.position = node.position;
    light.area = node.area;
    light.normal = node.normal;
    light.flux = node.flux;
    light.subset = light_subset(p, j % 2u);
    light.radius = VOLUME_EVERYWHERE;
    if is_fine(e) {
        let proxy = node_at(proxy_of(unpack_place(e.z, e.w), p));
        light.proxy_position = proxy.position;
        light.proxy_area = proxy.area;
        light.proxy_normal = proxy.normal;
        light.radius = params.volume_reach * proxy.extent;
    }
    if at < arrayLength(&stream) {
        stream[at] = light;
    }
}

// The sub-image a light is drawn into, by its place in the world, so a light keeps its
// subset as the view turns: the node's texel with the senders' grid's steps taken out (each
// step moves the flux G-buffer's content SENDER_PAD (8) base texels on, a whole number of
// nodes up to level 3, whose grouping the steps keep). Each N×N block of nodes of a level
// holds every subset once (stratified: a subset's lights spread over the view), in an order
// of its own (a hash of the block picks one of the affine orders a·i + b mod N², a prime to
// 2 and 3), so no subset keeps to a lattice that the receivers' sub-images could match.
// A block drawn as its halves gives its second side the subset half-way round.
fn light_subset(p: Place, side: u32) -> u32 {
    let steps =
        vec2i(i32(params.sender_steps & 0xffffu), i32(params.sender_steps >> 16u)) - SENDER_STEPS_OFFSET;
    // (Made positive before the modulo.)
    let world = bitcast<vec2u>(vec2i(p.t) - ((steps * SENDER_PAD) >> vec2u(p.level)) + vec2i(1 << 20u));
    let n = max(params.article_interleave, 1u);
    let block = world / n;
    var h = block.x * 0x9e3779b1u ^ (block.y + 0x7f4a7c15u) * 0x85ebca6bu ^ p.level * 0xc2b2ae35u;
    h = (h ^ (h >> 15u)) * 0x2c1b3c6du;
    h ^= h >> 13u;
    let a = array<u32, 5>(1u, 5u, 7u, 11u, 13u)[h % 5u];
    let i = world.x % n + n * (world.y % n);
    return (a * i + (h >> 8u) + side * (n * n / 2u)) % (n * n);
}

@group(1) @binding(7) var<uniform> params: GiParams;

@compute @workgroup_size(64)
fn main(@builtin(local_invocation_index) i: u32) {
    let total = arrayLength(&entries);
    // The instance stream, and the fine tier as lights for the `lights` view, each in the
    // table's order.
    var placed = 0u;
    var shown_count = 0u;
    for (var first = 0u; first < total; first += GROUP) {
        let index = first + i;
        var e = vec4u(0u);
        var masks = vec2u(0u);
        if index < total {
            e = entries[index];
            masks = light_masks(e);
        }
        let fine = select(0u, masks.x, is_fine(e));
        let prefix = exclusive_prefix(i, countOneBits(masks.y));
        let shown_prefix = exclusive_prefix(i, countOneBits(fine));
        var at = placed + prefix.x;
        var shown_at = shown_count + shown_prefix.x;
        let slot = unpack_place(e.x, e.y);
        for (var j = 0u; j < LIGHTS_PER_SLOT; j++) {
            if (masks.y & (1u << j)) != 0u {
                write_light(e, j, at);
                at++;
            }
            if (fine & (1u << j)) != 0u {
                let node = light_node(slot, j);
                if shown_at < arrayLength(&shown) {
                    let level = place_of(slot, j / 2u).level;
                    shown[shown_at] = ReflectionLight(node.position, node.area, node.normal, level, node.flux, 0.0);
                }
                shown_at++;
            }
        }
        placed += prefix.y;
        shown_count += shown_prefix.y;
    }
    if i == 0u {
        args = DrawArgs(VOLUME_VERTICES, min(placed, arrayLength(&stream)), 0u, 0u);
        atomicStore(&stats.lights, min(placed, arrayLength(&stream)));
        atomicStore(&stats.tiles, total);
        atomicStore(&stats.full, 0u);
        stats.vertex_count = 6u;
        stats.instance_count = min(shown_count, arrayLength(&shown));
        stats.first_vertex = 0u;
        stats.first_instance = 0u;
    }
}
