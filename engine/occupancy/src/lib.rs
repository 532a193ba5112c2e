//! Where a level's static surfaces are, as voxels, so that whether a segment between two
//! points crosses a surface can be asked anywhere in the level, seen by the camera or not.
//!
//! [`Occupancy::build`] marks every voxel of a grid over the level that a triangle touches
//! (conservatively: a segment that crosses a surface crosses a marked voxel, however thin the
//! surface), and for every block of 4×4×4 voxels how far away, in blocks, the nearest block
//! with a marked voxel lies, so a march skips empty space a block-sized cube at a time.
//! [`Occupancy::segment_clear`] is that march on the CPU; the GI's sight test runs the same on
//! the GPU (shaders/gi/world_sight.wgsl) from [`Occupancy::bits`] and
//! [`Occupancy::block_distances`].
//!
//! The voxel is as fine as the memory budget allows ([`Limits`]); a level too large for it at
//! the finest size gets coarser voxels (walls still stop light: marking is conservative), and
//! one too large even at the coarsest gets an error naming its size.

mod build;
mod march;
mod voxelize;

use glam::{UVec3, Vec3};

pub use build::{BuildError, Limits};
pub use march::MAX_STEPS;

/// Voxels along each side of a block.
pub const BLOCK: u32 = 4;

/// A level's surfaces as voxels (see the crate's documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct Occupancy {
    /// World position of the grid's lowest corner, metres.
    pub origin: Vec3,
    /// A voxel's side, metres.
    pub voxel: f32,
    /// The grid's size in blocks, each way.
    pub blocks: UVec3,
    /// Two words a block, in block order (x fastest, then y, then z): bit `x + 4y + 16z` of the
    /// block's 64 voxels set where a triangle touches that voxel.
    pub bits: Vec<u32>,
    /// A byte a block, in block order: 0 where the block has a marked voxel, else the
    /// Chebyshev distance in blocks to the nearest such block (at most 255).
    pub block_distances: Vec<u8>,
    /// Whether the voxel is coarser than [`Limits::finest_voxel`] to fit the budget.
    pub coarsened: bool,
}

impl Occupancy {
    /// The grid's size in voxels, each way.
    pub fn voxels(&self) -> UVec3 {
        self.blocks * BLOCK
    }

    /// Bytes the grid takes (both arrays).
    pub fn bytes(&self) -> u64 {
        (self.bits.len() * 4 + self.block_distances.len()) as u64
    }

    fn block_index(&self, block: UVec3) -> usize {
        (block.x + self.blocks.x * (block.y + self.blocks.y * block.z)) as usize
    }

    /// Whether voxel `v` (in voxel units from the origin) holds a surface.
    pub fn is_solid(&self, v: UVec3) -> bool {
        let (block, local) = (v / BLOCK, v % BLOCK);
        let bit = local.x + BLOCK * (local.y + BLOCK * local.z);
        (self.bits[self.block_index(block) * 2 + (bit / 32) as usize] >> (bit % 32)) & 1 == 1
    }

    /// The block distances packed four to a word (block i in byte i % 4 of word i / 4), as the
    /// GPU reads them.
    pub fn packed_block_distances(&self) -> Vec<u32> {
        self.block_distances
            .chunks(4)
            .map(|c| c.iter().enumerate().fold(0u32, |w, (i, &d)| w | u32::from(d) << (8 * i)))
            .collect()
    }
}
