//! The deferred renderer: core passes + plugins in one render graph, driven the same way for a
//! window and for headless rendering.

use std::cell::RefCell;
use std::rc::Rc;

use scene::{Scene, Vertex};

use crate::frame::Frame;
use crate::globals::{CoreLayouts, GlobalsGpu};
use crate::gpu::Gpu;
use crate::gpu_instances::GpuInstances;
use crate::gpu_scene::GpuScene;
use crate::graph::{GraphError, ImportedTexture, RenderGraph, SizeRule, Stage};
use crate::passes::{
    CompositePass, CoreResources, DirectLightPass, GBufferPass, LampViewPass, OutputView, PresentPass, PresentSettings,
    ViewModelIrradianceClearPass, ViewModelPass,
};
use crate::plugin::{Plugin, PluginContext, ViewEntry};
use crate::view_state::{MeshId, ViewState};

/// The view size the graph is checked at when it is built.
const BUILD_CHECK_SIZE: (u32, u32) = (640, 360);

pub struct Renderer {
    layouts: CoreLayouts,
    globals: GlobalsGpu,
    scene: GpuScene,
    instances: GpuInstances,
    graph: RenderGraph,
    core: CoreResources,
    present: Rc<RefCell<PresentSettings>>,
    views: Vec<ViewEntry>,
    plugins: Vec<Box<dyn Plugin>>,
    /// View-sized graph textures are this fraction of the output's size.
    render_scale: f32,
}

impl Renderer {
    pub fn new(gpu: &Gpu, scene: &Scene, mut plugins: Vec<Box<dyn Plugin>>) -> Result<Self, GraphError> {
        let layouts = CoreLayouts::new(&gpu.device);
        let globals = GlobalsGpu::new(gpu, &layouts);
        let gpu_scene = GpuScene::upload(gpu, &layouts, scene);
        let mut graph = RenderGraph::new();
        let core = CoreResources::register(&mut graph);
        let present = Rc::new(RefCell::new(PresentSettings { source: core.hdr, kind: OutputView::Radiance }));
        graph.add_pass(Stage::GBuffer, GBufferPass::new(gpu, &layouts, &gpu_scene, &core));
        // Declares the same resources whether the lamp is attached or not (it records nothing
        // while attached), so putting the lamp down or picking it up never recompiles the graph.
        graph.add_pass(Stage::GBuffer, LampViewPass::new(gpu, &layouts, &gpu_scene, core.lamp));
        graph.add_pass(Stage::Lighting, DirectLightPass::new(gpu, &layouts, &core));
        // Zero unless a plugin writes it (in a later stage).
        graph.add_pass(Stage::Lighting, ViewModelIrradianceClearPass(core.view_model_irradiance));
        graph.add_pass(Stage::Composite, CompositePass::new(gpu, &layouts, &core));
        graph.add_pass(Stage::ViewModels, ViewModelPass::new(gpu, &layouts, &core));
        graph.add_pass(Stage::Present, PresentPass::new(gpu, &layouts, present.clone(), core.output));

        let view = |name: &str, source, kind| ViewEntry { name: name.into(), source, kind };
        let mut views = vec![
            view("final", core.hdr, OutputView::Radiance),
            view("direct", core.direct, OutputView::Radiance),
            view("albedo", core.gbuffer.albedo, OutputView::Color),
            view("normal", core.gbuffer.normal, OutputView::Normal),
            view("depth", core.gbuffer.position, OutputView::Depth),
            // The detached lamp's own G-buffer, scaled to the output (black while attached).
            view("lamp_albedo", core.lamp.albedo, OutputView::Color),
            view("lamp_normal", core.lamp.normal, OutputView::Normal),
            view("lamp_depth", core.lamp.position, OutputView::Depth),
        ];
        for plugin in &mut plugins {
            let mut ctx = PluginContext { gpu, layouts: &layouts, scene, core, graph: &mut graph, views: &mut views };
            plugin.build(&mut ctx);
            log::info!("plugin '{}' built", plugin.name());
        }
        // An unclear graph is an error now, not when a view or the lamp changes what it declares.
        let mut detached = ViewState::default();
        detached.headlamp.detach_at(&detached.camera.clone());
        for view in [ViewState::default(), detached] {
            graph.compile(BUILD_CHECK_SIZE, &view)?;
        }
        let instances = GpuInstances::new(gpu);
        Ok(Self {
            layouts,
            globals,
            scene: gpu_scene,
            instances,
            graph,
            core,
            present,
            views,
            plugins,
            render_scale: 1.0,
        })
    }

    /// Uploads a mesh that [`crate::frame::Instance`]s can place (see [`crate::primitives`]).
    /// Panics if an index is out of range of `vertices`.
    pub fn add_mesh(&mut self, gpu: &Gpu, vertices: &[Vertex], indices: &[u32]) -> MeshId {
        self.instances.add_mesh(gpu, vertices, indices)
    }

    /// Renders every view-sized graph texture at `scale` × the output size (clamped to
    /// 0.25..=1) from the next frame on; the present pass scales the chosen view up to the
    /// output, bilinearly for radiance and colour views. 1, the default, renders at full size.
    pub fn set_render_scale(&mut self, scale: f32) {
        self.render_scale = if scale.is_nan() { 1.0 } else { scale.clamp(0.25, 1.0) };
    }

    pub fn render_scale(&self) -> f32 {
        self.render_scale
    }

    pub fn views(&self) -> &[ViewEntry] {
        &self.views
    }

    pub fn plugins(&self) -> &[Box<dyn Plugin>] {
        &self.plugins
    }

    pub fn graph(&self) -> &RenderGraph {
        &self.graph
    }

    /// The resources of the engine's own passes.
    pub fn core(&self) -> &CoreResources {
        &self.core
    }

    /// Starts every history and persistent resource of the graph from zeros at the next frame:
    /// for cuts (a level loaded, a restart, a teleport, the lamp set down or picked up), where
    /// last frame's light says nothing of this one's.
    pub fn reset_history(&mut self) {
        self.graph.reset_history();
    }

    /// Times each render-graph pass on the GPU from the next frame on (opt-in, for `bench`;
    /// nothing is recorded while off). Has no effect where [`Gpu::timestamps`] is false.
    pub fn set_timing(&mut self, on: bool) {
        self.graph.set_timing(on);
    }

    /// Each pass of the last timed frame and its GPU time in milliseconds, in execution order.
    /// None when timing is off or unsupported. Blocks until that frame is done on the GPU.
    pub fn last_pass_times(&self, gpu: &Gpu) -> Option<Vec<(String, f64)>> {
        self.graph.last_pass_times(gpu)
    }

    /// Shows view `name` from the next frame on.
    pub fn set_view(&mut self, name: &str) -> Result<(), String> {
        let entry = self.views.iter().find(|v| v.name == name).ok_or_else(|| {
            let known: Vec<&str> = self.views.iter().map(|v| v.name.as_str()).collect();
            format!("unknown view '{name}' (expected one of: {})", known.join(", "))
        })?;
        let wanted = PresentSettings { source: entry.source, kind: entry.kind };
        *self.present.borrow_mut() = wanted;
        Ok(())
    }

    /// Records and submits one frame into `target` (which the graph sees as `output`).
    pub fn render(
        &mut self,
        gpu: &Gpu,
        view: &ViewState,
        target: &wgpu::Texture,
        target_view: &wgpu::TextureView,
    ) -> Result<wgpu::SubmissionIndex, GraphError> {
        let output = (target.width(), target.height());
        let size = SizeRule::ViewScaled(self.render_scale).resolve(output);
        // Projections keep the output's aspect: the scaled size is rounded to whole pixels.
        let aspect = output.0 as f32 / output.1.max(1) as f32;
        let lamp = view.headlamp.frustum(&view.camera, aspect);
        self.globals.update(gpu, &self.layouts, view, &lamp, size, aspect);
        self.instances.upload(gpu, &view.instances, &view.view_models);
        let frame = Frame {
            size,
            view,
            lamp,
            scene: &self.scene,
            instances: &self.instances,
            layouts: &self.layouts,
            globals: &self.globals.bind_group,
        };
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame") });
        let imports = [ImportedTexture { handle: self.core.output, texture: target, view: target_view }];
        self.graph.execute(gpu, &frame, &mut encoder, &imports)?;
        Ok(gpu.queue.submit([encoder.finish()]))
    }
}
