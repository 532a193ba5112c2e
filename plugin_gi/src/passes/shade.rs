//! Deferred shading of the reflection lights: one instanced, indirect draw of light volumes.

use std::rc::Rc;

use engine::graph::{PassContext, PassDecl, RenderPass, TextureDesc};
use engine::passes::names::{GBUFFER_NORMAL, GBUFFER_POSITION};
use engine::passes::{color_pass, HDR_FORMAT};
use engine::wgpu;

use crate::bindings::{bind, layout, Resource as R, Slot as S};
use crate::gpu_types::names;
use crate::shared::{GiHandle, GpuShared};

pub const SHADER: &str = include_str!("../../../shaders/gi/shade.wgsl");

/// Adds two irradiance contributions: blending sums the lights.
pub const ADDITIVE: wgpu::BlendState = wgpu::BlendState {
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

pub struct ShadePass {
    /// f32 where the device can blend into it: thousands of small contributions are summed.
    format: wgpu::TextureFormat,
    handle: GiHandle,
    gpu: Rc<GpuShared>,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl ShadePass {
    pub(crate) fn new(
        gpu_ctx: &engine::gpu::Gpu,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gpu: Rc<GpuShared>,
    ) -> Self {
        let device = &gpu_ctx.device;
        let format = if gpu_ctx.float32_blendable() { wgpu::TextureFormat::Rgba32Float } else { HDR_FORMAT };
        let layout = layout(device, "gi shade", &[S::Uniform, S::Storage { read_only: true }, S::Texture, S::Texture]);
        let module = super::module(device, "gi shade", SHADER);
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("gi shade"),
            bind_group_layouts: &[Some(globals), Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("gi shade"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            // Back faces only, no depth test: each covered pixel is shaded once per light, also
            // when the camera is inside the volume.
            primitive: wgpu::PrimitiveState { cull_mode: Some(wgpu::Face::Front), ..Default::default() },
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: Some(ADDITIVE),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self { format, handle, gpu, layout, pipeline }
    }
}

impl RenderPass for ShadePass {
    fn name(&self) -> &str {
        "gi_shade"
    }

    fn declare(&self, d: &mut PassDecl) {
        let scale = self.handle.settings().resolution_scale;
        d.read(names::LIGHTS)
            .read(names::DRAW_ARGS)
            .read(GBUFFER_NORMAL)
            .read(GBUFFER_POSITION)
            .create_texture(names::IRRADIANCE, TextureDesc::target(self.format).scaled(scale));
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let group = bind(
            &ctx.gpu.device,
            &self.layout,
            &[
                R::Buffer(&self.gpu.params),
                R::Buffer(ctx.buffer(names::LIGHTS)),
                R::View(ctx.view(GBUFFER_NORMAL)),
                R::View(ctx.view(GBUFFER_POSITION)),
            ],
        );
        let args = ctx.buffer(names::DRAW_ARGS);
        let mut pass = color_pass(ctx.encoder, "gi shade", ctx.view(names::IRRADIANCE), false);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw_indirect(args, 0);
    }
}
