//! The GI's render-graph passes, in frame order. docs/architecture.md's table of the GI's
//! stages gives each pass its Rust modules, its WGSL files (shaders/gi/) and its tests.

mod article;
mod bounces;
mod flux;
mod gather;
mod indirect;
mod lights_view;
mod params;
mod reference;
mod temporal;
mod view_model_irradiance;

pub use article::ArticlePass;
pub use bounces::BouncePass;
pub use flux::FluxPass;
pub use gather::GatherPass;
pub use indirect::{IndirectCompositePass, IndirectViewPass};
pub use lights_view::LightsViewPass;
pub use params::GiParamsPass;
pub use reference::ReferencePass;
pub(crate) use reference::GROUP as REFERENCE_GROUP;
pub use temporal::TemporalPass;
pub use view_model_irradiance::ViewModelIrradiancePass;

/// Every WGSL file of the plugin, for validation tests.
pub const SHADERS: &[(&str, &str)] = &[
    ("gi/pyramid.wgsl", crate::pyramid::SHADER),
    ("gi/cuts.wgsl", crate::gather::CUTS_SHADER),
    ("gi/gather_subgroup.wgsl", crate::gather::GATHER_SUBGROUP_SHADER),
    ("gi/gather_invocation.wgsl", crate::gather::GATHER_INVOCATION_SHADER),
    ("gi/sight.wgsl", crate::gather::SIGHT_SHADER),
    ("gi/sight_depth.wgsl", crate::sight_depth::SHADER),
    ("gi/light_stream.wgsl", crate::light_volumes::STREAM_SHADER),
    ("gi/light_volumes.wgsl", crate::light_volumes::VOLUMES_SHADER),
    ("gi/sub_images.wgsl", crate::light_volumes::SUB_IMAGES_SHADER),
    ("gi/indirect.wgsl", indirect::SHADER),
    ("gi/lights_view.wgsl", lights_view::SHADER),
    ("gi/reference.wgsl", reference::SHADER),
    ("gi/temporal.wgsl", temporal::SHADER),
    ("gi/view_model_irradiance.wgsl", view_model_irradiance::SHADER),
];

/// Every bind group the GI's WGSL declares, with the list its layout is made from
/// (plugin_gi/tests/bindings.rs reflects the WGSL against these).
pub fn bindings() -> Vec<engine::bindings::WgslGroup> {
    [
        crate::pyramid::BINDINGS,
        crate::gather::BINDINGS,
        crate::sight_depth::BINDINGS,
        crate::light_volumes::BINDINGS,
        indirect::BINDINGS,
        lights_view::BINDINGS,
        reference::BINDINGS,
        temporal::BINDINGS,
        view_model_irradiance::BINDINGS,
    ]
    .concat()
}
