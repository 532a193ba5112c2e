// GI reference: the exact one bounce of the lamp's light. Every texel of the full-resolution
// flux G-buffer is a sender, with no merging, no cutoff and no clamp: each is the small
// surface patch it is (area A = Ω·d²/cos θ seen from the lamp), taken as the disc of that
// area (disc_irradiance, exact for a disc however close, as the gather's lights). As the lamp
// view's resolution rises the patches shrink and the sum converges to the integral. The indirect
// radiance ρ/π · E of each camera pixel is summed over all of them: O(pixels × texels), for
// tests and `bench` at small sizes. The flux is pyramid.wgsl's, so it holds the same sources:
// the lamp and, attached, the camera flash — but computed here for every texel of the lamp
// view, not taken from the pyramid's (subsampled) base.
//
// The senders are taken in ranges, one dispatch each, summing into `sums`: a CPU device
// (Mesa's llvmpipe) stops any loop nest after 65,535 iterations without a word, which cut the
// sum short from 320×240 up.
//
// Within NEAR_RADII of a receiver a sender is integrated over its footprint instead (the
// point-to-quad form factor).
#include "common.wgsl"
#include "gi_common.wgsl"

@group(1) @binding(0) var<uniform> params: GiParams;
// The senders: albedo, position and normal of each lamp-view texel.
@group(1) @binding(1) var light_albedo: texture_2d<f32>;
@group(1) @binding(2) var light_position: texture_2d<f32>;
@group(1) @binding(3) var light_normal: texture_2d<f32>;
// The receivers: the camera G-buffer.
@group(1) @binding(4) var gbuffer_albedo: texture_2d<f32>;
@group(1) @binding(5) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(6) var gbuffer_position: texture_2d<f32>;
@group(1) @binding(7) var reference_out: texture_storage_2d<rgba32float, write>;
// This dispatch's senders: [first, first + count); `last` = 1 on the final range. The
// receivers are the centre pixels of the view's `stride`×`stride` blocks (1: every pixel); the
// rest of each block is written black, so a view rendered at k times a size with stride k
// holds that size's receivers lit by k² as many senders.
struct SenderRange {
    first: u32,
    count: u32,
    last: u32,
    stride: u32,
};
@group(1) @binding(8) var<uniform> range: SenderRange;
// Irradiance summed so far, per receiver pixel.
@group(1) @binding(9) var<storage, read_write> sums: array<vec4f>;

struct Sender {
    position: vec3f,
    area: f32,
    normal: vec3f,
    lit: f32,
    flux: vec3f,
    pad: f32,
};

// Within this many patch radii of a receiver, a sender's light is integrated over its texel's
// footprint (quad_irradiance) rather than taken as a disc about its centre: next to a
// sender (where walls meet) the centre form depends on where the texel grid happens to fall
// and converges slowly; farther away its error falls as (size / distance)².
const NEAR_RADII: f32 = 8.0;

// The surface patch that texel t of a `size` lamp view covers: where its four corner rays meet
// the plane of its sample (p, n), in order around it. Grazing corner rays are held to the
// MIN_AREA_COS slope, as texel_area holds the area.
fn texel_footprint(t: vec2u, size: vec2u, p: vec3f, n: vec3f) -> array<vec3f, 4> {
    let o = params.view_origin.xyz;
    let height = dot(p - o, n);
    var corners: array<vec3f, 4>;
    for (var k = 0u; k < 4u; k++) {
        let c = vec2f(f32(k == 1u || k == 2u), f32(k >= 2u));
        let uv = (vec2f(t) + c) / vec2f(size);
        let dir = params.view_forward.xyz + (uv.x * 2.0 - 1.0) * params.view_right.xyz
            + (1.0 - uv.y * 2.0) * params.view_up.xyz;
        let slope = min(dot(dir, n), -MIN_AREA_COS * length(dir));
        corners[k] = o + dir * (height / slope);
    }
    return corners;
}

// Irradiance at x (normal n_x) from a Lambertian quad q (normal n_r) that spreads flux Φ evenly:
// E = Φ/A · F, F the point-to-polygon form factor of the quad's part above x's plane
// (Lambert's formula, F = 1/2π · Σ over edges of the angle they subtend times n_x · their
// plane's normal). Exact however close x lies, even where x's plane cuts the patch.
fn quad_irradiance(flux: vec3f, q: array<vec3f, 4>, n_r: vec3f, x: vec3f, n_x: vec3f) -> vec3f {
    let area = 0.5 * length(cross(q[2] - q[0], q[3] - q[1]));
    // A receiver (all but) on the patch's plane gets nothing; the test is against a hundredth
    // of the patch's size, since at a rise of rounding noise the clip below would be decided
    // by the (half-precision) normals' noise instead.
    if area <= 0.0 || dot(x - q[0], n_r) <= 0.01 * sqrt(area) {
        return vec3f(0.0);
    }
    // The quad relative to x, clipped to x's upper hemisphere (at most five corners).
    var poly: array<vec3f, 8>;
    var m = 0u;
    for (var i = 0u; i < 4u; i++) {
        let a = q[i] - x;
        let b = q[(i + 1u) % 4u] - x;
        let ha = dot(a, n_x);
        let hb = dot(b, n_x);
        if ha >= 0.0 {
            poly[m] = a;
            m++;
        }
        if (ha >= 0.0) != (hb >= 0.0) {
            poly[m] = a + (b - a) * (ha / (ha - hb));
            m++;
        }
    }
    var f = 0.0;
    for (var i = 0u; i < m; i++) {
        let a = poly[i];
        let b = poly[(i + 1u) % m];
        let c = cross(a, b);
        let s = length(c);
        let la = length(a);
        let lb = length(b);
        if s > 1e-12 * la * lb {
            f += atan2(s, dot(a, b)) * dot(n_x, c) / s;
        }
    }
    return flux * (abs(f) / (2.0 * PI * area));
}

const TILE: u32 = 64u;
var<workgroup> tile: array<Sender, 64>;
// Each sender's footprint, for receivers in its near field.
var<workgroup> footprints: array<array<vec3f, 4>, 64>;

// For the senders marked in `near`: their footprint's irradiance at x minus the disc's
// already summed.
fn near_field_correction(near: vec2u, x: vec3f, n: vec3f) -> vec3f {
    var e = vec3f(0.0);
    for (var half = 0u; half < 2u; half++) {
        var bits = near[half];
        while bits != 0u {
            let i = half * 32u + firstTrailingBit(bits);
            bits &= bits - 1u;
            let s = tile[i];
            e += quad_irradiance(s.flux, footprints[i], s.normal, x, n)
                - disc_irradiance(s.flux, s.area, s.position, s.normal, x, n);
        }
    }
    return e;
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
    let size = textureDimensions(gbuffer_normal);
    let stride = range.stride;
    let blocks = size / stride;
    let block = vec2u(id.x % blocks.x, id.x / blocks.x);
    let pixel = block * stride + stride / 2u;
    let in_view = id.x < blocks.x * blocks.y;
    var normal = vec4f(0.0);
    var x = vec3f(0.0);
    if in_view {
        normal = textureLoad(gbuffer_normal, vec2i(pixel), 0);
        x = textureLoad(gbuffer_position, vec2i(pixel), 0).xyz;
    }
    var e = vec3f(0.0);
    if in_view && range.first > 0u {
        e = sums[id.x].rgb;
    }
    let senders = textureDimensions(light_position);
    let end = min(range.first + range.count, senders.x * senders.y);
    for (var start = range.first; start < end; start += TILE) {
        workgroupBarrier();
        var sender: Sender;
        let k = start + local;
        if k < end {
            let t = vec2u(k % senders.x, k / senders.x);
            sender.position = textureLoad(light_position, vec2i(t), 0).xyz;
            let n = textureLoad(light_normal, vec2i(t), 0);
            sender.normal = n.xyz;
            let omega = texel_solid_angle(t, senders, params.lamp_tan);
            if n.w > 0.0 {
                let rho = textureLoad(light_albedo, vec2i(t), 0).rgb;
                sender.flux = lamp_reflected_flux(rho, sender.position, omega);
            }
            sender.lit = select(0.0, 1.0, n.w > 0.0 && any(sender.flux > vec3f(0.0)));
            sender.area = texel_area(omega, sender.position, n.xyz, globals.lamp_pos.xyz);
            footprints[local] = texel_footprint(t, senders, sender.position, n.xyz);
        }
        tile[local] = sender;
        workgroupBarrier();
        if in_view && normal.w > 0.0 {
            // The senders in this receiver's near field, as bits: corrected in a loop of their
            // own, since a CPU device runs both sides of a branch that any lane takes.
            var near = vec2u(0u);
            for (var i = 0u; i < TILE; i++) {
                let s = tile[i];
                if s.lit > 0.0 {
                    e += disc_irradiance(s.flux, s.area, s.position, s.normal, x, normal.xyz);
                    let d = x - s.position;
                    if dot(d, d) < NEAR_RADII * NEAR_RADII * s.area / PI {
                        near[i / 32u] |= 1u << (i % 32u);
                    }
                }
            }
            e += near_field_correction(near, x, normal.xyz);
        }
    }
    if in_view {
        if range.last == 1u {
            for (var k = 0u; k < stride * stride; k++) {
                let other = block * stride + vec2u(k % stride, k / stride);
                if any(other != pixel) {
                    textureStore(reference_out, vec2i(other), vec4f(0.0, 0.0, 0.0, 1.0));
                }
            }
            let rho = textureLoad(gbuffer_albedo, vec2i(pixel), 0).rgb;
            textureStore(reference_out, vec2i(pixel), vec4f(rho / PI * e, 1.0));
        } else {
            sums[id.x] = vec4f(e, 0.0);
        }
    }
}
