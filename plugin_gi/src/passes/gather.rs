//! The first bounce's gather: the irradiance of every indirect-target pixel from the pyramid.

use engine::graph::{Buffer, BufferDesc, Image, PassContext, PassDecl, Read, RenderPass, TextureDesc, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use super::params::fixed;
use crate::gather::{cuts_desc, receivers_desc, CutsLayout, Gather, GatherTargets, SumLanes};
use crate::gpu_types::{CENTRE_LIGHTS, GATHER_STATS_SIZE};
use crate::resources::GiResources;
use crate::settings::Method;
use crate::shared::GiHandle;
use crate::sight_depth::{self, SightDepth};

pub struct GatherPass {
    handle: GiHandle,
    core: CoreResources,
    gi: GiResources,
    gather: Gather,
    sight_depth: SightDepth,
    /// Stand in for the bounce-only bindings (one read, one written).
    sinks: [wgpu::TextureView; 2],
}

pub struct GatherIo {
    params: Read<Buffer>,
    levels: Read<Buffer>,
    nodes: Read<Buffer>,
    normal: Read<Image>,
    position: Read<Image>,
    cuts: Write<Buffer>,
    irradiance: Write<Image>,
    stats: Write<Buffer>,
    lights: Write<Buffer>,
    receivers: Write<Buffer>,
    /// With visibility: the view depth the sight pass marches, made here for every bounce.
    sight_depth: Option<Write<Image>>,
    layout: CutsLayout,
}

/// The irradiance format: f32 storage, summed by the gather itself (no blending).
pub const IRRADIANCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// A 1×1 Rgba32Float texture for bindings a pass does not use.
pub(crate) fn sink(device: &wgpu::Device) -> wgpu::TextureView {
    device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some("gi sink"),
            size: wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: IRRADIANCE_FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        })
        .create_view(&Default::default())
}

/// An irradiance-sized storage texture (a gather's output, or a bounce's).
pub(crate) fn irradiance_texture(size: (u32, u32)) -> TextureDesc {
    let usage = wgpu::TextureUsages::STORAGE_BINDING
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::COPY_DST;
    TextureDesc { usage, size: fixed(size), ..TextureDesc::target(IRRADIANCE_FORMAT) }
}

/// The gather's counters and the centre tile's lights.
pub(crate) fn stats_desc() -> BufferDesc {
    let usage = wgpu::BufferUsages::STORAGE
        | wgpu::BufferUsages::COPY_SRC
        | wgpu::BufferUsages::COPY_DST
        | wgpu::BufferUsages::INDIRECT;
    BufferDesc { size: GATHER_STATS_SIZE, usage }
}

pub(crate) fn lights_desc() -> BufferDesc {
    let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST;
    BufferDesc { size: CENTRE_LIGHTS * std::mem::size_of::<crate::ReflectionLight>() as u64, usage }
}

impl GatherPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        core: CoreResources,
        gi: GiResources,
        lanes: SumLanes,
    ) -> Self {
        Self {
            gather: Gather::new(device, globals, lanes),
            sight_depth: SightDepth::new(device, globals),
            handle,
            core,
            gi,
            sinks: [sink(device), sink(device)],
        }
    }
}

impl RenderPass for GatherPass {
    /// None with `gi.method = article` (`gi_article` makes the irradiance then).
    type Io = Option<GatherIo>;

    fn name(&self) -> &str {
        "gi_gather"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> Option<GatherIo> {
        let frame = self.handle.frame(d.size(), d.view().headlamp.attached);
        if frame.settings.method != Method::Cuts {
            return None;
        }
        let (size, layout) = (frame.indirect, frame.cuts);
        let gi = &self.gi;
        Some(GatherIo {
            params: d.read(gi.params),
            levels: d.read(gi.levels),
            nodes: d.read(gi.nodes),
            normal: d.read(self.core.gbuffer.normal),
            position: d.read(self.core.gbuffer.position),
            cuts: d.create(gi.cuts, cuts_desc(&layout)),
            irradiance: d.create(gi.irradiance, irradiance_texture(size)),
            stats: d.create(gi.stats, stats_desc()),
            lights: d.create(gi.lights, lights_desc()),
            receivers: d.create(gi.receivers, receivers_desc(size)),
            sight_depth: sight_depth::declare(d, gi.sight_depth, frame.visibility()),
            layout,
        })
    }

    fn run(&mut self, io: &Option<GatherIo>, ctx: &mut PassContext<'_>) {
        let Some(io) = io else { return };
        let mut dispatches = 0;
        if let Some(depth) = &io.sight_depth {
            dispatches += self.sight_depth.record(ctx, &io.position, depth);
        }
        let targets = GatherTargets {
            params: ctx.buffer(&io.params),
            levels: ctx.buffer(&io.levels),
            nodes: ctx.buffer(&io.nodes),
            cuts: ctx.buffer(&io.cuts),
            normal: ctx.view(&io.normal),
            position: ctx.view(&io.position),
            irradiance: ctx.view(&io.irradiance),
            accumulate: &self.sinks[0],
            bounce: &self.sinks[1],
            stats: ctx.buffer(&io.stats),
            lights: ctx.buffer(&io.lights),
            receivers: ctx.buffer(&io.receivers),
            sight_depth: io.sight_depth.as_ref().map(|h| ctx.view(h)),
        };
        dispatches += self.gather.record(&ctx.gpu.device, ctx.encoder, ctx.frame.globals, io.layout, &targets);
        ctx.count_dispatches(dispatches);
    }
}
