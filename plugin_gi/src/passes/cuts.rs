//! A bounce's cuts (shaders/gi/cuts.wgsl): each 8×8 tile of the indirect target takes its own
//! cut through the bounce's pyramid, fine lights near its receivers and coarse ones far away,
//! and finds the G-buffer texel each receiver is evaluated on. Two dispatches: one invocation
//! a tile, then the few tiles whose cut filled up walked again side by side (an indirect
//! dispatch). The layout of the cuts is crate::cuts_layout's.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::graph::{Buffer, BufferDesc, Image, PassContext, PassDecl, Read, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use crate::cuts_layout::{cuts_desc, receivers_desc, CutsLayout, CUTS_GROUP};
use crate::frame::GiFrame;
use crate::gpu_types::{CENTRE_LIGHTS, GATHER_STATS_SIZE, RETRY_HEADER};
use crate::pipelines::compute_pipeline;
use crate::resources::GiResources;
use crate::schedule::{bounce_pass_name, GiPass};
use crate::shader::module;

pub const SHADER: &str = include_str!("../../../shaders/gi/cuts.wgsl");

/// The cuts' group 1 (cuts.wgsl).
pub const CUTS: Group = Group::new(
    "gi cuts",
    &[
        B::uniform("params"),
        B::uniform("table"),
        B::storage("nodes"),
        B::texture("gbuffer_normal"),
        B::texture("gbuffer_position"),
        B::storage_rw("cuts"),
        B::storage_rw("stats"),
        B::storage_rw("centre_lights"),
        B::storage_rw("retry"),
        B::storage_rw("receiver_texels"),
    ],
);
/// The cuts' group 2: the retry dispatch's arguments, written by `main`.
pub const RETRY_ARGS: Group = Group::new("gi cuts retry arguments", &[B::storage_rw("retry_dispatch")]);

/// Where the cuts' groups are declared.
pub const BINDINGS: &[WgslGroup] = &[
    WgslGroup::new("gi/cuts.wgsl", 1, &CUTS),
    WgslGroup::new("gi/cuts.wgsl", 2, &RETRY_ARGS).for_entry_points(&["main"]),
];

/// The cuts' counters and the `lights` view's draw arguments.
pub(crate) fn stats_desc() -> BufferDesc {
    let usage = wgpu::BufferUsages::STORAGE
        | wgpu::BufferUsages::COPY_SRC
        | wgpu::BufferUsages::COPY_DST
        | wgpu::BufferUsages::INDIRECT;
    BufferDesc { size: GATHER_STATS_SIZE, usage }
}

/// The centre tile's lights.
pub(crate) fn lights_desc() -> BufferDesc {
    let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST;
    BufferDesc { size: CENTRE_LIGHTS * std::mem::size_of::<crate::ReflectionLight>() as u64, usage }
}

/// The tiles to walk again: a count, then a slot and a ratio each.
fn retry_desc(layout: &CutsLayout) -> BufferDesc {
    let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
    BufferDesc { size: RETRY_HEADER + 8 * u64::from(layout.tile_count()), usage }
}

/// The retry dispatch's workgroups, as its indirect arguments.
fn retry_args_desc() -> BufferDesc {
    let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_DST;
    BufferDesc { size: std::mem::size_of::<wgpu::util::DispatchIndirectArgs>() as u64, usage }
}

/// Takes bounce `bounce`'s cuts (1: the headlamp's).
pub struct CutsPass {
    name: String,
    bounce: u32,
    core: CoreResources,
    gi: GiResources,
    layout: wgpu::BindGroupLayout,
    retry_args_layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    retry_pipeline: wgpu::ComputePipeline,
}

pub struct CutsIo {
    params: Read<Buffer>,
    levels: Read<Buffer>,
    nodes: Read<Buffer>,
    normal: Read<Image>,
    position: Read<Image>,
    cuts: Write<Buffer>,
    stats: Write<Buffer>,
    lights: Write<Buffer>,
    retry: Write<Buffer>,
    retry_args: Write<Buffer>,
    receivers: Write<Buffer>,
    layout: CutsLayout,
}

impl CutsPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        bounce: u32,
        core: CoreResources,
        gi: GiResources,
    ) -> Self {
        let layout = CUTS.layout(device);
        let retry_args_layout = RETRY_ARGS.layout(device);
        let module = module(device, "gi cuts", SHADER);
        let pipeline = compute_pipeline(
            device,
            "gi cuts",
            &module,
            "main",
            &[Some(globals), Some(&layout), Some(&retry_args_layout)],
        );
        let retry_pipeline =
            compute_pipeline(device, "gi cuts retry", &module, "retry_full_tiles", &[Some(globals), Some(&layout)]);
        let name = bounce_pass_name("cuts", bounce);
        Self { name, bounce, core, gi, layout, retry_args_layout, pipeline, retry_pipeline }
    }
}

impl GiPass for CutsPass {
    type Io = CutsIo;

    fn name(&self) -> &str {
        &self.name
    }

    fn declare(&self, d: &mut PassDecl<'_>, frame: &GiFrame) -> CutsIo {
        let own = self.gi.bounce(self.bounce);
        let (_, layout) = frame.of_bounce(self.bounce);
        CutsIo {
            params: d.read(own.params),
            levels: d.read(self.gi.levels),
            nodes: d.read(own.nodes),
            normal: d.read(self.core.gbuffer.normal),
            position: d.read(self.core.gbuffer.position),
            cuts: d.create(own.cuts, cuts_desc(&layout, frame.visibility())),
            stats: d.create(own.stats, stats_desc()),
            lights: d.create(own.lights, lights_desc()),
            retry: d.create(own.retry, retry_desc(&layout)),
            retry_args: d.create(own.retry_args, retry_args_desc()),
            receivers: d.create(own.receivers, receivers_desc(frame.indirect)),
            layout,
        }
    }

    fn run(&mut self, io: &CutsIo, _: &GiFrame, ctx: &mut PassContext<'_>) {
        let (stats, retry, retry_args) = (ctx.buffer(&io.stats), ctx.buffer(&io.retry), ctx.buffer(&io.retry_args));
        ctx.encoder.clear_buffer(stats, 0, Some(GATHER_STATS_SIZE));
        // The first walk sets the arguments' y and z, and counts x up from 0.
        ctx.encoder.clear_buffer(retry, 0, Some(RETRY_HEADER));
        ctx.encoder.clear_buffer(retry_args, 0, None);
        let device = &ctx.gpu.device;
        let group = CUTS.bind(
            device,
            &self.layout,
            &[
                ("params", ctx.buffer(&io.params).into()),
                ("table", ctx.buffer(&io.levels).into()),
                ("nodes", ctx.buffer(&io.nodes).into()),
                ("gbuffer_normal", ctx.view(&io.normal).into()),
                ("gbuffer_position", ctx.view(&io.position).into()),
                ("cuts", ctx.buffer(&io.cuts).into()),
                ("stats", stats.into()),
                ("centre_lights", ctx.buffer(&io.lights).into()),
                ("retry", retry.into()),
                ("receiver_texels", ctx.buffer(&io.receivers).into()),
            ],
        );
        let args = RETRY_ARGS.bind(device, &self.retry_args_layout, &[("retry_dispatch", retry_args.into())]);
        let mut pass = ctx
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi cuts"), timestamp_writes: None });
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(1, &group, &[]);
        pass.set_bind_group(2, &args, &[]);
        pass.dispatch_workgroups(io.layout.tile_count().div_ceil(CUTS_GROUP), 1, 1);
        pass.set_pipeline(&self.retry_pipeline);
        pass.dispatch_workgroups_indirect(retry_args, 0);
        drop(pass);
        ctx.count_dispatches(2);
    }
}
