//! The `lights` view: the frame, dimmed, with a dot per reflection light coloured by its level.

use engine::graph::{PassContext, PassDecl, RenderPass, TextureDesc};
use engine::passes::names::HDR;
use engine::passes::{color_pass, procedural_pipeline};
use engine::wgpu;

use crate::bindings::{bind, layout, Resource as R, Slot as S};
use crate::gpu_types::names;

pub const SHADER: &str = include_str!("../../../shaders/gi/lights_view.wgsl");
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

pub struct LightsViewPass {
    layout: wgpu::BindGroupLayout,
    frame: wgpu::RenderPipeline,
    dots: wgpu::RenderPipeline,
}

impl LightsViewPass {
    pub(crate) fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout) -> Self {
        let layout = layout(device, "gi lights view", &[S::Storage { read_only: true }, S::Texture]);
        let module = super::module(device, "gi lights view", SHADER);
        let (layouts, targets) = ([Some(globals), Some(&layout)], [Some(FORMAT.into())]);
        let pipeline = |vs, fs| {
            procedural_pipeline(device, "gi lights view", &module, (vs, fs), &layouts, &targets, Default::default())
        };
        Self { frame: pipeline("vs_frame", "fs_frame"), dots: pipeline("vs_dot", "fs_dot"), layout }
    }
}

impl RenderPass for LightsViewPass {
    fn name(&self) -> &str {
        "gi_lights_view"
    }

    fn declare(&self, d: &mut PassDecl) {
        d.read(names::LIGHTS)
            .read(names::STATS)
            .read(HDR)
            .create_texture(names::LIGHTS_VIEW, TextureDesc::target(FORMAT));
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let group =
            bind(&ctx.gpu.device, &self.layout, &[R::Buffer(ctx.buffer(names::LIGHTS)), R::View(ctx.view(HDR))]);
        // The stats begin with the draw arguments of the centre tile's lights.
        let args = ctx.buffer(names::STATS);
        let mut pass = color_pass(ctx.encoder, "gi lights view", ctx.view(names::LIGHTS_VIEW), false);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.set_pipeline(&self.frame);
        pass.draw(0..3, 0..1);
        pass.set_pipeline(&self.dots);
        pass.draw_indirect(args, 0);
    }
}
