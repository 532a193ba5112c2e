//! The engine's core passes, by stage: G-buffer (+ lamp view when the headlamp is detached);
//! lighting (direct light); composite (hdr = direct + emissive); [plugins]; view models; present.

use crate::bindings::WgslGroup;

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
pub use fullscreen::{color_pass, fullscreen_pipeline, procedural_pipeline};
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

/// Every bind group the engine's WGSL declares, with the list its layout is made from: the
/// file that declares it (an include stands for every shader that includes it) and its group
/// (engine/tests/bindings.rs reflects the WGSL against these).
pub const BINDINGS: &[WgslGroup] = &[
    WgslGroup::new("common.wgsl", 0, &crate::globals::GLOBALS),
    WgslGroup::new("scene_surface.wgsl", 1, &crate::globals::MATERIAL),
    WgslGroup::new("direct_light.wgsl", 1, &direct_light::INPUTS),
    WgslGroup::new("composite.wgsl", 1, &composite::INPUTS),
    WgslGroup::new("present.wgsl", 1, &present::INPUTS),
    WgslGroup::new("present.wgsl", 1, &present::FILTERED_INPUTS),
    WgslGroup::new("view_model.wgsl", 2, &view_model::INPUTS),
];
