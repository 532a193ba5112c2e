//! Further bounces (settings.bounces ≥ 2, attached lamp): each feeds the previous bounce's
//! irradiance back as flux, Φ = ρ·E·A_texel, builds a new pyramid with the same machinery and
//! gathers it, adding its irradiance to the total.

use engine::graph::{Buffer, Image, PassContext, PassDecl, Read, RenderPass, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use super::flux::flux_texture;
use super::gather::{irradiance_texture, lights_desc, stats_desc};
use super::params::{params, params_desc};
use crate::gather::{CutsLayout, Gather, GatherTargets, SumLanes};
use crate::pyramid::{nodes_desc, FluxSource, PyramidBindings, PyramidPipelines};
use crate::resources::GiResources;
use crate::settings::Method;
use crate::shared::GiHandle;

pub struct BouncePass {
    handle: GiHandle,
    core: CoreResources,
    gi: GiResources,
    pyramid: PyramidPipelines,
    gather: Gather,
}

pub struct BounceIo {
    /// The camera G-buffer's albedo, normal and position.
    gbuffer: [Read<Image>; 3],
    levels: Read<Buffer>,
    params: Write<Buffer>,
    nodes: Write<Buffer>,
    flux: Write<Image>,
    flux_view: Write<Image>,
    alone: [Write<Image>; 2],
    total: Write<Image>,
    stats: Write<Buffer>,
    lights: Write<Buffer>,
    cuts: Write<Buffer>,
    receivers: Write<Buffer>,
    irradiance: Write<Image>,
    /// With visibility: the view depth the first bounce's gather made.
    sight_depth: Option<Read<Image>>,
    layout: CutsLayout,
    flux_size: (u32, u32),
    indirect_size: (u32, u32),
}

impl BouncePass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        core: CoreResources,
        gi: GiResources,
        lanes: SumLanes,
    ) -> Self {
        let gather = Gather::new(device, globals, lanes);
        Self { pyramid: PyramidPipelines::new(device, globals, FluxSource::Bounce), gather, handle, core, gi }
    }
}

impl RenderPass for BouncePass {
    type Io = Option<BounceIo>;

    fn name(&self) -> &str {
        "gi_bounces"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> Option<BounceIo> {
        let frame = self.handle.frame(d.size(), d.view().headlamp.attached);
        // (The article's method is its one bounce: see docs/gi.md.)
        if !(frame.runs(Method::Cuts) && frame.further_bounces() > 0 && frame.attached) {
            return None;
        }
        let (flux, low) = (frame.bounce.flux, frame.indirect);
        let (g, b) = (&self.core.gbuffer, &self.gi.bounce);
        Some(BounceIo {
            gbuffer: [g.albedo, g.normal, g.position].map(|h| d.read(h)),
            levels: d.read(self.gi.levels),
            params: d.create(b.params, params_desc()),
            nodes: d.create(b.nodes, nodes_desc(flux, frame.bounce.blocks())),
            flux: d.create(b.flux, flux_texture(engine::wgpu::TextureFormat::Rgba32Float, flux)),
            // The flux view is of the lamp's light only.
            flux_view: d.create(b.flux_view, flux_texture(engine::wgpu::TextureFormat::Rgba16Float, (1, 1))),
            alone: b.alone.map(|h| d.create(h, irradiance_texture(low))),
            total: d.create(b.total, irradiance_texture(low)),
            stats: d.create(b.stats, stats_desc()),
            lights: d.create(b.lights, lights_desc()),
            cuts: d.write(self.gi.cuts),
            receivers: d.write(self.gi.receivers),
            irradiance: d.write(self.gi.irradiance),
            layout: frame.bounce_cuts,
            flux_size: flux,
            indirect_size: low,
            sight_depth: frame.visibility().then(|| d.read(self.gi.sight_depth)),
        })
    }

    fn run(&mut self, io: &Option<BounceIo>, ctx: &mut PassContext<'_>) {
        let Some(io) = io else { return };
        let frame = self.handle.frame(ctx.frame.size, ctx.frame.view.headlamp.attached);
        let values = params(&frame, ctx, FluxSource::Bounce);
        ctx.write_buffer(&io.params, 0, bytemuck::bytes_of(&values));
        let device = &ctx.gpu.device;
        let low = io.indirect_size;
        let extent = wgpu::Extent3d { width: low.0, height: low.1, depth_or_array_layers: 1 };
        let total = ctx.texture(&io.irradiance);
        let [first, second] = &io.alone;
        ctx.encoder.copy_texture_to_texture(total.as_image_copy(), ctx.texture(first).as_image_copy(), extent);
        let [albedo, normal, position] = &io.gbuffer;
        let mut dispatches = 0;
        for bounce in 2..=frame.settings.bounces {
            let (src, dst) = if bounce % 2 == 0 { (first, second) } else { (second, first) };
            let bindings = PyramidBindings {
                params: ctx.buffer(&io.params),
                levels: ctx.buffer(&io.levels),
                nodes: ctx.buffer(&io.nodes),
                albedo: ctx.view(albedo),
                normal: ctx.view(normal),
                position: ctx.view(position),
                previous: ctx.view(src),
                flux: ctx.view(&io.flux),
                flux_view: ctx.view(&io.flux_view),
                blocks: values.flux_block > 1,
            };
            dispatches += self.pyramid.record(device, ctx.encoder, ctx.frame.globals, io.flux_size, &bindings);
            ctx.encoder.copy_texture_to_texture(total.as_image_copy(), ctx.texture(&io.total).as_image_copy(), extent);
            let targets = GatherTargets {
                params: ctx.buffer(&io.params),
                levels: ctx.buffer(&io.levels),
                nodes: ctx.buffer(&io.nodes),
                cuts: ctx.buffer(&io.cuts),
                normal: ctx.view(normal),
                position: ctx.view(position),
                irradiance: ctx.view(&io.irradiance),
                accumulate: ctx.view(&io.total),
                bounce: ctx.view(dst),
                stats: ctx.buffer(&io.stats),
                lights: ctx.buffer(&io.lights),
                receivers: ctx.buffer(&io.receivers),
                sight_depth: io.sight_depth.as_ref().map(|h| ctx.view(h)),
            };
            dispatches += self.gather.record(device, ctx.encoder, ctx.frame.globals, io.layout, &targets);
        }
        ctx.count_dispatches(dispatches);
    }
}
