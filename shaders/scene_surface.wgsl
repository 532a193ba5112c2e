#include "brdf.wgsl"

// What every pass that rasterises the scene shares: the vertex layout, the material (group 1)
// and how a fragment's albedo, alpha and emission are found.

struct Material {
    // Linear RGBA factor.
    base_color: vec4f,
    // rgb: emitted radiance factor (× KHR_materials_emissive_strength).
    emissive: vec4f,
    // KHR_texture_transform of the base colour texture: the rows of a 2×3 matrix acting on
    // (u, v, 1); base_color_uv_0.w is the uv set it reads (0 or 1).
    base_color_uv_0: vec4f,
    base_color_uv_1: vec4f,
    // The same for the emissive texture.
    emissive_uv_0: vec4f,
    emissive_uv_1: vec4f,
    // The same for the metallic-roughness texture.
    metallic_roughness_uv_0: vec4f,
    metallic_roughness_uv_1: vec4f,
    // x: alpha cutoff (fs_masked only: MASK, and BLEND drawn as MASK at 0.5).
    alpha: vec4f,
    // x: metallic factor; y: roughness factor; z: 1 for glTF's metallic-roughness BRDF, 0 for
    // Lambertian; w: 1 when there is a metallic-roughness texture (unread: the shader samples
    // the texture, or white, either way).
    reflection: vec4f,
};

@group(1) @binding(0) var<uniform> material: Material;
// Each texture is 1×1 white when the material has none; each sampler is the texture's own
// (wrap modes, filters).
@group(1) @binding(1) var base_color_texture: texture_2d<f32>;
@group(1) @binding(2) var base_color_sampler: sampler;
@group(1) @binding(3) var emissive_texture: texture_2d<f32>;
@group(1) @binding(4) var emissive_sampler: sampler;
// Linear: B = metallic, G = roughness.
@group(1) @binding(5) var metallic_roughness_texture: texture_2d<f32>;
@group(1) @binding(6) var metallic_roughness_sampler: sampler;

struct VertexIn {
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
    @location(3) uv1: vec2f,
    // Linear RGBA vertex colour (glTF COLOR_0; white when the file has none).
    @location(4) color: vec4f,
};

struct VertexOut {
    @builtin(position) clip: vec4f,
    @location(0) world: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
    @location(3) uv1: vec2f,
    @location(4) color: vec4f,
};

// Passes world-space attributes through, projected by `view_proj`.
fn surface_vertex(v: VertexIn, view_proj: mat4x4f) -> VertexOut {
    var out: VertexOut;
    out.clip = view_proj * vec4f(v.position, 1.0);
    out.world = v.position;
    out.normal = v.normal;
    out.uv = v.uv;
    out.uv1 = v.uv1;
    out.color = v.color;
    return out;
}

// A texture slot's coordinates: its uv set, through its transform (two matrix rows).
fn texture_uv(in: VertexOut, row0: vec4f, row1: vec4f) -> vec2f {
    let uv = vec3f(select(in.uv, in.uv1, row0.w > 0.5), 1.0);
    return vec2f(dot(row0.xyz, uv), dot(row1.xyz, uv));
}

// Linear base colour: the factor × the base colour texture × the vertex colour. rgb is the
// diffuse albedo ρ, a the coverage alpha-tested materials compare with their cutoff.
fn surface_base_color(in: VertexOut) -> vec4f {
    let uv = texture_uv(in, material.base_color_uv_0, material.base_color_uv_1);
    return material.base_color * textureSample(base_color_texture, base_color_sampler, uv) * in.color;
}

// Emitted radiance: the factor × the emissive texture.
fn surface_emissive(in: VertexOut) -> vec3f {
    let uv = texture_uv(in, material.emissive_uv_0, material.emissive_uv_1);
    return material.emissive.rgb * textureSample(emissive_texture, emissive_sampler, uv).rgb;
}

// The smallest perceptual roughness drawn: below it a point light's highlight (GGX's peak
// 1/(π·roughness⁴)) overflows the half-float radiance targets. Filament's value for half floats.
const MIN_ROUGHNESS: f32 = 0.089;

// How a surface point reflects light, as the G-buffers store it.
struct SurfaceReflection {
    // The diffuse albedo ρ = (1 − metallic)·base colour: what the GI's flux and the diffuse
    // lobe use.
    diffuse: vec3f,
    // rgb: Fresnel reflectance at normal incidence F0 = mix(0.04, base colour, metallic);
    // a: perceptual roughness (≥ MIN_ROUGHNESS). All 0 for a Lambertian surface.
    specular: vec4f,
};

// glTF's metallic-roughness split of a base colour, or a Lambertian surface.
fn surface_reflection(in: VertexOut, base_color: vec3f) -> SurfaceReflection {
    // Sampled unconditionally (a material without the texture samples a 1×1 white one) and
    // without branches: lavapipe runs a sample inside control flow per pixel, several times
    // the cost of the whole G-buffer fragment.
    let uv = texture_uv(in, material.metallic_roughness_uv_0, material.metallic_roughness_uv_1);
    let texel = textureSample(metallic_roughness_texture, metallic_roughness_sampler, uv);
    let metallic = clamp(material.reflection.x * texel.b, 0.0, 1.0);
    let roughness = clamp(material.reflection.y * texel.g, MIN_ROUGHNESS, 1.0);
    let pbr = material.reflection.z > 0.5;
    var out: SurfaceReflection;
    out.diffuse = select(base_color, (1.0 - metallic) * base_color, pbr);
    out.specular = select(vec4f(0.0), vec4f(mix(vec3f(BRDF_DIELECTRIC_F0), base_color, metallic), roughness), pbr);
    return out;
}

// Whether an alpha-tested fragment is cut out.
fn surface_cut_out(base_color: vec4f) -> bool {
    return base_color.a < material.alpha.x;
}

// A dynamic instance (engine::frame::Instance), per-instance vertex data after VertexIn's:
// the model matrix by columns, linear albedo ρ and emitted radiance.
struct InstanceIn {
    @location(5) model_0: vec4f,
    @location(6) model_1: vec4f,
    @location(7) model_2: vec4f,
    @location(8) model_3: vec4f,
    @location(9) base_color: vec4f,
    @location(10) emissive: vec4f,
};

struct InstanceOut {
    @builtin(position) clip: vec4f,
    @location(0) world: vec3f,
    @location(1) normal: vec3f,
    @location(2) @interpolate(flat) base_color: vec3f,
    @location(3) @interpolate(flat) emissive: vec3f,
};

// Places an instance's vertex in the world, projected by `view_proj`.
fn instance_vertex(v: VertexIn, i: InstanceIn, view_proj: mat4x4f) -> InstanceOut {
    let model = mat4x4f(i.model_0, i.model_1, i.model_2, i.model_3);
    // Normals go by the cofactor matrix, det(M)·M⁻ᵀ: the inverse-transpose up to a factor
    // that normalising removes, except its sign. Where M mirrors (det < 0) the normal turns
    // with the winding, which keeps it consistent with the fragment shaders' front-facing flip.
    let a = i.model_0.xyz;
    let b = i.model_1.xyz;
    let c = i.model_2.xyz;
    let normal_matrix = mat3x3f(cross(b, c), cross(c, a), cross(a, b));
    var out: InstanceOut;
    out.world = (model * vec4f(v.position, 1.0)).xyz;
    out.clip = view_proj * vec4f(out.world, 1.0);
    out.normal = normal_matrix * v.normal;
    out.base_color = i.base_color.rgb;
    out.emissive = i.emissive.rgb;
    return out;
}
