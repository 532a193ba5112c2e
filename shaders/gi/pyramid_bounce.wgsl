// GI flux pyramid (pyramid.wgsl) of a further bounce: the camera G-buffer's texels reflect the
// irradiance of the bounce before, Φ = ρ · E · A_texel.
#include "pyramid.wgsl"

// The bounce before's irradiance alone.
@group(2) @binding(0) var previous_irradiance: texture_2d<f32>;

// The flux the view texel t (of a view of `view` texels; albedo rho, at x, of solid angle
// omega and area `area`) reflects: from the irradiance sample nearest it (receiver_texel's
// inverse).
fn sender_flux(t: vec2u, view: vec2u, rho: vec3f, x: vec3f, omega: f32, area: f32) -> vec3f {
    let cells = (vec2f(t) + 0.5) * vec2f(params.indirect_size) / vec2f(view) - 0.5 - params.receiver_offset;
    let low = vec2u(clamp(vec2i(round(cells)), vec2i(0), vec2i(params.indirect_size) - 1));
    let e = textureLoad(previous_irradiance, vec2i(low), 0).rgb;
    return rho * e * area;
}

// The `flux` view shows the first bounce's senders only.
fn show_flux(shown: vec2i, flux: vec3f, omega: f32) {}
