//! Deferred shading of the reflection lights: one instanced, indirect draw of light volumes.

use std::rc::Rc;

use engine::graph::{PassContext, PassDecl, RenderPass, TextureDesc};
use engine::passes::names::{GBUFFER_NORMAL, GBUFFER_POSITION};
use engine::passes::{color_pass, procedural_pipeline, HDR_FORMAT};
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

/// Draws reflection lights as instanced volumes, adding their irradiance into a target.
pub struct VolumeShader {
    /// f32 where the device can blend into it: thousands of small contributions are summed.
    pub format: wgpu::TextureFormat,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl VolumeShader {
    pub fn new(gpu: &engine::gpu::Gpu, globals: &wgpu::BindGroupLayout) -> Self {
        let device = &gpu.device;
        let format = if gpu.float32_blendable() { wgpu::TextureFormat::Rgba32Float } else { HDR_FORMAT };
        let layout = layout(device, "gi shade", &[S::Uniform, S::Storage { read_only: true }, S::Texture, S::Texture]);
        let module = super::module(device, "gi shade", SHADER);
        let target = wgpu::ColorTargetState { format, blend: Some(ADDITIVE), write_mask: wgpu::ColorWrites::ALL };
        // Back faces only, no depth test: each covered pixel is shaded once per light, also
        // when the camera is inside the volume.
        let primitive = wgpu::PrimitiveState { cull_mode: Some(wgpu::Face::Front), ..Default::default() };
        let layouts = [Some(globals), Some(&layout)];
        let pipeline = procedural_pipeline(
            device,
            "gi shade",
            &module,
            ("vs_main", "fs_main"),
            &layouts,
            &[Some(target)],
            primitive,
        );
        Self { format, layout, pipeline }
    }

    /// Clears `target` and draws the lights of `args` into it (one indirect draw).
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        globals: &wgpu::BindGroup,
        params: &wgpu::Buffer,
        lights: &wgpu::Buffer,
        args: &wgpu::Buffer,
        gbuffer: (&wgpu::TextureView, &wgpu::TextureView),
        target: &wgpu::TextureView,
    ) {
        let group =
            bind(device, &self.layout, &[R::Buffer(params), R::Buffer(lights), R::View(gbuffer.0), R::View(gbuffer.1)]);
        let mut pass = color_pass(encoder, "gi shade", target, false);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw_indirect(args, 0);
    }
}

pub struct ShadePass {
    handle: GiHandle,
    gpu: Rc<GpuShared>,
    shader: VolumeShader,
}

impl ShadePass {
    pub(crate) fn new(
        gpu_ctx: &engine::gpu::Gpu,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gpu: Rc<GpuShared>,
    ) -> Self {
        Self { shader: VolumeShader::new(gpu_ctx, globals), handle, gpu }
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
            .create_texture(names::IRRADIANCE, TextureDesc::target(self.shader.format).scaled(scale));
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        self.shader.record(
            &ctx.gpu.device,
            ctx.encoder,
            ctx.frame.globals,
            &self.gpu.params,
            ctx.buffer(names::LIGHTS),
            ctx.buffer(names::DRAW_ARGS),
            (ctx.view(GBUFFER_NORMAL), ctx.view(GBUFFER_POSITION)),
            ctx.view(names::IRRADIANCE),
        );
    }
}
