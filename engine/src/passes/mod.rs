//! The engine's core passes: G-buffer (+ lamp view when the headlamp is detached) → direct
//! light → composite → [plugins] → view models → present.

mod composite;
mod direct_light;
mod fullscreen;
mod gbuffer;
mod lamp_view;
mod present;
mod view_model;

pub use composite::CompositePass;
pub use direct_light::DirectLightPass;
pub use fullscreen::{bind_textures, color_pass, fullscreen_pipeline, procedural_pipeline, textures_layout};
pub use gbuffer::GBufferPass;
pub use lamp_view::{LampViewPass, LAMP_MAP_SIZE};
pub(crate) use present::PresentUniform;
pub use present::{OutputView, PresentPass, PresentSettings};
pub use view_model::{ViewModelPass, ViewModelProbePass, VIEW_MODEL_IRRADIANCE_SIZE};

/// Names of the graph resources the core passes create; plugins read and write them by name.
pub mod names {
    /// Linear diffuse albedo ρ = (1 − metallic)·base colour, what diffuse light (the GI's
    /// included) reflects; the base colour itself for Lambertian surfaces (Rgba16Float).
    pub const GBUFFER_ALBEDO: &str = "gbuffer.albedo";
    /// World-space unit normal, facing the camera; w = 1 where there is geometry (Rgba16Float).
    pub const GBUFFER_NORMAL: &str = "gbuffer.normal";
    /// World-space position; w = view-space depth in metres, 0 for sky (Rgba32Float).
    pub const GBUFFER_POSITION: &str = "gbuffer.position";
    /// Emitted radiance (Rgba16Float).
    pub const GBUFFER_EMISSIVE: &str = "gbuffer.emissive";
    /// The specular lobe of glTF's metallic-roughness BRDF: rgb = Fresnel reflectance at
    /// normal incidence F0 = mix(0.04, base colour, metallic), a = perceptual roughness; all 0
    /// for Lambertian surfaces (Rgba16Float). Only the direct light reads it: the GI is diffuse.
    pub const GBUFFER_SPECULAR: &str = "gbuffer.specular";
    /// Reversed depth buffer (Depth32Float).
    pub const GBUFFER_DEPTH: &str = "gbuffer.depth";
    /// The lamp's view (a reflective shadow map), [`super::LAMP_MAP_SIZE`]² texels, rendered
    /// only while the headlamp is detached. While it is attached these hold nothing meaningful
    /// and the `gbuffer.*` textures above are the lamp's view (same formats and meanings, the
    /// camera being the lamp). Linear diffuse albedo ρ = (1 − metallic)·base colour
    /// (Rgba16Float).
    pub const LAMP_ALBEDO: &str = "lamp.albedo";
    /// World-space unit normal facing the lamp; w = 1 where there is geometry (Rgba16Float).
    pub const LAMP_NORMAL: &str = "lamp.normal";
    /// World-space position; w = distance along the lamp's view axis in metres, 0 where
    /// empty (Rgba32Float).
    pub const LAMP_POSITION: &str = "lamp.position";
    /// Reversed depth from the lamp, cleared to 0 (Depth32Float): the headlamp's shadow map.
    pub const LAMP_DEPTH: &str = "lamp.depth";
    /// Direct radiance from the headlamp and punctual lights (Rgba16Float).
    pub const DIRECT: &str = "direct";
    /// The frame's linear radiance; plugins blend additively into it (Rgba16Float).
    pub const HDR: &str = "hdr";
    /// Indirect irradiance E (W/m²) at `ViewState::view_model_probe`, an ambient cube: six
    /// `vec4<f32>` (w unused) for a surface facing +X, −X, +Y, −Y, +Z, −Z (world axes). Created
    /// zero each frame by the engine; a GI plugin that can tell the irradiance at a point
    /// `write`s it (plugins are registered after its creator), and the view-model pass reads it.
    /// The one place indirect light reaches the view models, which are in no G-buffer.
    pub const VIEW_MODEL_IRRADIANCE: &str = "view_model.irradiance";
    /// The view models' own reversed depth buffer (Depth32Float), cleared before they are drawn.
    pub const VIEW_MODEL_DEPTH: &str = "view_model.depth";
    /// The imported output image (swapchain or readback target).
    pub const OUTPUT: &str = "output";
}

pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Every WGSL file of the core passes, for tests that validate them.
pub const SHADERS: &[(&str, &str)] = &[
    ("gbuffer.wgsl", gbuffer::SHADER),
    ("lamp_view.wgsl", lamp_view::SHADER),
    ("direct_light.wgsl", direct_light::SHADER),
    ("composite.wgsl", composite::SHADER),
    ("present.wgsl", present::SHADER),
    ("view_model.wgsl", view_model::SHADER),
];
