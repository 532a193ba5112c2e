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

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> GBufferOut {
    let albedo = surface_albedo(in);
    // Surfaces are lit on the side the viewer sees: single-sided walls of any winding work.
    var n = normalize(in.normal);
    if !front {
        n = -n;
    }
    let view_depth = -(globals.view * vec4f(in.world, 1.0)).z;
    var out: GBufferOut;
    out.albedo = vec4f(albedo, 1.0);
    out.normal = vec4f(n, 1.0);
    out.position = vec4f(in.world, view_depth);
    out.emissive = vec4f(material.emissive.rgb, 1.0);
    return out;
}
