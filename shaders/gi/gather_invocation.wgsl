// GI gather (gather.wgsl) where each invocation sums its lights alone: for devices without
// subgroups of 4 or 8 lanes (a GPU's loads of one address by a whole subgroup are one load
// anyway).
#include "gather.wgsl"

// Irradiance at x (normal n) from a sequence's lights; nothing is summed where not `wanted`.
fn sequence_irradiance(s: Sequence, centre: vec3f, x: vec3f, n: vec3f, lanes: Lanes, wanted: bool) -> vec3f {
    if !wanted {
        return vec3f(0.0);
    }
    return own_sequence_irradiance(s, centre, x, n);
}

@compute @workgroup_size(64)
fn main(@builtin(local_invocation_index) r: u32, @builtin(workgroup_id) group: vec3u) {
    store(gather(r, Lanes(0u, 1u), group.xy));
}

@compute @workgroup_size(64)
fn main_bounce(@builtin(local_invocation_index) r: u32, @builtin(workgroup_id) group: vec3u) {
    store_bounce(gather(r, Lanes(0u, 1u), group.xy));
}
