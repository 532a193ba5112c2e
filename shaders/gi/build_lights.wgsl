// GI light-building pass ("render to vertex buffer"): walks the precomputed distribution
// table's slots and appends one reflection light per coherent node into the instance buffer,
// counting them into the indirect draw arguments. An incoherent slot is refined from the
// levels below (two at most); what is still incoherent there is emitted from its most
// significant texel with its full flux, so the lights always carry all of the G-buffer's flux.
#include "common.wgsl"
#include "gi_common.wgsl"

struct DrawArgs {
    vertex_count: u32,
    instance_count: atomic<u32>,
    first_vertex: u32,
    first_instance: u32,
};

// Per level: offset into `nodes`, width, height.
struct Levels {
    levels: array<vec4u, 16>,
};

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var<uniform> table: Levels;
@group(1) @binding(2) var<storage, read> nodes: array<Node>;
// x: level, y: texel x | texel y << 16.
@group(1) @binding(3) var<storage, read> slots: array<vec2u>;
@group(1) @binding(4) var<storage, read_write> reflection_lights: array<ReflectionLight>;
@group(1) @binding(5) var<storage, read_write> args: DrawArgs;
// x: the irradiance (W/m², brightest channel) at which light volumes end this frame.
@group(1) @binding(6) var<storage, read_write> volume_cutoff: vec4f;

// Vertices of one light volume (an icosahedron drawn as 20 triangles).
const VOLUME_VERTICES: u32 = 60u;
const MAX_REFINE: u32 = 2u;

// Starts the frame's light list, and turns the relative cutoff setting into an irradiance:
// cutoff × E_ref, E_ref = Φ_total / (π d̄²) being what all the reflected flux gives at the
// flux-weighted mean distance from the lamp, read off the quadtree's coarsest level.
@compute @workgroup_size(1)
fn reset() {
    args.vertex_count = VOLUME_VERTICES;
    atomicStore(&args.instance_count, 0u);
    args.first_vertex = 0u;
    args.first_instance = 0u;
    var top = 0u;
    for (var l = 1u; l < 16u; l++) {
        if table.levels[l].y > 0u {
            top = l;
        }
    }
    let level = table.levels[top];
    var flux = vec3f(0.0);
    var weight = 0.0;
    var dist = 0.0;
    for (var i = 0u; i < level.y * level.z; i++) {
        let n = nodes[level.x + i];
        flux += n.flux;
        weight += n.weight;
        dist += n.dist * n.weight;
    }
    let mean_dist = select(1.0, dist / weight, weight > 0.0);
    let e_ref = max(flux.r, max(flux.g, flux.b)) / (PI * mean_dist * mean_dist);
    volume_cutoff = vec4f(params.cutoff * e_ref, e_ref, mean_dist, 0.0);
}

fn node_at(level: u32, t: vec2u) -> Node {
    let l = table.levels[level];
    return nodes[l.x + t.y * l.y + t.x];
}

fn in_level(level: u32, t: vec2u) -> bool {
    let l = table.levels[level];
    return t.x < l.y && t.y < l.z;
}

fn emit(node: Node, level: u32) {
    if node.weight <= 0.0 {
        return;
    }
    let index = atomicAdd(&args.instance_count, 1u);
    if index >= arrayLength(&reflection_lights) {
        return; // cannot happen: capacity = slots × 4^MAX_REFINE
    }
    var light: ReflectionLight;
    light.position = node.position;
    light.normal = node.normal;
    light.flux = node.flux;
    light.level = level;
    // Where Φ/π · 1 · 1 / d² (the most a receiver can get) falls to the cutoff.
    let peak = max(node.flux.r, max(node.flux.g, node.flux.b));
    light.radius = sqrt(peak / (PI * max(volume_cutoff.x, 1e-30)));
    reflection_lights[index] = light;
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= arrayLength(&slots) {
        return;
    }
    let slot = slots[id.x];
    let level = slot.x;
    let t = vec2u(slot.y & 0xffffu, slot.y >> 16u);
    let node = node_at(level, t);
    if node.merged == 1u || level == 0u {
        emit(node, level);
        return;
    }
    // Refine: children, then grandchildren; the last level emits whatever it finds.
    for (var i = 0u; i < 4u; i++) {
        let c = t * 2u + vec2u(i & 1u, i >> 1u);
        if !in_level(level - 1u, c) {
            continue;
        }
        let child = node_at(level - 1u, c);
        if child.merged == 1u || level == 1u || MAX_REFINE < 2u {
            emit(child, level - 1u);
            continue;
        }
        for (var j = 0u; j < 4u; j++) {
            let g = c * 2u + vec2u(j & 1u, j >> 1u);
            if in_level(level - 2u, g) {
                emit(node_at(level - 2u, g), level - 2u);
            }
        }
    }
}
