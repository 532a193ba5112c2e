// View-model pass: meshes held in front of the camera (ViewState::view_models), drawn over the
// lit frame with their own depth buffer, so they never go into a wall. Lit as the G-buffer's
// surfaces are (lights.wgsl: the headlamp with its shadow while detached, the camera flash,
// the punctual lights), plus the indirect irradiance at the probe point, an ambient cube that
// a GI plugin may have written (zero otherwise). L = ρ/π · (E_direct + E_indirect) + emission.
#include "common.wgsl"
#include "scene_surface.wgsl"
#include "lights.wgsl"

// Group 2, as group 1 is scene_surface.wgsl's material (unused here).
// E for a surface facing +X, −X, +Y, −Y, +Z, −Z (W/m²; `view_model.irradiance`).
@group(2) @binding(0) var<storage, read> ambient_cube: array<vec4f, 6>;
@group(2) @binding(1) var lamp_depth: texture_depth_2d;
@group(2) @binding(2) var lamp_shadow: sampler_comparison;

@vertex
fn vs_main(v: VertexIn, i: InstanceIn) -> InstanceOut {
    return instance_vertex(v, i, globals.view_proj);
}

// The ambient cube's irradiance for unit normal n: each axis weighted by n², the face it
// looks towards chosen by the sign (Half-Life 2's ambient cube).
fn indirect_irradiance(n: vec3f) -> vec3f {
    let w = n * n;
    let x = select(ambient_cube[1].rgb, ambient_cube[0].rgb, n.x >= 0.0);
    let y = select(ambient_cube[3].rgb, ambient_cube[2].rgb, n.y >= 0.0);
    let z = select(ambient_cube[5].rgb, ambient_cube[4].rgb, n.z >= 0.0);
    return w.x * x + w.y * y + w.z * z;
}

@fragment
fn fs_main(in: InstanceOut, @builtin(front_facing) front: bool) -> @location(0) vec4f {
    // Lit on the side the camera sees, as the G-buffer's instances are.
    var n = normalize(in.normal);
    if !front {
        n = -n;
    }
    let x = in.world;
    let e = headlamp_light(lamp_depth, lamp_shadow, x, n).e + flash_light(x, n).e + punctual_irradiance(x, n)
        + indirect_irradiance(n);
    return vec4f(in.base_color / PI * e + in.emissive, 1.0);
}
