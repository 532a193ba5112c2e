// GI flux pyramid (pyramid.wgsl) of the first bounce: the headlamp's light reflected by the
// lamp view's texels, Φ = ρ · I(ω) · Ω_texel, shown as the `flux` view.
#include "pyramid.wgsl"

// The flux view: one texel a base texel over the lamp view, no padding.
@group(2) @binding(0) var flux_view_out: texture_storage_2d<rgba16float, write>;

// The flux the lamp-view texel t (of a view of `view` texels; albedo rho, at x, of solid angle
// omega and area `area`) reflects.
fn sender_flux(t: vec2u, view: vec2u, rho: vec3f, x: vec3f, omega: f32, area: f32) -> vec3f {
    return lamp_reflected_flux(rho, x, omega);
}

// A base texel's flux (over `omega` of the lamp's solid angle) in the flux view at `shown`:
// Φ per unit lamp solid angle relative to the lamp power, i.e. ρ·T(ω). (A store outside the
// texture is dropped.)
fn show_flux(shown: vec2i, flux: vec3f, omega: f32) {
    textureStore(flux_view_out, shown, vec4f(flux / (omega * max(params.lamp_power, 1e-20)), 1.0));
}
