//! The distribution table: precomputed once per resolution, budget and lamp profile, it lists
//! the quadtree slots (level, texel) that reflection lights are taken from. The slots tile the
//! whole image (every texel belongs to exactly one slot, so no flux is left out); where the
//! lamp sends more energy — T(uv)·Ω(uv), the expected flux per unit albedo — slots are finer,
//! and higher levels stand for more texels where it sends less.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::quadtree::Quadtree;

/// One slot: a node of the quadtree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Slot {
    pub level: u32,
    pub x: u32,
    pub y: u32,
}

impl Slot {
    /// The GPU form: (level, x | y << 16).
    pub fn packed(&self) -> [u32; 2] {
        [self.level, self.x | (self.y << 16)]
    }
}

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
    // Most important first; ties broken by position so the table is deterministic.
    fn cmp(&self, other: &Self) -> Ordering {
        self.importance.total_cmp(&other.importance).then_with(|| {
            (other.slot.level, other.slot.y, other.slot.x).cmp(&(self.slot.level, self.slot.y, self.slot.x))
        })
    }
}

/// Builds the table for a quadtree whose level-0 texels have expected flux `importance`
/// (row-major, width × height of level 0), splitting the most important slot until `budget`
/// slots exist (or nothing can be split).
pub fn build(tree: &Quadtree, importance: &[f64], budget: u32) -> Vec<Slot> {
    // Importance summed up the levels.
    let mut sums: Vec<Vec<f64>> = vec![importance.to_vec()];
    for level in 1..=tree.top() {
        let (w, h) = tree.size(level);
        let (cw, ch) = tree.size(level - 1);
        let below = &sums[level as usize - 1];
        let mut here = vec![0.0; (w * h) as usize];
        for y in 0..h {
            for x in 0..w {
                let mut s = 0.0;
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let (cx, cy) = (x * 2 + dx, y * 2 + dy);
                    if cx < cw && cy < ch {
                        s += below[(cy * cw + cx) as usize];
                    }
                }
                here[(y * w + x) as usize] = s;
            }
        }
        sums.push(here);
    }
    let importance_of = |s: Slot| sums[s.level as usize][(s.y * tree.size(s.level).0 + s.x) as usize];

    let top = tree.top();
    let (tw, th) = tree.size(top);
    let mut heap = BinaryHeap::new();
    let mut done = Vec::new();
    for y in 0..th {
        for x in 0..tw {
            let slot = Slot { level: top, x, y };
            heap.push(Candidate { importance: importance_of(slot), slot });
        }
    }
    while let Some(c) = heap.pop() {
        let total = heap.len() + done.len() + 1;
        if c.slot.level == 0 || c.importance <= 0.0 || total + 3 > budget as usize {
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
    done.sort_by_key(|s| (s.level, s.y, s.x));
    done
}

/// Expected flux per unit albedo of each texel of a `width`×`height` lamp view: T(uv)·Ω(uv),
/// with T given as a `tw`×`th` texture over the frustum and `tan` the frustum's half-angle tangents.
pub fn lamp_importance(width: u32, height: u32, tan: (f32, f32), t: &[[f32; 4]], tw: u32, th: u32) -> Vec<f64> {
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let u = (x as f32 + 0.5) / width as f32;
            let v = (y as f32 + 0.5) / height as f32;
            let (nx, ny) = (u * 2.0 - 1.0, 1.0 - v * 2.0);
            let (ax, ay) = (nx * tan.0, ny * tan.1);
            let r2 = 1.0 + ax * ax + ay * ay;
            let omega = 1.0 / (r2 * r2.sqrt());
            let texel = t[(((v * th as f32) as u32).min(th - 1) * tw + ((u * tw as f32) as u32).min(tw - 1)) as usize];
            out.push((omega * (texel[0] + texel[1] + texel[2]) / 3.0) as f64);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every level-0 texel is covered by exactly one slot.
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
        assert!(cover.iter().all(|&c| c == 1), "slots must tile the image exactly once");
    }

    #[test]
    fn slots_tile_the_image_and_respect_the_budget() {
        let tree = Quadtree::new(160, 90);
        let importance = lamp_importance(160, 90, (0.7, 0.4), &[[1.0; 4]], 1, 1);
        for budget in [16, 100, 1024, 5000] {
            let slots = build(&tree, &importance, budget);
            assert!(slots.len() <= budget.max(tree.size(tree.top()).0 * tree.size(tree.top()).1) as usize);
            assert!(
                slots.len() + 3 > budget as usize || slots.iter().all(|s| s.level == 0),
                "budget {budget} underused"
            );
            assert_tiles(&tree, &slots);
        }
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
        let importance = lamp_importance(w, h, (0.5, 0.5), &t, 4, 4);
        let slots = build(&tree, &importance, 256);
        assert_tiles(&tree, &slots);
        let centre = |s: &Slot| {
            let span = 1u32 << s.level;
            let (cx, cy) = ((s.x * span + span / 2) as f32 / w as f32, (s.y * span + span / 2) as f32 / h as f32);
            (0.25..0.75).contains(&cx) && (0.25..0.75).contains(&cy)
        };
        let inner_level = slots.iter().filter(|s| centre(s)).map(|s| s.level).max().unwrap();
        let outer_level = slots.iter().filter(|s| !centre(s)).map(|s| s.level).min().unwrap();
        assert!(
            inner_level < outer_level,
            "lit centre slots (≤{inner_level}) must be finer than dark ones (≥{outer_level})"
        );
    }

    #[test]
    fn the_table_is_deterministic() {
        let tree = Quadtree::new(64, 48);
        let importance = lamp_importance(64, 48, (0.5, 0.4), &[[1.0; 4]], 1, 1);
        assert_eq!(build(&tree, &importance, 300), build(&tree, &importance, 300));
    }
}
