//! Direct radiance from the headlamp and the punctual lights, evaluated per G-buffer texel with
//! glTF's metallic-roughness BRDF (shaders/brdf.wgsl), Lambertian where the texel says so.
//! A detached headlamp is shadowed by its own depth map, `lamp.depth` (see lamp_view.rs).

use super::core_resources::{CoreResources, HDR_FORMAT};
use super::fullscreen::{color_pass, fullscreen_pipeline};
use crate::bindings::{Group, ShaderBinding};
use crate::globals::CoreLayouts;
use crate::gpu::Gpu;
use crate::graph::{Image, PassContext, PassDecl, Read, RenderPass, TextureDesc, Write};

pub const SHADER: &str = include_str!("../../../shaders/direct_light.wgsl");

/// The G-buffer and the detached lamp's shadow map (group 1).
pub const INPUTS: Group = Group::new(
    "direct light inputs",
    &[
        ShaderBinding::texture("gbuffer_albedo"),
        ShaderBinding::texture("gbuffer_normal"),
        ShaderBinding::texture("gbuffer_position"),
        ShaderBinding::depth_texture("lamp_depth"),
        ShaderBinding::comparison_sampler("lamp_shadow"),
        ShaderBinding::texture("gbuffer_specular"),
    ],
);

pub struct DirectLightPass {
    pipeline: wgpu::RenderPipeline,
    inputs: wgpu::BindGroupLayout,
    /// Bilinear depth comparison for percentage-closer filtering of `lamp.depth`.
    shadow_sampler: wgpu::Sampler,
    core: CoreResources,
}

pub struct DirectLightIo {
    /// Albedo, normal, position, the lamp's depth, specular.
    inputs: [Read<Image>; 5],
    direct: Write<Image>,
}

impl DirectLightPass {
    pub fn new(gpu: &Gpu, layouts: &CoreLayouts, core: &CoreResources) -> Self {
        let device = &gpu.device;
        let module = crate::shader::module(device, "direct light", SHADER, &[]);
        let inputs = INPUTS.layout(device);
        let pipeline = fullscreen_pipeline(
            device,
            "direct light",
            &module,
            &[Some(&layouts.globals), Some(&inputs)],
            HDR_FORMAT,
            None,
        );
        let shadow_sampler = super::lamp_view::lamp_shadow_sampler(device, "lamp shadow");
        Self { pipeline, inputs, shadow_sampler, core: *core }
    }
}

impl RenderPass for DirectLightPass {
    type Io = DirectLightIo;

    fn name(&self) -> &str {
        "direct_light"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> DirectLightIo {
        // The lamp's depth is read in both modes so the graph does not change when the lamp is
        // picked up or put down; attached, the shader never samples it.
        let (g, c) = (&self.core.gbuffer, &self.core);
        DirectLightIo {
            inputs: [g.albedo, g.normal, g.position, c.lamp.depth, c.specular].map(|h| d.read(h)),
            direct: d.create(c.direct, TextureDesc::target(HDR_FORMAT)),
        }
    }

    fn run(&mut self, io: &DirectLightIo, ctx: &mut PassContext<'_>) {
        let [albedo, normal, position, lamp_depth, specular] = &io.inputs;
        let inputs = INPUTS.bind(
            &ctx.gpu.device,
            &self.inputs,
            &[
                ("gbuffer_albedo", ctx.view(albedo).into()),
                ("gbuffer_normal", ctx.view(normal).into()),
                ("gbuffer_position", ctx.view(position).into()),
                ("lamp_depth", ctx.view(lamp_depth).into()),
                ("lamp_shadow", (&self.shadow_sampler).into()),
                ("gbuffer_specular", ctx.view(specular).into()),
            ],
        );
        let target = ctx.view(&io.direct);
        let mut pass = color_pass(ctx.encoder, "direct light", target, false);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &inputs, &[]);
        pass.draw(0..3, 0..1);
    }
}
