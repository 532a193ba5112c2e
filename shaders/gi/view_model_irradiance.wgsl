// GI view-model probe: the first bounce's indirect irradiance at one point, the engine's view
// model probe (ViewState::view_model_probe), for a surface facing each world axis: the ambient
// cube `view_model.irradiance` the engine's view-model pass reads (view_model.wgsl). It sums
// one level of the flux pyramid, whose nodes share out every lamp-view texel's flux once, each
// node a Lambertian disc (disc_irradiance, as the gather's lights). No visibility, as the
// gather's. One workgroup.
#include "common.wgsl"
#include "gi_common.wgsl"

struct Probe {
    // xyz: the point (m).
    position: vec4f,
    // x: the pyramid level summed.
    level: vec4u,
};

@group(1) @binding(0) var<uniform> probe: Probe;
@group(1) @binding(1) var<uniform> levels: Levels;
@group(1) @binding(2) var<storage, read> nodes: array<Node>;
// E (W/m²) for normals +X, −X, +Y, −Y, +Z, −Z; zeroed by the engine, added to here.
@group(1) @binding(3) var<storage, read_write> ambient_cube: array<vec4f, 6>;

const THREADS: u32 = 64u;

// Each lane's six sums, one array per axis (arrays of structs cost dearly on a CPU device).
var<workgroup> sum_px: array<vec3f, THREADS>;
var<workgroup> sum_nx: array<vec3f, THREADS>;
var<workgroup> sum_py: array<vec3f, THREADS>;
var<workgroup> sum_ny: array<vec3f, THREADS>;
var<workgroup> sum_pz: array<vec3f, THREADS>;
var<workgroup> sum_nz: array<vec3f, THREADS>;

fn node_irradiance(node: Node, x: vec3f, n: vec3f) -> vec3f {
    return disc_irradiance(node.flux, node.area, node.position, node.normal, x, n);
}

@compute @workgroup_size(64)
fn main(@builtin(local_invocation_index) lane: u32) {
    let level = levels.levels[probe.level.x];
    let count = level.y * level.z;
    let x = probe.position.xyz;
    var px = vec3f(0.0);
    var nx = vec3f(0.0);
    var py = vec3f(0.0);
    var ny = vec3f(0.0);
    var pz = vec3f(0.0);
    var nz = vec3f(0.0);
    for (var i = lane; i < count; i += THREADS) {
        let node = nodes[level.x + i];
        if all(node.flux <= vec3f(0.0)) {
            continue;
        }
        px += node_irradiance(node, x, vec3f(1.0, 0.0, 0.0));
        nx += node_irradiance(node, x, vec3f(-1.0, 0.0, 0.0));
        py += node_irradiance(node, x, vec3f(0.0, 1.0, 0.0));
        ny += node_irradiance(node, x, vec3f(0.0, -1.0, 0.0));
        pz += node_irradiance(node, x, vec3f(0.0, 0.0, 1.0));
        nz += node_irradiance(node, x, vec3f(0.0, 0.0, -1.0));
    }
    sum_px[lane] = px;
    sum_nx[lane] = nx;
    sum_py[lane] = py;
    sum_ny[lane] = ny;
    sum_pz[lane] = pz;
    sum_nz[lane] = nz;
    workgroupBarrier();
    if lane != 0u {
        return;
    }
    var e = array<vec3f, 6>();
    for (var k = 0u; k < THREADS; k++) {
        e[0] += sum_px[k];
        e[1] += sum_nx[k];
        e[2] += sum_py[k];
        e[3] += sum_ny[k];
        e[4] += sum_pz[k];
        e[5] += sum_nz[k];
    }
    for (var k = 0u; k < 6u; k++) {
        ambient_cube[k] += vec4f(e[k], 0.0);
    }
}
