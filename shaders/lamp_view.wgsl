// Lamp view pass: rasterises the scene from the detached headlamp's frustum into the lamp's own
// G-buffer (a reflective shadow map): albedo ρ, world normal facing the lamp, world position
// (+ distance along the lamp's view axis) and reversed-Z depth, which the direct light pass
// uses as the lamp's shadow map.
#include "common.wgsl"

struct Material {
    base_color: vec4f,
    // rgb emissive radiance; w: 1 when a base colour texture is bound.
    emissive: vec4f,
};

@group(1) @binding(0) var<uniform> material: Material;
@group(1) @binding(1) var base_color_texture: texture_2d<f32>;
@group(1) @binding(2) var material_sampler: sampler;

struct VertexIn {
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
};

struct VertexOut {
    @builtin(position) clip: vec4f,
    @location(0) world: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
};

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = globals.lamp_view_proj * vec4f(v.position, 1.0);
    out.world = v.position;
    out.normal = v.normal;
    out.uv = v.uv;
    return out;
}

struct LampOut {
    @location(0) albedo: vec4f,
    @location(1) normal: vec4f,
    @location(2) position: vec4f,
};

@fragment
fn fs_main(in: VertexOut) -> LampOut {
    var albedo = material.base_color;
    if material.emissive.w > 0.5 {
        albedo *= textureSample(base_color_texture, material_sampler, in.uv);
    }
    // The side the lamp sees, whatever the winding: n·(lamp − x) ≥ 0.
    var n = normalize(in.normal);
    if dot(n, globals.lamp_pos.xyz - in.world) < 0.0 {
        n = -n;
    }
    // The lamp's projection is a perspective one: clip w is the distance along its view axis.
    let axis_distance = (globals.lamp_view_proj * vec4f(in.world, 1.0)).w;
    var out: LampOut;
    out.albedo = vec4f(albedo.rgb, 1.0);
    out.normal = vec4f(n, 1.0);
    out.position = vec4f(in.world, axis_distance);
    return out;
}
