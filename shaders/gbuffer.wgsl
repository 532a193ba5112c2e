// G-buffer pass: rasterises the scene from the camera into diffuse albedo, world normal, world
// position (+ view depth), emissive and specular (F0, roughness) targets.
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
    @location(4) specular: vec4f,
};

// The G-buffer texel of a surface point; reflection and emitted radiance from the material or
// instance.
fn gbuffer_texel(world: vec3f, normal: vec3f, front: bool, surface: SurfaceReflection, emissive: vec3f) -> GBufferOut {
    // Surfaces are lit on the side the viewer sees: single-sided walls of any winding work.
    var n = normalize(normal);
    if !front {
        n = -n;
    }
    let view_depth = -(globals.view * vec4f(world, 1.0)).z;
    var out: GBufferOut;
    out.albedo = vec4f(surface.diffuse, 1.0);
    out.normal = vec4f(n, 1.0);
    out.position = vec4f(world, view_depth);
    out.emissive = vec4f(emissive, 1.0);
    out.specular = surface.specular;
    return out;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> GBufferOut {
    let surface = surface_reflection(in, surface_base_color(in).rgb);
    return gbuffer_texel(in.world, in.normal, front, surface, surface_emissive(in));
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
    return gbuffer_texel(in.world, in.normal, front, surface_reflection(in, base_color.rgb), emissive);
}

// Dynamic instances: same targets, colours from the instance instead of a material; Lambertian.
@vertex
fn vs_instance(v: VertexIn, i: InstanceIn) -> InstanceOut {
    return instance_vertex(v, i, globals.view_proj);
}

@fragment
fn fs_instance(in: InstanceOut, @builtin(front_facing) front: bool) -> GBufferOut {
    let surface = SurfaceReflection(in.base_color, vec4f(0.0));
    return gbuffer_texel(in.world, in.normal, front, surface, in.emissive);
}
