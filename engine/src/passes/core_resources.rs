//! The graph resources the engine's own passes create, which plugins read and write through
//! their handles, and the format of the frame's radiance.

use crate::graph::{Buffer, Handle, Image, RenderGraph};

/// The G-buffer of a view: the camera's, or the detached lamp's own (a reflective shadow map).
#[derive(Clone, Copy, Debug)]
pub struct GBuffer {
    /// Linear diffuse albedo ρ = (1 − metallic)·base colour, what diffuse light (the GI's
    /// included) reflects; the base colour itself for Lambertian surfaces (Rgba16Float).
    pub albedo: Handle<Image>,
    /// World-space unit normal, facing the viewer; w = 1 where there is geometry (Rgba16Float).
    pub normal: Handle<Image>,
    /// World-space position; w = depth along the view axis in metres, 0 where empty
    /// (Rgba32Float).
    pub position: Handle<Image>,
    /// Reversed depth buffer, cleared to 0 (Depth32Float); the lamp's is its shadow map.
    pub depth: Handle<Image>,
}

/// The graph resources the core passes create: plugins read and write them through these
/// handles (from `PluginContext::core`).
#[derive(Clone, Copy, Debug)]
pub struct CoreResources {
    /// The camera's G-buffer (labels `gbuffer.*`).
    pub gbuffer: GBuffer,
    /// Emitted radiance (Rgba16Float).
    pub emissive: Handle<Image>,
    /// The specular lobe of glTF's metallic-roughness BRDF: rgb = Fresnel reflectance at
    /// normal incidence F0 = mix(0.04, base colour, metallic), a = perceptual roughness; all 0
    /// for Lambertian surfaces (Rgba16Float). Only the direct light reads it: the GI is diffuse.
    pub specular: Handle<Image>,
    /// The lamp's view, [`LAMP_MAP_SIZE`](crate::headlamp::LAMP_MAP_SIZE)² texels (labels `lamp.*`), rendered only while the
    /// headlamp is detached. While it is attached these hold nothing meaningful and the
    /// camera's G-buffer is the lamp's view (the camera being the lamp).
    pub lamp: GBuffer,
    /// Direct radiance from the headlamp and punctual lights (Rgba16Float).
    pub direct: Handle<Image>,
    /// The frame's linear radiance; plugins blend additively into it (Rgba16Float).
    pub hdr: Handle<Image>,
    /// Indirect irradiance E (W/m²) at `ViewState::view_model_probe`, an ambient cube: six
    /// `vec4<f32>` (w unused) for a surface facing +X, −X, +Y, −Y, +Z, −Z (world axes). Created
    /// zero each frame by the engine (stage Lighting); a GI plugin that can tell the irradiance
    /// at a point `write`s it, and the view-model pass reads it. The one place indirect light
    /// reaches the view models, which are in no G-buffer.
    pub view_model_irradiance: Handle<Buffer>,
    /// The view models' own reversed depth buffer (Depth32Float), cleared before they are drawn.
    pub view_model_depth: Handle<Image>,
    /// The imported output image (swapchain or readback target).
    pub output: Handle<Image>,
}

impl CoreResources {
    pub fn register(graph: &mut RenderGraph) -> Self {
        let mut gbuffer = |prefix: &str| GBuffer {
            albedo: graph.image(&format!("{prefix}.albedo")),
            normal: graph.image(&format!("{prefix}.normal")),
            position: graph.image(&format!("{prefix}.position")),
            depth: graph.image(&format!("{prefix}.depth")),
        };
        let (camera, lamp) = (gbuffer("gbuffer"), gbuffer("lamp"));
        Self {
            gbuffer: camera,
            lamp,
            emissive: graph.image("gbuffer.emissive"),
            specular: graph.image("gbuffer.specular"),
            direct: graph.image("direct"),
            hdr: graph.image("hdr"),
            view_model_irradiance: graph.buffer("view_model.irradiance"),
            view_model_depth: graph.image("view_model.depth"),
            output: graph.import_image("output"),
        }
    }
}

pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
