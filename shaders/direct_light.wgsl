// Direct light pass: L_d = f(l, v) · I(ω) · max(0, n·l) / d² from the headlamp, the camera
// flash and every punctual light, f being glTF's metallic-roughness BRDF (brdf.wgsl); ρ/π for
// Lambertian surfaces.
#include "common.wgsl"
#include "lights.wgsl"
#include "brdf.wgsl"

@group(1) @binding(0) var gbuffer_albedo: texture_2d<f32>;
@group(1) @binding(1) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(2) var gbuffer_position: texture_2d<f32>;
// The detached headlamp's shadow map (reversed Z) and a bilinear GreaterEqual comparison.
@group(1) @binding(3) var lamp_depth: texture_depth_2d;
@group(1) @binding(4) var lamp_shadow: sampler_comparison;
// rgb: F0; a: perceptual roughness, 0 for Lambertian surfaces.
@group(1) @binding(5) var gbuffer_specular: texture_2d<f32>;

// A surface point as the BRDF needs it: position, unit normal, unit direction to the eye,
// diffuse albedo, specular row.
struct Surface {
    x: vec3f,
    n: vec3f,
    v: vec3f,
    rho: vec3f,
    specular: vec4f,
};

// Reflected radiance towards the eye of a light's incident irradiance.
fn reflected(s: Surface, light: Incident) -> vec3f {
    return brdf(s.n, s.v, light.l, s.rho, s.specular) * light.e;
}

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    let texel = vec2i(in.position.xy);
    let normal = textureLoad(gbuffer_normal, texel, 0);
    if normal.w == 0.0 {
        return vec4f(0.0, 0.0, 0.0, 1.0);
    }
    // Renormalised: the half-float normal is off unit length by up to ~5e-4, which GGX's peak
    // (where 1 − (n·h)²·(1 − α²) ≈ α²) turns into several per cent at low roughness.
    let n = normalize(normal.xyz);
    let x = textureLoad(gbuffer_position, texel, 0).xyz;
    let to_eye = globals.camera_pos.xyz - x;
    let v = to_eye * inverseSqrt(max(dot(to_eye, to_eye), 1e-8));
    let s = Surface(x, n, v, textureLoad(gbuffer_albedo, texel, 0).rgb, textureLoad(gbuffer_specular, texel, 0));

    // Σ f · I·cos/d² over the lights (f · E for directional ones), each light's irradiance from
    // lights.wgsl (shared with the view models) and its direction for the BRDF.
    var radiance = reflected(s, headlamp_light(lamp_depth, lamp_shadow, x, n));
    radiance += reflected(s, flash_light(x, n));
    let count = u32(globals.params.y);
    for (var i = 0u; i < count; i++) {
        radiance += reflected(s, punctual(lights[i], x, n));
    }
    return vec4f(radiance, 1.0);
}
