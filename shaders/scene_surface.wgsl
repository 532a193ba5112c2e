// What every pass that rasterises the scene shares: the vertex layout, the material (group 1)
// and how a fragment's albedo is found.

struct Material {
    base_color: vec4f,
    // rgb emissive radiance; w: 1 when a base colour texture is bound.
    emissive: vec4f,
};

@group(1) @binding(0) var<uniform> material: Material;
@group(1) @binding(1) var base_color_texture: texture_2d<f32>;
@group(1) @binding(2) var material_sampler: sampler;

struct VertexIn {
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
};

struct VertexOut {
    @builtin(position) clip: vec4f,
    @location(0) world: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
};

// Passes world-space attributes through, projected by `view_proj`.
fn surface_vertex(v: VertexIn, view_proj: mat4x4f) -> VertexOut {
    var out: VertexOut;
    out.clip = view_proj * vec4f(v.position, 1.0);
    out.world = v.position;
    out.normal = v.normal;
    out.uv = v.uv;
    return out;
}

// Linear diffuse albedo ρ: the base colour factor times the base colour texture.
fn surface_albedo(in: VertexOut) -> vec3f {
    var albedo = material.base_color;
    if material.emissive.w > 0.5 {
        albedo *= textureSample(base_color_texture, material_sampler, in.uv);
    }
    return albedo.rgb;
}

// A dynamic instance (engine::frame::Instance), per-instance vertex data after VertexIn's:
// the model matrix by columns, linear albedo ρ and emitted radiance.
struct InstanceIn {
    @location(3) model_0: vec4f,
    @location(4) model_1: vec4f,
    @location(5) model_2: vec4f,
    @location(6) model_3: vec4f,
    @location(7) base_color: vec4f,
    @location(8) emissive: vec4f,
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
