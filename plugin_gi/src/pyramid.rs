//! The flux pyramid (shaders/gi/pyramid.wgsl): the lamp view's reflected flux per texel,
//! merged up a quadtree into reflection lights of every size. Two dispatches whatever the
//! resolution (levels 0–3, then 4–6, each reduced in workgroup memory). Used once per bounce.
//! Its node buffer and level table are graph resources: the passes that build and read a
//! pyramid declare them.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::graph::BufferDesc;
use engine::wgpu;

use crate::gpu_types::{Levels, NODE_SIZE};
use crate::pipelines::{compute_pipeline, compute_pipeline_with};
use crate::quadtree::Quadtree;
use crate::shader::module;

pub const SHADER: &str = include_str!("../../shaders/gi/pyramid.wgsl");

/// The pyramid's group 1 (pyramid.wgsl).
pub const PYRAMID: Group = Group::new(
    "gi pyramid",
    &[
        B::texture("gbuffer_albedo"),
        B::texture("gbuffer_normal"),
        B::texture("gbuffer_position"),
        B::uniform("params"),
        B::uniform("table"),
        B::storage_rw("nodes"),
        B::storage_texture("flux_out", wgpu::TextureFormat::Rgba32Float),
        B::storage_texture("flux_view_out", wgpu::TextureFormat::Rgba16Float),
        B::texture("previous_irradiance"),
    ],
);

/// Where the pyramid's group is declared.
pub const BINDINGS: &[WgslGroup] = &[WgslGroup::new("gi/pyramid.wgsl", 1, &PYRAMID)];

/// The levels a workgroup merges above its GROUP_SIDE × GROUP_SIDE nodes, in workgroup memory
/// (`GROUP_LEVELS` in pyramid.wgsl): the first dispatch builds levels 0 to GROUP_LEVELS, the
/// second the rest from level GROUP_LEVELS.
pub(crate) const GROUP_LEVELS: u32 = 3;
/// A workgroup's side in nodes of the level it starts from.
pub(crate) const GROUP_SIDE: u32 = 1 << GROUP_LEVELS;

/// The node buffer of a pyramid over a flux G-buffer of `size` (of texel blocks: `blocks`).
pub fn nodes_desc(size: (u32, u32), blocks: bool) -> BufferDesc {
    BufferDesc {
        size: Quadtree::of_blocks(size.0, size.1, blocks).node_count() as u64 * NODE_SIZE,
        usage: wgpu::BufferUsages::STORAGE,
    }
}

/// The level table (offset, width, height per level), a uniform its builder writes.
pub fn levels_desc() -> BufferDesc {
    BufferDesc {
        size: std::mem::size_of::<Levels>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    }
}

/// What one build reads and writes.
pub struct PyramidBindings<'a> {
    /// The GiParams this build reads (its `source` says lamp or bounce).
    pub params: &'a wgpu::Buffer,
    pub levels: &'a wgpu::Buffer,
    pub nodes: &'a wgpu::Buffer,
    pub albedo: &'a wgpu::TextureView,
    pub normal: &'a wgpu::TextureView,
    pub position: &'a wgpu::TextureView,
    /// Previous bounce's irradiance (any float texture when building from the lamp).
    pub previous: &'a wgpu::TextureView,
    pub flux: &'a wgpu::TextureView,
    pub flux_view: &'a wgpu::TextureView,
    /// Whether the base's texels are blocks of lamp-view texels (GiParams.flux_block > 1).
    pub blocks: bool,
}

/// Where the base's flux comes from (GiParams.source, as [`FluxSource::code`]). Each source,
/// and each kind of base (single lamp-view texels or blocks of them), has its own pipeline,
/// made with the shader's override constants, so it compiles only its own way (a CPU device
/// runs both sides of a branch on a uniform value).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FluxSource {
    /// The headlamp's light on the lamp view (the first bounce).
    Lamp,
    /// The previous bounce's irradiance (bounces after the first).
    Bounce,
}

/// FluxSource's codes (`FROM_LAMP`, `FROM_BOUNCE` in gi_common.wgsl).
pub(crate) const FROM_LAMP: u32 = 0;
pub(crate) const FROM_BOUNCE: u32 = 1;

impl FluxSource {
    /// Its value of GiParams.source and of the shader's FLUX_SOURCE.
    pub(crate) fn code(self) -> u32 {
        match self {
            FluxSource::Lamp => FROM_LAMP,
            FluxSource::Bounce => FROM_BOUNCE,
        }
    }
}

pub struct PyramidPipelines {
    layout: wgpu::BindGroupLayout,
    /// Over single lamp-view texels, and over blocks of them.
    flux: [wgpu::ComputePipeline; 2],
    reduce: wgpu::ComputePipeline,
}

impl PyramidPipelines {
    pub fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout, source: FluxSource) -> Self {
        let layout = PYRAMID.layout(device);
        let module = module(device, "gi pyramid", SHADER);
        let layouts = [Some(globals), Some(&layout)];
        let from = f64::from(source.code());
        Self {
            flux: [false, true].map(|blocks| {
                let constants = [("FLUX_SOURCE", from), ("FLUX_BLOCKS", f64::from(u8::from(blocks)))];
                let label = format!("gi flux ({source:?}, blocks {blocks})");
                compute_pipeline_with(device, &label, &module, "flux_levels", &layouts, &constants)
            }),
            reduce: compute_pipeline(device, "gi reduce", &module, "reduce", &layouts),
            layout,
        }
    }

    /// Records the flux and the reduction over a lamp view of `size`; returns the number of
    /// dispatches.
    pub fn record(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        globals: &wgpu::BindGroup,
        size: (u32, u32),
        b: &PyramidBindings<'_>,
    ) -> u32 {
        let group = PYRAMID.bind(
            device,
            &self.layout,
            &[
                ("gbuffer_albedo", b.albedo.into()),
                ("gbuffer_normal", b.normal.into()),
                ("gbuffer_position", b.position.into()),
                ("params", b.params.into()),
                ("table", b.levels.into()),
                ("nodes", b.nodes.into()),
                ("flux_out", b.flux.into()),
                ("flux_view_out", b.flux_view.into()),
                ("previous_irradiance", b.previous.into()),
            ],
        );
        let mut pass = encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi pyramid"), timestamp_writes: None });
        pass.set_bind_group(0, globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.set_pipeline(&self.flux[usize::from(b.blocks)]);
        pass.dispatch_workgroups(size.0.div_ceil(GROUP_SIDE), size.1.div_ceil(GROUP_SIDE), 1);
        // Each workgroup of the second dispatch reduces GROUP_SIDE² nodes of level GROUP_LEVELS.
        let (w, h) = Quadtree::new(size.0, size.1).size(GROUP_LEVELS);
        pass.set_pipeline(&self.reduce);
        pass.dispatch_workgroups(w.div_ceil(GROUP_SIDE), h.div_ceil(GROUP_SIDE), 1);
        2
    }
}
