//! How the cuts of an indirect target lie in their buffer (shaders/gi/gi_common.wgsl,
//! `tile_cut`, `sight_word`): one cut of the flux pyramid a tile of 8×8 receivers, and with
//! visibility one u32 of sight bits a slot after them; and the budget that bounds them.

use engine::graph::BufferDesc;
use engine::wgpu;

use crate::quadtree::Quadtree;

/// Receivers per tile side (`CUT_TILE` in gi_common.wgsl).
pub const TILE: u32 = 8;

/// The most lights a tile's cut holds (`CUT_MAX` in gi_common.wgsl), unless the pyramid's top
/// level has more: every one of those is in every cut.
pub const CUT_MAX: u32 = 1536;

/// Invocations (tiles) per workgroup of the cuts pass (`CUTS_GROUP` in cuts.wgsl).
pub const CUTS_GROUP: u32 = 8;

/// At most this much memory holds the cuts, so no setting can ask for an unbounded buffer: an
/// indirect target with more tiles than fit is made smaller ([`fit_cuts_budget`]). Below the
/// 128 MiB storage binding every wgpu device allows; 1,365 tiles of 1,536 lights, e.g. 320×180
/// receivers at 2560×1440 with the default scale.
const CUTS_BUDGET_BYTES: u64 = 64 << 20;

/// The cuts of an indirect target of `size` over a pyramid on a flux G-buffer of `flux_size`.
pub fn cuts_layout(size: (u32, u32), flux_size: (u32, u32)) -> CutsLayout {
    CutsLayout::new(size, &Quadtree::new(flux_size.0, flux_size.1))
}

/// The largest indirect target no larger than `size`, same shape, whose cuts over a pyramid on
/// `flux_size` fit the budget; `size` itself at every size people play.
pub fn fit_cuts_budget(size: (u32, u32), flux_size: (u32, u32)) -> (u32, u32) {
    let fits = |s: (u32, u32)| cuts_layout(s, flux_size).bytes() <= CUTS_BUDGET_BYTES;
    if fits(size) {
        return size;
    }
    // Scale both sides by the same factor, the largest that fits (bisection on rows).
    let scaled = |rows: u32| {
        let w = (u64::from(size.0) * u64::from(rows) / u64::from(size.1.max(1))).max(1) as u32;
        (w, rows)
    };
    let (mut lo, mut hi) = (1, size.1);
    while lo + 1 < hi {
        let mid = (lo + hi) / 2;
        if fits(scaled(mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    scaled(lo)
}

/// The cuts buffer, with room for the sight bits where `visibility`.
pub fn cuts_desc(layout: &CutsLayout, visibility: bool) -> BufferDesc {
    let sight = if visibility { layout.sight_bytes() } else { 0 };
    BufferDesc { size: layout.bytes() + sight, usage: wgpu::BufferUsages::STORAGE }
}

/// Where each receiver of an indirect target of `size` is evaluated: a G-buffer texel, one
/// u32 a receiver (x | y << 16), row by row.
pub fn receivers_desc(size: (u32, u32)) -> BufferDesc {
    BufferDesc { size: 4 * u64::from(size.0) * u64::from(size.1), usage: wgpu::BufferUsages::STORAGE }
}

/// How the cuts of an indirect target lie in their buffer: `tiles` across and down, each
/// tile's cut `stride` vec4s (its counts, its centre, then one a light with room for the
/// classes' padding: see gi_common.wgsl).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CutsLayout {
    pub tiles: (u32, u32),
    pub stride: u32,
}

impl CutsLayout {
    /// For an indirect target of `size` over `tree`.
    pub fn new(size: (u32, u32), tree: &Quadtree) -> Self {
        let (w, h) = tree.size(crate::quadtree::TOP);
        let tiles = (size.0.div_ceil(TILE), size.1.div_ceil(TILE));
        Self { tiles, stride: 2 + 2 * CUT_MAX.max(w * h) }
    }

    /// Bytes of the cuts.
    pub fn bytes(&self) -> u64 {
        u64::from(self.tiles.0) * u64::from(self.tiles.1) * u64::from(self.stride) * 16
    }

    /// Bytes of the sight bits after them: one u32 a slot (a vec4).
    pub fn sight_bytes(&self) -> u64 {
        self.bytes() / 4
    }

    /// Tiles, one workgroup each in the sight and the sum.
    pub fn tile_count(&self) -> u32 {
        self.tiles.0 * self.tiles.1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_tile_has_room_for_its_cut_and_the_whole_top_level() {
        let small = Quadtree::new(160, 90);
        let one = CutsLayout::new((160, 90), &small);
        assert_eq!(one, CutsLayout { tiles: (20, 12), stride: 2 + 2 * CUT_MAX });
        assert_eq!(one.bytes(), 20 * 12 * (2 + 2 * CUT_MAX as u64) * 16);
        // A top level of 60×34 lights is more than a cut holds: each tile has room for all.
        let large = Quadtree::new(3840, 2160);
        assert_eq!(CutsLayout::new((8, 8), &large).stride, 2 + 2 * 60 * 34);
    }

    #[test]
    fn play_sizes_keep_their_target_and_larger_ones_shrink_to_fit_the_budget() {
        // The defaults' targets up to 2560×1440 (their flux G-buffers halved three times).
        for (size, flux) in [((160, 90), (160, 90)), ((240, 135), (240, 135)), ((320, 180), (320, 180))] {
            assert_eq!(fit_cuts_budget(size, flux), size);
        }
        // 3840×2160 at full resolution: 480×270 tiles would need 9.6 GiB.
        let (w, h) = fit_cuts_budget((3840, 2160), (3840, 2160));
        assert!(cuts_layout((w, h), (3840, 2160)).bytes() <= CUTS_BUDGET_BYTES, "{w}x{h}");
        assert!(cuts_layout((w, h), (3840, 2160)).bytes() > CUTS_BUDGET_BYTES * 9 / 10, "{w}x{h} is far smaller");
        assert!((w as f32 / h as f32 - 16.0 / 9.0).abs() < 0.05, "{w}x{h} keeps the shape");
    }
}
