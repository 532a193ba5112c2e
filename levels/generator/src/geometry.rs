//! Geometry primitives: axis-aligned boxes, ramps and the per-material mesh buffers they are
//! merged into.
//!
//! Every face is emitted with its own four (or three) vertices so normals are flat; faces are wound
//! counter-clockwise seen from outside, i.e. their winding agrees with the outward normal.

/// An axis-aligned box in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl Aabb {
    pub fn new(min: [f64; 3], max: [f64; 3]) -> Self {
        assert!((0..3).all(|i| min[i] < max[i]), "degenerate box {min:?} .. {max:?}");
        Self { min, max }
    }

    pub fn center(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| 0.5 * (self.min[i] + self.max[i]))
    }

    pub fn size(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| self.max[i] - self.min[i])
    }

    /// Closed containment test.
    pub fn contains(&self, p: [f64; 3]) -> bool {
        (0..3).all(|i| p[i] >= self.min[i] && p[i] <= self.max[i])
    }

    /// True when the interiors overlap by more than `eps` on every axis (touching is not overlapping).
    pub fn overlaps(&self, other: &Aabb, eps: f64) -> bool {
        (0..3).all(|i| self.min[i] + eps < other.max[i] && other.min[i] + eps < self.max[i])
    }

    /// Slab test: distance along `dir` (need not be unit) at which the ray from `origin` first
    /// touches the box, or None. A ray starting inside reports the exit distance.
    pub fn ray_hit(&self, origin: [f64; 3], dir: [f64; 3]) -> Option<f64> {
        let mut t0 = 0.0_f64;
        let mut t1 = f64::INFINITY;
        for i in 0..3 {
            if dir[i].abs() < 1e-300 {
                if origin[i] < self.min[i] || origin[i] > self.max[i] {
                    return None;
                }
                continue;
            }
            let inv = 1.0 / dir[i];
            let (mut a, mut b) = ((self.min[i] - origin[i]) * inv, (self.max[i] - origin[i]) * inv);
            if a > b {
                std::mem::swap(&mut a, &mut b);
            }
            t0 = t0.max(a);
            t1 = t1.min(b);
            if t0 > t1 {
                return None;
            }
        }
        Some(if t0 > 0.0 { t0 } else { t1 })
    }
}

/// One of the four horizontal directions. North is -Z (where yaw 0 looks), East is +X.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    North,
    East,
    South,
    West,
}

impl Side {
    pub const ALL: [Side; 4] = [Side::North, Side::East, Side::South, Side::West];

    pub fn index(self) -> usize {
        self as usize
    }

    pub fn name(self) -> &'static str {
        match self {
            Side::North => "north",
            Side::East => "east",
            Side::South => "south",
            Side::West => "west",
        }
    }

    /// Unit vector pointing towards this side.
    pub fn vector(self) -> [f64; 3] {
        match self {
            Side::North => [0.0, 0.0, -1.0],
            Side::East => [1.0, 0.0, 0.0],
            Side::South => [0.0, 0.0, 1.0],
            Side::West => [-1.0, 0.0, 0.0],
        }
    }
}

/// Triangle-list buffers for one material, ready to be written as one glTF primitive.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshBuffers {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub uvs: Vec<[f32; 2]>,
    pub indices: Vec<u32>,
}

/// The outward normal of each box face with a (u, v) tangent frame such that u × v = normal.
/// Texture coordinates are world-scaled: (dot(p, u), -dot(p, v)) metres.
pub const BOX_FACES: [([f64; 3], [f64; 3], [f64; 3]); 6] = [
    ([1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]),
    ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
    ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
    ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
    ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
    ([0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
];

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[cfg(test)]
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

fn centroid(points: &[[f64; 3]]) -> [f64; 3] {
    let n = points.len() as f64;
    let mut c = [0.0; 3];
    for p in points {
        for i in 0..3 {
            c[i] += p[i] / n;
        }
    }
    c
}

/// The tangent frame used for texture coordinates of a face with (unit) normal `n`: the frame of
/// the box face whose normal is closest.
fn uv_frame(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let mut best = BOX_FACES[0];
    for face in BOX_FACES {
        if dot(face.0, n) > dot(best.0, n) {
            best = face;
        }
    }
    (best.1, best.2)
}

fn to_f32(p: [f64; 3]) -> [f32; 3] {
    p.map(|c| c as f32)
}

impl MeshBuffers {
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn is_empty(&self) -> bool {
        self.indices.is_empty()
    }

    /// Appends a planar convex polygon whose corners are given counter-clockwise seen from the
    /// side `normal` points to. Triangulated as a fan.
    pub fn add_face(&mut self, corners: &[[f64; 3]], normal: [f64; 3]) {
        assert!(corners.len() >= 3);
        let (u, v) = uv_frame(normal);
        let base = u32::try_from(self.positions.len()).expect("too many vertices");
        for &p in corners {
            self.positions.push(to_f32(p));
            self.normals.push(to_f32(normal));
            self.uvs.push([dot(p, u) as f32, -dot(p, v) as f32]);
        }
        for i in 1..corners.len() as u32 - 1 {
            self.indices.extend_from_slice(&[base, base + i, base + i + 1]);
        }
    }

    /// Appends a face of a convex solid whose centroid is `solid_center`, fixing the corner
    /// order so that the face winds counter-clockwise seen from outside.
    pub fn add_face_outward(&mut self, corners: &[[f64; 3]], solid_center: [f64; 3]) {
        // Newell's method: robust polygon normal.
        let mut n = [0.0; 3];
        for (i, a) in corners.iter().enumerate() {
            let b = corners[(i + 1) % corners.len()];
            n[0] += (a[1] - b[1]) * (a[2] + b[2]);
            n[1] += (a[2] - b[2]) * (a[0] + b[0]);
            n[2] += (a[0] - b[0]) * (a[1] + b[1]);
        }
        let mut n = normalize(n);
        let out = sub(centroid(corners), solid_center);
        if dot(n, out) < 0.0 {
            let reversed: Vec<[f64; 3]> = corners.iter().rev().copied().collect();
            n = n.map(|c| -c);
            self.add_face(&reversed, n);
        } else {
            self.add_face(corners, n);
        }
    }

    /// Appends a box: 6 faces, 24 vertices, 36 indices.
    pub fn add_box(&mut self, b: &Aabb) {
        let c = b.center();
        let h = b.size().map(|s| 0.5 * s);
        for (n, u, v) in BOX_FACES {
            let dn = dot(h, n.map(f64::abs));
            let du = dot(h, u.map(f64::abs));
            let dv = dot(h, v.map(f64::abs));
            let fc = [0, 1, 2].map(|i| c[i] + n[i] * dn);
            let corner = |su: f64, sv: f64| [0, 1, 2].map(|i| fc[i] + u[i] * su * du + v[i] * sv * dv);
            let corners = [corner(-1.0, -1.0), corner(1.0, -1.0), corner(1.0, 1.0), corner(-1.0, 1.0)];
            self.add_face(&corners, n);
        }
    }

    /// Appends a wedge-shaped ramp filling `b`'s footprint: its top rises from `b.min.y` on the
    /// side opposite `high` to `b.max.y` on side `high`. 5 faces, 18 vertices, 24 indices.
    pub fn add_ramp(&mut self, b: &Aabb, high: Side) {
        let [x0, y0, z0] = b.min;
        let [x1, y1, z1] = b.max;
        // Footprint corners (x, z) on the high side and their counterparts on the low side.
        let (hi, lo) = match high {
            Side::North => ([[x0, z0], [x1, z0]], [[x0, z1], [x1, z1]]),
            Side::South => ([[x0, z1], [x1, z1]], [[x0, z0], [x1, z0]]),
            Side::West => ([[x0, z0], [x0, z1]], [[x1, z0], [x1, z1]]),
            Side::East => ([[x1, z0], [x1, z1]], [[x0, z0], [x0, z1]]),
        };
        let at = |xz: [f64; 2], y: f64| [xz[0], y, xz[1]];
        let (h0b, h1b, h0t, h1t) = (at(hi[0], y0), at(hi[1], y0), at(hi[0], y1), at(hi[1], y1));
        let (l0b, l1b) = (at(lo[0], y0), at(lo[1], y0));
        let center = centroid(&[h0b, h1b, h0t, h1t, l0b, l1b]);
        self.add_face_outward(&[h0b, h1b, l1b, l0b], center); // bottom
        self.add_face_outward(&[h0b, h1b, h1t, h0t], center); // high end
        self.add_face_outward(&[h0t, h1t, l1b, l0b], center); // slope
        self.add_face_outward(&[h0b, l0b, h0t], center); // side
        self.add_face_outward(&[h1b, l1b, h1t], center); // side
    }

    /// Divides every texture coordinate by `metres` (how many metres one repeat of the texture
    /// covers); a power of two divides exactly.
    pub fn scale_uvs(&mut self, metres: f64) {
        let s = (1.0 / metres) as f32;
        for uv in &mut self.uvs {
            *uv = [uv[0] * s, uv[1] * s];
        }
    }

    /// Component-wise bounds of the positions, as stored (f32).
    pub fn position_bounds(&self) -> ([f32; 3], [f32; 3]) {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in &self.positions {
            for i in 0..3 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f64v(p: [f32; 3]) -> [f64; 3] {
        p.map(f64::from)
    }

    /// For every triangle: its geometric normal (from the winding) agrees with the stored vertex
    /// normal, and points away from `center`.
    fn assert_outward(m: &MeshBuffers, center: [f64; 3]) {
        assert_eq!(m.indices.len() % 3, 0);
        for tri in m.indices.chunks(3) {
            let [a, b, c] = [0, 1, 2].map(|k| f64v(m.positions[tri[k] as usize]));
            let geometric = normalize(cross(sub(b, a), sub(c, a)));
            let tri_center = [0, 1, 2].map(|i| (a[i] + b[i] + c[i]) / 3.0);
            for &k in tri {
                let n = f64v(m.normals[k as usize]);
                assert!((dot(n, n) - 1.0).abs() < 1e-6, "normal not unit: {n:?}");
                assert!(dot(n, geometric) > 0.999, "winding disagrees with normal {n:?}");
            }
            assert!(dot(geometric, sub(tri_center, center)) > 0.0, "triangle faces inwards: {tri:?}");
        }
    }

    #[test]
    fn box_has_24_vertices_36_indices_and_outward_faces() {
        let b = Aabb::new([-1.0, 0.0, 2.0], [0.5, 3.0, 2.2]);
        let mut m = MeshBuffers::default();
        m.add_box(&b);
        assert_eq!(m.positions.len(), 24);
        assert_eq!(m.normals.len(), 24);
        assert_eq!(m.uvs.len(), 24);
        assert_eq!(m.indices.len(), 36);
        assert_outward(&m, b.center());
        // Face by face: normal · (face centre − box centre) > 0.
        for face in 0..6 {
            let verts = face * 4..face * 4 + 4;
            let n = f64v(m.normals[verts.start]);
            let fc = centroid(&m.positions[verts].iter().map(|&p| f64v(p)).collect::<Vec<_>>());
            assert!(dot(n, sub(fc, b.center())) > 0.0);
        }
        // Every corner lies on the box.
        for p in &m.positions {
            let p = f64v(*p);
            assert!((0..3).all(|i| p[i] == b.min[i] as f32 as f64 || p[i] == b.max[i] as f32 as f64));
        }
        assert_eq!(m.position_bounds(), (b.min.map(|c| c as f32), b.max.map(|c| c as f32)));
    }

    #[test]
    fn box_uvs_are_world_scaled() {
        let mut m = MeshBuffers::default();
        m.add_box(&Aabb::new([0.0, 0.0, 0.0], [2.0, 3.0, 0.2]));
        // The +Z face is 2 m wide and 3 m tall.
        let face = 4 * 4..5 * 4;
        let us: Vec<f32> = m.uvs[face.clone()].iter().map(|t| t[0]).collect();
        let vs: Vec<f32> = m.uvs[face].iter().map(|t| t[1]).collect();
        let span = |v: &[f32]| v.iter().cloned().fold(f32::MIN, f32::max) - v.iter().cloned().fold(f32::MAX, f32::min);
        assert!((span(&us) - 2.0).abs() < 1e-6);
        assert!((span(&vs) - 3.0).abs() < 1e-6);
    }

    #[test]
    fn ramps_face_outwards_in_every_orientation() {
        for high in Side::ALL {
            let b = Aabb::new([1.0, 0.0, -3.0], [3.4, 0.4, -1.2]);
            let mut m = MeshBuffers::default();
            m.add_ramp(&b, high);
            assert_eq!(m.positions.len(), 18);
            assert_eq!(m.indices.len(), 24);
            // The wedge's centroid lies inside it.
            let c = [b.center()[0], 0.1, b.center()[2]];
            assert_outward(&m, c);
            // The top vertices (y = 0.4) are on the `high` side.
            for p in &m.positions {
                if p[1] > 0.3 {
                    let d = sub(f64v(*p), b.center());
                    assert!(dot(d, high.vector()) > 0.0, "{high:?}: {p:?}");
                }
            }
        }
    }

    #[test]
    fn ray_hits_box() {
        let b = Aabb::new([1.0, -1.0, -1.0], [2.0, 1.0, 1.0]);
        assert_eq!(b.ray_hit([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), Some(1.0));
        assert_eq!(b.ray_hit([0.0, 0.0, 0.0], [-1.0, 0.0, 0.0]), None);
        assert_eq!(b.ray_hit([0.0, 2.0, 0.0], [1.0, 0.0, 0.0]), None);
        assert_eq!(b.ray_hit([1.5, 0.0, 0.0], [1.0, 0.0, 0.0]), Some(0.5));
    }
}
