// The receivers of the article's light volumes (article_volumes.wgsl) split into N×N
// sub-images and joined again (interleaved sampling, Segovia et al. 2006).
//
// `split`: each receiver of the indirect target is placed on its G-buffer texel as the cuts
// gather places it (receivers.wgsl; recorded for the temporal pass), and its position and
// normal are written where its sub-image holds it: sub-image (i, j) of the target holds the
// receivers q with q mod N = (i, j), at q / N (shifted with the receivers' grid:
// article_sub_image_layout.wgsl).
//
// `join`: each receiver's irradiance is the sum over the N² subsets of lights of that subset's
// light here, read from the nearest receivers of the subset's sub-image (the receiver's own
// subset from itself), weighted by a tent over N receivers, among those on its surface where
// there are any, else among those facing its way, else any (beside a fold, on a strip
// narrower than N receivers). Only where a subset has no receiver within N at all (at the
// view's edge) do the subsets found stand for the missing ones in proportion: standing in for
// three quarters of them, one subset's near light made a lintel glow five times too bright.
#include "common.wgsl"
#include "gi_common.wgsl"
#include "receivers.wgsl"
#include "article_sub_image_layout.wgsl"

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(2) var gbuffer_position: texture_2d<f32>;
// Where each receiver is evaluated: a G-buffer texel (x | y << 16), row by row.
@group(1) @binding(3) var<storage, read_write> receiver_texels: array<u32>;

// `split` writes each receiver's position (as bits) and packed normal (NO_NORMAL: none).
@group(2) @binding(0) var receivers_out: texture_storage_2d<rgba32uint, write>;

// `join` reads them, and the light volumes' irradiance in the same layout.
@group(3) @binding(0) var receivers_in: texture_2d<u32>;
@group(3) @binding(1) var shaded: texture_2d<f32>;
@group(3) @binding(2) var irradiance_out: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn split(@builtin(global_invocation_id) id: vec3u) {
    let q = id.xy;
    if any(q >= params.indirect_size) {
        return;
    }
    let r = receiver_at(q, textureDimensions(gbuffer_normal), params.indirect_size);
    receiver_texels[q.y * params.indirect_size.x + q.x] = pack_texel(r.texel);
    var v = vec4u(0u, 0u, 0u, NO_NORMAL);
    if r.surface.valid {
        v = vec4u(bitcast<vec3u>(r.surface.x), pack_normal(r.surface.n));
    }
    textureStore(receivers_out, sub_place(q), v);
}

struct Receiver {
    x: vec3f,
    n: vec3f,
    valid: bool,
};

fn receiver(q: vec2i) -> Receiver {
    let v = textureLoad(receivers_in, sub_place(vec2u(q)), 0);
    return Receiver(bitcast<vec3f>(v.xyz), unpack_normal(v.w), v.w != NO_NORMAL);
}

@compute @workgroup_size(8, 8)
fn join(@builtin(global_invocation_id) id: vec3u) {
    let q = vec2i(id.xy);
    let size = vec2i(params.indirect_size);
    if any(q >= size) {
        return;
    }
    let own = receiver(q);
    if !own.valid {
        textureStore(irradiance_out, q, vec4f(0.0));
        return;
    }
    let d = length(own.x - globals.camera_pos.xyz);
    let n = i32(sub_side());
    var total = vec3f(0.0);
    var found = 0;
    for (var s = 0; s < n * n; s++) {
        // The subset's receivers on either side of q, each way, in three ranks: on q's
        // surface; facing its way (a thin strip, a lintel, has receivers of only some subsets
        // on it); any. Each subset's light comes from the best rank that has one.
        let first = q - ((q - vec2i(s % n, s / n) + vec2i(sub_shift()) % n + n) % n);
        var sums: array<vec4f, 3>;
        for (var c = 0; c < 4; c++) {
            let r = first + vec2i(c & 1, c >> 1u) * n;
            if any(r < vec2i(0)) || any(r >= size) {
                continue;
            }
            let other = receiver(r);
            if !other.valid {
                continue;
            }
            let tent = (1.0 - f32(abs(r.x - q.x)) / f32(n)) * (1.0 - f32(abs(r.y - q.y)) / f32(n));
            let e = vec4f(textureLoad(shaded, sub_place(vec2u(r)), 0).rgb, 1.0) * tent;
            let facing = dot(own.n, other.n) > 0.9;
            if facing && length(other.x - own.x) < 0.1 * d && on_plane(own.x, own.n, d, other.x, other.n) {
                sums[0] += e;
            } else if facing {
                sums[1] += e;
            } else {
                sums[2] += e;
            }
        }
        var best = sums[2];
        if sums[1].w > 0.0 {
            best = sums[1];
        }
        if sums[0].w > 0.0 {
            best = sums[0];
        }
        if best.w > 0.0 {
            total += best.rgb / best.w;
            found++;
        }
    }
    let e = total * f32(n * n) / f32(max(found, 1));
    let depth = textureLoad(gbuffer_position, unpack_texel(receiver_texels[u32(q.y * size.x + q.x)]), 0).w;
    textureStore(irradiance_out, q, vec4f(e, pack_receiver(depth, own.n)));
}
