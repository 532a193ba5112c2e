//! Layout of the flux pyramid: a quadtree over the lamp view, stored level after level in one
//! node buffer.

/// The pyramid always has levels 0 (one texel) to `TOP` (64×64 texels): two dispatches of three
/// workgroup-local reductions each build it (see shaders/gi/pyramid.wgsl).
pub const LEVELS: u32 = 7;
pub const TOP: u32 = LEVELS - 1;

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
        for _ in 0..LEVELS {
            levels.push((offset, w, h));
            offset += w * h;
            (w, h) = (w.div_ceil(2), h.div_ceil(2));
        }
        Self { levels }
    }

    pub fn node_count(&self) -> u32 {
        self.levels.iter().map(|(_, w, h)| w * h).sum()
    }

    pub fn size(&self, level: u32) -> (u32, u32) {
        let (_, w, h) = self.levels[level as usize];
        (w, h)
    }

    /// The GPU form: per level (offset, width, height, 0), padded to 8 entries.
    pub fn table(&self) -> [[u32; 4]; 8] {
        let mut table = [[0u32; 4]; 8];
        for (i, &(offset, w, h)) in self.levels.iter().enumerate() {
            table[i] = [offset, w, h, 0];
        }
        table
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_halve_rounding_up_down_to_the_top() {
        let q = Quadtree::new(100, 60);
        assert_eq!(q.levels[0], (0, 100, 60));
        assert_eq!(q.levels[1], (6000, 50, 30));
        assert_eq!(q.size(2), (25, 15));
        assert_eq!(q.size(3), (13, 8));
        assert_eq!(q.size(TOP), (2, 1));
        assert_eq!(q.levels.len() as u32, LEVELS);
        let small = Quadtree::new(3, 2);
        assert_eq!(&small.levels[..3], &[(0, 3, 2), (6, 2, 1), (8, 1, 1)]);
        assert_eq!(small.node_count(), 6 + 2 + 5);
    }
}
