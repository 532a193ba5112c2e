// GI gather: the irradiance of each receiver (a pixel of the indirect target) from the
// reflection lights of its 8×8 tile's cut through the flux pyramid (built by cuts.wgsl). The
// body of the pass, included by its two entry points: gather_subgroup.wgsl, where the lanes of
// a subgroup share the loading and unpacking of lights, and gather_invocation.wgsl, where each
// invocation sums alone (see plugin_gi/src/passes/gather.rs for which a device gets). Each
// supplies `sequence_irradiance`, and two entry points: `main` for the first bounce (`store`)
// and `main_bounce` for a further one (`store_bounce`).
//
// The receivers sum each light's irradiance as a disc of its area (disc_irradiance) over the
// cut, interleaved: the cut's lights fall into four classes (cuts.wgsl stores class c at the
// slots whose index mod 4 is c) and each receiver of a 2×2 pattern evaluates one class itself
// and takes the other three from its neighbours with that class (a tent filter over its 3×3
// neighbourhood) where they lie on its surface. A receiver with no such neighbour for a class,
// at an edge or a corner, evaluates that class itself. The cut's near list (lights next to the
// tile's receivers, see cuts.wgsl) every receiver sums whole. Every light is counted once per
// receiver either way; smooth surfaces cost a quarter. A receiver on the pixel next to a fold
// is evaluated a pixel further along its surface (`evaluated_at`). The workgroup's invocations
// take the tile's receivers in runs of eight of one class (`receiver_position`), so a run
// sums one sequence of lights.
#include "common.wgsl"
#include "gi_common.wgsl"
#include "receivers.wgsl"

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var<uniform> table: Levels;
@group(1) @binding(2) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(3) var gbuffer_position: texture_2d<f32>;
@group(1) @binding(4) var irradiance_out: texture_storage_2d<rgba32float, write>;
@group(1) @binding(5) var<storage, read> cuts: array<vec4u>;
// Where each receiver is evaluated, as the cuts pass found it (receivers.wgsl).
@group(1) @binding(6) var<storage, read> receiver_texels: array<u32>;
// The same buffer as `cuts`, read as words: with VISIBILITY, the sight bits after the cuts
// (`sight_start`, sight.wgsl).
@group(1) @binding(7) var<storage, read> sight: array<u32>;
// Further bounces (`main_bounce`): the total of the bounces before, added to the output, and
// this bounce's irradiance alone, for the next bounce's flux.
@group(2) @binding(0) var accumulate: texture_2d<f32>;
@group(2) @binding(1) var bounce_out: texture_storage_2d<rgba32float, write>;

// Whether light is stopped by the surfaces between (gi.visibility): a pipeline each way, so
// the way without reads nothing more.
override VISIBILITY: bool = false;

// Where this invocation's receiver lies among the nine receivers the sight pass tested: the
// bits of the four around it, and their bilinear weights.
var<private> sight_bits: vec4u;
var<private> sight_mix: vec4f;
// Where the sight bits begin in `sight`.
var<private> sight_base: u32;

// `sight_bits` and `sight_mix` for the receiver at tile position p (at x, normal n, where
// `valid`): bilinear among the four tested receivers around it, of those on its surface only
// where there are any (a receiver in a doorway's shadow takes nothing from the receivers
// beyond the doorway's edge that see the light).
fn place_in_sight(p: vec2i, x: vec3f, n: vec3f, valid: bool) {
    let far = p >= vec2i(4);
    let f = select(vec2f(p) / 4.0, (vec2f(p) - 4.0) / 3.0, far);
    let i = u32(far.y) * 3u + u32(far.x);
    sight_bits = vec4u(i, i + 1u, i + 3u, i + 4u);
    let bilinear = vec4f((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    sight_mix = bilinear;
    if valid {
        let d = length(x - globals.camera_pos.xyz);
        var same = vec4f(0.0);
        for (var k = 0u; k < 4u; k++) {
            let at = vec2u(SIGHT_AT[sight_bits[k] % 3u], SIGHT_AT[sight_bits[k] / 3u]);
            same[k] = select(0.0, 1.0, all(vec2i(at) == p) || same_surface(x, n, d, at.y * 8u + at.x));
        }
        let kept = bilinear * same;
        let total = kept.x + kept.y + kept.z + kept.w;
        if total > 0.0 {
            sight_mix = kept / total;
        }
    }
}

// The tile's receivers: position, and the normal packed in w (NO_NORMAL where there is no
// surface), so a neighbour is one load.
var<workgroup> receivers: array<vec4f, 64>;
// Each receiver's irradiance from its own class of lights, for its neighbours.
var<workgroup> partials: array<vec3f, 64>;
// The number of class slots this tile evaluates (its cut less those facing away and the near
// list, padded), and the lights of its near list.
var<workgroup> cut_size: vec2u;

// Whether receiver b (a neighbour in the tile) lies on the surface of the receiver at x with
// normal n, seen from distance d: near, on its plane, facing the same way. Its irradiance
// from a class of lights then stands for this one's.
fn same_surface(x: vec3f, n: vec3f, d: f32, b: u32) -> bool {
    let other = receivers[b];
    let packed = bitcast<u32>(other.w);
    return packed != NO_NORMAL && length(other.xyz - x) < 0.1 * d
        && on_plane(x, n, d, other.xyz, unpack_normal(packed));
}

// The class of lights the receiver at tile position p evaluates itself: a 2×2 pattern that
// stays on its world points as the receivers' grid steps back (GiParams.receiver_steps).
fn light_class(p: vec2i) -> u32 {
    let stepped = vec2i(receiver_steps(params) & vec2u(1u));
    return u32((p.x + stepped.x) & 1) + 2u * u32((p.y + stepped.y) & 1);
}

// Neighbour k of p's 3×3 (k = (dy + 1) * 3 + dx + 1; 4 is p itself).
fn neighbour(p: vec2i, k: u32) -> vec2i {
    return p + vec2i(i32(k % 3u) - 1, i32(k / 3u) - 1);
}

// same_surface_mask with all eight neighbours on p's surface.
const EVERY_NEIGHBOUR: u32 = 0x1efu;

// Which of p's 3×3 neighbours (bit (dy + 1) * 3 + dx + 1) lie on p's surface (at x, normal n).
fn same_surface_mask(p: vec2i, x: vec3f, n: vec3f) -> u32 {
    var mask = 0u;
    let d = length(x - globals.camera_pos.xyz);
    for (var k = 0u; k < 9u; k++) {
        let q = neighbour(p, k);
        if k != 4u && all(q >= vec2i(0)) && all(q <= vec2i(7)) && same_surface(x, n, d, u32(q.y * 8 + q.x)) {
            mask |= 1u << k;
        }
    }
    return mask;
}

// A sequence of the cut's lights: `count` of them, the k-th stored at slot `first` + k·`step`
// (step < 0 runs down from the end of the tile's room).
struct Sequence {
    first: u32,
    step: i32,
    count: u32,
};

// Every `step`-th light of the cut at `base` from `first` on (step 4: one interleaved class;
// step 1: the whole cut), of `lights` class slots.
fn class_sequence(base: u32, first: u32, step: u32, lights: u32) -> Sequence {
    return Sequence(base + 2u + first, i32(step), (lights - min(first, lights) + step - 1u) / step);
}

// The cut's near list (stored from the end of its room, see cuts.wgsl), every light of it:
// these lie close to some receiver of the tile, where their light changes too fast across the
// 2×2 pattern for a neighbour's value to stand for this one's.
fn near_sequence(base: u32, stride: u32, count: u32) -> Sequence {
    return Sequence(near_slot(base, stride, 0u), -1, count);
}

fn sequence_light(s: Sequence, k: u32, centre: vec3f) -> CutLight {
    return unpack_cut_light(cuts[u32(i32(s.first) + i32(k) * s.step)], centre);
}

// Which of the tile's nine tested receivers see the k-th light of a sequence (all without
// VISIBILITY).
fn sequence_sight(s: Sequence, k: u32) -> u32 {
    if !VISIBILITY {
        return 511u;
    }
    return sight[sight_base + u32(i32(s.first) + i32(k) * s.step)];
}

// The share of a light's irradiance that reaches this invocation's receiver: the sight of it
// of the four tested receivers around it (`bits`, sight.wgsl), bilinearly; 1 without
// VISIBILITY.
fn sight_weight(bits: u32) -> f32 {
    if !VISIBILITY {
        return 1.0;
    }
    let corner = vec4f((vec4u(bits) >> sight_bits) & vec4u(1u));
    return dot(corner, sight_mix);
}

// Irradiance at x (normal n) from a sequence's lights, summed by this invocation alone.
fn own_sequence_irradiance(s: Sequence, centre: vec3f, x: vec3f, n: vec3f) -> vec3f {
    var e = vec3f(0.0);
    for (var k = 0u; k < s.count; k++) {
        let l = sequence_light(s, k, centre);
        e += disc_irradiance(l.flux, l.area, l.position, l.normal, x, n) * sight_weight(sequence_sight(s, k));
    }
    return e;
}

// The tile position of the workgroup's receiver r: eight runs of eight, each of one light
// class (`light_class`), so that a subgroup of eight lanes or fewer sums one sequence.
fn receiver_position(r: u32) -> vec2i {
    let run = r / 8u;
    let lane = r % 8u;
    let kind = run % 4u;
    let stepped = vec2i(receiver_steps(params) & vec2u(1u));
    let first = (vec2i(i32(kind & 1u), i32(kind >> 1u)) - stepped) & vec2i(1);
    return first + 2 * vec2i(i32(lane & 3u), 2 * i32(run / 4u) + i32(lane >> 2u));
}

// Whether G-buffer texel t lies on the plane of the receiver at x (normal n, distance d).
fn texel_on_plane(t: vec2i, x: vec3f, n: vec3f, d: f32) -> bool {
    let s = surface_point(t);
    return s.valid && on_plane(x, n, d, s.x, s.n);
}

// Where the receiver at x (normal n, G-buffer texel g) is evaluated: on the texel beyond it
// along its surface when the texel on the other side is off its plane (a fold, a contact or
// an edge). A receiver within a pixel of a fold takes half of its light from the wall across
// it within a few pixel widths of the corner, which the senders there (blocks of several
// texels, one disc each, the one across the corner tilted between the walls) cannot resolve:
// the receiver column that fell on the fold's pixel went 37 % dark for a frame as a pan slid
// the fold across the receivers. One pixel further off the light changes by about 1 %.
fn evaluated_at(g: vec2i, x: vec3f, n: vec3f) -> vec3f {
    let d = length(x - globals.camera_pos.xyz);
    var moved = x;
    for (var axis = 0; axis < 2; axis++) {
        let o = select(vec2i(0, 1), vec2i(1, 0), axis == 0);
        let ahead = texel_on_plane(g + o, x, n, d);
        if ahead != texel_on_plane(g - o, x, n, d) {
            moved += textureLoad(gbuffer_position, select(g - o, g + o, ahead), 0).xyz - x;
        }
    }
    return moved;
}

// The tent weight of neighbour k of the 3×3 (½ along each axis it is off the centre).
fn tent(k: u32) -> f32 {
    return select(1.0, 0.5, k % 3u != 1u) * select(1.0, 0.5, k / 3u != 1u);
}

// An invocation's lane in its subgroup and the subgroup's size, for `sequence_irradiance`
// (0 and 1 where each invocation sums alone). The entry point supplies
// `sequence_irradiance(s, centre, x, n, lanes, wanted)`: the irradiance at x (normal n) from
// sequence s's lights, for an invocation that needs it where `wanted`.
struct Lanes {
    lane: u32,
    count: u32,
};

// One receiver's irradiance from this bounce's lights: where it lies in the indirect target,
// whether it lies in it, and its depth and normal packed (pack_receiver), which ride along for
// the composite's upsampling.
struct Gathered {
    q: vec2u,
    in_view: bool,
    e: vec3f,
    receiver: f32,
};

// The first bounce's irradiance out.
fn store(g: Gathered) {
    if g.in_view {
        textureStore(irradiance_out, vec2i(g.q), vec4f(g.e, g.receiver));
    }
}

// A further bounce's: its own, and the total with the bounces before.
fn store_bounce(g: Gathered) {
    if g.in_view {
        textureStore(bounce_out, vec2i(g.q), vec4f(g.e, 1.0));
        let total = g.e + textureLoad(accumulate, vec2i(g.q), 0).rgb;
        textureStore(irradiance_out, vec2i(g.q), vec4f(total, g.receiver));
    }
}

// Receiver r of the tile of workgroup `group`.
fn gather(r: u32, lanes: Lanes, group: vec2u) -> Gathered {
    let p = receiver_position(r);
    let li = u32(p.y * 8 + p.x);
    let q = group * CUT_TILE + vec2u(p);
    let in_view = all(q < params.indirect_size);
    var x = vec3f(0.0);
    var n = vec4f(0.0);
    var depth = 0.0;
    var g = vec2i(0);
    if in_view {
        g = unpack_texel(receiver_texels[q.y * params.indirect_size.x + q.x]);
        n = textureLoad(gbuffer_normal, g, 0);
        let position = textureLoad(gbuffer_position, g, 0);
        x = position.xyz;
        depth = position.w;
    }
    let valid = in_view && n.w > 0.0;
    receivers[li] = vec4f(x, bitcast<f32>(select(NO_NORMAL, pack_normal(n.xyz), valid)));
    let cut = tile_cut(group, params.indirect_size, table.levels[PYRAMID_LEVELS - 1u]);
    let base = cut.x;
    let stride = cut.y;
    if li == 0u {
        cut_size = cuts[base].xz;
    }
    // (Its barrier also makes every receiver visible to its neighbours.)
    let counts = workgroupUniformLoad(&cut_size);
    if VISIBILITY {
        place_in_sight(p, x, n.xyz, valid);
        sight_base = sight_start(params.indirect_size, table.levels[PYRAMID_LEVELS - 1u]);
    }
    let lights = counts.x;
    let centre = bitcast<vec3f>(cuts[base + 1u].xyz);
    var e = vec3f(0.0);
    // Interleaving: this receiver's own class, and the classes it must evaluate itself too
    // (bit c) because no neighbour on its surface has them.
    let interleaved = params.interleave == 2u;
    let own_class = select(0u, light_class(p), interleaved);
    let step = select(1u, 4u, interleaved);
    var weights = vec4f(0.0);
    var similar = 0u;
    var lacking = 0u;
    if valid {
        similar = same_surface_mask(p, x, n.xyz);
    }
    if valid && interleaved {
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
    if lights + counts.y > 0u {
        // The lights are read from the cut itself, shared within a subgroup where the entry
        // point can (gather_subgroup.wgsl): copying the cut through workgroup memory in
        // batches cost a CPU device more (its loads are per lane either way) than the
        // barriers saved.
        // (Where its eight neighbours lie on its surface no fold is that close; where the
        // senders are single texels none straddles the fold.)
        var x = x;
        if valid && params.flux_block > 1u && similar != EVERY_NEIGHBOUR {
            x = evaluated_at(g, x, n.xyz);
        }
        // Its class, and the near list, all of it, kept to this receiver. Every invocation
        // calls these, those without a receiver too, as the lanes of a run may share the work.
        own = sequence_irradiance(class_sequence(base, own_class, step, lights), centre, x, n.xyz, lanes, valid);
        let near = sequence_irradiance(near_sequence(base, stride, counts.y), centre, x, n.xyz, lanes, valid);
        own = select(vec3f(0.0), own, valid);
        // The classes no neighbour on this surface has, evaluated here.
        for (var c = 0u; c < 4u; c++) {
            if valid && ((lacking >> c) & 1u) != 0u {
                e += own_sequence_irradiance(class_sequence(base, c, 4u, lights), centre, x, n.xyz);
            }
        }
        e += select(vec3f(0.0), near, valid);
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
    return Gathered(q, in_view, e, select(0.0, pack_receiver(depth, n.xyz), valid));
}
