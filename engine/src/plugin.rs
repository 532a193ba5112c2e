//! Plugins extend the renderer: one `build` registers their passes and extra views, the way a
//! Bevy plugin registers its systems. They see the engine's public API only.

use crate::globals::CoreLayouts;
use crate::gpu::Gpu;
use crate::graph::{RenderGraph, RenderPass};
use crate::passes::OutputView;

pub trait Plugin {
    fn name(&self) -> &str;
    fn build(&mut self, ctx: &mut PluginContext<'_>);
    /// Figures about the last frame (e.g. light counts, draw calls), for `bench` and overlays.
    fn stats(&self) -> Vec<(String, f64)> {
        Vec::new()
    }
}

/// A view `headlamp render --view NAME` can show: a graph resource and how to display it.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewEntry {
    pub name: String,
    pub source: String,
    pub kind: OutputView,
}

pub struct PluginContext<'a> {
    pub gpu: &'a Gpu,
    pub layouts: &'a CoreLayouts,
    pub(crate) graph: &'a mut RenderGraph,
    pub(crate) views: &'a mut Vec<ViewEntry>,
}

impl PluginContext<'_> {
    pub fn add_pass(&mut self, pass: impl RenderPass + 'static) {
        self.graph.add_pass(Box::new(pass));
    }

    /// Makes the graph resource `source` selectable as view `name`.
    pub fn add_view(&mut self, name: &str, source: &str, kind: OutputView) {
        self.views.retain(|v| v.name != name);
        self.views.push(ViewEntry { name: name.into(), source: source.into(), kind });
    }
}
