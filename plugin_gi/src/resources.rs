//! The graph resources the GI passes exchange, made once when the plugin is built.

use engine::graph::{Buffer, Handle, History, Image};
use engine::plugin::PluginContext;

use crate::gpu_types::names;

#[derive(Clone, Copy, Debug)]
pub(crate) struct GiResources {
    /// The frame's GiParams for the first bounce (a uniform, written by `gi_params`).
    pub params: Handle<Buffer>,
    /// Reflected flux Φ per texel of the flux G-buffer, the pyramid's base.
    pub flux: Handle<Image>,
    pub flux_view: Handle<Image>,
    /// The first bounce's pyramid: its level table (a uniform) and its nodes, kept across
    /// frames (re-made when the flux G-buffer changes size).
    pub levels: Handle<Buffer>,
    pub nodes: Handle<Buffer>,
    /// Every tile's cut, kept across frames, shared by every bounce's gather.
    pub cuts: Handle<Buffer>,
    pub irradiance: Handle<Image>,
    /// The G-buffer texel each receiver of the indirect target is evaluated on, one u32 each
    /// (x | y << 16), found by the cuts pass for the gather and temporal passes.
    pub receivers: Handle<Buffer>,
    /// With `gi.visibility`: the view depth the sight pass marches, at half the G-buffer's
    /// size (crate::sight_depth), made by `gi_gather` for every bounce, or by `gi_article`.
    pub sight_depth: Handle<Image>,
    /// The irradiance blended over frames (`gi_temporal`), which the composite upsamples.
    pub history: History<Image>,
    pub stats: Handle<Buffer>,
    pub lights: Handle<Buffer>,
    pub indirect: Handle<Image>,
    pub lights_view: Handle<Image>,
    pub reference: Handle<Image>,
    pub bounce: BounceResources,
}

/// What the second and third bounces use besides the first's.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BounceResources {
    /// GiParams with `source` = the previous bounce (a uniform, written by `gi_bounces`).
    pub params: Handle<Buffer>,
    pub nodes: Handle<Buffer>,
    pub flux: Handle<Image>,
    pub flux_view: Handle<Image>,
    /// Each bounce's irradiance alone, ping-ponged: the next bounce's source.
    pub alone: [Handle<Image>; 2],
    /// The total so far, which each bounce's gather adds to.
    pub total: Handle<Image>,
    pub stats: Handle<Buffer>,
    pub lights: Handle<Buffer>,
}

impl GiResources {
    pub fn register(ctx: &mut PluginContext<'_>) -> Self {
        let bounce = BounceResources {
            params: ctx.persistent_buffer("gi.bounce_params"),
            nodes: ctx.persistent_buffer("gi.bounce_nodes"),
            flux: ctx.image("gi.bounce_flux"),
            flux_view: ctx.image("gi.bounce_flux_view"),
            alone: [ctx.image("gi.bounce_a"), ctx.image("gi.bounce_b")],
            total: ctx.image("gi.bounce_total"),
            stats: ctx.buffer("gi.bounce_stats"),
            lights: ctx.buffer("gi.bounce_lights"),
        };
        Self {
            params: ctx.persistent_buffer("gi.params"),
            flux: ctx.image(names::FLUX),
            flux_view: ctx.image(names::FLUX_VIEW),
            levels: ctx.persistent_buffer("gi.levels"),
            nodes: ctx.persistent_buffer("gi.nodes"),
            cuts: ctx.persistent_buffer("gi.cuts"),
            irradiance: ctx.image(names::IRRADIANCE),
            receivers: ctx.buffer("gi.receivers"),
            sight_depth: ctx.image("gi.sight_depth"),
            history: ctx.history_image(names::IRRADIANCE_HISTORY),
            stats: ctx.buffer(names::STATS),
            lights: ctx.buffer(names::LIGHTS),
            indirect: ctx.image(names::INDIRECT),
            lights_view: ctx.image(names::LIGHTS_VIEW),
            reference: ctx.image(names::REFERENCE),
            bounce,
        }
    }
}
