// GI shading pass: each reflection light is an instanced low-poly volume enclosing the region
// where its irradiance exceeds the cutoff; its fragments read the camera G-buffer and add
// E = Φ/π · max(0, n_r·ω) · max(0, n_x·(−ω)) / max(d², d_min²) into the irradiance target.
#include "common.wgsl"
#include "gi_common.wgsl"

@group(1) @binding(0) var<uniform> params: GiParams;
@group(1) @binding(1) var<storage, read> reflection_lights: array<ReflectionLight>;
@group(1) @binding(2) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(3) var gbuffer_position: texture_2d<f32>;

// An icosahedron: 12 unit vertices, 20 faces.
const T: f32 = 1.618034;
const ICO_VERTICES = array<vec3f, 12>(
    vec3f(-1.0, T, 0.0), vec3f(1.0, T, 0.0), vec3f(-1.0, -T, 0.0), vec3f(1.0, -T, 0.0),
    vec3f(0.0, -1.0, T), vec3f(0.0, 1.0, T), vec3f(0.0, -1.0, -T), vec3f(0.0, 1.0, -T),
    vec3f(T, 0.0, -1.0), vec3f(T, 0.0, 1.0), vec3f(-T, 0.0, -1.0), vec3f(-T, 0.0, 1.0),
);
const ICO_INDICES = array<u32, 60>(
    0u, 11u, 5u, 0u, 5u, 1u, 0u, 1u, 7u, 0u, 7u, 10u, 0u, 10u, 11u,
    1u, 5u, 9u, 5u, 11u, 4u, 11u, 10u, 2u, 10u, 7u, 6u, 7u, 1u, 8u,
    3u, 9u, 4u, 3u, 4u, 2u, 3u, 2u, 6u, 3u, 6u, 8u, 3u, 8u, 9u,
    4u, 9u, 5u, 2u, 4u, 11u, 6u, 2u, 10u, 8u, 6u, 7u, 9u, 8u, 1u,
);
// Scales the unit-circumradius icosahedron so its inscribed sphere has radius 1.
const INSCRIBED: f32 = 1.2584;
// A Lambertian emitter's cutoff surface, r(θ) = R·√cos θ, lies in front of it and inside the
// sphere centred R/2 along its normal with radius √(4/27 + 1/4)·R (the worst case is at
// cos θ = 4/9): a quarter of the volume of the sphere of radius R around the light.
const VOLUME_OFFSET: f32 = 0.5;
const VOLUME_RADIUS: f32 = 0.6311;

struct VolumeOut {
    @builtin(position) clip: vec4f,
    @location(0) @interpolate(flat) light: u32,
};

@vertex
fn vs_main(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VolumeOut {
    let light = reflection_lights[i];
    let corner = normalize(ICO_VERTICES[ICO_INDICES[v]]) * INSCRIBED * VOLUME_RADIUS * light.radius;
    let centre = light.position + light.normal * (VOLUME_OFFSET * light.radius);
    var out: VolumeOut;
    out.clip = globals.view_proj * vec4f(centre + corner, 1.0);
    out.light = i;
    return out;
}

// The full-resolution G-buffer texel an indirect-target pixel stands for.
fn gbuffer_texel(frag: vec2f) -> vec2i {
    let scale = vec2f(textureDimensions(gbuffer_normal)) / vec2f(params.indirect_size);
    return vec2i(frag * scale);
}

@fragment
fn fs_main(in: VolumeOut) -> @location(0) vec4f {
    let t = gbuffer_texel(in.clip.xy);
    let normal = textureLoad(gbuffer_normal, t, 0);
    if normal.w == 0.0 {
        discard;
    }
    let x = textureLoad(gbuffer_position, t, 0).xyz;
    let light = reflection_lights[in.light];
    let e = reflection_irradiance(light.flux, light.position, light.normal, x, normal.xyz, params.d_min);
    return vec4f(e, 1.0);
}
