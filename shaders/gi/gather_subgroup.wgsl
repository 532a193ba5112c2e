// GI gather (gather.wgsl) where the lanes of a subgroup share their lights: each lane loads and
// unpacks one light of every `lanes.count`, and each light is broadcast to the others in turn.
// On a CPU device a subgroup is a SIMD row, whose loads from storage go lane by lane and whose
// unpacking is the same work in every lane: this halved the gather's time on lavapipe. Taken
// where every subgroup has 4 or 8 lanes (plugin_gi/src/passes/gather.rs), so that one lies within a
// run of eight receivers of one class (`receiver_position`) and sums one sequence.
#include "gather.wgsl"

// Irradiance at x (normal n) from a sequence's lights, shared by the subgroup's lanes; every
// lane of the subgroup must call it with the same sequence. Nothing is summed where no lane
// of the subgroup is `wanted` (a row of the tile on the void).
fn sequence_irradiance(s: Sequence, centre: vec3f, x: vec3f, n: vec3f, lanes: Lanes, wanted: bool) -> vec3f {
    var e = vec3f(0.0);
    if !subgroupAny(wanted) {
        return e;
    }
    for (var k0 = 0u; k0 < s.count; k0 += lanes.count) {
        let k = k0 + lanes.lane;
        var l = sequence_light(s, min(k, s.count - 1u), centre);
        l.flux = select(vec3f(0.0), l.flux, k < s.count);
        let bits = sequence_sight(s, min(k, s.count - 1u));
        // (subgroupBroadcast takes a constant lane.)
        e += disc_irradiance(subgroupBroadcast(l.flux, 0u), subgroupBroadcast(l.area, 0u),
            subgroupBroadcast(l.position, 0u), subgroupBroadcast(l.normal, 0u), x, n)
            * sight_weight(subgroupBroadcast(bits, 0u));
        e += disc_irradiance(subgroupBroadcast(l.flux, 1u), subgroupBroadcast(l.area, 1u),
            subgroupBroadcast(l.position, 1u), subgroupBroadcast(l.normal, 1u), x, n)
            * sight_weight(subgroupBroadcast(bits, 1u));
        e += disc_irradiance(subgroupBroadcast(l.flux, 2u), subgroupBroadcast(l.area, 2u),
            subgroupBroadcast(l.position, 2u), subgroupBroadcast(l.normal, 2u), x, n)
            * sight_weight(subgroupBroadcast(bits, 2u));
        e += disc_irradiance(subgroupBroadcast(l.flux, 3u), subgroupBroadcast(l.area, 3u),
            subgroupBroadcast(l.position, 3u), subgroupBroadcast(l.normal, 3u), x, n)
            * sight_weight(subgroupBroadcast(bits, 3u));
        if lanes.count == 8u {
            e += disc_irradiance(subgroupBroadcast(l.flux, 4u), subgroupBroadcast(l.area, 4u),
                subgroupBroadcast(l.position, 4u), subgroupBroadcast(l.normal, 4u), x, n)
            * sight_weight(subgroupBroadcast(bits, 4u));
            e += disc_irradiance(subgroupBroadcast(l.flux, 5u), subgroupBroadcast(l.area, 5u),
                subgroupBroadcast(l.position, 5u), subgroupBroadcast(l.normal, 5u), x, n)
            * sight_weight(subgroupBroadcast(bits, 5u));
            e += disc_irradiance(subgroupBroadcast(l.flux, 6u), subgroupBroadcast(l.area, 6u),
                subgroupBroadcast(l.position, 6u), subgroupBroadcast(l.normal, 6u), x, n)
            * sight_weight(subgroupBroadcast(bits, 6u));
            e += disc_irradiance(subgroupBroadcast(l.flux, 7u), subgroupBroadcast(l.area, 7u),
                subgroupBroadcast(l.position, 7u), subgroupBroadcast(l.normal, 7u), x, n)
            * sight_weight(subgroupBroadcast(bits, 7u));
        }
    }
    return e;
}

@compute @workgroup_size(64)
fn main(@builtin(subgroup_invocation_id) lane: u32, @builtin(subgroup_size) size: u32,
    @builtin(subgroup_id) subgroup: u32, @builtin(workgroup_id) group: vec3u) {
    store(gather(subgroup * size + lane, Lanes(lane, size), group.xy));
}

@compute @workgroup_size(64)
fn main_bounce(@builtin(subgroup_invocation_id) lane: u32, @builtin(subgroup_size) size: u32,
    @builtin(subgroup_id) subgroup: u32, @builtin(workgroup_id) group: vec3u) {
    store_bounce(gather(subgroup * size + lane, Lanes(lane, size), group.xy));
}
