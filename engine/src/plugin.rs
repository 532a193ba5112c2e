//! Plugins extend the renderer: one `build` registers their passes (each in a stage) and extra
//! views, the way a Bevy plugin registers its systems. They see the engine's public API only.

use crate::globals::CoreLayouts;
use crate::gpu::Gpu;
use crate::graph::{Buffer, Handle, History, Image, PassOrder, RenderGraph, RenderPass, Stage};
use crate::passes::{CoreResources, OutputView};
use crate::scene::Scene;

pub trait Plugin {
    fn name(&self) -> &str;
    fn build(&mut self, ctx: &mut PluginContext<'_>);
}

/// A view `headlamp render --view NAME` can show: a graph texture and how to display it.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewEntry {
    pub name: String,
    pub source: Handle<Image>,
    pub kind: OutputView,
}

pub struct PluginContext<'a> {
    pub gpu: &'a Gpu,
    pub layouts: &'a CoreLayouts,
    /// The level the renderer draws: its static meshes (world space), materials and lights. A
    /// renderer is made again for another level and on a live reload, so this is the level's
    /// for the plugin's whole life.
    pub scene: &'a Scene,
    pub(crate) core: CoreResources,
    pub(crate) graph: &'a mut RenderGraph,
    pub(crate) views: &'a mut Vec<ViewEntry>,
}

impl PluginContext<'_> {
    /// The resources of the engine's own passes (G-buffer, hdr, …).
    pub fn core(&self) -> &CoreResources {
        &self.core
    }

    /// Adds a pass to `stage` (see [`RenderGraph::add_pass`]).
    pub fn add_pass<P: RenderPass>(&mut self, stage: Stage, pass: P) -> PassOrder<'_> {
        self.graph.add_pass(stage, pass)
    }

    /// Puts `pass` in the place of the engine's pass named `name` (see
    /// [`RenderGraph::replace_pass`]).
    pub fn replace_pass<P: RenderPass>(&mut self, name: &str, pass: P) -> PassOrder<'_> {
        self.graph.replace_pass(name, pass)
    }

    /// A texture that lives within a frame.
    pub fn image(&mut self, label: &str) -> Handle<Image> {
        self.graph.image(label)
    }

    /// A buffer that lives within a frame.
    pub fn buffer(&mut self, label: &str) -> Handle<Buffer> {
        self.graph.buffer(label)
    }

    /// A texture kept across frames.
    pub fn persistent_image(&mut self, label: &str) -> Handle<Image> {
        self.graph.persistent_image(label)
    }

    /// A buffer kept across frames.
    pub fn persistent_buffer(&mut self, label: &str) -> Handle<Buffer> {
        self.graph.persistent_buffer(label)
    }

    /// A texture with last frame's contents beside this frame's.
    pub fn history_image(&mut self, label: &str) -> History<Image> {
        self.graph.history_image(label)
    }

    /// A buffer with last frame's contents beside this frame's.
    pub fn history_buffer(&mut self, label: &str) -> History<Buffer> {
        self.graph.history_buffer(label)
    }

    /// Makes the graph texture `source` selectable as view `name`.
    pub fn add_view(&mut self, name: &str, source: Handle<Image>, kind: OutputView) {
        self.views.retain(|v| v.name != name);
        self.views.push(ViewEntry { name: name.into(), source, kind });
    }
}
