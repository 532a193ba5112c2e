//! What the GI's passes derive from the frame and the settings, in one typed value computed
//! once a frame ([`GiFrame::of`], kept by the plugin's handle): where the senders come from and
//! the sizes of their flux G-buffer and pyramid, the indirect target's size and its cuts'
//! layout, and the method, visibility and bounces the settings ask for. Every pass reads it
//! rather than deriving a size of its own.

use engine::passes::LAMP_MAP_SIZE;

use crate::cuts_layout::{cuts_layout, CutsLayout};
use crate::grids::SENDER_PAD;
use crate::settings::{GiSettings, Method};

/// Halvings of the lamp view the pyramid's base is subsampled by: attached, down to the
/// indirect target's resolution (finer senders than the receivers would only be merged back
/// up to that footprint by the gather), at most three; detached, none.
const MAX_HALVINGS: u32 = 3;

/// One bounce's senders: the view whose texels reflect the light, and the flux G-buffer and
/// pyramid built from it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Senders {
    /// The sending view's size: the camera's G-buffer (the lamp on the head, or a further
    /// bounce) or the detached lamp's own.
    pub view: (u32, u32),
    /// How many times the flux G-buffer halves the view: as many times as the view, halved
    /// (rounding up), stays at least as tall as the indirect target; none detached.
    pub halvings: u32,
    /// The blocks that cover the view, ⌈view / 2^halvings⌉ each way (the `flux` debug view).
    pub flux_view: (u32, u32),
    /// The flux G-buffer (the pyramid's base): the blocks, and where they are blocks of
    /// several texels SENDER_PAD more each way, as their grid moves with the picture
    /// (crate::grids).
    pub flux: (u32, u32),
    /// The pyramid's finest level that is built and used: the receivers' footprint, in levels
    /// above the (already subsampled) base.
    pub finest_level: u32,
}

impl Senders {
    /// The senders for a frame of `size` pixels: the camera's G-buffer where `attached` (the
    /// lamp on the head, and every further bounce), subsampled toward the receivers' height
    /// `indirect_rows`; the detached lamp's own view, whole, otherwise.
    fn new(settings: &GiSettings, size: (u32, u32), attached: bool) -> Self {
        let (view, halvings) = if attached {
            let target = settings.indirect_size().resolve(size).1;
            let mut k = 0;
            while k < MAX_HALVINGS && size.1.max(1).div_ceil(1 << (k + 1)) >= target {
                k += 1;
            }
            (size, k)
        } else {
            ((LAMP_MAP_SIZE, LAMP_MAP_SIZE), 0)
        };
        let flux_view = (view.0.max(1).div_ceil(1 << halvings), view.1.max(1).div_ceil(1 << halvings));
        let pad = if halvings > 0 { SENDER_PAD } else { 0 };
        Self { view, halvings, flux_view, flux: (flux_view.0 + pad, flux_view.1 + pad), finest_level: 0 }
    }

    /// Whether the flux G-buffer's texels are blocks of view texels (its nodes then have
    /// halves: see Quadtree::halves).
    pub fn blocks(&self) -> bool {
        self.halvings > 0
    }

    /// The side of a block, in view texels.
    pub fn block(&self) -> u32 {
        1 << self.halvings
    }
}

/// The frame as the GI's passes see it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct GiFrame {
    /// The settings this frame renders with.
    pub settings: GiSettings,
    /// The frame's size, pixels.
    pub size: (u32, u32),
    /// Whether the headlamp is on the head (the lamp's view is then the camera's).
    pub attached: bool,
    /// The first bounce's senders: the lamp's view.
    pub lamp: Senders,
    /// Further bounces' senders: the camera's G-buffer, lit by the bounce before.
    pub bounce: Senders,
    /// The indirect target's size: the settings' rule, made smaller only where its cuts would
    /// outgrow their budget (far above play sizes), so the gather is always three calls.
    pub indirect: (u32, u32),
    /// The cuts' layout over the indirect target and the first bounce's pyramid …
    pub cuts: CutsLayout,
    /// … and over further bounces' pyramid.
    pub bounce_cuts: CutsLayout,
}

impl GiFrame {
    pub fn of(settings: &GiSettings, size: (u32, u32), attached: bool) -> Self {
        let mut bounce = Senders::new(settings, size, true);
        let mut lamp = Senders::new(settings, size, attached);
        // A cut has room for the pyramid's whole top level, which only the camera's flux
        // G-buffer can make larger than CUT_MAX (a detached lamp's has 16×16 nodes).
        let indirect = crate::cuts_layout::fit_cuts_budget(settings.indirect_size().resolve(size), bounce.flux);
        let floor = crate::settings::min_level(size.1, indirect.1);
        bounce.finest_level = floor.saturating_sub(bounce.halvings);
        lamp.finest_level = floor.saturating_sub(lamp.halvings);
        let (cuts, bounce_cuts) = (cuts_layout(indirect, lamp.flux), cuts_layout(indirect, bounce.flux));
        Self { settings: settings.clone(), size, attached, lamp, bounce, indirect, cuts, bounce_cuts }
    }

    /// The GI is on.
    pub fn enabled(&self) -> bool {
        self.settings.enabled
    }

    /// Light is stopped by the surfaces between a sender and a receiver.
    pub fn visibility(&self) -> bool {
        self.settings.visibility == 1
    }

    /// … those the camera does not see too, the level's walls (its voxels).
    pub fn world_sight(&self) -> bool {
        self.visibility() && self.settings.world_sight == 1
    }

    /// The bounces computed: `gi.bounces` with the cuts' method and the lamp on the head,
    /// else the first alone (the article's method is its one bounce, see docs/gi.md; a
    /// further bounce's senders are the camera's view, lit by the bounce before).
    pub fn bounces(&self) -> u32 {
        if self.settings.method == Method::Cuts && self.attached {
            self.settings.bounces.max(1)
        } else {
            1
        }
    }

    /// The `k`th bounce's senders (k from 1) and its cuts' layout.
    pub fn of_bounce(&self, k: u32) -> (Senders, CutsLayout) {
        if k <= 1 {
            (self.lamp, self.cuts)
        } else {
            (self.bounce, self.bounce_cuts)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halving_toward_the_indirect_target_stops_before_it_gets_shorter() {
        let mut s = GiSettings { resolution_scale: 0.25, min_rows: 90, ..GiSettings::default() };
        let senders = |s: &GiSettings, view, attached| GiFrame::of(s, view, attached).lamp;
        // Blocks of lamp-view texels: their grid moves with the picture, SENDER_PAD more of them.
        let rule = |s: &GiSettings, view| senders(s, view, true).flux_view;
        // 360 rows → 180 → 90: two halvings reach the 90-row target exactly.
        assert_eq!(rule(&s, (640, 360)), (160, 90));
        assert_eq!(senders(&s, (640, 360), true).flux, (160 + SENDER_PAD, 90 + SENDER_PAD));
        // 720 rows: a quarter is 180 rows, so two halvings; a third would give 90 < 180.
        assert_eq!(rule(&s, (1280, 720)), (320, 180));
        // 240 rows: the target is 90; 120 ≥ 90 but 60 < 90.
        assert_eq!(rule(&s, (320, 240)), (160, 120));
        // No halving: the lamp view's own texels, no padding.
        assert_eq!(rule(&s, (160, 120)), (160, 120));
        assert_eq!(senders(&s, (160, 120), true).flux, (160, 120));
        assert_eq!(rule(&s, (1281, 721)), (321, 181));
        // Never more than three halvings.
        s.resolution_scale = 0.0625;
        s.min_rows = 16;
        assert_eq!(rule(&s, (1024, 1024)), (128, 128));
        // Detached: the lamp's own map, whole; further bounces still from the camera's view.
        let detached = GiFrame::of(&s, (640, 360), false);
        assert_eq!(detached.lamp.flux, (LAMP_MAP_SIZE, LAMP_MAP_SIZE));
        assert_eq!(detached.bounce, GiFrame::of(&s, (640, 360), true).lamp);
    }
}
