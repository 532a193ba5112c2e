// Shared declarations of the GI plugin's passes: the node of the reduced flux G-buffer (the
// pyramid of reflection lights), the per-frame parameters, the merge filter and the
// patch-to-point transport every pass evaluates.

// One node of the flux pyramid: a Lambertian emitter standing for every texel below it.
struct Node {
    // Flux-weighted centroid of the texels below (m).
    position: vec3f,
    // Radius about `position` that holds every texel patch below (m): how big the light is.
    extent: f32,
    // Flux-weighted mean normal, normalised.
    normal: vec3f,
    // 1 when every texel below merged under the thresholds (one plane, no depth step).
    merged: u32,
    // Reflected flux Φ (W), summed over the texels below: never dropped, only grouped.
    flux: vec3f,
    // Surface area of the texels below (m²).
    area: f32,
};

// A reflection light as the `lights` view and tests read it back: one node of a tile's cut.
struct ReflectionLight {
    position: vec3f,
    area: f32,
    normal: vec3f,
    // The pyramid level it came from (0 = one texel).
    level: u32,
    flux: vec3f,
    // 1 when it faces away from every receiver of its tile (so it was not evaluated).
    faces_away: f32,
};

// The gather's counters (cuts.wgsl fills them; with `gi.method = article`, article_stream.wgsl):
// first the `lights` view's draw arguments (the cut of the tile at the centre of the view; the
// article's fine lights), then Σ cut sizes over the tiles, the tiles with receivers, the tiles
// whose cut filled up (the article's: the volumes drawn, the table's slots, 0).
struct Stats {
    vertex_count: u32,
    instance_count: u32,
    first_vertex: u32,
    first_instance: u32,
    lights: atomic<u32>,
    tiles: atomic<u32>,
    full: atomic<u32>,
    pad: u32,
};

// The article method's instance stream (article_stream.wgsl writes it, article_volumes.wgsl
// draws it): one light volume each.
struct VolumeLight {
    position: vec3f,
    area: f32,
    normal: vec3f,
    // The volume's radius about `proxy_position` (m); < 0 for a coarse light, which covers
    // every receiver of its sub-image.
    radius: f32,
    flux: vec3f,
    // The sub-image it is drawn into (interleaved sampling).
    subset: u32,
    // The coarse light it lies in (a fine light's): whose share it replaces.
    proxy_position: vec3f,
    proxy_area: f32,
    proxy_normal: vec3f,
    pad: u32,
};

struct GiParams {
    // Size of the flux G-buffer (level 0) and of the indirect (irradiance) target.
    flux_size: vec2u,
    indirect_size: vec2u,
    // tan of the lamp frustum's half angles (x, y), the lamp's power P (for the flux view).
    lamp_tan: vec2f,
    lamp_power: f32,
    // cos(merge normal threshold), merge distance fraction.
    cos_merge: f32,
    merge_distance: f32,
    // A light is split while its extent exceeds this fraction of its distance to the receivers.
    split_ratio: f32,
    // Lights are never split below this pyramid level (a receiver's footprint).
    min_level: u32,
    // 2: receivers evaluate the cut interleaved in a 2×2 pattern; 1: each evaluates all of it.
    interleave: u32,
    // The side in lamp-view texels of one flux G-buffer texel (a power of two).
    flux_block: u32,
    // The article method's interleaved sampling: N, its lights dealt over N×N sub-images
    // (article_sub_image_layout.wgsl).
    article_interleave: u32,
    // Where the receivers' grid lies this frame, in cells (−½ to ½ each way), and how many
    // lamp-view texels before the view's corner the flux G-buffer's blocks begin: both grids
    // move with the picture as the camera turns, so receivers and senders keep to their world
    // points (plugin_gi/src/grids.rs).
    receiver_offset: vec2f,
    sender_offset: vec2f,
    // The article method's fine light volumes' radius in sizes of their coarse lights
    // (article_stream.wgsl).
    volume_reach: f32,
    // The whole cells the receivers' grid has stepped back, mod RECEIVER_PERIOD each way
    // (x | y << 16: `receiver_steps`): the gather's 2×2 interleave pattern follows their
    // parity (gather.wgsl's `light_class`), the article's sub-images them mod N
    // (article_sub_image_layout.wgsl), so a world point keeps its class of lights.
    receiver_steps: u32,
    // The periods (SENDER_PAD blocks) the senders' grid has stepped back, plus
    // SENDER_STEPS_OFFSET, each way (x | y << 16): the article's lights keep their subsets by
    // them (article_stream.wgsl).
    sender_steps: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
    // The frame the lamp view was rendered from: origin, forward axis, and right and up axes
    // scaled by lamp_tan, so a texel's corner rays follow from its index.
    view_origin: vec4f,
    view_forward: vec4f,
    view_right: vec4f,
    view_up: vec4f,
};


// The grids' steps (plugin_gi/src/grids.rs): the receivers' are kept mod RECEIVER_PERIOD; the
// senders' are whole periods of SENDER_PAD base blocks, stored plus SENDER_STEPS_OFFSET (both
// signed, as the steps are once it is taken off).
const RECEIVER_PERIOD: u32 = 12u;
const SENDER_PAD: i32 = 8;
const SENDER_STEPS_OFFSET: i32 = 2048;

const PYRAMID_LEVELS: u32 = 7u;

// GiParams.receiver_steps, across and down.
fn receiver_steps(p: GiParams) -> vec2u {
    return vec2u(p.receiver_steps & 0xffffu, p.receiver_steps >> 16u);
}

// The cuts pass (cuts.wgsl) builds one cut per tile of CUT_TILE × CUT_TILE receivers, each
// of at most CUT_MAX lights (or every light of the top level, when it has more); the gather
// (gather.wgsl) sums them. A tile's cut is stored as the lights themselves, one vec4 each
// (see `pack_cut_light`), after a vec4 of counts and one of the tile's centre: the gather then
// loads one vec4 a light, where an index into the pyramid and the node behind it took four
// (a CPU device loads per lane).
const CUT_TILE: u32 = 8u;

// The receivers of a tile (per axis) whose sight of each light the sight pass tests
// (sight.wgsl) and the sum blends (gather.wgsl): its corners and the middle between them.
const SIGHT_AT = array<u32, 3>(0u, 4u, 7u);
const CUT_MAX: u32 = 1536u;

// What the gather needs of a light: where, how large, its flux, and its normal.
struct CutLight {
    position: vec3f,
    area: f32,
    flux: vec3f,
    normal: vec3f,
};

// A light in a cut as one vec4u: its position relative to the tile's centre and the square
// root of its area as four f16, its flux in a shared-exponent RGB (9 bits a channel), its
// normal in octahedral 2×16 bits. f16 keeps a light's place to 1/2048 of its distance from
// the tile, and the shared exponent its flux to 1/512 of its brightest channel.
fn pack_cut_light(node: Node, centre: vec3f) -> vec4u {
    let rel = node.position - centre;
    return vec4u(pack2x16float(rel.xy), pack2x16float(vec2f(rel.z, sqrt(node.area))), pack_rgb9e5(node.flux),
        pack_normal(node.normal));
}

fn unpack_cut_light(v: vec4u, centre: vec3f) -> CutLight {
    let xy = unpack2x16float(v.x);
    let z_side = unpack2x16float(v.y);
    return CutLight(centre + vec3f(xy, z_side.x), z_side.y * z_side.y, unpack_rgb9e5(v.z), unpack_normal(v.w));
}

// A unit normal on the octahedron's square, [-1, 1]², the lower half folded over the upper.
fn octahedral(normal: vec3f) -> vec2f {
    let n = normal / (abs(normal.x) + abs(normal.y) + abs(normal.z) + 1e-20);
    var oct = n.xy;
    if n.z < 0.0 {
        oct = (1.0 - abs(n.yx)) * select(vec2f(-1.0), vec2f(1.0), n.xy >= vec2f(0.0));
    }
    return oct;
}

fn from_octahedral(oct: vec2f) -> vec3f {
    var n = vec3f(oct, 1.0 - abs(oct.x) - abs(oct.y));
    if n.z < 0.0 {
        n = vec3f((1.0 - abs(n.yx)) * select(vec2f(-1.0), vec2f(1.0), n.xy >= vec2f(0.0)), n.z);
    }
    return normalize(n);
}

// A unit normal in 32 bits: octahedral, 2×16 bits (snorm; never 0x80008000, see NO_NORMAL).
fn pack_normal(normal: vec3f) -> u32 {
    return pack2x16snorm(octahedral(normal));
}

fn unpack_normal(v: u32) -> vec3f {
    return from_octahedral(unpack2x16snorm(v));
}

// A receiver's depth and normal in the irradiance target's alpha, for the composite's
// geometry-aware upsampling (one load a sample instead of two): the depth as f16 in the high
// half, the octahedral normal in 2 × 8 bits in the low half; 0 where there is no surface. The
// depth is positive and at least the near plane, so the f16's exponent is neither 0 nor 31 and
// the word, read as f32, is never a NaN, an infinity or a denormal: it survives any f32 store.
fn pack_receiver(depth: f32, normal: vec3f) -> f32 {
    let d = pack2x16float(vec2f(max(depth, 1e-3), 0.0)) << 16u;
    return bitcast<f32>(d | (pack4x8snorm(vec4f(octahedral(normal), 0.0, 0.0)) & 0xffffu));
}

fn receiver_depth(packed: f32) -> f32 {
    return unpack2x16float(bitcast<u32>(packed) >> 16u).x;
}

fn receiver_normal(packed: f32) -> vec3f {
    return from_octahedral(unpack4x8snorm(bitcast<u32>(packed)).xy);
}

// What pack_normal never gives (it writes −1 as −32767): "no surface here".
const NO_NORMAL: u32 = 0x80008000u;

// RGB with one shared exponent (the GL_EXT_texture_shared_exponent encoding, rounded).
fn pack_rgb9e5(c: vec3f) -> u32 {
    let m = clamp(c, vec3f(0.0), vec3f(65408.0));
    let top = max(m.x, max(m.y, m.z));
    // floor(log2(top)) and the powers of two from the float's exponent bits: exact, and a
    // CPU device's log2 and exp2 are polynomials evaluated per light of every cut.
    var e = max(-16, i32((bitcast<u32>(max(top, 1e-30)) >> 23u) & 0xffu) - 127) + 16;
    if floor(top * power_of_two(24 - e) + 0.5) >= 512.0 {
        e += 1;
    }
    let q = vec3u(min(floor(m * power_of_two(24 - e) + 0.5), vec3f(511.0)));
    return q.x | (q.y << 9u) | (q.z << 18u) | (u32(e) << 27u);
}

fn unpack_rgb9e5(v: u32) -> vec3f {
    let q = vec3f(f32(v & 511u), f32((v >> 9u) & 511u), f32((v >> 18u) & 511u));
    return q * power_of_two(i32(v >> 27u) - 24);
}

// 2^k for -126 <= k <= 127, built from its exponent bits.
fn power_of_two(k: i32) -> f32 {
    return bitcast<f32>(u32(k + 127) << 23u);
}


// vec4s per tile in the cuts buffer: the counts (class slots to sum, facing away, near), the
// tile's centre, then one a light, with room for twice the most lights (the interleaved
// classes are padded to one length, from the start; the near list from the end: see cuts.wgsl).
fn cut_stride(top_lights: u32) -> u32 {
    return 2u + 2u * max(CUT_MAX, top_lights);
}

// Where the cut of tile `tile` starts in `cuts`, and its vec4s (`cut_stride`), for an
// indirect target of `indirect_size` over a pyramid whose top level is `top_level`.
fn tile_cut(tile: vec2u, indirect_size: vec2u, top_level: vec4u) -> vec2u {
    let tiles = (indirect_size + CUT_TILE - 1u) / CUT_TILE;
    let stride = cut_stride(top_level.y * top_level.z);
    return vec2u((tile.y * tiles.x + tile.x) * stride, stride);
}

// Where the k-th light of the near list of the cut at `base` (of `stride` vec4s) is stored.
fn near_slot(base: u32, stride: u32, k: u32) -> u32 {
    return base + stride - 1u - k;
}

// With visibility the cuts buffer goes on past every tile's cut with one u32 a slot of them
// (written by sight.wgsl): which of its tile's nine tested receivers see the light in that
// slot. Where they begin, in u32 words of the buffer, for cuts laid out as in `tile_cut`: slot
// s's are word `sight_start(…) + s`.
fn sight_start(indirect_size: vec2u, top_level: vec4u) -> u32 {
    let tiles = (indirect_size + CUT_TILE - 1u) / CUT_TILE;
    return 4u * tiles.x * tiles.y * cut_stride(top_level.y * top_level.z);
}

// Per level of the pyramid: offset into the node buffer, width, height; then (entry
// PYRAMID_LEVELS) where the base blocks' halves lie, 0 wide over a base of texels (see
// Quadtree::halves).
struct Levels {
    levels: array<vec4u, 8>,
};

// Texel areas are Ω·d²/cos θ; past this cosine (grazing) the patch is taken as this wide. It
// only shapes the near field of one texel, never its flux, and shrinks with the texel.
const MIN_AREA_COS: f32 = 0.01;

// Solid angle of texel t of a `size` lamp view seen from the lamp: the texel's area in the
// tangent plane at unit distance, times cos³ of its angle from the axis.
fn texel_solid_angle(t: vec2u, size: vec2u, lamp_tan: vec2f) -> f32 {
    let s = vec2f(size);
    let ndc = vec2f((f32(t.x) + 0.5) / s.x * 2.0 - 1.0, 1.0 - (f32(t.y) + 0.5) / s.y * 2.0);
    let tan_xy = ndc * lamp_tan;
    let area = 4.0 * lamp_tan.x * lamp_tan.y / (s.x * s.y);
    let r2 = 1.0 + dot(tan_xy, tan_xy);
    return area / (r2 * sqrt(r2));
}

// The surface area a texel of solid angle Ω covers at x (normal n) seen from the lamp.
fn texel_area(omega: f32, x: vec3f, n: vec3f, lamp: vec3f) -> f32 {
    let to_lamp = lamp - x;
    let d2 = dot(to_lamp, to_lamp);
    let cos_theta = max(dot(n, to_lamp * inverseSqrt(max(d2, 1e-20))), MIN_AREA_COS);
    return omega * d2 / cos_theta;
}

// The flux a lamp-view texel of solid angle Ω reflects at x (albedo ρ): Φ = ρ·I(ω)·Ω, I the
// lamp's intensity towards x, plus the camera flash while the lamp is attached (it then sits
// where the lamp does and sees what it sees; detached, this view is the lamp's and cannot
// tell what the flash lights, so the flash lights directly only).
fn lamp_reflected_flux(rho: vec3f, x: vec3f, omega: f32) -> vec3f {
    var intensity = vec3f(0.0);
    if globals.lamp_pos.w > 0.5 {
        intensity = lamp_intensity_towards(x);
    }
    if globals.params.z < 0.5 {
        intensity += globals.camera_flash.rgb;
    }
    return rho * intensity * omega;
}

// The G-buffer texel that receiver q of an `indirect`-sized target stands for (the one at its
// footprint's centre in a `view`-sized G-buffer), its grid shifted by `offset` cells (this
// frame's GiParams.receiver_offset, or last frame's for its samples).
fn receiver_texel(q: vec2u, view: vec2u, indirect: vec2u, offset: vec2f) -> vec2i {
    return min(vec2i((vec2f(q) + 0.5 + offset) * vec2f(view) / vec2f(indirect)), vec2i(view) - 1);
}

// A receiver's G-buffer texel as the cuts pass records it for the gather and temporal passes
// (`receiver_texels`, one a receiver, row by row): x and y in 16 bits each.
fn pack_texel(t: vec2i) -> u32 {
    return u32(t.x) | (u32(t.y) << 16u);
}

fn unpack_texel(v: u32) -> vec2i {
    return vec2i(i32(v & 0xffffu), i32(v >> 16u));
}

// Where pixel centre p of a `view`-sized frame lies among the samples of an `indirect`-sized
// target: `base` the sample before it on each axis, `f` its place towards the next (0 at
// base, 1 at the next; outside that range beyond the target's edge samples). Taken from
// where the gather evaluated each sample (`receiver_texel`) rather than from the ratio of the
// sizes: at a ratio like 4/3 the two differ by up to half a pixel.
struct SamplePlace {
    base: vec2i,
    f: vec2f,
};

fn sample_place(p: vec2f, view: vec2u, indirect: vec2u, offset: vec2f) -> SamplePlace {
    let low = vec2i(indirect);
    var base = max(min(vec2i(floor(p * vec2f(indirect) / vec2f(view) - 0.5 - offset)), low - 2), vec2i(0));
    base -= vec2i((p < sample_centre(base, view, indirect, offset)) & (base > vec2i(0)));
    base += vec2i((p > sample_centre(base + 1, view, indirect, offset)) & (base + 2 < low));
    let c0 = sample_centre(base, view, indirect, offset);
    return SamplePlace(base, (p - c0) / max(sample_centre(base + 1, view, indirect, offset) - c0, vec2f(1e-6)));
}

// Where the gather evaluated sample s (s ≥ 0) of an `indirect`-sized target, in pixels.
fn sample_centre(s: vec2i, view: vec2u, indirect: vec2u, offset: vec2f) -> vec2f {
    return vec2f(receiver_texel(vec2u(s), view, indirect, offset)) + 0.5;
}

// Whether a surface point y (normal m) lies on the plane of the receiver at x (normal n), seen
// from distance d: facing the same way and within 2 % of d of its plane.
fn on_plane(x: vec3f, n: vec3f, d: f32, y: vec3f, m: vec3f) -> bool {
    return abs(dot(n, y - x)) < 0.02 * d && dot(n, m) > 0.9;
}

fn luminance(c: vec3f) -> f32 {
    return dot(c, vec3f(0.2126, 0.7152, 0.0722));
}

// Irradiance at x (normal n_x) from a Lambertian disc of flux Φ and area A = πa², centred at p
// with normal n_r: exact wherever the disc lies wholly above x's plane, however close. It is
// the disc's vector irradiance (the closed forms of the form factors from a point parallel
// and perpendicular to a disc) dotted with n_x:
//   E = Φ/(πa²) · [F∥ · n_x·(−n_r) + F⊥ · n_x·(−ŝ)],
//   F∥ = ½(1 − t/R), F⊥ = h/(2|s|) · (q/R − 1),
// h = n_r·(x − p) the height above the disc's plane, s the rest of x − p, q = |x − p|² + a²,
// t = q − 2a², R = √(q² − 4a²|s|²); written below so that no term cancels in f32, whether the
// disc is small and far or x is just above it. Far away it is the point light's
// Φ/π·cos·cos/d²; close by it stays finite, so nothing has to be clamped. (The form it replaces,
// Φ/π·cos·cos/(d² + A/π) from the centre, was 8–20 % off at the 2–5 radii where the cuts take
// most lights, and a third off next to a fold.) Where x's plane cuts the disc the dot product
// counts the part below it negatively; that happens only where the disc reaches within its
// radius of that plane (next to a fold), and the result is held at 0 or above.
fn disc_irradiance(flux: vec3f, area: f32, p: vec3f, n_r: vec3f, x: vec3f, n_x: vec3f) -> vec3f {
    let v = x - p;
    let h = dot(v, n_r);
    if h <= 0.0 {
        return vec3f(0.0);
    }
    let a2 = area * (1.0 / PI);
    let s = v - h * n_r;
    let s2 = dot(s, s);
    let q = s2 + h * h + a2;
    let root = max(sqrt(max(q * q - 4.0 * a2 * s2, 0.0)), 1e-6 * q);
    let t = q - 2.0 * a2;
    // F∥/a² = (R − t)/(2a²R), and R − t = 4a²h²/(R + t) where t > 0 (no cancellation either
    // way): num/den below. F⊥/(a²|s|) = 2h/(R(q + R)). Over one denominator, one division.
    let num = select(root - t, 4.0 * h * h, t > 0.0);
    let den = select(a2, root + t, t > 0.0);
    let e = (num * dot(n_x, -n_r) * (q + root) - 4.0 * h * dot(n_x, s) * den)
        / (2.0 * PI * root * den * (q + root));
    return flux * max(e, 0.0);
}

// The merge filter: one node from four children (those without flux count for nothing).
// Flux and area sum, position and normal are flux-weighted; the node is coherent when every
// child with flux is and their normals and positions agree within the thresholds. Written out
// for four named children: arrays of structs cost dearly on a CPU device.
fn merge4(c0: Node, c1: Node, c2: Node, c3: Node, lamp: vec3f, cos_merge: f32, merge_distance: f32) -> Node {
    let w = vec4f(luminance(c0.flux), luminance(c1.flux), luminance(c2.flux), luminance(c3.flux));
    var node: Node;
    node.flux = c0.flux + c1.flux + c2.flux + c3.flux;
    let weight = w.x + w.y + w.z + w.w;
    node.merged = 1u;
    if weight <= 0.0 {
        node.flux = vec3f(0.0);
        return node;
    }
    let has = w > vec4f(0.0);
    node.area = select(0.0, c0.area, has.x) + select(0.0, c1.area, has.y) + select(0.0, c2.area, has.z)
        + select(0.0, c3.area, has.w);
    node.position = (c0.position * w.x + c1.position * w.y + c2.position * w.z + c3.position * w.w) / weight;
    let n = c0.normal * w.x + c1.normal * w.y + c2.normal * w.z + c3.normal * w.w;
    node.normal = normalize(n + vec3f(0.0, 0.0, 1e-12));
    let limit = merge_distance * length(node.position - lamp);
    node.extent = max(max(child_reach(c0, has.x, node), child_reach(c1, has.y, node)),
        max(child_reach(c2, has.z, node), child_reach(c3, has.w, node)));
    let similar = child_agrees(c0, has.x, node, cos_merge, limit) && child_agrees(c1, has.y, node, cos_merge, limit)
        && child_agrees(c2, has.z, node, cos_merge, limit) && child_agrees(c3, has.w, node, cos_merge, limit);
    node.merged = select(0u, 1u, similar);
    return node;
}

// How far from the node's centre a child's patches reach.
fn child_reach(c: Node, has: bool, node: Node) -> f32 {
    return select(0.0, length(c.position - node.position) + c.extent, has);
}

fn child_agrees(c: Node, has: bool, node: Node, cos_merge: f32, limit: f32) -> bool {
    return !has || (c.merged == 1u && dot(c.normal, node.normal) >= cos_merge
        && length(c.position - node.position) <= limit);
}
