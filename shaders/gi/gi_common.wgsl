// Shared declarations of the GI plugin's passes: the quadtree node of the reduced flux
// G-buffer, the reflection light, and the per-frame parameters.

// One texel of the flux G-buffer's mip chain. A coherent node stands for all texels below it
// as one Lambertian emitter; an incoherent one keeps its most significant child's position
// and normal but always the full flux sum, so energy is never dropped.
struct Node {
    position: vec3f,
    // Flux-weighted distance from the lamp (m).
    dist: f32,
    normal: vec3f,
    // 1 when every texel below merged under the thresholds.
    merged: u32,
    // Reflected flux Φ (W), summed over the texels below.
    flux: vec3f,
    // Σ luminance(Φ): the weight of position and normal averages.
    weight: f32,
};

// A reflection light: I_r(ω) = Φ/π · max(0, n_r·ω).
struct ReflectionLight {
    position: vec3f,
    // Distance along the normal at which the irradiance falls to the cutoff; the light's
    // volume encloses the region where it is above.
    radius: f32,
    normal: vec3f,
    // The mip level it came from (0 = one texel).
    level: u32,
    flux: vec3f,
    pad: f32,
};

struct GiParams {
    // Size of the flux G-buffer (level 0) and of the indirect (irradiance) target.
    flux_size: vec2u,
    indirect_size: vec2u,
    // tan of the lamp frustum's half angles (x, y), the lamp's power P (for the flux view).
    lamp_tan: vec2f,
    lamp_power: f32,
    // cos(merge normal threshold), merge distance fraction, cutoff (W/m²), d_min (m).
    cos_merge: f32,
    merge_distance: f32,
    cutoff: f32,
    d_min: f32,
    // 0: flux from the lamp, Φ = ρ·I·Ω; 1: flux from the previous bounce, Φ = ρ·E·A.
    source: u32,
};

fn luminance(c: vec3f) -> f32 {
    return dot(c, vec3f(0.2126, 0.7152, 0.0722));
}

// Irradiance at x (normal n_x) from a Lambertian emitter at p (normal n_r) of flux Φ:
// E = Φ/π · max(0, n_r·ω) · max(0, n_x·(−ω)) / max(d², d_min²), ω from the light to x.
fn reflection_irradiance(flux: vec3f, p: vec3f, n_r: vec3f, x: vec3f, n_x: vec3f, d_min: f32) -> vec3f {
    let v = x - p;
    let d2 = dot(v, v);
    let w = v * inverseSqrt(max(d2, 1e-12));
    let g = max(0.0, dot(n_r, w)) * max(0.0, dot(n_x, -w)) / max(d2, d_min * d_min);
    return flux * (g / PI);
}
