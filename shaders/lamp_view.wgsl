// Lamp view pass: rasterises the scene from the detached headlamp's frustum into the lamp's own
// G-buffer (a reflective shadow map): diffuse albedo ρ = (1 − metallic)·base colour, world
// normal facing the lamp, world position (+ distance along the lamp's view axis) and reversed-Z
// depth, which the direct light pass uses as the lamp's shadow map.
#include "common.wgsl"
#include "scene_surface.wgsl"

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    return surface_vertex(v, globals.lamp_view_proj);
}

struct LampOut {
    @location(0) albedo: vec4f,
    @location(1) normal: vec4f,
    @location(2) position: vec4f,
};

// The lamp-view texel of a surface point of albedo ρ.
fn lamp_texel(world: vec3f, normal: vec3f, albedo: vec3f) -> LampOut {
    // The side the lamp sees, whatever the winding: n·(lamp − x) ≥ 0.
    var n = normalize(normal);
    if dot(n, globals.lamp_pos.xyz - world) < 0.0 {
        n = -n;
    }
    // The lamp's projection is a perspective one: clip w is the distance along its view axis.
    let axis_distance = (globals.lamp_view_proj * vec4f(world, 1.0)).w;
    var out: LampOut;
    out.albedo = vec4f(albedo, 1.0);
    out.normal = vec4f(n, 1.0);
    out.position = vec4f(world, axis_distance);
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> LampOut {
    return lamp_texel(in.world, in.normal, surface_reflection(in, surface_base_color(in).rgb).diffuse);
}

// Alpha-tested materials: the lamp sees through their holes (shadows and the GI's flux).
@fragment
fn fs_masked(in: VertexOut) -> LampOut {
    let base_color = surface_base_color(in);
    if surface_cut_out(base_color) {
        discard;
    }
    return lamp_texel(in.world, in.normal, surface_reflection(in, base_color.rgb).diffuse);
}

// Dynamic instances: they shadow the lamp and reflect its light like the level.
@vertex
fn vs_instance(v: VertexIn, i: InstanceIn) -> InstanceOut {
    return instance_vertex(v, i, globals.lamp_view_proj);
}

@fragment
fn fs_instance(in: InstanceOut) -> LampOut {
    return lamp_texel(in.world, in.normal, in.base_color);
}
