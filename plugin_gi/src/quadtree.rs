//! Layout of the flux pyramid: a quadtree over the lamp view, stored level after level in one
//! node buffer, then (over a base of texel blocks) the halves of level 0's nodes (see
//! [`Quadtree::halves`]).

/// The pyramid always has levels 0 (one texel) to `TOP` (64×64 texels): two dispatches of three
/// workgroup-local reductions each build it (see shaders/gi/pyramid.wgsl).
pub const LEVELS: u32 = 7;
pub const TOP: u32 = LEVELS - 1;

/// Sizes and offsets of each level of a quadtree over a `width`×`height` image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Quadtree {
    /// (offset in nodes, width, height) per level, level 0 = full resolution.
    pub levels: Vec<(u32, u32, u32)>,
    /// Whether the buffer holds the halves of level 0's nodes: only where each is a block of
    /// lamp-view texels (`GiParams.flux_block` > 1); a texel has no halves.
    pub blocks: bool,
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
        Self { levels, blocks: false }
    }

    /// The same over a base of blocks of lamp-view texels, with room for their halves.
    pub fn of_blocks(width: u32, height: u32, blocks: bool) -> Self {
        Self { blocks, ..Self::new(width, height) }
    }

    /// Where the two halves of each level-0 node are stored, after the levels: a block of
    /// lamp-view texels that spans a fold is one node up the pyramid, and for the cut's near
    /// list also its two sides, each a light on its own plane (see shaders/gi/pyramid.wgsl).
    /// (offset in nodes, width, height) of the first halves; the second follow them. None
    /// (width and height 0) unless the base is of blocks.
    pub fn halves(&self) -> (u32, u32, u32) {
        let (_, w, h) = if self.blocks { self.levels[0] } else { (0, 0, 0) };
        (self.levels_node_count(), w, h)
    }

    fn levels_node_count(&self) -> u32 {
        self.levels.iter().map(|(_, w, h)| w * h).sum()
    }

    /// Nodes in the buffer: every level's, and two halves per level-0 node of blocks.
    pub fn node_count(&self) -> u32 {
        let (_, w, h) = self.halves();
        self.levels_node_count() + 2 * w * h
    }

    pub fn size(&self, level: u32) -> (u32, u32) {
        let (_, w, h) = self.levels[level as usize];
        (w, h)
    }

    /// The GPU form: per level (offset, width, height, 0), then the halves, in 8 entries.
    pub fn table(&self) -> [[u32; 4]; 8] {
        let mut table = [[0u32; 4]; 8];
        for (i, &(offset, w, h)) in self.levels.iter().enumerate() {
            table[i] = [offset, w, h, 0];
        }
        let (offset, w, h) = self.halves();
        table[LEVELS as usize] = [offset, w, h, 0];
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
        assert_eq!(small.table()[LEVELS as usize], [13, 0, 0, 0], "texels have no halves");
        let blocks = Quadtree::of_blocks(3, 2, true);
        assert_eq!(blocks.node_count(), 6 + 2 + 5 + 2 * 6, "the levels, then two halves per level-0 node");
        assert_eq!(blocks.table()[LEVELS as usize], [13, 3, 2, 0]);
    }
}
