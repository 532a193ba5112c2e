//! The march along a segment: through empty blocks a cube of them at a time (as far as the
//! block's distance says nothing lies), through blocks with marked voxels a voxel at a time.
//! shaders/gi/world_sight.wgsl is the same march on the GPU.

use glam::Vec3;

use crate::{Occupancy, BLOCK};

/// Most steps of one march; a segment that needs more is taken as clear. A segment across a
/// grid of 256 voxels a side crosses at most 3 × 256 voxels, and the empty blocks between
/// surfaces are skipped: no march of a level's room comes near it.
pub const MAX_STEPS: u32 = 256;

/// How far past a boundary a step lands, in voxels, so that it is inside the next cell.
const NUDGE: f32 = 1e-3;

impl Occupancy {
    /// Whether the segment from `a` to `b` (world space, metres) crosses no marked voxel,
    /// leaving out the first and last `skip` metres (the voxels of the surfaces its ends lie
    /// on). Outside the grid nothing is marked.
    pub fn segment_clear(&self, a: Vec3, b: Vec3, skip: f32) -> bool {
        let (a, b) = ((a - self.origin) / self.voxel, (b - self.origin) / self.voxel);
        let d = b - a;
        let length = d.length();
        let skip = skip / self.voxel;
        if length <= 2.0 * skip {
            return true;
        }
        let size = self.voxels().as_vec3();
        // The part of the segment inside the grid, less the skipped ends.
        let (mut t, mut end) = (skip / length, 1.0 - skip / length);
        for axis in 0..3 {
            if d[axis] == 0.0 {
                if a[axis] < 0.0 || a[axis] >= size[axis] {
                    return true;
                }
                continue;
            }
            let (t0, t1) = ((0.0 - a[axis]) / d[axis], (size[axis] - a[axis]) / d[axis]);
            t = t.max(t0.min(t1));
            end = end.min(t0.max(t1));
        }
        let nudge = NUDGE / length;
        for _ in 0..MAX_STEPS {
            if t >= end {
                return true;
            }
            let p = (a + d * t).clamp(Vec3::ZERO, size - NUDGE);
            let block = (p / BLOCK as f32).floor();
            let distance = self.block_distances[self.block_index(block.as_uvec3())];
            let (lo, hi) = if distance > 0 {
                // The cube of blocks around this one that holds nothing.
                let r = f32::from(distance);
                ((block - (r - 1.0)) * BLOCK as f32, (block + r) * BLOCK as f32)
            } else {
                let voxel = p.floor();
                if self.is_solid(voxel.as_uvec3()) {
                    return false;
                }
                (voxel, voxel + 1.0)
            };
            t = exit(a, d, lo, hi) + nudge;
        }
        true
    }
}

/// When the line a + d·t leaves the box [lo, hi] it is in.
pub(crate) fn exit(a: Vec3, d: Vec3, lo: Vec3, hi: Vec3) -> f32 {
    let mut t = f32::INFINITY;
    for axis in 0..3 {
        if d[axis] > 0.0 {
            t = t.min((hi[axis] - a[axis]) / d[axis]);
        } else if d[axis] < 0.0 {
            t = t.min((lo[axis] - a[axis]) / d[axis]);
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Limits;

    /// Two quads of a box's faces (a wall `thickness` thick, between x = 0 and x = thickness,
    /// 4 m tall and wide), and a floor under both rooms.
    fn wall(thickness: f32) -> Vec<[Vec3; 3]> {
        let quad = |a: Vec3, b: Vec3, c: Vec3, d: Vec3| [[a, b, c], [a, c, d]];
        let mut t = Vec::new();
        for x in [0.0, thickness] {
            t.extend(quad(
                Vec3::new(x, 0.0, -2.0),
                Vec3::new(x, 4.0, -2.0),
                Vec3::new(x, 4.0, 2.0),
                Vec3::new(x, 0.0, 2.0),
            ));
        }
        t.extend(quad(
            Vec3::new(-4.0, 0.0, -2.0),
            Vec3::new(4.0, 0.0, -2.0),
            Vec3::new(4.0, 0.0, 2.0),
            Vec3::new(-4.0, 0.0, 2.0),
        ));
        t
    }

    #[test]
    fn a_ten_centimetre_wall_stops_every_segment_across_it_and_nothing_beside_it() {
        let g = Occupancy::build(&wall(0.1), Limits::default()).unwrap();
        let skip = 1.5 * g.voxel;
        let mut blocked = 0;
        for i in 0..200 {
            // Points 8 cm above the floor on either side, near and far, at every angle.
            let f = i as f32 / 200.0;
            let a = Vec3::new(-0.1 - 3.0 * f, 0.08 + 3.5 * f * f, -1.8 + 3.6 * f);
            let b = Vec3::new(0.2 + 3.0 * (1.0 - f), 3.9 - 3.8 * f, 1.8 - 3.6 * (f * 7.0).fract());
            assert!(!g.segment_clear(a, b, skip), "{a} to {b} crosses the wall");
            assert!(!g.segment_clear(b, a, skip), "{b} to {a} crosses the wall");
            blocked += 1;
            // The same room: nothing between.
            let c = Vec3::new(-3.9 + 3.0 * f, 0.1 + 3.8 * (1.0 - f), 1.8 - 3.6 * f);
            assert!(g.segment_clear(a, c, skip) || (a - c).length() < 0.3, "{a} to {c} is in one room");
        }
        assert_eq!(blocked, 200);
        // Over the top of the wall, and around its end: clear.
        assert!(g.segment_clear(Vec3::new(-1.0, 4.5, 0.0), Vec3::new(1.0, 5.0, 0.0), skip));
        assert!(g.segment_clear(Vec3::new(-1.0, 1.0, 2.0), Vec3::new(1.0, 1.0, 4.0), skip));
    }

    #[test]
    fn the_march_agrees_with_a_fine_walk_along_the_segment() {
        // A slanted roof and the wall, marched against sampling every 1/20 voxel along the segment.
        let mut t = wall(0.3);
        t.push([Vec3::new(-3.0, 2.0, -2.0), Vec3::new(3.0, 3.5, -2.0), Vec3::new(-3.0, 2.0, 2.0)]);
        let g = Occupancy::build(&t, Limits { finest_voxel: 0.1, ..Limits::default() }).unwrap();
        let mut disagree = Vec::new();
        for i in 0..400 {
            let f = |k: u32| ((i * k + 17) % 97) as f32 / 97.0;
            let a = Vec3::new(-3.9 + 7.8 * f(3), 0.05 + 4.5 * f(5), -1.9 + 3.8 * f(7));
            let b = Vec3::new(-3.9 + 7.8 * f(11), 0.05 + 4.5 * f(13), -1.9 + 3.8 * f(19));
            if a.distance(b) < 0.5 {
                continue;
            }
            let fine = {
                let (la, lb) = ((a - g.origin) / g.voxel, (b - g.origin) / g.voxel);
                let n = ((lb - la).length() * 20.0).ceil() as u32;
                (0..=n).all(|k| {
                    let p = la.lerp(lb, k as f32 / n as f32);
                    p.cmplt(Vec3::ZERO).any()
                        || p.cmpge(g.voxels().as_vec3()).any()
                        || !g.is_solid(p.floor().as_uvec3())
                })
            };
            if g.segment_clear(a, b, 0.0) != fine {
                disagree.push((a, b, fine));
            }
        }
        // A sampled walk can step over the corner of a voxel it grazes; the march cannot.
        assert!(disagree.iter().all(|&(_, _, fine)| fine), "the march let through {disagree:?}");
        assert!(disagree.len() <= 8, "{} of 400 disagree", disagree.len());
    }
}
