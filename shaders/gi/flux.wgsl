// GI flux pass: turns the lamp-view G-buffer into reflected flux per texel,
// Φ = ρ · I(ω) · Ω_texel (I: the lamp, plus the camera flash while attached), and writes
// level 0 of the node quadtree. Attached, the lamp view is the camera view, so the camera
// G-buffer is read directly (the article's key economy).
// For further bounces the source is the previous bounce's irradiance instead:
// Φ = ρ · E · A_texel, A_texel = Ω_texel · d² / cos θ being the surface area the texel covers.
#include "common.wgsl"
#include "gi_common.wgsl"

@group(1) @binding(0) var gbuffer_albedo: texture_2d<f32>;
@group(1) @binding(1) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(2) var gbuffer_position: texture_2d<f32>;
@group(1) @binding(3) var<uniform> params: GiParams;
@group(1) @binding(4) var<storage, read_write> nodes: array<Node>;
@group(1) @binding(5) var flux_out: texture_storage_2d<rgba32float, write>;
@group(1) @binding(6) var flux_view_out: texture_storage_2d<rgba16float, write>;
// The previous bounce's irradiance (only read when params.source == 1).
@group(1) @binding(7) var previous_irradiance: texture_2d<f32>;

// Grazing texels cover unbounded area; past this cosine their area is clamped.
const MIN_COS: f32 = 0.1;

// Solid angle of texel t seen from the lamp: the texel's area in the tangent plane at unit
// distance, times cos³ of its angle from the axis.
fn texel_solid_angle(t: vec2u) -> f32 {
    let size = vec2f(params.flux_size);
    let ndc = vec2f((f32(t.x) + 0.5) / size.x * 2.0 - 1.0, 1.0 - (f32(t.y) + 0.5) / size.y * 2.0);
    let tan_xy = ndc * params.lamp_tan;
    let area = 4.0 * params.lamp_tan.x * params.lamp_tan.y / (size.x * size.y);
    let r2 = 1.0 + dot(tan_xy, tan_xy);
    return area / (r2 * sqrt(r2));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3u) {
    if any(id.xy >= params.flux_size) {
        return;
    }
    let t = vec2i(id.xy);
    let normal = textureLoad(gbuffer_normal, t, 0);
    var node: Node;
    node.merged = 1u;
    var flux = vec3f(0.0);
    var omega = texel_solid_angle(id.xy);
    if normal.w > 0.0 {
        let x = textureLoad(gbuffer_position, t, 0).xyz;
        let rho = textureLoad(gbuffer_albedo, t, 0).rgb;
        if params.source == 0u {
            var intensity = vec3f(0.0);
            if globals.lamp_pos.w > 0.5 {
                intensity = lamp_intensity_towards(x);
            }
            // Attached, the camera flash sits where the lamp does and sees what it sees, so
            // its reflected flux is ρ·I_flash·Ω_texel too. Detached, this view is the lamp's
            // and cannot tell what the flash lights: the flash then lights directly only.
            if globals.params.z < 0.5 {
                intensity += globals.camera_flash.rgb;
            }
            flux = rho * intensity * omega;
        } else {
            let to_lamp = globals.lamp_pos.xyz - x;
            let d2 = dot(to_lamp, to_lamp);
            let cos_theta = max(dot(normal.xyz, to_lamp * inverseSqrt(d2)), MIN_COS);
            let low = vec2u(vec2f(id.xy) * vec2f(params.indirect_size) / vec2f(params.flux_size));
            let e = textureLoad(previous_irradiance, vec2i(low), 0).rgb;
            flux = rho * e * omega * d2 / cos_theta;
        }
        node.position = x;
        node.normal = normal.xyz;
        node.dist = length(x - globals.lamp_pos.xyz);
    }
    node.flux = flux;
    node.weight = luminance(flux);
    nodes[id.y * params.flux_size.x + id.x] = node;
    textureStore(flux_out, t, vec4f(flux, 1.0));
    // The flux view: Φ per unit lamp solid angle relative to the lamp power, i.e. ρ·T(ω).
    textureStore(flux_view_out, t, vec4f(flux / (omega * max(params.lamp_power, 1e-20)), 1.0));
}
