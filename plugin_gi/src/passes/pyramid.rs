//! A bounce's flux pyramid (shaders/gi/pyramid.wgsl): its senders' reflected flux per texel,
//! merged up a quadtree into reflection lights of every size. Two dispatches whatever the
//! resolution (levels 0–3, then 4–6, each reduced in workgroup memory). The first bounce's
//! senders are lit by the headlamp (pyramid_lamp.wgsl); a further bounce's by the bounce
//! before (pyramid_bounce.wgsl).

use engine::bindings::{Group, Resource, ShaderBinding as B, WgslGroup};
use engine::graph::{Buffer, BufferDesc, Image, PassContext, PassDecl, Read, TextureDesc, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use super::params::{fixed, lamp_view};
use crate::frame::GiFrame;
use crate::gpu_types::{Levels, NODE_SIZE};
use crate::pipelines::{compute_pipeline, compute_pipeline_with};
use crate::quadtree::Quadtree;
use crate::resources::GiResources;
use crate::schedule::{bounce_pass_name, GiPass};
use crate::shader::module;

pub const LAMP_SHADER: &str = include_str!("../../../shaders/gi/pyramid_lamp.wgsl");
pub const BOUNCE_SHADER: &str = include_str!("../../../shaders/gi/pyramid_bounce.wgsl");

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
    ],
);
/// The first bounce's group 2: the `flux` view it shows its senders in.
pub const LAMP: Group =
    Group::new("gi pyramid lamp", &[B::storage_texture("flux_view_out", wgpu::TextureFormat::Rgba16Float)]);
/// A further bounce's group 2: the irradiance its senders reflect.
pub const BOUNCE: Group = Group::new("gi pyramid bounce", &[B::texture("previous_irradiance")]);

/// Where the pyramid's groups are declared.
pub const BINDINGS: &[WgslGroup] = &[
    WgslGroup::new("pyramid.wgsl", 1, &PYRAMID),
    WgslGroup::new("gi/pyramid_lamp.wgsl", 2, &LAMP).for_entry_points(&["flux_levels"]),
    WgslGroup::new("gi/pyramid_bounce.wgsl", 2, &BOUNCE).for_entry_points(&["flux_levels"]),
];

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

/// A storage texture of the flux G-buffer's size.
pub(crate) fn flux_texture(format: wgpu::TextureFormat, size: (u32, u32)) -> TextureDesc {
    let usage =
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC;
    TextureDesc { format, size: fixed(size), usage, mip_levels: 1 }
}

/// Builds bounce `bounce`'s pyramid (1: the headlamp's).
pub struct PyramidPass {
    name: String,
    bounce: u32,
    core: CoreResources,
    gi: GiResources,
    layout: wgpu::BindGroupLayout,
    /// Group 2: [`LAMP`]'s or [`BOUNCE`]'s.
    source_layout: wgpu::BindGroupLayout,
    /// Over single lamp-view texels, and over blocks of them (the shader's FLUX_BLOCKS).
    flux: [wgpu::ComputePipeline; 2],
    reduce: wgpu::ComputePipeline,
}

pub struct PyramidIo {
    params: Read<Buffer>,
    /// The senders' albedo, normal and position: the lamp view's, or a further bounce's
    /// camera view.
    senders: [Read<Image>; 3],
    flux: Write<Image>,
    nodes: Write<Buffer>,
    source: Source,
    size: (u32, u32),
    /// Whether the base is of lamp-view texel blocks (which have halves: see Quadtree).
    blocks: bool,
}

/// What differs between the first bounce's pyramid and a further one's.
enum Source {
    /// The first writes the level table, and shows its senders in the `flux` view.
    Lamp { levels: Write<Buffer>, flux_view: Write<Image> },
    /// A further one reads the table (its base is the same size) and reflects the bounce
    /// before's irradiance.
    Bounce { levels: Read<Buffer>, previous: Read<Image> },
}

impl PyramidPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        bounce: u32,
        core: CoreResources,
        gi: GiResources,
    ) -> Self {
        let layout = PYRAMID.layout(device);
        let (label, source, shader) =
            if bounce == 1 { ("gi flux", &LAMP, LAMP_SHADER) } else { ("gi bounce flux", &BOUNCE, BOUNCE_SHADER) };
        let source_layout = source.layout(device);
        let module = module(device, label, shader);
        let flux = [false, true].map(|blocks| {
            let constants = [("FLUX_BLOCKS", f64::from(u8::from(blocks)))];
            let layouts = [Some(globals), Some(&layout), Some(&source_layout)];
            compute_pipeline_with(device, label, &module, "flux_levels", &layouts, &constants)
        });
        let reduce = compute_pipeline(device, "gi reduce", &module, "reduce", &[Some(globals), Some(&layout)]);
        let name = bounce_pass_name("flux", bounce);
        Self { name, bounce, core, gi, layout, source_layout, flux, reduce }
    }
}

impl GiPass for PyramidPass {
    type Io = PyramidIo;

    fn name(&self) -> &str {
        &self.name
    }

    fn declare(&self, d: &mut PassDecl<'_>, frame: &GiFrame) -> PyramidIo {
        let first = self.bounce == 1;
        let (senders, _) = frame.of_bounce(self.bounce);
        let own = self.gi.bounce(self.bounce);
        let view =
            if first { lamp_view(&self.core.gbuffer, &self.core.lamp, frame.attached) } else { self.core.gbuffer };
        let (size, blocks) = (senders.flux, senders.blocks());
        let source = if first {
            Source::Lamp {
                levels: d.create(self.gi.levels, levels_desc()),
                flux_view: d
                    .create(self.gi.flux_view, flux_texture(wgpu::TextureFormat::Rgba16Float, senders.flux_view)),
            }
        } else {
            let previous = self.gi.bounce(self.bounce - 1).alone;
            Source::Bounce { levels: d.read(self.gi.levels), previous: d.read(previous) }
        };
        PyramidIo {
            params: d.read(own.params),
            senders: [view.albedo, view.normal, view.position].map(|h| d.read(h)),
            flux: d.create(own.flux, flux_texture(wgpu::TextureFormat::Rgba32Float, size)),
            nodes: d.create(own.nodes, nodes_desc(size, blocks)),
            source,
            size,
            blocks,
        }
    }

    fn run(&mut self, io: &PyramidIo, _: &GiFrame, ctx: &mut PassContext<'_>) {
        let (levels, source): (&wgpu::Buffer, (&str, Resource<'_>)) = match &io.source {
            Source::Lamp { levels, flux_view } => {
                let table = Levels { levels: Quadtree::of_blocks(io.size.0, io.size.1, io.blocks).table() };
                ctx.write_buffer(levels, 0, bytemuck::bytes_of(&table));
                (ctx.buffer(levels), ("flux_view_out", ctx.view(flux_view).into()))
            }
            Source::Bounce { levels, previous } => {
                (ctx.buffer(levels), ("previous_irradiance", ctx.view(previous).into()))
            }
        };
        let [albedo, normal, position] = &io.senders;
        let device = &ctx.gpu.device;
        let group = PYRAMID.bind(
            device,
            &self.layout,
            &[
                ("gbuffer_albedo", ctx.view(albedo).into()),
                ("gbuffer_normal", ctx.view(normal).into()),
                ("gbuffer_position", ctx.view(position).into()),
                ("params", ctx.buffer(&io.params).into()),
                ("table", levels.into()),
                ("nodes", ctx.buffer(&io.nodes).into()),
                ("flux_out", ctx.view(&io.flux).into()),
            ],
        );
        let source_group = match io.source {
            Source::Lamp { .. } => &LAMP,
            Source::Bounce { .. } => &BOUNCE,
        }
        .bind(device, &self.source_layout, &[source]);
        let mut pass = ctx
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi pyramid"), timestamp_writes: None });
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.set_bind_group(2, &source_group, &[]);
        pass.set_pipeline(&self.flux[usize::from(io.blocks)]);
        pass.dispatch_workgroups(io.size.0.div_ceil(GROUP_SIDE), io.size.1.div_ceil(GROUP_SIDE), 1);
        // Each workgroup of the second dispatch reduces GROUP_SIDE² nodes of level GROUP_LEVELS.
        let (w, h) = Quadtree::new(io.size.0, io.size.1).size(GROUP_LEVELS);
        pass.set_pipeline(&self.reduce);
        pass.dispatch_workgroups(w.div_ceil(GROUP_SIDE), h.div_ceil(GROUP_SIDE), 1);
        drop(pass);
        ctx.count_dispatches(2);
    }
}
