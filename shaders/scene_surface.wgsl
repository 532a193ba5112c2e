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
