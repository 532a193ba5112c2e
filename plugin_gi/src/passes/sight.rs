//! A bounce's sight test (shaders/gi/sight.wgsl): which of nine receivers of each tile see
//! each light of its cut, marched through the sight depth, written after the cuts for the sum
//! to weigh each light by. One workgroup a tile.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use std::rc::Rc;

use engine::graph::{Buffer, Image, PassContext, PassDecl, Read, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use crate::cuts_layout::CutsLayout;
use crate::frame::GiFrame;
use crate::pipelines::compute_pipeline_with;
use crate::resources::GiResources;
use crate::schedule::{bounce_pass_name, GiPass};
use crate::shader::module;
use crate::world_grid::{WorldGrid, WORLD};

pub const SHADER: &str = include_str!("../../../shaders/gi/sight.wgsl");

/// The sight's group 1 (sight.wgsl).
pub const SIGHT: Group = Group::new(
    "gi sight",
    &[
        B::uniform("params"),
        B::uniform("table"),
        B::texture("gbuffer_normal"),
        B::texture("gbuffer_position"),
        B::storage_rw("cuts"),
        B::storage("receiver_texels"),
        B::texture("sight_depth"),
    ],
);

/// Where its group is declared.
pub const BINDINGS: &[WgslGroup] =
    &[WgslGroup::new("gi/sight.wgsl", 1, &SIGHT), WgslGroup::new("gi/sight.wgsl", 2, &WORLD)];

/// Tests bounce `bounce`'s cuts (1: the headlamp's).
pub struct SightPass {
    name: String,
    bounce: u32,
    core: CoreResources,
    gi: GiResources,
    layout: wgpu::BindGroupLayout,
    world: Rc<WorldGrid>,
    /// Through the camera's depth, and through the level's voxels too (the shader's WORLD).
    pipelines: [wgpu::ComputePipeline; 2],
}

pub struct SightIo {
    params: Read<Buffer>,
    levels: Read<Buffer>,
    normal: Read<Image>,
    position: Read<Image>,
    receivers: Read<Buffer>,
    depth: Read<Image>,
    cuts: Write<Buffer>,
    layout: CutsLayout,
    world: bool,
}

impl SightPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        bounce: u32,
        core: CoreResources,
        gi: GiResources,
        world: Rc<WorldGrid>,
    ) -> Self {
        let layout = SIGHT.layout(device);
        let module = module(device, "gi sight", SHADER);
        let layouts = [Some(globals), Some(&layout), Some(&world.layout)];
        let pipelines = [false, true].map(|on| {
            let constants = [("WORLD", f64::from(u8::from(on)))];
            compute_pipeline_with(device, "gi sight", &module, "main", &layouts, &constants)
        });
        let name = bounce_pass_name("sight", bounce);
        Self { name, bounce, core, gi, layout, world, pipelines }
    }
}

impl GiPass for SightPass {
    type Io = SightIo;

    fn name(&self) -> &str {
        &self.name
    }

    fn declare(&self, d: &mut PassDecl<'_>, frame: &GiFrame) -> SightIo {
        let own = self.gi.bounce(self.bounce);
        SightIo {
            params: d.read(own.params),
            levels: d.read(self.gi.levels),
            normal: d.read(self.core.gbuffer.normal),
            position: d.read(self.core.gbuffer.position),
            receivers: d.read(own.receivers),
            depth: d.read(self.gi.sight_depth),
            cuts: d.write(own.cuts),
            layout: frame.of_bounce(self.bounce).1,
            world: frame.world_sight(),
        }
    }

    fn run(&mut self, io: &SightIo, _: &GiFrame, ctx: &mut PassContext<'_>) {
        let group = SIGHT.bind(
            &ctx.gpu.device,
            &self.layout,
            &[
                ("params", ctx.buffer(&io.params).into()),
                ("table", ctx.buffer(&io.levels).into()),
                ("gbuffer_normal", ctx.view(&io.normal).into()),
                ("gbuffer_position", ctx.view(&io.position).into()),
                ("cuts", ctx.buffer(&io.cuts).into()),
                ("receiver_texels", ctx.buffer(&io.receivers).into()),
                ("sight_depth", ctx.view(&io.depth).into()),
            ],
        );
        let mut pass = ctx
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi sight"), timestamp_writes: None });
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_pipeline(&self.pipelines[usize::from(io.world)]);
        pass.set_bind_group(1, &group, &[]);
        pass.set_bind_group(2, &self.world.group, &[]);
        pass.dispatch_workgroups(io.layout.tiles.0, io.layout.tiles.1, 1);
        drop(pass);
        ctx.count_dispatches(1);
    }
}
