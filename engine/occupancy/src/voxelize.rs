//! Conservative voxelization: every voxel a triangle touches, found column by column along
//! the triangle's dominant axis and confirmed by the separating-axis test of a triangle
//! against a box (Akenine-Möller, "Fast 3D triangle-box overlap testing", 2001).

use glam::{IVec3, Vec3};

/// Calls `mark` with every voxel (integer cell, voxel units) of a grid of `size` voxels that
/// triangle `t` (voxel units) touches.
pub(crate) fn voxelize(t: [Vec3; 3], size: IVec3, mut mark: impl FnMut(IVec3)) {
    let normal = (t[1] - t[0]).cross(t[2] - t[0]);
    if !normal.is_finite() || normal.length_squared() == 0.0 {
        return;
    }
    // Along the axis the triangle faces most, a column of voxels meets its plane in one to
    // three voxels; the other two axes are walked over its bounds.
    let k = normal.abs().max_position();
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    // (A voxel whose face the triangle touches counts: a bound on a voxel boundary takes the
    // voxels on both sides.)
    let lo = (t[0].min(t[1]).min(t[2]).ceil() - 1.0).as_ivec3().max(IVec3::ZERO);
    let hi = t[0].max(t[1]).max(t[2]).floor().as_ivec3().min(size - 1);
    let d = normal.dot(t[0]);
    for a in lo[i]..=hi[i] {
        for b in lo[j]..=hi[j] {
            // The plane's height along k over the column's square, at its four corners.
            let height = |x: f32, y: f32| (d - normal[i] * x - normal[j] * y) / normal[k];
            let (a0, b0) = (a as f32, b as f32);
            let corners = [height(a0, b0), height(a0 + 1.0, b0), height(a0, b0 + 1.0), height(a0 + 1.0, b0 + 1.0)];
            let below = corners.iter().copied().fold(f32::INFINITY, f32::min).ceil() as i32 - 1;
            let above = corners.iter().copied().fold(f32::NEG_INFINITY, f32::max).floor() as i32;
            for c in below.max(lo[k])..=above.min(hi[k]) {
                let mut v = IVec3::ZERO;
                v[i] = a;
                v[j] = b;
                v[k] = c;
                if overlaps(t, v.as_vec3() + 0.5) {
                    mark(v);
                }
            }
        }
    }
}

/// Whether triangle `t` meets the unit cube centred on `centre` (faces included).
fn overlaps(t: [Vec3; 3], centre: Vec3) -> bool {
    let v = t.map(|p| p - centre);
    let half = Vec3::splat(0.5);
    // The cube's three face normals.
    for axis in 0..3 {
        let (lo, hi) = (v[0][axis].min(v[1][axis]).min(v[2][axis]), v[0][axis].max(v[1][axis]).max(v[2][axis]));
        if lo > half[axis] || hi < -half[axis] {
            return false;
        }
    }
    // The triangle's plane.
    let edges = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
    let normal = edges[0].cross(edges[1]);
    let reach = half.dot(normal.abs());
    let offset = normal.dot(v[0]);
    if offset.abs() > reach {
        return false;
    }
    // The nine cross products of the cube's axes with the triangle's edges.
    for e in edges {
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            let a = axis.cross(e);
            if a == Vec3::ZERO {
                continue;
            }
            let p = [a.dot(v[0]), a.dot(v[1]), a.dot(v[2])];
            let r = half.dot(a.abs());
            if p[0].min(p[1]).min(p[2]) > r || p[0].max(p[1]).max(p[2]) < -r {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn marked(t: [Vec3; 3], size: i32) -> Vec<IVec3> {
        let mut out = Vec::new();
        voxelize(t, IVec3::splat(size), |v| out.push(v));
        out.sort_by_key(|v| (v.x, v.y, v.z));
        out
    }

    #[test]
    fn a_triangle_marks_the_voxels_it_touches_and_no_others() {
        // In the plane y = 1.5: the layer y = 1, over the triangle's footprint.
        let t = [Vec3::new(0.2, 1.5, 0.2), Vec3::new(3.8, 1.5, 0.2), Vec3::new(0.2, 1.5, 3.8)];
        let v = marked(t, 8);
        assert!(v.iter().all(|v| v.y == 1), "{v:?}");
        assert!(
            v.contains(&IVec3::new(0, 1, 0)) && v.contains(&IVec3::new(3, 1, 0)) && v.contains(&IVec3::new(0, 1, 3))
        );
        assert!(!v.contains(&IVec3::new(3, 1, 3)), "beyond the hypotenuse");
        // On a voxel boundary (y = 2) both layers touch it.
        let t = [Vec3::new(0.5, 2.0, 0.5), Vec3::new(1.5, 2.0, 0.5), Vec3::new(0.5, 2.0, 1.5)];
        let layers: Vec<i32> = marked(t, 8).iter().map(|v| v.y).collect();
        assert!(layers.contains(&1) && layers.contains(&2));
        // A tilted triangle marks a connected staircase: every column it spans has a voxel.
        let t = [Vec3::new(0.1, 0.1, 0.5), Vec3::new(7.9, 5.9, 0.5), Vec3::new(0.1, 0.1, 7.5)];
        let v = marked(t, 8);
        for x in 0..8 {
            assert!(v.iter().any(|v| v.x == x), "column x = {x}");
        }
    }

    #[test]
    fn degenerate_and_outside_triangles_mark_nothing() {
        let line = [Vec3::ZERO, Vec3::ONE, Vec3::splat(2.0)];
        assert!(marked(line, 8).is_empty());
        let outside = [Vec3::splat(20.0), Vec3::new(21.0, 20.0, 20.0), Vec3::new(20.0, 21.0, 20.0)];
        assert!(marked(outside, 8).is_empty());
        let nan = [Vec3::NAN, Vec3::ONE, Vec3::X];
        assert!(marked(nan, 8).is_empty());
    }
}
