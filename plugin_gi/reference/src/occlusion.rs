//! A conservative occlusion map from the lamp, to spare the shadow rays of patches that are
//! certainly in shadow. Per texel of the lamp's view it holds the farthest clip-space w at which
//! a single occluding triangle covers the whole texel: the ray to any point of that texel
//! beyond it passes through that triangle. Every other patch still gets its exact ray, so the
//! map decides nothing the ray would not; it only saves the ~90 % of rays that go to patches
//! in rooms behind the lit one.

use engine::glam::{Mat4, Vec2, Vec3};
use rayon::prelude::*;

/// Texels across and down.
const SIZE: u32 = 1024;
/// Rows rasterised by one task.
const BAND: u32 = 16;
/// A corner counts as inside a triangle only this far inside (barycentric units).
const INSIDE: f32 = 1e-4;

pub(crate) struct OcclusionMap {
    view_proj: Mat4,
    /// Per texel, row by row from the top: the clip w beyond which the texel is in shadow
    /// (infinite where no single triangle covers it).
    far: Vec<f32>,
}

/// An occluder in the lamp's view: its corners in normalised device coordinates and 1/w.
struct Projected {
    ndc: [Vec2; 3],
    inv_w: [f32; 3],
    /// Twice its signed area in NDC.
    area2: f32,
    /// Its texel rows and columns (inclusive).
    rows: (u32, u32),
    columns: (u32, u32),
}

fn cross(a: Vec2, b: Vec2) -> f32 {
    a.x * b.y - a.y * b.x
}

/// The texel row and column of NDC `p` (unclamped).
fn texel(p: Vec2) -> (f32, f32) {
    ((p.x + 1.0) * 0.5 * SIZE as f32, (1.0 - p.y) * 0.5 * SIZE as f32)
}

impl OcclusionMap {
    /// The map of `occluders` (triangles a ray from the lamp would stop at) in the lamp frustum
    /// `view_proj`.
    pub(crate) fn new(view_proj: Mat4, occluders: impl Iterator<Item = [Vec3; 3]>) -> Self {
        let projected: Vec<Projected> = occluders
            .filter_map(|corners| {
                let clip = corners.map(|p| view_proj * p.extend(1.0));
                // Wholly in front of the lamp, or not used (it only ever hides less).
                if clip.iter().any(|c| c.w <= 1e-4) {
                    return None;
                }
                let ndc = clip.map(|c| Vec2::new(c.x, c.y) / c.w);
                let area2 = cross(ndc[1] - ndc[0], ndc[2] - ndc[0]);
                if area2.abs() < 1e-12 {
                    return None;
                }
                let (lo, hi) = (ndc[0].min(ndc[1]).min(ndc[2]), ndc[0].max(ndc[1]).max(ndc[2]));
                let (x0, y0) = texel(Vec2::new(lo.x, hi.y));
                let (x1, y1) = texel(Vec2::new(hi.x, lo.y));
                let last = (SIZE - 1) as f32;
                if x1 < 0.0 || y1 < 0.0 || x0 > last + 1.0 || y0 > last + 1.0 {
                    return None;
                }
                let range = |a: f32, b: f32| (a.floor().clamp(0.0, last) as u32, b.floor().clamp(0.0, last) as u32);
                Some(Projected {
                    ndc,
                    inv_w: clip.map(|c| 1.0 / c.w),
                    area2,
                    rows: range(y0, y1),
                    columns: range(x0, x1),
                })
            })
            .collect();
        let mut far = vec![f32::INFINITY; (SIZE * SIZE) as usize];
        far.par_chunks_mut((SIZE * BAND) as usize).enumerate().for_each(|(band, texels)| {
            let first = band as u32 * BAND;
            for t in projected.iter().filter(|t| t.rows.0 < first + BAND && t.rows.1 >= first) {
                for y in t.rows.0.max(first)..=t.rows.1.min(first + BAND - 1) {
                    for x in t.columns.0..=t.columns.1 {
                        if let Some(w) = covered(t, x, y) {
                            let slot = &mut texels[((y - first) * SIZE + x) as usize];
                            *slot = slot.min(w);
                        }
                    }
                }
            }
        });
        Self { view_proj, far }
    }

    /// Whether the segment from the lamp to `p` certainly passes through an occluder (well
    /// before `p`: by 1 cm and 1/10,000 of the distance, more than any shadow ray's offset).
    pub(crate) fn hides(&self, p: Vec3) -> bool {
        let clip = self.view_proj * p.extend(1.0);
        if clip.w <= 0.0 {
            return false;
        }
        let (x, y) = texel(Vec2::new(clip.x, clip.y) / clip.w);
        let last = (SIZE - 1) as f32;
        if !(0.0..=SIZE as f32).contains(&x) || !(0.0..=SIZE as f32).contains(&y) {
            return false;
        }
        let (x, y) = (x.floor().min(last) as u32, y.floor().min(last) as u32);
        clip.w > self.far[(y * SIZE + x) as usize] * (1.0 + 1e-4) + 0.01
    }
}

/// The farthest w of triangle `t` over texel (`x`, `y`) when it covers all of it: 1/w is affine
/// over the screen on a plane, so w is largest at a corner of the texel.
fn covered(t: &Projected, x: u32, y: u32) -> Option<f32> {
    let mut farthest = 0.0f32;
    for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let p = Vec2::new(2.0 * (x + dx) as f32 / SIZE as f32 - 1.0, 1.0 - 2.0 * (y + dy) as f32 / SIZE as f32);
        let [a, b, c] = t.ndc;
        let l = [cross(c - b, p - b), cross(a - c, p - c), cross(b - a, p - a)].map(|e| e / t.area2);
        if l.iter().any(|&l| l < INSIDE) {
            return None;
        }
        let inv_w = l[0] * t.inv_w[0] + l[1] * t.inv_w[1] + l[2] * t.inv_w[2];
        farthest = farthest.max(1.0 / inv_w);
    }
    Some(farthest)
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::camera::Camera;

    #[test]
    fn a_wall_hides_what_is_behind_it_but_not_what_is_in_front_or_beside() {
        let camera = Camera::look_at(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), 1.2);
        let view_proj = camera.view_projection(1.0);
        // A wall 2 m away, 2 m wide, as two triangles.
        let (a, b, c, d) = (
            Vec3::new(-1.0, -1.0, -2.0),
            Vec3::new(1.0, -1.0, -2.0),
            Vec3::new(1.0, 1.0, -2.0),
            Vec3::new(-1.0, 1.0, -2.0),
        );
        let map = OcclusionMap::new(view_proj, [[a, b, c], [a, c, d]].into_iter());
        assert!(map.hides(Vec3::new(0.3, 0.2, -5.0)), "behind its middle");
        assert!(map.hides(Vec3::new(-0.4, -0.3, -2.5)));
        assert!(!map.hides(Vec3::new(0.3, 0.2, -1.5)), "in front");
        assert!(!map.hides(Vec3::new(0.3, 0.2, -2.005)), "just behind: left to the ray");
        assert!(!map.hides(Vec3::new(3.0, 0.0, -5.0)), "beside it");
        // Where the two halves meet no one triangle covers a texel: the ray decides there.
        assert!(!map.hides(Vec3::new(1.25, 1.25, -5.0)), "on the diagonal");
    }
}
