//! The GI's render-graph passes, in frame order. docs/architecture.md's table of the GI's
//! stages gives each pass its Rust module here, its WGSL files (shaders/gi/, named as the
//! module) and its tests.

mod article;
mod cuts;
mod gather;
mod indirect;
mod lights_view;
mod params;
mod pyramid;
mod reference;
mod sight;
mod sight_depth;
mod temporal;
mod view_model_irradiance;

pub use article::volumes::LIGHTS_PER_SLOT;
pub use article::ArticlePass;
pub use cuts::CutsPass;
pub use gather::{GatherPass, SumLanes};
pub(crate) use indirect::Gi;
pub use indirect::{IndirectCompositePass, IndirectViewPass};
pub use lights_view::LightsViewPass;
pub use params::GiParamsPass;
pub use pyramid::PyramidPass;
pub(crate) use pyramid::{GROUP_LEVELS, GROUP_SIDE};
pub use reference::ReferencePass;
pub(crate) use reference::GROUP as REFERENCE_GROUP;
pub use sight::SightPass;
pub use sight_depth::SightDepthPass;
pub use temporal::TemporalPass;
pub use view_model_irradiance::ViewModelIrradiancePass;

/// Every WGSL file of the plugin that is a module of its own (the includes are
/// crate::shader's), for validation tests.
pub const SHADERS: &[(&str, &str)] = &[
    ("gi/pyramid_lamp.wgsl", pyramid::LAMP_SHADER),
    ("gi/pyramid_bounce.wgsl", pyramid::BOUNCE_SHADER),
    ("gi/sight_depth.wgsl", sight_depth::SHADER),
    ("gi/cuts.wgsl", cuts::SHADER),
    ("gi/sight.wgsl", sight::SHADER),
    ("gi/gather_subgroup.wgsl", gather::SUBGROUP_SHADER),
    ("gi/gather_invocation.wgsl", gather::INVOCATION_SHADER),
    ("gi/article_stream.wgsl", article::volumes::STREAM_SHADER),
    ("gi/article_volumes.wgsl", article::volumes::VOLUMES_SHADER),
    ("gi/article_sub_images.wgsl", article::volumes::SUB_IMAGES_SHADER),
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
        pyramid::BINDINGS,
        sight_depth::BINDINGS,
        cuts::BINDINGS,
        sight::BINDINGS,
        gather::BINDINGS,
        article::volumes::BINDINGS,
        indirect::BINDINGS,
        lights_view::BINDINGS,
        reference::BINDINGS,
        temporal::BINDINGS,
        view_model_irradiance::BINDINGS,
    ]
    .concat()
}
