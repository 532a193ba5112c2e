//! Layout of the flux G-buffer's mip chain, stored level after level in one node buffer.

/// The coarsest level slots start from: one node stands for at most 64×64 texels, as in
/// multiresolution splatting (max mip level 5–6).
pub const MAX_LEVEL: u32 = 6;

/// Sizes and offsets of each level of a quadtree over a `width`×`height` image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Quadtree {
    /// (offset in nodes, width, height) per level, level 0 = full resolution.
    pub levels: Vec<(u32, u32, u32)>,
}

impl Quadtree {
    pub fn new(width: u32, height: u32) -> Self {
        let mut levels = Vec::new();
        let (mut w, mut h, mut offset) = (width.max(1), height.max(1), 0);
        for _ in 0..=MAX_LEVEL {
            levels.push((offset, w, h));
            offset += w * h;
            if w == 1 && h == 1 {
                break;
            }
            (w, h) = (w.div_ceil(2), h.div_ceil(2));
        }
        Self { levels }
    }

    pub fn top(&self) -> u32 {
        self.levels.len() as u32 - 1
    }

    pub fn node_count(&self) -> u32 {
        self.levels.iter().map(|(_, w, h)| w * h).sum()
    }

    pub fn size(&self, level: u32) -> (u32, u32) {
        let (_, w, h) = self.levels[level as usize];
        (w, h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_halve_rounding_up_and_stop_at_the_max_level() {
        let q = Quadtree::new(100, 60);
        assert_eq!(q.levels[0], (0, 100, 60));
        assert_eq!(q.levels[1], (6000, 50, 30));
        assert_eq!(q.size(2), (25, 15));
        assert_eq!(q.size(3), (13, 8));
        assert_eq!(q.top(), MAX_LEVEL);
        let small = Quadtree::new(3, 2);
        assert_eq!(small.levels, vec![(0, 3, 2), (6, 2, 1), (8, 1, 1)]);
        assert_eq!(small.node_count(), 9);
    }
}
