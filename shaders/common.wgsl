// Shared declarations of the engine's core passes: the per-frame globals (group 0).
// Units are docs/gi.md's: radiance in W·sr⁻¹·m⁻², intensity in W/sr, metres.

const PI: f32 = 3.14159265358979;

struct Globals {
    view_proj: mat4x4f,
    inv_view_proj: mat4x4f,
    view: mat4x4f,
    // Maps a world position into the lamp frustum; uv(ω) of I(ω) = P·T(uv(ω)).
    lamp_view_proj: mat4x4f,
    camera_pos: vec4f,
    // xyz: lamp position; w: 1 when the lamp is on.
    lamp_pos: vec4f,
    // rgb: P · colour of the lamp.
    lamp_intensity: vec4f,
    // width, height, 1/width, 1/height of the view as rendered (the output × the render scale).
    viewport: vec4f,
    // x: exposure; y: number of punctual lights; z: 1 when the headlamp is detached (its shadow
    // map `lamp.depth` is valid); w: size of a lamp-map texel per metre of distance from the
    // lamp, 2·tan(fov/2)/LAMP_MAP_SIZE (0 when attached).
    params: vec4f,
    // rgb: radiant intensity (W/sr) of the camera flash, an isotropic point emitter at
    // camera_pos; 0 when off.
    camera_flash: vec4f,
};

// A punctual light. kind: LIGHT_POINT, LIGHT_SPOT or LIGHT_DIRECTIONAL.
struct Light {
    // xyz position; w range (0 = infinite).
    position_range: vec4f,
    // xyz unit direction the light points to; w kind.
    direction_kind: vec4f,
    // rgb colour × intensity (W/sr, or W/m² for directional).
    color: vec4f,
    // x cos(inner cone), y cos(outer cone).
    cone: vec4f,
};

const LIGHT_POINT: u32 = 0u;
const LIGHT_SPOT: u32 = 1u;
const LIGHT_DIRECTIONAL: u32 = 2u;

@group(0) @binding(0) var<uniform> globals: Globals;
@group(0) @binding(1) var<storage, read> lights: array<Light>;
@group(0) @binding(2) var lamp_distribution: texture_2d<f32>;
@group(0) @binding(3) var linear_clamp: sampler;

// Radiant intensity of the headlamp towards world point x: I(ω) = P · T(uv(ω)); zero outside
// the lamp frustum.
fn lamp_intensity_towards(x: vec3f) -> vec3f {
    let clip = globals.lamp_view_proj * vec4f(x, 1.0);
    if clip.w <= 0.0 {
        return vec3f(0.0);
    }
    let ndc = clip.xy / clip.w;
    if any(abs(ndc) > vec2f(1.0)) {
        return vec3f(0.0);
    }
    let uv = vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
    let t = textureSampleLevel(lamp_distribution, linear_clamp, uv, 0.0).rgb;
    return globals.lamp_intensity.rgb * t;
}

// Narkowicz's fit of the ACES filmic curve.
fn aces(x: vec3f) -> vec3f {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), vec3f(0.0), vec3f(1.0));
}

// A triangle covering the screen; uv has (0,0) at the top left.
struct FullscreenOut {
    @builtin(position) position: vec4f,
    @location(0) uv: vec2f,
};

fn fullscreen_vertex(index: u32) -> FullscreenOut {
    let uv = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
    var out: FullscreenOut;
    out.position = vec4f(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
    out.uv = uv;
    return out;
}
