//! The article's distribution table: precomputed once per resolution, light budget and lamp
//! profile, the pyramid slots (level, texel) its reflection lights are taken from. The slots
//! tile the whole base (each texel belongs to exactly one, so no flux is left out), finer
//! where the lamp sends more, T(uv)·Ω(uv) being the flux a texel can reflect per unit albedo.
//!
//! It is made by splitting the most important slot into its four children until the budget is
//! reached, and has two tiers: the slots when `coarse_budget` was reached (the coarse tier,
//! whose lights reach every receiver) and the slots at the end (the fine tier, whose light
//! volumes end). As the fine slots refine the coarse ones, each lies inside one coarse slot:
//! a fine light's volume adds what it gives beyond what its share of that coarse light gives,
//! so where the volume ends, the light beyond it is still there, in the coarse light
//! (shaders/gi/article_stream.wgsl, article_volumes.wgsl).

use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};

use crate::quadtree::{Quadtree, TOP};

/// One slot: a node of the pyramid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Slot {
    pub level: u32,
    pub x: u32,
    pub y: u32,
}

impl Slot {
    fn contains(&self, other: &Slot) -> bool {
        other.level <= self.level
            && (other.x >> (self.level - other.level), other.y >> (self.level - other.level)) == (self.x, self.y)
    }

    /// Its place along a Z-order curve over the base, for dealing slots into subsets.
    fn morton(&self) -> u64 {
        let half = (1u32 << self.level) >> 1;
        let (x, y) = (self.x << self.level | half, self.y << self.level | half);
        (0..16).fold(0u64, |m, b| m | (u64::from(x >> b & 1) << (2 * b)) | (u64::from(y >> b & 1) << (2 * b + 1)))
    }
}

/// The table: both tiers tile the base.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DistributionTable {
    pub coarse: Vec<Slot>,
    /// Each fine slot and the index in `coarse` of the slot it lies in.
    pub fine: Vec<(Slot, u32)>,
}

/// What a table entry is (`ENTRY_*` in article_stream.wgsl).
pub const ENTRY_COARSE: u32 = 0;
pub const ENTRY_FINE: u32 = 1;

struct Candidate {
    importance: f64,
    slot: Slot,
}

impl PartialEq for Candidate {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Candidate {}
impl PartialOrd for Candidate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Candidate {
    // Most important first; ties broken by place, so the table is deterministic.
    fn cmp(&self, other: &Self) -> Ordering {
        let place = |s: &Slot| (s.level, s.y, s.x);
        self.importance.total_cmp(&other.importance).then_with(|| place(&other.slot).cmp(&place(&self.slot)))
    }
}

impl DistributionTable {
    /// The table over `tree` whose base texels have `importance` (row by row, the base's
    /// width × height): the most important slot is split until `budget` slots exist (or none
    /// can be split: no slot is split below level `floor`, the finest the pyramid builds), the
    /// coarse tier taken when `coarse_budget` did.
    pub fn build(tree: &Quadtree, importance: &[f64], floor: u32, budget: u32, coarse_budget: u32) -> Self {
        let sums = level_sums(tree, importance);
        let importance_of = |s: Slot| sums[s.level as usize][(s.y * tree.size(s.level).0 + s.x) as usize];
        let (tw, th) = tree.size(TOP);
        let mut heap: BinaryHeap<Candidate> = (0..th)
            .flat_map(|y| (0..tw).map(move |x| Slot { level: TOP, x, y }))
            .map(|slot| Candidate { importance: importance_of(slot), slot })
            .collect();
        let mut done = Vec::new();
        let mut coarse = None;
        loop {
            let count = heap.len() + done.len();
            if coarse.is_none() && count + 3 > coarse_budget as usize {
                coarse = Some(heap.iter().map(|c| c.slot).chain(done.iter().copied()).collect::<Vec<_>>());
            }
            let Some(c) = heap.pop() else { break };
            if c.slot.level <= floor || c.importance <= 0.0 || count + 3 > budget as usize {
                done.push(c.slot);
                continue;
            }
            let (cw, ch) = tree.size(c.slot.level - 1);
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let (x, y) = (c.slot.x * 2 + dx, c.slot.y * 2 + dy);
                if x < cw && y < ch {
                    let slot = Slot { level: c.slot.level - 1, x, y };
                    heap.push(Candidate { importance: importance_of(slot), slot });
                }
            }
        }
        let mut coarse = coarse.unwrap_or_else(|| done.clone());
        coarse.sort_by_key(Slot::morton);
        done.sort_by_key(Slot::morton);
        let index: HashMap<Slot, u32> = coarse.iter().enumerate().map(|(i, s)| (*s, i as u32)).collect();
        let fine = done
            .into_iter()
            .map(|s| {
                let mut up = s;
                loop {
                    if let Some(&i) = index.get(&up) {
                        return (s, i);
                    }
                    assert!(up.level < TOP, "the coarse tier tiles the base, so it holds an ancestor of every slot");
                    up = Slot { level: up.level + 1, x: up.x / 2, y: up.y / 2 };
                }
            })
            .collect();
        Self { coarse, fine }
    }

    /// The GPU form (article_stream.wgsl's `entries`): the coarse slots, then the fine ones,
    /// each tier along a Z-order curve over the base.
    pub fn entries(&self) -> Vec<[u32; 4]> {
        let pack = |s: &Slot| s.x | s.y << 16;
        let coarse = self.coarse.iter().map(|s| [s.level | ENTRY_COARSE << 8, pack(s), 0, 0]);
        let fine = self.fine.iter().map(|(s, c)| {
            let up = &self.coarse[*c as usize];
            [s.level | ENTRY_FINE << 8, pack(s), up.level, pack(up)]
        });
        coarse.chain(fine).collect()
    }

    /// Whether every slot of the fine tier lies in its coarse slot.
    pub fn nests(&self) -> bool {
        self.fine.iter().all(|(s, c)| self.coarse[*c as usize].contains(s))
    }
}

/// Importance summed up the levels.
fn level_sums(tree: &Quadtree, importance: &[f64]) -> Vec<Vec<f64>> {
    let mut sums: Vec<Vec<f64>> = vec![importance.to_vec()];
    for level in 1..=TOP {
        let ((w, h), (cw, ch)) = (tree.size(level), tree.size(level - 1));
        let below = &sums[level as usize - 1];
        let mut here = vec![0.0; (w * h) as usize];
        for y in 0..h {
            for x in 0..w {
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let (cx, cy) = (x * 2 + dx, y * 2 + dy);
                    if cx < cw && cy < ch {
                        here[(y * w + x) as usize] += below[(cy * cw + cx) as usize];
                    }
                }
            }
        }
        sums.push(here);
    }
    sums
}

/// The distribution texture T over the lamp frustum: width, height and texels, top row first
/// (`engine::headlamp::distribution_texels`).
pub type Distribution<'a> = (u32, u32, &'a [[f32; 4]]);

/// The flux one base texel can reflect per unit albedo and lamp power, T(uv)·Ω, for a base of
/// `base` texels each a `block`×`block` of a `view`-sized lamp view (texels past the view hold
/// nothing: the base's padding), `tan` the frustum's half-angle tangents.
pub fn lamp_importance(base: (u32, u32), view: (u32, u32), block: u32, tan: (f32, f32), t: Distribution) -> Vec<f64> {
    let (tw, th, texels) = t;
    let mut out = Vec::with_capacity((base.0 * base.1) as usize);
    for y in 0..base.1 {
        for x in 0..base.0 {
            let u = (x as f32 + 0.5) * block as f32 / view.0 as f32;
            let v = (y as f32 + 0.5) * block as f32 / view.1 as f32;
            if u >= 1.0 || v >= 1.0 {
                out.push(0.0);
                continue;
            }
            let (ax, ay) = ((u * 2.0 - 1.0) * tan.0, (1.0 - v * 2.0) * tan.1);
            let r2 = 1.0 + ax * ax + ay * ay;
            let omega = 1.0 / (r2 * r2.sqrt());
            let at = ((v * th as f32) as u32).min(th - 1) * tw + ((u * tw as f32) as u32).min(tw - 1);
            let [r, g, b, _] = texels[at as usize];
            out.push(f64::from(omega * (r + g + b) / 3.0));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every base texel is covered by exactly one slot.
    fn assert_tiles(tree: &Quadtree, slots: &[Slot]) {
        let (w, h) = tree.size(0);
        let mut cover = vec![0u32; (w * h) as usize];
        for s in slots {
            let span = 1 << s.level;
            for y in s.y * span..((s.y + 1) * span).min(h) {
                for x in s.x * span..((s.x + 1) * span).min(w) {
                    cover[(y * w + x) as usize] += 1;
                }
            }
        }
        assert!(cover.iter().all(|&c| c == 1), "slots must tile the base exactly once");
    }

    fn uniform(w: u32, h: u32) -> Vec<f64> {
        lamp_importance((w, h), (w, h), 1, (0.7, 0.4), (1, 1, &[[1.0; 4]]))
    }

    #[test]
    fn both_tiers_tile_the_base_within_their_budgets_and_nest() {
        let tree = Quadtree::new(160, 90);
        let importance = uniform(160, 90);
        for (budget, coarse) in [(16, 8), (100, 20), (1024, 64), (5000, 300)] {
            let t = DistributionTable::build(&tree, &importance, 0, budget, coarse);
            assert!(
                t.fine.len() <= budget as usize && t.fine.len() + 3 > budget as usize,
                "{budget}: {}",
                t.fine.len()
            );
            assert!(t.coarse.len() <= coarse.max(15) as usize, "{coarse}: {}", t.coarse.len());
            assert_tiles(&tree, &t.coarse);
            assert_tiles(&tree, &t.fine.iter().map(|(s, _)| *s).collect::<Vec<_>>());
            assert!(t.nests(), "every fine slot lies in its coarse slot");
        }
    }

    #[test]
    fn no_slot_is_finer_than_the_floor() {
        let tree = Quadtree::new(160, 90);
        let table = DistributionTable::build(&tree, &uniform(160, 90), 1, 4000, 100);
        assert!(table.fine.iter().all(|(s, _)| s.level >= 1) && table.coarse.iter().all(|s| s.level >= 1));
        assert_tiles(&tree, &table.fine.iter().map(|(s, _)| *s).collect::<Vec<_>>());
        // 80×45 level-1 nodes at most: the budget cannot be reached.
        assert_eq!(table.fine.len(), 80 * 45);
    }

    #[test]
    fn bright_regions_get_finer_slots() {
        // A spot: only the centre quarter of the frustum is lit.
        let (w, h) = (128, 128);
        let tree = Quadtree::new(w, h);
        let mut t = vec![[0.0f32; 4]; 16];
        for (y, x) in [(1, 1), (1, 2), (2, 1), (2, 2)] {
            t[y * 4 + x] = [1.0; 4];
        }
        let importance = lamp_importance((w, h), (w, h), 1, (0.5, 0.5), (4, 4, &t));
        let table = DistributionTable::build(&tree, &importance, 0, 256, 32);
        let centre = |s: &Slot| {
            let span = 1u32 << s.level;
            let (cx, cy) = ((s.x * span + span / 2) as f32 / w as f32, (s.y * span + span / 2) as f32 / h as f32);
            (0.25..0.75).contains(&cx) && (0.25..0.75).contains(&cy)
        };
        let inner = table.fine.iter().filter(|(s, _)| centre(s)).map(|(s, _)| s.level).max().unwrap();
        let outer = table.fine.iter().filter(|(s, _)| !centre(s)).map(|(s, _)| s.level).min().unwrap();
        assert!(inner < outer, "lit centre slots (≤{inner}) must be finer than dark ones (≥{outer})");
    }

    #[test]
    fn the_padding_beyond_the_view_is_never_split() {
        // A base of 4×4 blocks of a 200×100 view, with 3 texels of padding each way.
        let importance = lamp_importance((53, 28), (200, 100), 4, (0.7, 0.4), (1, 1, &[[1.0; 4]]));
        assert_eq!(importance[52], 0.0, "the last column is past the view");
        assert!(importance[49] > 0.0);
        let tree = Quadtree::new(53, 28);
        let table = DistributionTable::build(&tree, &importance, 0, 1000, 64);
        // A slot wholly in the padding exists only as the sibling of one with light: its
        // parent reaches into the view.
        let past = |level: u32, x: u32, y: u32| x << level >= 50 || y << level >= 25;
        for (s, _) in &table.fine {
            if past(s.level, s.x, s.y) {
                assert!(!past(s.level + 1, s.x / 2, s.y / 2), "{s:?} was split from a slot with no light");
            }
        }
    }

    #[test]
    fn entries_list_the_coarse_tier_then_the_fine_with_their_coarse_slots() {
        let tree = Quadtree::new(64, 48);
        let table = DistributionTable::build(&tree, &uniform(64, 48), 0, 300, 40);
        assert_eq!(table, DistributionTable::build(&tree, &uniform(64, 48), 0, 300, 40), "deterministic");
        let entries = table.entries();
        assert_eq!(entries.len(), table.coarse.len() + table.fine.len());
        let kind = |e: &[u32; 4]| (e[0] >> 8) & 0xff;
        let slot = |level: u32, xy: u32| Slot { level, x: xy & 0xffff, y: xy >> 16 };
        assert!(entries[..table.coarse.len()].iter().all(|e| kind(e) == ENTRY_COARSE));
        for (e, (s, c)) in entries[table.coarse.len()..].iter().zip(&table.fine) {
            assert_eq!((kind(e), slot(e[0] & 0xff, e[1])), (ENTRY_FINE, *s));
            assert_eq!(slot(e[2], e[3]), table.coarse[*c as usize]);
        }
    }
}
