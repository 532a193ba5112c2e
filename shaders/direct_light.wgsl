// Direct light pass: L_d = f(l, v) · I(ω) · max(0, n·l) / d² from the headlamp, the camera
// flash and every punctual light, f being glTF's metallic-roughness BRDF (brdf.wgsl); ρ/π for
// Lambertian surfaces.
#include "common.wgsl"
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

// Reflected radiance towards the eye of `irradiance` arriving along unit direction l.
fn reflected(s: Surface, l: vec3f, irradiance: vec3f) -> vec3f {
    return brdf(s.n, s.v, l, s.rho, s.specular) * irradiance;
}

// Shadow bias, in lamp-map texel footprints at the receiver, applied by moving the receiver
// towards the lamp. A lamp texel covers `footprint` metres across the ray at the receiver, and
// a plane at angle θ to the ray changes its distance by footprint·tan θ from one texel to the
// next. The 3×3 bilinear PCF compares against texels up to 2 texels from the receiver's own,
// so the slope term needs 2·tan θ, plus margin; the constant term covers rounding of depth and
// projection. Solid occluders keep their contact shadows: the biased point is still behind
// the occluder's lit face unless the bias exceeds the occluder's thickness along the ray.
const SHADOW_BIAS_TEXELS: f32 = 1.5;
const SHADOW_SLOPE_TEXELS: f32 = 2.5;
// tan θ is capped (θ ≈ 84°): beyond it the cosine leaves almost no light to shadow.
const SHADOW_MAX_SLOPE: f32 = 10.0;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

// Radiance a punctual light reflects off s towards the eye.
fn punctual(light: Light, s: Surface) -> vec3f {
    let kind = u32(light.direction_kind.w);
    if kind == 2u {
        // Directional: irradiance E = intensity · cos.
        let l = -light.direction_kind.xyz;
        return reflected(s, l, light.color.rgb * max(0.0, dot(s.n, l)));
    }
    let x = s.x;
    let n = s.n;
    let to_light = light.position_range.xyz - x;
    let d2 = max(dot(to_light, to_light), 1e-8);
    let l = to_light * inverseSqrt(d2);
    var intensity = light.color.rgb;
    let range = light.position_range.w;
    if range > 0.0 {
        // KHR_lights_punctual's recommended smooth window, reaching zero at `range`.
        let r = sqrt(d2) / range;
        let window = clamp(1.0 - r * r * r * r, 0.0, 1.0);
        intensity *= window * window;
    }
    if kind == 1u {
        let cos_angle = dot(-l, light.direction_kind.xyz);
        intensity *= smoothstep(light.cone.y, light.cone.x, cos_angle);
    }
    return reflected(s, l, intensity * max(0.0, dot(n, l)) / d2);
}

// Fraction of the detached headlamp that x (normal n, unit direction l to the lamp at
// `distance`) sees: 3×3 bilinear comparisons of `lamp.depth`, i.e. percentage-closer filtering
// over a 4×4-texel tent. Exactly 0 in the umbra, exactly 1 well outside the penumbra.
fn lamp_visibility(x: vec3f, n: vec3f, l: vec3f, distance: f32) -> f32 {
    let cos_t = clamp(dot(n, l), 1e-4, 1.0);
    let tan_t = min(sqrt(1.0 - cos_t * cos_t) / cos_t, SHADOW_MAX_SLOPE);
    let footprint = globals.params.w * distance;
    let biased = x + l * (footprint * (SHADOW_BIAS_TEXELS + SHADOW_SLOPE_TEXELS * tan_t));
    let clip = globals.lamp_view_proj * vec4f(biased, 1.0);
    if clip.w <= 0.0 {
        return 1.0;
    }
    let ndc = clip.xyz / clip.w;
    let uv = vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
    let texel = 1.0 / vec2f(textureDimensions(lamp_depth));
    var lit = 0.0;
    for (var j = -1; j <= 1; j++) {
        for (var i = -1; i <= 1; i++) {
            let offset = vec2f(f32(i), f32(j)) * texel;
            lit += textureSampleCompareLevel(lamp_depth, lamp_shadow, uv + offset, ndc.z);
        }
    }
    return lit / 9.0;
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
    let eye_d2 = max(dot(to_eye, to_eye), 1e-8);
    let v = to_eye * inverseSqrt(eye_d2);
    let s = Surface(x, n, v, textureLoad(gbuffer_albedo, texel, 0).rgb, textureLoad(gbuffer_specular, texel, 0));

    // Σ f · I·cos/d² over the lights (f · E for directional ones).
    var radiance = vec3f(0.0);
    if globals.lamp_pos.w > 0.5 {
        let to_lamp = globals.lamp_pos.xyz - x;
        let d2 = max(dot(to_lamp, to_lamp), 1e-8);
        let l = to_lamp * inverseSqrt(d2);
        var lamp = lamp_intensity_towards(x) * max(0.0, dot(n, l)) / d2;
        // Attached, the lamp sits at the eye and sees everything the camera sees: no test.
        if globals.params.z > 0.5 && any(lamp > vec3f(0.0)) {
            lamp *= lamp_visibility(x, n, l, sqrt(d2));
        }
        radiance += reflected(s, l, lamp);
    }
    // The camera flash, isotropic at the eye. No shadow test: every point the eye sees has a
    // clear line to a light at the eye.
    if any(globals.camera_flash.rgb > vec3f(0.0)) {
        radiance += reflected(s, v, globals.camera_flash.rgb * max(0.0, dot(n, v)) / eye_d2);
    }
    let count = u32(globals.params.y);
    for (var i = 0u; i < count; i++) {
        radiance += punctual(lights[i], s);
    }
    return vec4f(radiance, 1.0);
}
