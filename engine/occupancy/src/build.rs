//! Building the grid: its size and voxel from the level's bounds and the budget, the
//! triangles marked, and the blocks' distances to the nearest marked block.

use glam::{IVec3, UVec3, Vec3};

use crate::voxelize::voxelize;
use crate::{Occupancy, BLOCK};

/// What a grid may cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// The voxel's side where the budget allows, metres.
    pub finest_voxel: f32,
    /// The coarsest voxel taken before the level is refused, metres.
    pub coarsest_voxel: f32,
    /// Most bytes the grid may take.
    pub max_bytes: u64,
}

impl Default for Limits {
    /// 5 cm voxels (a wall's surfaces marked to within 5 cm) where they fit 64 MiB, doubled
    /// until they do, up to 1.6 m.
    fn default() -> Self {
        Self { finest_voxel: 0.05, coarsest_voxel: 1.6, max_bytes: 64 << 20 }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum BuildError {
    /// A vertex is NaN or infinite.
    NotFinite { triangle: usize },
    /// Even the coarsest voxel makes a grid larger than the budget.
    TooLarge { extent: Vec3, bytes: u64, max_bytes: u64 },
}

impl std::fmt::Display for BuildError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BuildError::NotFinite { triangle } => {
                write!(f, "triangle {triangle} has a vertex that is not a finite number")
            }
            BuildError::TooLarge { extent, bytes, max_bytes } => write!(
                f,
                "the level spans {:.0} × {:.0} × {:.0} m: its occupancy grid would take {} MiB even with the coarsest \
                 voxels, more than the {} MiB allowed",
                extent.x,
                extent.y,
                extent.z,
                bytes >> 20,
                max_bytes >> 20
            ),
        }
    }
}

impl std::error::Error for BuildError {}

/// Bytes of a grid of `blocks` blocks: two words of bits and a distance byte each.
fn grid_bytes(blocks: UVec3) -> u64 {
    u64::from(blocks.x).saturating_mul(u64::from(blocks.y)).saturating_mul(u64::from(blocks.z)).saturating_mul(9)
}

/// Blocks covering `extent` metres with voxels of `voxel` metres and a voxel of margin on
/// every side.
fn blocks_for(extent: Vec3, voxel: f32) -> UVec3 {
    let side = voxel * BLOCK as f32;
    ((extent + 2.0 * voxel) / side).ceil().max(Vec3::ONE).as_uvec3()
}

impl Occupancy {
    /// The grid of a level's static meshes (world space) within `limits`. An index beyond its
    /// mesh's vertices leaves that triangle out (the loader refuses such a mesh).
    pub fn of_scene(scene: &scene::Scene, limits: Limits) -> Result<Occupancy, BuildError> {
        let triangles: Vec<[Vec3; 3]> = scene
            .meshes
            .iter()
            .flat_map(|m| {
                m.indices.chunks_exact(3).filter_map(|t| {
                    let p = |i: u32| m.vertices.get(i as usize).map(|v| Vec3::from(v.position));
                    Some([p(t[0])?, p(t[1])?, p(t[2])?])
                })
            })
            .collect();
        Self::build(&triangles, limits)
    }

    /// The grid of `triangles` (world space, metres) within `limits`.
    pub fn build(triangles: &[[Vec3; 3]], limits: Limits) -> Result<Occupancy, BuildError> {
        if let Some(triangle) = triangles.iter().position(|t| !t.iter().all(|p| p.is_finite())) {
            return Err(BuildError::NotFinite { triangle });
        }
        let (min, max) = triangles
            .iter()
            .flatten()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let (min, extent) = if triangles.is_empty() { (Vec3::ZERO, Vec3::ZERO) } else { (min, max - min) };
        let mut voxel = limits.finest_voxel;
        let mut blocks = blocks_for(extent, voxel);
        while grid_bytes(blocks) > limits.max_bytes {
            if voxel * 2.0 > limits.coarsest_voxel {
                return Err(BuildError::TooLarge { extent, bytes: grid_bytes(blocks), max_bytes: limits.max_bytes });
            }
            voxel *= 2.0;
            blocks = blocks_for(extent, voxel);
        }
        let count = (blocks.x * blocks.y * blocks.z) as usize;
        let mut grid = Occupancy {
            origin: min - Vec3::splat(voxel),
            voxel,
            blocks,
            bits: vec![0; count * 2],
            block_distances: vec![0; count],
            coarsened: voxel > limits.finest_voxel,
        };
        let size = (blocks * BLOCK).as_ivec3();
        for t in triangles {
            let local = t.map(|p| (p - grid.origin) / voxel);
            voxelize(local, size, |v| grid.mark(v));
        }
        grid.block_distances = block_distances(&grid);
        Ok(grid)
    }

    fn mark(&mut self, v: IVec3) {
        let v = v.as_uvec3();
        let (block, local) = (v / BLOCK, v % BLOCK);
        let bit = local.x + BLOCK * (local.y + BLOCK * local.z);
        let index = self.block_index(block) * 2 + (bit / 32) as usize;
        self.bits[index] |= 1 << (bit % 32);
    }
}

/// Each block's Chebyshev distance, in blocks, to the nearest block with a marked voxel (0
/// for those, at most 255): two raster passes of the 26-neighbour chamfer mask with unit
/// weights, which is exact for the Chebyshev distance.
fn block_distances(grid: &Occupancy) -> Vec<u8> {
    let n = grid.blocks.as_ivec3();
    let index = |p: IVec3| (p.x + n.x * (p.y + n.y * p.z)) as usize;
    let mut d: Vec<u8> = (0..grid.block_distances.len())
        .map(|i| if grid.bits[2 * i] | grid.bits[2 * i + 1] != 0 { 0 } else { u8::MAX })
        .collect();
    // The neighbours before a block in raster order (z, then y, then x), and after it.
    let before: Vec<IVec3> = (-1..=1)
        .flat_map(|z| (-1..=1).flat_map(move |y| (-1..=1).map(move |x| IVec3::new(x, y, z))))
        .filter(|o| (o.z, o.y, o.x) < (0, 0, 0))
        .collect();
    let relax = |p: IVec3, offsets: &[IVec3], d: &mut Vec<u8>| {
        let mut best = d[index(p)];
        for &o in offsets {
            let q = p + o;
            if q.cmpge(IVec3::ZERO).all() && q.cmplt(n).all() {
                best = best.min(d[index(q)].saturating_add(1));
            }
        }
        d[index(p)] = best;
    };
    for z in 0..n.z {
        for y in 0..n.y {
            for x in 0..n.x {
                relax(IVec3::new(x, y, z), &before, &mut d);
            }
        }
    }
    let after: Vec<IVec3> = before.iter().map(|o| -*o).collect();
    for z in (0..n.z).rev() {
        for y in (0..n.y).rev() {
            for x in (0..n.x).rev() {
                relax(IVec3::new(x, y, z), &after, &mut d);
            }
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_are_chebyshev_distances_to_the_nearest_marked_block() {
        // One triangle in the middle of a 12 m cube of empty space (a corner point far away
        // sets the bounds).
        let t = [Vec3::new(6.0, 6.0, 6.0), Vec3::new(6.1, 6.0, 6.0), Vec3::new(6.0, 6.1, 6.0)];
        let far = [Vec3::ZERO, Vec3::new(0.0, 0.0, 0.01), Vec3::new(0.01, 0.0, 0.0)];
        let far2 = [Vec3::splat(12.0), Vec3::new(12.0, 12.0, 11.99), Vec3::new(11.99, 12.0, 12.0)];
        let limits = Limits { finest_voxel: 0.25, ..Limits::default() };
        let g = Occupancy::build(&[t, far, far2], limits).unwrap();
        let n = g.blocks.as_ivec3();
        let marked: Vec<IVec3> = (0..g.block_distances.len() as i32)
            .filter(|&i| g.block_distances[i as usize] == 0)
            .map(|i| IVec3::new(i % n.x, (i / n.x) % n.y, i / (n.x * n.y)))
            .collect();
        assert!(marked.len() >= 3);
        for z in 0..n.z {
            for y in 0..n.y {
                for x in 0..n.x {
                    let p = IVec3::new(x, y, z);
                    let want = marked.iter().map(|m| (*m - p).abs().max_element()).min().unwrap().min(255);
                    assert_eq!(g.block_distances[(x + n.x * (y + n.y * z)) as usize] as i32, want, "{p}");
                }
            }
        }
    }

    #[test]
    fn a_level_too_large_for_the_budget_gets_coarser_voxels_then_an_error() {
        let wide = [Vec3::ZERO, Vec3::new(600.0, 0.0, 0.0), Vec3::new(0.0, 100.0, 600.0)];
        let g = Occupancy::build(&[wide], Limits::default()).unwrap();
        assert!(g.coarsened && g.voxel > 0.05 && g.bytes() <= 64 << 20, "{} m, {} bytes", g.voxel, g.bytes());
        let huge = [Vec3::ZERO, Vec3::new(1e6, 0.0, 0.0), Vec3::new(0.0, 1e6, 1e6)];
        let e = Occupancy::build(&[huge], Limits::default()).unwrap_err();
        assert!(matches!(e, BuildError::TooLarge { .. }), "{e}");
        assert!(e.to_string().contains("1000000 × 1000000 × 1000000 m"), "{e}");
        let nan = [Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0), Vec3::Z];
        assert_eq!(Occupancy::build(&[wide, nan], Limits::default()), Err(BuildError::NotFinite { triangle: 1 }));
        // Nothing at all: one empty block.
        let empty = Occupancy::build(&[], Limits::default()).unwrap();
        assert_eq!(empty.blocks, UVec3::ONE);
    }
}
