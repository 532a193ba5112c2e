//! The `lights` view: the frame, dimmed, with a dot per reflection light coloured by its level.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::graph::{Buffer, Handle, Image, PassContext, PassDecl, Read, RenderPass, TextureDesc, Write};
use engine::passes::{color_pass, procedural_pipeline};
use engine::wgpu;

use crate::resources::GiResources;

pub const SHADER: &str = include_str!("../../../shaders/gi/lights_view.wgsl");
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// The lights view's group 1 (lights_view.wgsl): the centre tile's lights and the frame.
pub const LIGHTS_VIEW: Group = Group::new("gi lights view", &[B::storage("reflection_lights"), B::texture("frame")]);

/// Where its group is declared.
pub const BINDINGS: &[WgslGroup] = &[WgslGroup::new("gi/lights_view.wgsl", 1, &LIGHTS_VIEW)];

pub struct LightsViewPass {
    layout: wgpu::BindGroupLayout,
    frame: wgpu::RenderPipeline,
    dots: wgpu::RenderPipeline,
    gi: GiResources,
    hdr: Handle<Image>,
}

pub struct LightsViewIo {
    lights: Read<Buffer>,
    stats: Read<Buffer>,
    hdr: Read<Image>,
    target: Write<Image>,
}

impl LightsViewPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        gi: GiResources,
        hdr: Handle<Image>,
    ) -> Self {
        let layout = LIGHTS_VIEW.layout(device);
        let module = crate::shader::module(device, "gi lights view", SHADER);
        let (layouts, targets) = ([Some(globals), Some(&layout)], [Some(FORMAT.into())]);
        let pipeline = |vs, fs| {
            procedural_pipeline(device, "gi lights view", &module, (vs, fs), &layouts, &targets, Default::default())
        };
        Self { frame: pipeline("vs_frame", "fs_frame"), dots: pipeline("vs_dot", "fs_dot"), layout, gi, hdr }
    }
}

impl RenderPass for LightsViewPass {
    type Io = LightsViewIo;

    fn name(&self) -> &str {
        "gi_lights_view"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> LightsViewIo {
        LightsViewIo {
            lights: d.read(self.gi.first().lights),
            stats: d.read(self.gi.first().stats),
            hdr: d.read(self.hdr),
            target: d.create(self.gi.lights_view, TextureDesc::target(FORMAT)),
        }
    }

    fn run(&mut self, io: &LightsViewIo, ctx: &mut PassContext<'_>) {
        let group = LIGHTS_VIEW.bind(
            &ctx.gpu.device,
            &self.layout,
            &[("reflection_lights", ctx.buffer(&io.lights).into()), ("frame", ctx.view(&io.hdr).into())],
        );
        // The stats begin with the draw arguments of the centre tile's lights.
        let args = ctx.buffer(&io.stats);
        let mut pass = color_pass(ctx.encoder, "gi lights view", ctx.view(&io.target), false);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.set_pipeline(&self.frame);
        pass.draw(0..3, 0..1);
        pass.set_pipeline(&self.dots);
        pass.draw_indirect(args, 0);
        drop(pass);
        ctx.count_draws(2);
    }
}
