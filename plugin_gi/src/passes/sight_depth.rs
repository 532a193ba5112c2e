//! The view depth the sight test marches (shaders/gi/sight_depth.wgsl): the G-buffer's, at
//! half its size each way, R32Float, so the march's scattered loads are small ones. Made once
//! a frame with `gi.visibility`, for every bounce and either method.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::graph::{Image, PassContext, PassDecl, Read, TextureDesc, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use crate::frame::GiFrame;
use crate::pipelines::{compute_pipeline, TEXEL_GROUP};
use crate::resources::GiResources;
use crate::schedule::GiPass;
use crate::shader::module;

pub const SHADER: &str = include_str!("../../../shaders/gi/sight_depth.wgsl");

/// The sight depth's group 1 (sight_depth.wgsl).
pub const SIGHT_DEPTH: Group = Group::new(
    "gi sight depth",
    &[B::texture("gbuffer_position"), B::storage_texture("depth", wgpu::TextureFormat::R32Float)],
);

/// Where its group is declared.
pub const BINDINGS: &[WgslGroup] = &[WgslGroup::new("gi/sight_depth.wgsl", 1, &SIGHT_DEPTH)];

/// The sight depth for a G-buffer of `gbuffer` texels: half its size each way, rounded up.
fn sight_depth_desc(gbuffer: (u32, u32)) -> TextureDesc {
    let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
    TextureDesc { usage, ..TextureDesc::target(wgpu::TextureFormat::R32Float) }
        .fixed(gbuffer.0.div_ceil(2), gbuffer.1.div_ceil(2))
}

pub struct SightDepthPass {
    core: CoreResources,
    gi: GiResources,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

pub struct SightDepthIo {
    position: Read<Image>,
    depth: Write<Image>,
}

impl SightDepthPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        core: CoreResources,
        gi: GiResources,
    ) -> Self {
        let layout = SIGHT_DEPTH.layout(device);
        let module = module(device, "gi sight depth", SHADER);
        let pipeline = compute_pipeline(device, "gi sight depth", &module, "main", &[Some(globals), Some(&layout)]);
        Self { core, gi, layout, pipeline }
    }
}

impl GiPass for SightDepthPass {
    type Io = SightDepthIo;

    fn name(&self) -> &str {
        "gi_sight_depth"
    }

    fn declare(&self, d: &mut PassDecl<'_>, _: &GiFrame) -> SightDepthIo {
        SightDepthIo {
            position: d.read(self.core.gbuffer.position),
            depth: d.create(self.gi.sight_depth, sight_depth_desc(d.size())),
        }
    }

    fn run(&mut self, io: &SightDepthIo, _: &GiFrame, ctx: &mut PassContext<'_>) {
        let size = ctx.texture(&io.depth).size();
        let group = SIGHT_DEPTH.bind(
            &ctx.gpu.device,
            &self.layout,
            &[("gbuffer_position", ctx.view(&io.position).into()), ("depth", ctx.view(&io.depth).into())],
        );
        let mut pass = ctx
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi sight depth"), timestamp_writes: None });
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(1, &group, &[]);
        pass.dispatch_workgroups(size.width.div_ceil(TEXEL_GROUP), size.height.div_ceil(TEXEL_GROUP), 1);
        drop(pass);
        ctx.count_dispatches(1);
    }
}
