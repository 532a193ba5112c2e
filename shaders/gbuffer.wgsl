// G-buffer pass: rasterises the scene from the camera into albedo, world normal, world position
// (+ view depth) and emissive targets.
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
    out.clip = globals.view_proj * vec4f(v.position, 1.0);
    out.world = v.position;
    out.normal = v.normal;
    out.uv = v.uv;
    return out;
}

struct GBufferOut {
    @location(0) albedo: vec4f,
    @location(1) normal: vec4f,
    @location(2) position: vec4f,
    @location(3) emissive: vec4f,
};

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> GBufferOut {
    var albedo = material.base_color;
    if material.emissive.w > 0.5 {
        albedo *= textureSample(base_color_texture, material_sampler, in.uv);
    }
    // Surfaces are lit on the side the viewer sees: single-sided walls of any winding work.
    var n = normalize(in.normal);
    if !front {
        n = -n;
    }
    let view_depth = -(globals.view * vec4f(in.world, 1.0)).z;
    var out: GBufferOut;
    out.albedo = vec4f(albedo.rgb, 1.0);
    out.normal = vec4f(n, 1.0);
    out.position = vec4f(in.world, view_depth);
    out.emissive = vec4f(material.emissive.rgb, 1.0);
    return out;
}
