// Direct light pass: L_d = ρ/π · I(ω) · max(0, n·l) / d² from the headlamp and every punctual light.
#include "common.wgsl"

@group(1) @binding(0) var gbuffer_albedo: texture_2d<f32>;
@group(1) @binding(1) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(2) var gbuffer_position: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenOut {
    return fullscreen_vertex(index);
}

fn punctual(light: Light, x: vec3f, n: vec3f) -> vec3f {
    let kind = u32(light.direction_kind.w);
    if kind == 2u {
        // Directional: irradiance E = intensity · cos.
        return light.color.rgb * max(0.0, dot(n, -light.direction_kind.xyz));
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
    if kind == 1u {
        let cos_angle = dot(-l, light.direction_kind.xyz);
        intensity *= smoothstep(light.cone.y, light.cone.x, cos_angle);
    }
    return intensity * max(0.0, dot(n, l)) / d2;
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    let texel = vec2i(in.position.xy);
    let normal = textureLoad(gbuffer_normal, texel, 0);
    if normal.w == 0.0 {
        return vec4f(0.0, 0.0, 0.0, 1.0);
    }
    let n = normal.xyz;
    let x = textureLoad(gbuffer_position, texel, 0).xyz;
    let rho = textureLoad(gbuffer_albedo, texel, 0).rgb;

    // Irradiance-like sum Σ I·cos/d² (and E of directional lights); radiance is ρ/π times it.
    var e = vec3f(0.0);
    if globals.lamp_pos.w > 0.5 {
        let to_lamp = globals.lamp_pos.xyz - x;
        let d2 = max(dot(to_lamp, to_lamp), 1e-8);
        let l = to_lamp * inverseSqrt(d2);
        e += lamp_intensity_towards(x) * max(0.0, dot(n, l)) / d2;
    }
    let count = u32(globals.params.y);
    for (var i = 0u; i < count; i++) {
        e += punctual(lights[i], x, n);
    }
    return vec4f(rho / PI * e, 1.0);
}
