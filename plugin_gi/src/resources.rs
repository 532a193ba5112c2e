//! The graph resources the GI passes exchange, made once when the plugin is built.

use engine::graph::{Buffer, Handle, History, Image};
use engine::plugin::PluginContext;

use crate::gpu_types::names;

#[derive(Clone, Debug)]
pub(crate) struct GiResources {
    /// The first bounce's pyramid level table (a uniform), kept across frames; further
    /// bounces build theirs over the same base, so they read it too.
    pub levels: Handle<Buffer>,
    /// The first bounce's flux as the `flux` view.
    pub flux_view: Handle<Image>,
    /// With `gi.visibility`: the view depth the sight test marches, at half the G-buffer's
    /// size (`gi_sight_depth`).
    pub sight_depth: Handle<Image>,
    /// Each bounce's own, the first's at 0: `gi.bounces` of them run.
    pub bounces: Vec<BounceResources>,
    /// The irradiance blended over frames (`gi_temporal`), which the composite upsamples,
    /// and the blend's parameters (a uniform).
    pub history: History<Image>,
    pub temporal: Handle<Buffer>,
    /// Where the view models' irradiance is summed (a uniform, `gi_view_model`).
    pub probe: Handle<Buffer>,
    /// The exact one bounce (`gi_reference`) and its running sums over sender ranges.
    pub reference: Handle<Image>,
    pub reference_sums: Handle<Buffer>,
    pub indirect: Handle<Image>,
    pub lights_view: Handle<Image>,
}

/// What one bounce's passes make and read: its parameters, its pyramid, its cuts and the
/// irradiance they gather.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BounceResources {
    /// GiParams for this bounce's senders (a uniform, one for the first bounce and one every
    /// further bounce shares).
    pub params: Handle<Buffer>,
    /// Reflected flux Φ per texel of the flux G-buffer, the pyramid's base.
    pub flux: Handle<Image>,
    /// The pyramid's nodes, kept across frames (re-made when the flux G-buffer changes size).
    pub nodes: Handle<Buffer>,
    /// Every tile's cut, and with visibility the sight bits after them.
    pub cuts: Handle<Buffer>,
    /// The G-buffer texel each receiver of the indirect target is evaluated on, one u32 each
    /// (x | y << 16), found by the cuts pass for the sum (and the first bounce's for the
    /// temporal blend).
    pub receivers: Handle<Buffer>,
    /// The tiles whose cut filled up on the first walk, and the arguments of the dispatch
    /// that walks them again.
    pub retry: Handle<Buffer>,
    pub retry_args: Handle<Buffer>,
    /// The cuts' counters (beginning with the `lights` view's draw arguments) and the centre
    /// tile's lights.
    pub stats: Handle<Buffer>,
    pub lights: Handle<Buffer>,
    /// The irradiance of every bounce up to this one.
    pub irradiance: Handle<Image>,
    /// This bounce's irradiance alone, which the next one reflects; the first bounce's is its
    /// `irradiance`.
    pub alone: Handle<Image>,
}

impl GiResources {
    /// The resources for up to `bounces` bounces.
    pub fn register(ctx: &mut PluginContext<'_>, bounces: u32) -> Self {
        let irradiance = ctx.image(names::IRRADIANCE);
        let first = BounceResources {
            params: ctx.persistent_buffer("gi.params"),
            flux: ctx.image(names::FLUX),
            nodes: ctx.persistent_buffer("gi.nodes"),
            cuts: ctx.buffer("gi.cuts"),
            receivers: ctx.buffer("gi.receivers"),
            retry: ctx.buffer("gi.retry"),
            retry_args: ctx.buffer("gi.retry_args"),
            stats: ctx.buffer(names::STATS),
            lights: ctx.buffer(names::LIGHTS),
            irradiance,
            alone: irradiance,
        };
        let mut all = vec![first];
        if bounces > 1 {
            let params = ctx.persistent_buffer("gi.bounce_params");
            for k in 2..=bounces {
                let name = |what: &str| format!("gi.bounce{k}.{what}");
                all.push(BounceResources {
                    params,
                    flux: ctx.image(&name("flux")),
                    nodes: ctx.persistent_buffer(&name("nodes")),
                    cuts: ctx.buffer(&name("cuts")),
                    receivers: ctx.buffer(&name("receivers")),
                    retry: ctx.buffer(&name("retry")),
                    retry_args: ctx.buffer(&name("retry_args")),
                    stats: ctx.buffer(&name("stats")),
                    lights: ctx.buffer(&name("lights")),
                    irradiance: ctx.image(&name("irradiance")),
                    alone: ctx.image(&name("alone")),
                });
            }
        }
        Self {
            levels: ctx.persistent_buffer("gi.levels"),
            flux_view: ctx.image(names::FLUX_VIEW),
            sight_depth: ctx.image("gi.sight_depth"),
            bounces: all,
            history: ctx.history_image(names::IRRADIANCE_HISTORY),
            temporal: ctx.buffer("gi.temporal"),
            probe: ctx.buffer("gi.view_model_probe"),
            reference: ctx.image(names::REFERENCE),
            reference_sums: ctx.buffer("gi.reference_sums"),
            indirect: ctx.image(names::INDIRECT),
            lights_view: ctx.image(names::LIGHTS_VIEW),
        }
    }

    /// The first bounce's.
    pub fn first(&self) -> &BounceResources {
        self.bounce(1)
    }

    /// The `k`th bounce's (k from 1).
    pub fn bounce(&self, k: u32) -> &BounceResources {
        &self.bounces[k as usize - 1]
    }

    /// The first bounce's parameters, which every pass but a further bounce's reads.
    pub fn params(&self) -> Handle<Buffer> {
        self.first().params
    }
}
