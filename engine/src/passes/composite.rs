//! Starts the frame's HDR radiance as direct + emissive; plugins then add into it.

use super::fullscreen::{bind_textures, color_pass, fullscreen_pipeline, textures_layout};
use super::names::*;
use super::HDR_FORMAT;
use crate::globals::CoreLayouts;
use crate::gpu::Gpu;
use crate::graph::{PassContext, PassDecl, RenderPass, TextureDesc};

pub const SHADER: &str = include_str!("../../../shaders/composite.wgsl");

pub struct CompositePass {
    pipeline: wgpu::RenderPipeline,
    inputs: wgpu::BindGroupLayout,
}

impl CompositePass {
    pub fn new(gpu: &Gpu, layouts: &CoreLayouts) -> Self {
        let device = &gpu.device;
        let module = crate::shader::module(device, "composite", SHADER, &[]);
        let inputs = textures_layout(device, "composite inputs", 2, false);
        let pipeline = fullscreen_pipeline(
            device,
            "composite",
            &module,
            &[Some(&layouts.globals), Some(&inputs)],
            HDR_FORMAT,
            None,
        );
        Self { pipeline, inputs }
    }
}

impl RenderPass for CompositePass {
    fn name(&self) -> &str {
        "composite"
    }

    fn declare(&self, d: &mut PassDecl) {
        d.read(DIRECT).read(GBUFFER_EMISSIVE).create_texture(HDR, TextureDesc::target(HDR_FORMAT));
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let views = [ctx.view(DIRECT), ctx.view(GBUFFER_EMISSIVE)];
        let inputs = bind_textures(&ctx.gpu.device, &self.inputs, &views, None);
        let target = ctx.view(HDR);
        let mut pass = color_pass(ctx.encoder, "composite", target, false);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &inputs, &[]);
        pass.draw(0..3, 0..1);
    }
}
