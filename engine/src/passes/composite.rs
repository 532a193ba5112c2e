//! Starts the frame's HDR radiance as direct + emissive; plugins then add into it.

use super::core_resources::{CoreResources, HDR_FORMAT};
use super::fullscreen::{color_pass, fullscreen_pipeline};
use crate::bindings::{Group, ShaderBinding};
use crate::globals::CoreLayouts;
use crate::gpu::Gpu;
use crate::graph::{Image, PassContext, PassDecl, Read, RenderPass, TextureDesc, Write};

pub const SHADER: &str = include_str!("../../../shaders/composite.wgsl");

/// The direct light and the emission it adds to (group 1).
pub const INPUTS: Group = Group::new(
    "composite inputs",
    &[ShaderBinding::texture("direct_radiance"), ShaderBinding::texture("gbuffer_emissive")],
);

pub struct CompositePass {
    pipeline: wgpu::RenderPipeline,
    inputs: wgpu::BindGroupLayout,
    core: CoreResources,
}

pub struct CompositeIo {
    direct: Read<Image>,
    emissive: Read<Image>,
    hdr: Write<Image>,
}

impl CompositePass {
    pub fn new(gpu: &Gpu, layouts: &CoreLayouts, core: &CoreResources) -> Self {
        let device = &gpu.device;
        let module = crate::shader::module(device, "composite", SHADER, &[]);
        let inputs = INPUTS.layout(device);
        let pipeline = fullscreen_pipeline(
            device,
            "composite",
            &module,
            &[Some(&layouts.globals), Some(&inputs)],
            HDR_FORMAT,
            None,
        );
        Self { pipeline, inputs, core: *core }
    }
}

impl RenderPass for CompositePass {
    type Io = CompositeIo;

    fn name(&self) -> &str {
        "composite"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> CompositeIo {
        CompositeIo {
            direct: d.read(self.core.direct),
            emissive: d.read(self.core.emissive),
            hdr: d.create(self.core.hdr, TextureDesc::target(HDR_FORMAT)),
        }
    }

    fn run(&mut self, io: &CompositeIo, ctx: &mut PassContext<'_>) {
        let inputs = INPUTS.bind(
            &ctx.gpu.device,
            &self.inputs,
            &[("direct_radiance", ctx.view(&io.direct).into()), ("gbuffer_emissive", ctx.view(&io.emissive).into())],
        );
        let target = ctx.view(&io.hdr);
        let mut pass = color_pass(ctx.encoder, "composite", target, false);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &inputs, &[]);
        pass.draw(0..3, 0..1);
    }
}
