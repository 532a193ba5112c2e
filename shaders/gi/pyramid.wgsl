// GI flux pyramid: turns the lamp-view G-buffer into reflected flux per texel and reduces it
// into a quadtree of reflection lights with the article's merge filter, in two dispatches:
// `flux_levels` writes levels 0–3 (each workgroup reduces its 8×8 texels in workgroup memory)
// and `reduce` levels 4–6 from level 3 the same way. The body of the pass, included by the
// file for each source of flux, which supplies `sender_flux` and `show_flux`:
// pyramid_lamp.wgsl (the first bounce) and pyramid_bounce.wgsl (further ones). What the base's
// texels are (single lamp-view texels, blocks) is a constant each pipeline is made with, so
// that it compiles only its own way: a CPU device runs both sides of a branch, on a uniform
// value too.
//
// The base (level 0) is the lamp view reduced to params.flux_size: each base texel merges its
// block of lamp-view texels as the levels above merge theirs. Attached, the base is as fine as
// the indirect target's receivers, which never see finer senders.
//
// Flux per texel: Φ = ρ · I(ω) · Ω_texel (I: the lamp, plus the camera flash while attached);
// for further bounces Φ = ρ · E · A_texel from the previous bounce's irradiance. A texel is a
// small surface patch of area A = Ω·d²/cos θ, which the transport uses near the light.
#include "common.wgsl"
#include "gi_common.wgsl"

@group(1) @binding(0) var gbuffer_albedo: texture_2d<f32>;
@group(1) @binding(1) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(2) var gbuffer_position: texture_2d<f32>;
@group(1) @binding(3) var<uniform> params: GiParams;
@group(1) @binding(4) var<uniform> table: Levels;
@group(1) @binding(5) var<storage, read_write> nodes: array<Node>;
@group(1) @binding(6) var flux_out: texture_storage_2d<rgba32float, write>;

// The levels each workgroup builds above its 8×8 nodes: `flux_levels` levels 0 to
// GROUP_LEVELS, `reduce` the rest from level GROUP_LEVELS.
const GROUP_LEVELS: u32 = 3u;

var<workgroup> wide: array<Node, 64>;
var<workgroup> narrow: array<Node, 16>;

// Whether the base's texels are blocks of lamp-view texels (as params.flux_block > 1 says).
override FLUX_BLOCKS: bool = false;

fn store_node(level: u32, t: vec2u, node: Node) {
    let l = table.levels[level];
    if level >= params.min_level && t.x < l.y && t.y < l.z {
        nodes[l.x + t.y * l.y + t.x] = node;
    }
}

fn merge(c0: Node, c1: Node, c2: Node, c3: Node) -> Node {
    return merge4(c0, c1, c2, c3, globals.lamp_pos.xyz, params.cos_merge, params.merge_distance);
}

// `wide` holds this workgroup's 8×8 nodes of level `base`: writes its 4×4, 2×2 and 1×1 nodes
// of the three levels above.
fn reduce_three_levels(local: vec2u, group: vec2u, base: u32) {
    workgroupBarrier();
    if all(local < vec2u(4u)) {
        let c = local * 2u;
        let node = merge(wide[c.y * 8u + c.x], wide[c.y * 8u + c.x + 1u], wide[(c.y + 1u) * 8u + c.x],
            wide[(c.y + 1u) * 8u + c.x + 1u]);
        narrow[local.y * 4u + local.x] = node;
        store_node(base + 1u, group * 4u + local, node);
    }
    workgroupBarrier();
    if all(local < vec2u(2u)) {
        let c = local * 2u;
        let node = merge(narrow[c.y * 4u + c.x], narrow[c.y * 4u + c.x + 1u], narrow[(c.y + 1u) * 4u + c.x],
            narrow[(c.y + 1u) * 4u + c.x + 1u]);
        wide[local.y * 2u + local.x] = node;
        store_node(base + 2u, group * 2u + local, node);
    }
    workgroupBarrier();
    if all(local == vec2u(0u)) {
        store_node(base + 3u, group, merge(wide[0], wide[1], wide[2], wide[3]));
    }
}

// One texel of the lamp view (at `t`, of a view of `view` texels) as a light: zero flux where
// nothing is seen or nothing is lit.
fn view_texel_node(t: vec2u, view: vec2u) -> Node {
    var node: Node;
    node.merged = 1u;
    if any(t >= view) {
        return node;
    }
    let normal = textureLoad(gbuffer_normal, vec2i(t), 0);
    if normal.w <= 0.0 {
        return node;
    }
    let omega = texel_solid_angle(t, view, params.lamp_tan);
    let x = textureLoad(gbuffer_position, vec2i(t), 0).xyz;
    let rho = textureLoad(gbuffer_albedo, vec2i(t), 0).rgb;
    let area = texel_area(omega, x, normal.xyz, globals.lamp_pos.xyz);
    node.flux = sender_flux(t, view, rho, x, omega, area);
    node.position = x;
    node.normal = normal.xyz;
    node.area = area;
    node.extent = sqrt(area / PI);
    return node;
}

// Sums of texel lights (flux, area, flux-weighted position and normal), for block_node.
struct Sums {
    flux: vec3f,
    area: f32,
    position: vec3f,
    weight: f32,
    normal: vec3f,
};

fn add_texel(s: ptr<function, Sums>, texel: Node, w: f32) {
    (*s).flux += texel.flux;
    (*s).area += texel.area;
    (*s).position += texel.position * w;
    (*s).normal += texel.normal * w;
    (*s).weight += w;
}

fn sum_of(a: Sums, b: Sums) -> Sums {
    return Sums(a.flux + b.flux, a.area + b.area, a.position + b.position, a.weight + b.weight, a.normal + b.normal);
}

// The light of texels summed in `s`: a patch of their area on their mean plane.
fn sums_node(s: Sums) -> Node {
    var node: Node;
    node.merged = 1u;
    if s.weight <= 0.0 {
        return node;
    }
    node.flux = s.flux;
    node.area = s.area;
    node.position = s.position / s.weight;
    node.normal = normalize(s.normal + vec3f(0.0, 0.0, 1e-12));
    node.extent = sqrt(s.area / PI);
    return node;
}

// Where the two halves of base node `id` are stored (see Quadtree::halves).
fn half_index(id: vec2u, second: bool) -> u32 {
    let h = table.levels[PYRAMID_LEVELS];
    return h.x + select(0u, h.y * h.z, second) + id.y * h.y + id.x;
}

// The k×k block of view texels from `t` as one light, in one pass (the pyramid's merge4 over
// the block, nested, cost a CPU device more than the rest of the GI): flux and area sum,
// position and normal are flux-weighted, and the block is coherent when its normals agree
// (their flux-weighted mean is at least `cos_merge` long) and its box is within
// `merge_distance` of the lamp distance. An incoherent block also stores its two halves
// (`id`'s entries of the halves): the texels that face the way its first lit texel does and
// the rest. Where the block spans a fold the cut's near list takes those two lights, each on
// its own plane, instead of the one light tilted between the planes, which a receiver next to
// the fold sees from behind.
fn block_node(t: vec2u, k: u32, view: vec2u, id: vec2u) -> Node {
    var first = Sums();
    var second = Sums();
    var facing = vec3f(0.0);
    var lo = vec3f(1e30);
    var hi = vec3f(-1e30);
    var reach = 0.0;
    // At most 4×4 of them: an 8×8 block (a CPU preset's third halving) takes every other
    // texel each way, each standing for its 2×2.
    let step = max(k / 4u, 1u);
    let n = k / step;
    for (var j = 0u; j < n * n; j++) {
        var texel = view_texel_node(t + vec2u(j % n, j / n) * step, view);
        let share = f32(step * step);
        texel.flux *= share;
        texel.area *= share;
        let w = luminance(texel.flux);
        if w <= 0.0 {
            continue;
        }
        if first.weight <= 0.0 {
            facing = texel.normal;
        }
        if dot(texel.normal, facing) >= params.cos_merge {
            add_texel(&first, texel, w);
        } else {
            add_texel(&second, texel, w);
        }
        lo = min(lo, texel.position);
        hi = max(hi, texel.position);
        reach = max(reach, texel.extent);
    }
    let all = sum_of(first, second);
    if all.weight <= 0.0 {
        return Node();
    }
    var node = sums_node(all);
    let agreement = length(all.normal) / all.weight;
    let limit = params.merge_distance * length(node.position - globals.lamp_pos.xyz);
    node.merged = select(0u, 1u, agreement >= params.cos_merge && length(hi - lo) <= limit);
    // A coherent block is a patch of its area, sized as one texel is (the disc of that area),
    // so the cuts split it as they would split one texel of that area; an incoherent one
    // reaches as far as its farthest texel.
    let bound = length(max(node.position - lo, hi - node.position)) + reach * f32(step);
    node.extent = select(bound, sqrt(node.area / PI), node.merged == 1u);
    // (Only an incoherent block's halves are ever read: see `fold_halves` in cuts.wgsl.)
    if node.merged == 0u {
        nodes[half_index(id, false)] = sums_node(first);
        nodes[half_index(id, true)] = sums_node(second);
    }
    return node;
}

// Texel `id` of the flux G-buffer: the block of lamp-view texels it stands for, every one of
// them a sender merged into it (not the one at its centre alone, which jumped from surface to
// surface as the view moved and made the senders shimmer).
fn texel_node(id: vec2u) -> Node {
    let view = textureDimensions(gbuffer_normal);
    // The block's side: the power of two the view was halved by. Blocks begin
    // `sender_offset` texels before the view's corner, and their grid moves with the picture
    // (plugin_gi/src/grids.rs), so flux_size = ⌈view / k⌉ + SENDER_PAD. Texels before the
    // corner wrap to beyond the view, which holds nothing.
    let k = params.flux_block;
    var node: Node;
    var omega: f32;
    // Where the flux view (one texel a block over the view, no padding) shows it.
    var shown = vec2i(id);
    if !FLUX_BLOCKS {
        node = view_texel_node(id, view);
        omega = texel_solid_angle(id, params.flux_size, params.lamp_tan);
    } else {
        let first = vec2u(vec2i(id * k) - vec2i(params.sender_offset));
        node = block_node(first, k, view, id);
        omega = texel_solid_angle(min(first + k / 2u, view - 1u), view, params.lamp_tan) * f32(k * k);
        shown -= vec2i(round(params.sender_offset / f32(k)));
    }
    textureStore(flux_out, vec2i(id), vec4f(node.flux, 1.0));
    show_flux(shown, node.flux, omega);
    return node;
}

// Levels 0–3 from the flux G-buffer's texels.
@compute @workgroup_size(8, 8)
fn flux_levels(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_id) local: vec3u,
    @builtin(workgroup_id) group: vec3u) {
    var node: Node;
    if all(id.xy < params.flux_size) {
        node = texel_node(id.xy);
        store_node(0u, id.xy, node);
    }
    wide[local.y * 8u + local.x] = node;
    reduce_three_levels(local.xy, group.xy, 0u);
}

@compute @workgroup_size(8, 8)
fn reduce(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_id) local: vec3u,
    @builtin(workgroup_id) group: vec3u) {
    var node: Node;
    let l = table.levels[GROUP_LEVELS];
    if id.x < l.y && id.y < l.z {
        node = nodes[l.x + id.y * l.y + id.x];
    }
    wide[local.y * 8u + local.x] = node;
    reduce_three_levels(local.xy, group.xy, GROUP_LEVELS);
}
