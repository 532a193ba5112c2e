//! Direct radiance from the headlamp and the punctual lights, evaluated per G-buffer texel.

use super::fullscreen::{bind_textures, color_pass, fullscreen_pipeline, textures_layout};
use super::names::*;
use super::HDR_FORMAT;
use crate::globals::CoreLayouts;
use crate::gpu::Gpu;
use crate::graph::{PassContext, PassDecl, RenderPass, TextureDesc};

pub const SHADER: &str = include_str!("../../../shaders/direct_light.wgsl");

pub struct DirectLightPass {
    pipeline: wgpu::RenderPipeline,
    inputs: wgpu::BindGroupLayout,
}

impl DirectLightPass {
    pub fn new(gpu: &Gpu, layouts: &CoreLayouts) -> Self {
        let device = &gpu.device;
        let module = crate::shader::module(device, "direct light", SHADER, &[]);
        let inputs = textures_layout(device, "direct light inputs", 3, false);
        let pipeline = fullscreen_pipeline(
            device,
            "direct light",
            &module,
            &[Some(&layouts.globals), Some(&inputs)],
            HDR_FORMAT,
            None,
        );
        Self { pipeline, inputs }
    }
}

impl RenderPass for DirectLightPass {
    fn name(&self) -> &str {
        "direct_light"
    }

    fn declare(&self, d: &mut PassDecl) {
        d.read(GBUFFER_ALBEDO)
            .read(GBUFFER_NORMAL)
            .read(GBUFFER_POSITION)
            .create_texture(DIRECT, TextureDesc::target(HDR_FORMAT));
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let views = [ctx.view(GBUFFER_ALBEDO), ctx.view(GBUFFER_NORMAL), ctx.view(GBUFFER_POSITION)];
        let inputs = bind_textures(&ctx.gpu.device, &self.inputs, &views, None);
        let target = ctx.view(DIRECT);
        let mut pass = color_pass(ctx.encoder, "direct light", target, false);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &inputs, &[]);
        pass.draw(0..3, 0..1);
    }
}
