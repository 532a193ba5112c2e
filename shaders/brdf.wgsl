// glTF 2.0's metallic-roughness BRDF (the spec's Appendix B) as the direct light evaluates it,
// from a G-buffer texel's diffuse albedo ρ = (1 − metallic)·base colour and its specular row
// (F0 = mix(0.04, base colour, metallic), perceptual roughness; all 0 for Lambertian):
//   f(l, v) = (1 − F_dielectric(v·h))·ρ/π + F(v·h)·D(n·h)·V(n·l, n·v)
// with Schlick's Fresnel F = F0 + (1 − F0)(1 − v·h)⁵, GGX's distribution D and the
// height-correlated Smith visibility V = G/(4 n·l n·v), α = roughness². Since Schlick's F is
// linear in F0, F with the mixed F0 is exactly the spec's mix of the dielectric and metal
// Fresnel terms; the diffuse lobe is weighted by the dielectric's 1 − F (metals have ρ = 0).
// Lambertian texels (roughness 0 marks them) get ρ/π exactly.

// Fresnel reflectance at normal incidence of glTF's dielectrics (index of refraction 1.5).
const BRDF_DIELECTRIC_F0: f32 = 0.04;

// f(l, v) in sr⁻¹ per colour channel, for unit normal n, unit direction l to the light and v to
// the viewer; the caller multiplies by the irradiance I·max(0, n·l)/d².
fn brdf(n: vec3f, v: vec3f, l: vec3f, rho: vec3f, specular: vec4f) -> vec3f {
    let diffuse = rho / PI;
    let roughness = specular.a;
    if roughness == 0.0 {
        return diffuse;
    }
    let n_l = clamp(dot(n, l), 0.0, 1.0);
    // Interpolated normals can turn slightly away from the eye; keep V finite.
    let n_v = clamp(dot(n, v), 1e-4, 1.0);
    let half_sum = l + v;
    // l = −v (a light exactly behind the surface seen edge-on) has no half vector; n·l = 0 there.
    let h = half_sum * inverseSqrt(max(dot(half_sum, half_sum), 1e-12));
    let n_h = clamp(dot(n, h), 0.0, 1.0);
    let v_h = clamp(dot(v, h), 0.0, 1.0);
    let schlick = pow(1.0 - v_h, 5.0);
    let f_dielectric = BRDF_DIELECTRIC_F0 + (1.0 - BRDF_DIELECTRIC_F0) * schlick;
    let f = specular.rgb + (vec3f(1.0) - specular.rgb) * schlick;
    let alpha = roughness * roughness;
    let a2 = alpha * alpha;
    let d_denom = n_h * n_h * (a2 - 1.0) + 1.0;
    let d = a2 / (PI * d_denom * d_denom);
    let vis = 0.5 / (n_l * sqrt(n_v * n_v * (1.0 - a2) + a2) + n_v * sqrt(n_l * n_l * (1.0 - a2) + a2));
    return (1.0 - f_dielectric) * diffuse + f * (d * vis);
}
