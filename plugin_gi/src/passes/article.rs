//! The first bounce by the article's method (`gi.method = article`), in place of the cuts
//! gather: the distribution table's lights of the pyramid, drawn as light volumes into the
//! irradiance (crate::light_volumes). It writes what the gather writes, so the temporal pass,
//! the composite and the `lights` view read either.

use engine::graph::{Buffer, Image, PassContext, PassDecl, Read, RenderPass, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use super::gather::{irradiance_texture, lights_desc, sink, stats_desc};
use crate::gather::receivers_desc;
use crate::light_volumes::{LightVolumes, TableFrame, TableKey, VolumeTargets};
use crate::resources::GiResources;
use crate::settings::Method;
use crate::shared::GiHandle;
use crate::sight_depth::{self, SightDepth};

pub struct ArticlePass {
    handle: GiHandle,
    core: CoreResources,
    gi: GiResources,
    volumes: LightVolumes,
    sight_depth: SightDepth,
    /// Bound in the sight depth's place without visibility.
    sink: wgpu::TextureView,
}

pub struct ArticleIo {
    params: Read<Buffer>,
    levels: Read<Buffer>,
    nodes: Read<Buffer>,
    normal: Read<Image>,
    position: Read<Image>,
    irradiance: Write<Image>,
    stats: Write<Buffer>,
    lights: Write<Buffer>,
    receivers: Write<Buffer>,
    /// With visibility: the view depth the volumes march, made here.
    sight_depth: Option<Write<Image>>,
    indirect: (u32, u32),
}

impl ArticlePass {
    pub(crate) fn new(
        gpu: &engine::gpu::Gpu,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        core: CoreResources,
        gi: GiResources,
    ) -> Self {
        Self {
            volumes: LightVolumes::new(&gpu.device, globals, gpu.float32_blendable()),
            sight_depth: SightDepth::new(&gpu.device, globals),
            sink: sink(&gpu.device),
            handle,
            core,
            gi,
        }
    }
}

impl RenderPass for ArticlePass {
    type Io = Option<ArticleIo>;

    fn name(&self) -> &str {
        "gi_article"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> Option<ArticleIo> {
        let frame = self.handle.frame(d.size(), d.view().headlamp.attached);
        if frame.settings.method != Method::Article {
            return None;
        }
        let indirect = frame.indirect;
        let gi = &self.gi;
        Some(ArticleIo {
            params: d.read(gi.params),
            levels: d.read(gi.levels),
            nodes: d.read(gi.nodes),
            normal: d.read(self.core.gbuffer.normal),
            position: d.read(self.core.gbuffer.position),
            irradiance: d.create(gi.irradiance, irradiance_texture(indirect)),
            stats: d.create(gi.stats, stats_desc()),
            lights: d.create(gi.lights, lights_desc()),
            receivers: d.create(gi.receivers, receivers_desc(indirect)),
            sight_depth: sight_depth::declare(d, gi.sight_depth, frame.visibility()),
            indirect,
        })
    }

    fn run(&mut self, io: &Option<ArticleIo>, ctx: &mut PassContext<'_>) {
        let Some(io) = io else { return };
        let gi = self.handle.frame(ctx.frame.size, ctx.frame.view.headlamp.attached);
        let (settings, lamp) = (&gi.settings, gi.lamp);
        let frame = TableFrame {
            base: lamp.flux,
            view: lamp.view,
            block: lamp.block(),
            floor: lamp.finest_level,
            budget: settings.light_budget,
            fov_y: ctx.frame.lamp.fov_y,
            aspect: ctx.frame.lamp.aspect,
        };
        let key = TableKey { frame, distribution: &ctx.frame.view.headlamp.profile.distribution };
        let mut dispatches = 0;
        if let Some(depth) = &io.sight_depth {
            dispatches += self.sight_depth.record(ctx, &io.position, depth);
        }
        let targets = VolumeTargets {
            params: ctx.buffer(&io.params),
            levels: ctx.buffer(&io.levels),
            nodes: ctx.buffer(&io.nodes),
            normal: ctx.view(&io.normal),
            position: ctx.view(&io.position),
            receivers: ctx.buffer(&io.receivers),
            irradiance: ctx.view(&io.irradiance),
            stats: ctx.buffer(&io.stats),
            lights: ctx.buffer(&io.lights),
            sight_depth: io.sight_depth.as_ref().map(|h| ctx.view(h)),
            sink: &self.sink,
            indirect: io.indirect,
            interleave: settings.article_interleave,
        };
        let (volume_dispatches, draws) =
            self.volumes.record(&ctx.gpu.device, ctx.encoder, ctx.frame.globals, &key, &targets);
        ctx.count_dispatches(dispatches + volume_dispatches);
        ctx.count_draws(draws);
    }
}
