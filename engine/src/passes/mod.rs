//! The engine's core passes, by stage: G-buffer (+ lamp view when the headlamp is detached);
//! lighting (direct light); composite (hdr = direct + emissive); [plugins]; view models; present.

mod composite;
mod core_resources;
mod direct_light;
mod fullscreen;
mod gbuffer;
mod lamp_view;
mod present;
mod view_model;

pub use crate::headlamp::LAMP_MAP_SIZE;
pub use composite::CompositePass;
pub use direct_light::DirectLightPass;
pub use fullscreen::{bind_textures, color_pass, fullscreen_pipeline, procedural_pipeline, textures_layout};
pub use gbuffer::GBufferPass;
pub use lamp_view::LampViewPass;
pub(crate) use present::PresentUniform;
pub use present::{OutputView, PresentPass, PresentSettings, VIEW_COLOR, VIEW_DEPTH, VIEW_NORMAL, VIEW_RADIANCE};

pub use core_resources::{CoreResources, GBuffer, HDR_FORMAT};
pub use view_model::{ViewModelIrradianceClearPass, ViewModelPass, VIEW_MODEL_IRRADIANCE_SIZE};

/// Every WGSL file of the core passes, for tests that validate them.
pub const SHADERS: &[(&str, &str)] = &[
    ("gbuffer.wgsl", gbuffer::SHADER),
    ("lamp_view.wgsl", lamp_view::SHADER),
    ("direct_light.wgsl", direct_light::SHADER),
    ("composite.wgsl", composite::SHADER),
    ("present.wgsl", present::SHADER),
    ("view_model.wgsl", view_model::SHADER),
];
