// G-buffer pass: rasterises the scene from the camera into albedo, world normal, world position
// (+ view depth) and emissive targets.
#include "common.wgsl"
#include "scene_surface.wgsl"

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    return surface_vertex(v, globals.view_proj);
}

struct GBufferOut {
    @location(0) albedo: vec4f,
    @location(1) normal: vec4f,
    @location(2) position: vec4f,
    @location(3) emissive: vec4f,
};

// The G-buffer texel of a surface point; ρ and emitted radiance from the material or instance.
fn gbuffer_texel(world: vec3f, normal: vec3f, front: bool, albedo: vec3f, emissive: vec3f) -> GBufferOut {
    // Surfaces are lit on the side the viewer sees: single-sided walls of any winding work.
    var n = normalize(normal);
    if !front {
        n = -n;
    }
    let view_depth = -(globals.view * vec4f(world, 1.0)).z;
    var out: GBufferOut;
    out.albedo = vec4f(albedo, 1.0);
    out.normal = vec4f(n, 1.0);
    out.position = vec4f(world, view_depth);
    out.emissive = vec4f(emissive, 1.0);
    return out;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> GBufferOut {
    return gbuffer_texel(in.world, in.normal, front, surface_base_color(in).rgb, surface_emissive(in));
}

// Alpha-tested materials: a fragment whose alpha is below the cutoff is a hole. A separate
// entry point so that opaque materials keep early depth testing.
@fragment
fn fs_masked(in: VertexOut, @builtin(front_facing) front: bool) -> GBufferOut {
    let base_color = surface_base_color(in);
    let emissive = surface_emissive(in);
    if surface_cut_out(base_color) {
        discard;
    }
    return gbuffer_texel(in.world, in.normal, front, base_color.rgb, emissive);
}

// Dynamic instances: same targets, colours from the instance instead of a material.
@vertex
fn vs_instance(v: VertexIn, i: InstanceIn) -> InstanceOut {
    return instance_vertex(v, i, globals.view_proj);
}

@fragment
fn fs_instance(in: InstanceOut, @builtin(front_facing) front: bool) -> GBufferOut {
    return gbuffer_texel(in.world, in.normal, front, in.base_color, in.emissive);
}
