// The direct light at a point, shared by the passes that light surfaces (direct_light.wgsl for
// the G-buffer, view_model.wgsl for the view models): each light's `Incident` at x with unit
// normal n, its irradiance-like I·cos/d² (E for a directional light) and where it comes from; a
// Lambertian surface's radiance is ρ/π times the sum. Needs common.wgsl.

// Light arriving at a point: the unit direction l towards its source and the irradiance-like
// e = I·cos/d² it brings (E for a directional light; 0 from a light that is off).
struct Incident {
    l: vec3f,
    e: vec3f,
};

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

fn punctual(light: Light, x: vec3f, n: vec3f) -> Incident {
    let kind = u32(light.direction_kind.w);
    if kind == LIGHT_DIRECTIONAL {
        // Directional: irradiance E = intensity · cos.
        let l = -light.direction_kind.xyz;
        return Incident(l, light.color.rgb * max(0.0, dot(n, l)));
    }
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
    if kind == LIGHT_SPOT {
        let cos_angle = dot(-l, light.direction_kind.xyz);
        intensity *= smoothstep(light.cone.y, light.cone.x, cos_angle);
    }
    return Incident(l, intensity * max(0.0, dot(n, l)) / d2);
}

// Fraction of the detached headlamp that x (normal n, unit direction l to the lamp at
// `distance`) sees: 3×3 bilinear comparisons of `lamp.depth`, i.e. percentage-closer filtering
// over a 4×4-texel tent. Exactly 0 in the umbra, exactly 1 well outside the penumbra. `lamp_depth`
// is `lamp.depth`, `lamp_shadow` a bilinear GreaterEqual comparison (reversed Z).
fn lamp_visibility(
    lamp_depth: texture_depth_2d,
    lamp_shadow: sampler_comparison,
    x: vec3f,
    n: vec3f,
    l: vec3f,
    distance: f32,
) -> f32 {
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

// The headlamp's light at x: its intensity distribution, shadowed by `lamp.depth` while it is
// detached (attached, it sits at the eye and sees everything the camera sees: no test).
fn headlamp_light(lamp_depth: texture_depth_2d, lamp_shadow: sampler_comparison, x: vec3f, n: vec3f) -> Incident {
    let to_lamp = globals.lamp_pos.xyz - x;
    let d2 = max(dot(to_lamp, to_lamp), 1e-8);
    let l = to_lamp * inverseSqrt(d2);
    if globals.lamp_pos.w < 0.5 {
        return Incident(l, vec3f(0.0));
    }
    var lamp = lamp_intensity_towards(x) * max(0.0, dot(n, l)) / d2;
    if globals.params.z > 0.5 && any(lamp > vec3f(0.0)) {
        lamp *= lamp_visibility(lamp_depth, lamp_shadow, x, n, l, sqrt(d2));
    }
    return Incident(l, lamp);
}

// The camera flash, isotropic at the eye: its light arrives along the way to the eye. No
// shadow test: every point the eye sees has a clear line to a light at the eye.
fn flash_light(x: vec3f, n: vec3f) -> Incident {
    let to_eye = globals.camera_pos.xyz - x;
    let d2 = max(dot(to_eye, to_eye), 1e-8);
    let l = to_eye * inverseSqrt(d2);
    if all(globals.camera_flash.rgb <= vec3f(0.0)) {
        return Incident(l, vec3f(0.0));
    }
    return Incident(l, globals.camera_flash.rgb * max(0.0, dot(n, l)) / d2);
}

// Every punctual light of the level (unshadowed).
fn punctual_irradiance(x: vec3f, n: vec3f) -> vec3f {
    var e = vec3f(0.0);
    let count = u32(globals.params.y);
    for (var i = 0u; i < count; i++) {
        e += punctual(lights[i], x, n).e;
    }
    return e;
}
