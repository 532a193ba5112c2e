//! The first bounce by the article's method (`gi.method = article`), in place of the cuts,
//! sight and sum: the distribution table's lights of the pyramid, drawn as light volumes into
//! the irradiance ([`volumes`]). It writes what the cuts and the sum write, so the
//! temporal pass, the composite and the `lights` view read either.

pub(crate) mod volumes;

use engine::graph::{Buffer, Image, PassContext, PassDecl, Read, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use super::cuts::{lights_desc, stats_desc};
use super::gather::irradiance_texture;
use crate::cuts_layout::receivers_desc;
use crate::frame::GiFrame;
use crate::resources::GiResources;
use crate::schedule::GiPass;
use volumes::{LightVolumes, TableFrame, TableKey, VolumeTargets};

pub struct ArticlePass {
    core: CoreResources,
    gi: GiResources,
    volumes: LightVolumes,
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
    /// With visibility: the view depth the volumes march.
    sight_depth: Option<Read<Image>>,
}

impl ArticlePass {
    pub(crate) fn new(
        gpu: &engine::gpu::Gpu,
        globals: &wgpu::BindGroupLayout,
        core: CoreResources,
        gi: GiResources,
        world: std::rc::Rc<crate::world_grid::WorldGrid>,
    ) -> Self {
        Self { volumes: LightVolumes::new(&gpu.device, globals, gpu.float32_blendable(), world), core, gi }
    }
}

impl GiPass for ArticlePass {
    type Io = ArticleIo;

    fn name(&self) -> &str {
        "gi_article"
    }

    fn declare(&self, d: &mut PassDecl<'_>, frame: &GiFrame) -> ArticleIo {
        let (gi, first) = (&self.gi, self.gi.first());
        ArticleIo {
            params: d.read(first.params),
            levels: d.read(gi.levels),
            nodes: d.read(first.nodes),
            normal: d.read(self.core.gbuffer.normal),
            position: d.read(self.core.gbuffer.position),
            irradiance: d.create(first.irradiance, irradiance_texture(frame.indirect)),
            stats: d.create(first.stats, stats_desc()),
            lights: d.create(first.lights, lights_desc()),
            receivers: d.create(first.receivers, receivers_desc(frame.indirect)),
            sight_depth: frame.visibility().then(|| d.read(gi.sight_depth)),
        }
    }

    fn run(&mut self, io: &ArticleIo, gi: &GiFrame, ctx: &mut PassContext<'_>) {
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
            world_sight: gi.world_sight(),
            indirect: gi.indirect,
            interleave: settings.article_interleave,
        };
        let (dispatches, draws) = self.volumes.record(&ctx.gpu.device, ctx.encoder, ctx.frame.globals, &key, &targets);
        ctx.count_dispatches(dispatches);
        ctx.count_draws(draws);
    }
}
