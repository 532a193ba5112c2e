//! Geometry-aware upsampling of the irradiance, L_i = ρ/π · E (shaders/gi/composite.wgsl), drawn
//! by two passes: `gi_composite` adds it to the frame's HDR radiance, `gi_indirect_view` writes
//! it alone as the `indirect` view (culled unless something shows or reads that). With the GI
//! off neither reads anything upstream: the composite only resets the figures and the view is
//! cleared.

use std::rc::Rc;

use engine::graph::{PassContext, PassDecl, RenderPass, TextureDesc};
use engine::passes::names::{GBUFFER_ALBEDO, GBUFFER_NORMAL, GBUFFER_POSITION, HDR};
use engine::passes::{color_pass, procedural_pipeline, HDR_FORMAT};
use engine::wgpu;

use crate::bindings::{bind, layout, Resource as R, Slot as S};
use crate::gpu_types::names;
use crate::shared::{GiHandle, GpuShared};

pub const SHADER: &str = include_str!("../../../shaders/gi/composite.wgsl");

/// Adds the indirect radiance to the frame.
const ADDITIVE: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
};

/// The upsampling draw, into one target.
struct Upsample {
    handle: GiHandle,
    gpu: Rc<GpuShared>,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl Upsample {
    fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gpu: Rc<GpuShared>,
        label: &str,
        blend: Option<wgpu::BlendState>,
    ) -> Self {
        let layout = layout(device, label, &[S::Uniform, S::Texture, S::Texture, S::Texture, S::Texture]);
        let module = super::module(device, label, SHADER);
        let targets = [Some(wgpu::ColorTargetState { format: HDR_FORMAT, blend, write_mask: wgpu::ColorWrites::ALL })];
        let pipeline = procedural_pipeline(
            device,
            label,
            &module,
            ("vs_main", "fs_main"),
            &[Some(globals), Some(&layout)],
            &targets,
            Default::default(),
        );
        Self { handle, gpu, layout, pipeline }
    }

    fn enabled(&self) -> bool {
        self.handle.settings().enabled
    }

    fn declare_reads(d: &mut PassDecl) {
        d.read(names::IRRADIANCE).read(GBUFFER_ALBEDO).read(GBUFFER_NORMAL).read(GBUFFER_POSITION);
    }

    /// Draws into `target`, cleared first or blended onto.
    fn draw(&self, ctx: &mut PassContext<'_>, label: &str, target: &str, clear: bool) {
        let group = bind(
            &ctx.gpu.device,
            &self.layout,
            &[
                R::Buffer(&self.gpu.params),
                R::View(ctx.view(names::IRRADIANCE)),
                R::View(ctx.view(GBUFFER_ALBEDO)),
                R::View(ctx.view(GBUFFER_NORMAL)),
                R::View(ctx.view(GBUFFER_POSITION)),
            ],
        );
        let load = if clear { wgpu::LoadOp::Clear(wgpu::Color::BLACK) } else { wgpu::LoadOp::Load };
        let mut pass = ctx.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: ctx.view(target),
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw(0..3, 0..1);
        self.handle.0.borrow_mut().stats.draws += 1;
    }
}

/// Adds the indirect radiance to the frame.
pub struct CompositePass(Upsample);

impl CompositePass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gpu: Rc<GpuShared>,
    ) -> Self {
        Self(Upsample::new(device, globals, handle, gpu, "gi composite", Some(ADDITIVE)))
    }
}

impl RenderPass for CompositePass {
    fn name(&self) -> &str {
        "gi_composite"
    }

    fn declare(&self, d: &mut PassDecl) {
        // Declared even when off (it then draws nothing), so that it runs and resets the figures.
        d.write(HDR);
        if self.0.enabled() {
            Upsample::declare_reads(d);
        }
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        if !self.0.enabled() {
            self.0.handle.0.borrow_mut().stats = Default::default();
            return;
        }
        self.0.draw(ctx, "gi composite", HDR, false);
    }
}

/// The indirect radiance alone: the `indirect` view.
pub struct IndirectViewPass(Upsample);

impl IndirectViewPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gpu: Rc<GpuShared>,
    ) -> Self {
        Self(Upsample::new(device, globals, handle, gpu, "gi indirect view", None))
    }
}

impl RenderPass for IndirectViewPass {
    fn name(&self) -> &str {
        "gi_indirect_view"
    }

    fn declare(&self, d: &mut PassDecl) {
        d.create_texture(names::INDIRECT, TextureDesc::target(HDR_FORMAT));
        if self.0.enabled() {
            Upsample::declare_reads(d);
        }
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        if self.0.enabled() {
            self.0.draw(ctx, "gi indirect view", names::INDIRECT, true);
        } else {
            color_pass(ctx.encoder, "gi off", ctx.view(names::INDIRECT), false);
        }
    }
}
