//! Direct radiance from the headlamp and the punctual lights, evaluated per G-buffer texel with
//! glTF's metallic-roughness BRDF (shaders/brdf.wgsl), Lambertian where the texel says so.
//! A detached headlamp is shadowed by its own depth map, `lamp.depth` (see lamp_view.rs).

use super::core_resources::{CoreResources, HDR_FORMAT};
use super::fullscreen::{color_pass, fullscreen_pipeline};
use crate::globals::{texture_entry, CoreLayouts};
use crate::gpu::Gpu;
use crate::graph::{Image, PassContext, PassDecl, Read, RenderPass, TextureDesc, Write};

pub const SHADER: &str = include_str!("../../../shaders/direct_light.wgsl");

pub struct DirectLightPass {
    pipeline: wgpu::RenderPipeline,
    inputs: wgpu::BindGroupLayout,
    /// Bilinear depth comparison for percentage-closer filtering of `lamp.depth`.
    shadow_sampler: wgpu::Sampler,
    core: CoreResources,
}

pub struct DirectLightIo {
    /// Albedo, normal, position, the lamp's depth, specular: bindings 0–3 and 5.
    inputs: [Read<Image>; 5],
    direct: Write<Image>,
}

impl DirectLightPass {
    pub fn new(gpu: &Gpu, layouts: &CoreLayouts, core: &CoreResources) -> Self {
        let device = &gpu.device;
        let module = crate::shader::module(device, "direct light", SHADER, &[]);
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let [shadow_map, shadow_compare] = super::lamp_view::lamp_shadow_entries(3, fragment);
        let inputs = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("direct light inputs"),
            entries: &[
                texture_entry(0, fragment, false),
                texture_entry(1, fragment, false),
                texture_entry(2, fragment, false),
                shadow_map,
                shadow_compare,
                texture_entry(5, fragment, false),
            ],
        });
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
        let texture = |binding: u32, input: &Read<Image>| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(ctx.view(input)),
        };
        let inputs = ctx.gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("direct light inputs"),
            layout: &self.inputs,
            entries: &[
                texture(0, albedo),
                texture(1, normal),
                texture(2, position),
                texture(3, lamp_depth),
                wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::Sampler(&self.shadow_sampler) },
                texture(5, specular),
            ],
        });
        let target = ctx.view(&io.direct);
        let mut pass = color_pass(ctx.encoder, "direct light", target, false);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &inputs, &[]);
        pass.draw(0..3, 0..1);
    }
}
