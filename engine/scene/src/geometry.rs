//! Baking a triangle list into world space: positions, normals, winding, flat normals.
//!
//! Shared by the glTF and OBJ loaders so both obey the same rules: front faces are
//! counter-clockwise in world space, normals are unit length, nothing non-finite survives.

use glam::{Mat3, Mat4, Vec3};

use crate::Vertex;

/// One primitive as read from a file, in its local space; indices already validated.
#[derive(Debug, Default)]
pub(crate) struct RawTriangles {
    pub positions: Vec<[f32; 3]>,
    pub normals: Option<Vec<[f32; 3]>>,
    pub uvs: Option<Vec<[f32; 2]>>,
    /// The second texture coordinate set (glTF TEXCOORD_1).
    pub uvs1: Option<Vec<[f32; 2]>>,
    /// Linear RGBA vertex colours (glTF COLOR_0, RGB given alpha 1); white when None.
    pub colors: Option<Vec<[f32; 4]>>,
    /// Triangle list, length a multiple of 3, every index < positions.len().
    pub indices: Vec<u32>,
}

/// Transforms `raw` by `world` into renderer vertices.
///
/// Normals use the inverse-transpose (so non-uniform scale keeps them perpendicular); a
/// mirroring transform (negative determinant) flips each triangle's winding so that front
/// faces stay counter-clockwise. Without normals every triangle gets its own three vertices
/// with the face normal (flat shading). Returns an error message if a transformed position is
/// not finite.
pub(crate) fn bake(raw: &RawTriangles, world: &Mat4) -> Result<(Vec<Vertex>, Vec<u32>), String> {
    let linear = Mat3::from_mat4(*world);
    let det = linear.determinant();
    let mirrored = det < 0.0;

    let mut positions = Vec::with_capacity(raw.positions.len());
    for (i, p) in raw.positions.iter().enumerate() {
        let w = world.transform_point3(Vec3::from(*p));
        if !w.is_finite() {
            return Err(format!("vertex {i} has a non-finite position {p:?} after transformation"));
        }
        positions.push(w);
    }

    let mut indices = raw.indices.clone();
    if mirrored {
        for tri in indices.chunks_exact_mut(3) {
            tri.swap(1, 2);
        }
    }
    let uv_of = |set: &Option<Vec<[f32; 2]>>, i: usize| -> [f32; 2] {
        let t = set.as_ref().and_then(|u| u.get(i)).copied().unwrap_or([0.0; 2]);
        [finite_or_zero(t[0]), finite_or_zero(t[1])]
    };
    let vertex = |i: usize, position: Vec3, normal: Vec3| Vertex {
        position: position.into(),
        normal: normal.into(),
        uv: uv_of(&raw.uvs, i),
        uv1: uv_of(&raw.uvs1, i),
        color: raw.colors.as_ref().and_then(|c| c.get(i)).copied().unwrap_or([1.0; 4]),
    };

    let Some(normals) = &raw.normals else {
        // Flat shading: un-share the vertices so each triangle carries its own normal.
        let mut vertices = Vec::with_capacity(indices.len());
        for tri in indices.chunks_exact(3) {
            let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| i as usize);
            let n = face_normal(positions[a], positions[b], positions[c]).unwrap_or(Vec3::Y);
            for i in [a, b, c] {
                vertices.push(vertex(i, positions[i], n));
            }
        }
        let flat_indices = (0..vertices.len() as u32).collect();
        return Ok((vertices, flat_indices));
    };

    // Inverse-transpose = cofactor / det; using the cofactor times sign(det) stays defined
    // when the transform is singular (a flattened mesh still gets usable normals).
    let [c0, c1, c2] = [linear.x_axis, linear.y_axis, linear.z_axis];
    let normal_matrix = Mat3::from_cols(c1.cross(c2), c2.cross(c0), c0.cross(c1)) * if mirrored { -1.0 } else { 1.0 };

    let mut smooth: Option<Vec<Vec3>> = None; // fallback for bad normals, built on demand
    let mut vertices = Vec::with_capacity(positions.len());
    for (i, p) in positions.iter().enumerate() {
        let given = normals.get(i).map(|n| normal_matrix * Vec3::from(*n));
        let n = match given.and_then(|n| n.try_normalize()) {
            Some(n) => n,
            None => {
                let smooth = smooth.get_or_insert_with(|| smooth_normals(&positions, &indices));
                smooth[i]
            }
        };
        vertices.push(vertex(i, *p, n));
    }
    Ok((vertices, indices))
}

/// Unit normal of a counter-clockwise triangle, None if degenerate.
pub(crate) fn face_normal(a: Vec3, b: Vec3, c: Vec3) -> Option<Vec3> {
    (b - a).cross(c - a).try_normalize()
}

/// Area-weighted vertex normals: the stand-in for zero-length or non-finite file normals.
fn smooth_normals(positions: &[Vec3], indices: &[u32]) -> Vec<Vec3> {
    let mut acc = vec![Vec3::ZERO; positions.len()];
    for tri in indices.chunks_exact(3) {
        let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| i as usize);
        let n = (positions[b] - positions[a]).cross(positions[c] - positions[a]);
        if n.is_finite() {
            for i in [a, b, c] {
                acc[i] += n;
            }
        }
    }
    acc.into_iter().map(|n| n.try_normalize().unwrap_or(Vec3::Y)).collect()
}

fn finite_or_zero(v: f32) -> f32 {
    if v.is_finite() {
        v
    } else {
        0.0
    }
}

/// Position and rotation of a transform with scale (and shear, and mirroring) removed,
/// keeping the local -Z (forward) and +Y (up) axes' directions. None if degenerate.
pub(crate) fn rigid_pose(world: &Mat4) -> Option<(Vec3, glam::Quat)> {
    let position = world.w_axis.truncate();
    let back = world.z_axis.truncate().try_normalize()?;
    let up = world.y_axis.truncate();
    let right = up.cross(back).try_normalize()?;
    let up = back.cross(right);
    let rotation = glam::Quat::from_mat3(&Mat3::from_cols(right, up, back)).normalize();
    (position.is_finite() && rotation.is_finite()).then_some((position, rotation))
}
