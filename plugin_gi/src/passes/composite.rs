//! Geometry-aware upsampling of the irradiance, L_i = ρ/π · E, added to the frame's HDR radiance.
//! With the GI off it only clears the `indirect` view, and nothing upstream runs.

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

pub struct CompositePass {
    handle: GiHandle,
    gpu: Rc<GpuShared>,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl CompositePass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gpu: Rc<GpuShared>,
    ) -> Self {
        let layout = layout(device, "gi composite", &[S::Uniform, S::Texture, S::Texture, S::Texture, S::Texture]);
        let module = super::module(device, "gi composite", SHADER);
        let target =
            |blend| Some(wgpu::ColorTargetState { format: HDR_FORMAT, blend, write_mask: wgpu::ColorWrites::ALL });
        let (layouts, targets) = ([Some(globals), Some(&layout)], [target(None), target(Some(ADDITIVE))]);
        let entries = ("vs_main", "fs_main");
        let pipeline =
            procedural_pipeline(device, "gi composite", &module, entries, &layouts, &targets, Default::default());
        Self { handle, gpu, layout, pipeline }
    }
}

impl RenderPass for CompositePass {
    fn name(&self) -> &str {
        "gi_composite"
    }

    fn declare(&self, d: &mut PassDecl) {
        d.create_texture(names::INDIRECT, TextureDesc::target(HDR_FORMAT));
        if self.handle.settings().enabled {
            d.read(names::IRRADIANCE).read(GBUFFER_ALBEDO).read(GBUFFER_NORMAL).read(GBUFFER_POSITION).write(HDR);
        }
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let enabled = self.handle.settings().enabled;
        if !enabled {
            color_pass(ctx.encoder, "gi off", ctx.view(names::INDIRECT), false);
            self.handle.0.borrow_mut().stats = Default::default();
            return;
        }
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
        let attachment = |view| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
            })
        };
        let mut indirect = attachment(ctx.view(names::INDIRECT));
        if let Some(a) = &mut indirect {
            a.ops.load = wgpu::LoadOp::Clear(wgpu::Color::BLACK);
        }
        let mut pass = ctx.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("gi composite"),
            color_attachments: &[indirect, attachment(ctx.view(HDR))],
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
