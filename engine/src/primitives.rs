//! Simple closed meshes for instances (`Renderer::add_mesh`): unit outward normals, triangles
//! counter-clockwise seen from outside (as glTF's, which the G-buffer's front-facing test
//! expects), indices into the returned vertices. The axis of the round shapes is +Y.

use std::f32::consts::{FRAC_PI_2, PI, TAU};

use glam::{Vec2, Vec3};
use scene::Vertex;

/// A box centred on the origin, from −`half_extents` to +`half_extents`; flat faces.
pub fn cuboid(half_extents: Vec3) -> (Vec<Vertex>, Vec<u32>) {
    // Each face: outward normal n and tangents u, v with u × v = n, so corners listed
    // −u−v, +u−v, +u+v, −u+v run counter-clockwise seen from outside.
    let faces = [
        (Vec3::X, Vec3::Y, Vec3::Z),
        (Vec3::NEG_X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::Z, Vec3::X),
        (Vec3::NEG_Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (Vec3::NEG_Z, Vec3::Y, Vec3::X),
    ];
    let mut vertices = Vec::with_capacity(24);
    let mut indices = Vec::with_capacity(36);
    for (n, u, v) in faces {
        let base = vertices.len() as u32;
        for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            vertices.push(Vertex::new(
                ((n + u * su + v * sv) * half_extents).to_array(),
                n.to_array(),
                [(su + 1.0) * 0.5, (1.0 - sv) * 0.5],
            ));
        }
        indices.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
    }
    (vertices, indices)
}

/// Boxes (centre, half extents) in one mesh: a shape built of blocks, drawn as one instance.
pub fn boxes(parts: &[(Vec3, Vec3)]) -> (Vec<Vertex>, Vec<u32>) {
    let mut vertices = Vec::with_capacity(24 * parts.len());
    let mut indices = Vec::with_capacity(36 * parts.len());
    for &(centre, half) in parts {
        let (v, i) = cuboid(half);
        let base = vertices.len() as u32;
        vertices.extend(v.into_iter().map(|mut v| {
            v.position = (Vec3::from(v.position) + centre).to_array();
            v
        }));
        indices.extend(i.into_iter().map(|k| k + base));
    }
    (vertices, indices)
}

/// A sphere centred on the origin: `segments` around the axis (at least 3), `rings` from pole
/// to pole (at least 2).
pub fn uv_sphere(radius: f32, segments: u32, rings: u32) -> (Vec<Vertex>, Vec<u32>) {
    let rings = rings.max(2);
    // From the south pole up: angle θ ∈ [−π/2, π/2] above the equator.
    let profile: Vec<ProfilePoint> = (0..=rings)
        .map(|k| {
            let n = unit_at(PI * (k as f32 / rings as f32 - 0.5));
            ProfilePoint { at: n * radius, normal: n }
        })
        .collect();
    lathe(&profile, segments)
}

/// A capsule standing on the origin: y from 0 to `height` (the total height, at least 2 ×
/// `radius`, a sphere when equal), a cylinder between two hemispheres. `segments` around the
/// axis (at least 3); each hemisphere gets `segments / 4` rings (at least 2).
pub fn capsule(radius: f32, height: f32, segments: u32) -> (Vec<Vertex>, Vec<u32>) {
    let rings = (segments / 4).max(2);
    let (low, high) = (radius, height.max(2.0 * radius) - radius);
    let mut profile = Vec::with_capacity(2 * rings as usize + 2);
    for (centre, from) in [(low, -FRAC_PI_2), (high, 0.0)] {
        for k in 0..=rings {
            let n = unit_at(from + FRAC_PI_2 * k as f32 / rings as f32);
            profile.push(ProfilePoint { at: Vec2::new(0.0, centre) + n * radius, normal: n });
        }
    }
    lathe(&profile, segments)
}

/// A closed cylinder standing on the origin: y from 0 to `height`, flat caps. `segments`
/// around the axis (at least 3).
pub fn cylinder(radius: f32, height: f32, segments: u32) -> (Vec<Vertex>, Vec<u32>) {
    let point = |r: f32, y: f32, normal: Vec2| ProfilePoint { at: Vec2::new(r, y), normal };
    let (down, out, up) = (Vec2::NEG_Y, Vec2::X, Vec2::Y);
    // Rim points appear twice, once per normal, so the edges stay sharp.
    let profile = [
        point(0.0, 0.0, down),
        point(radius, 0.0, down),
        point(radius, 0.0, out),
        point(radius, height, out),
        point(radius, height, up),
        point(0.0, height, up),
    ];
    lathe(&profile, segments)
}

/// (cos θ, sin θ), exactly on the axis at the poles (cos(±π/2) is not 0 in f32).
fn unit_at(theta: f32) -> Vec2 {
    if theta.abs() >= FRAC_PI_2 {
        Vec2::new(0.0, theta.signum())
    } else {
        Vec2::new(theta.cos(), theta.sin())
    }
}

/// A point of a surface of revolution's profile: `at` = (distance from the axis, y), and the
/// outward normal in the same plane.
struct ProfilePoint {
    at: Vec2,
    normal: Vec2,
}

/// Revolves `profile` (listed from the bottom of the axis to its top: pole or cap centre →
/// rim → pole or cap centre) around +Y in `segments` steps. Bands
/// between equal points (normal splits) are skipped; bands touching the axis become triangle
/// fans, so no triangle is degenerate.
fn lathe(profile: &[ProfilePoint], segments: u32) -> (Vec<Vertex>, Vec<u32>) {
    let segments = segments.max(3);
    let columns = segments + 1; // the seam is duplicated for its u coordinate
    let mut vertices = Vec::with_capacity(profile.len() * columns as usize);
    for (k, p) in profile.iter().enumerate() {
        for s in 0..columns {
            // φ = 0 on +Z, growing towards +X.
            let phi = TAU * (s % segments) as f32 / segments as f32;
            let (sin, cos) = phi.sin_cos();
            let radial = |v: Vec2| Vec3::new(v.x * sin, v.y, v.x * cos);
            vertices.push(Vertex::new(
                radial(p.at).to_array(),
                radial(p.normal).normalize().to_array(),
                [s as f32 / segments as f32, 1.0 - k as f32 / (profile.len() - 1) as f32],
            ));
        }
    }
    let mut indices = Vec::new();
    for k in 0..profile.len() - 1 {
        let (lower, upper) = (&profile[k], &profile[k + 1]);
        if lower.at == upper.at {
            continue;
        }
        for s in 0..segments {
            // a, b along the lower circle (towards +φ), c, d above them: counter-clockwise
            // seen from outside, as the tangent ∂/∂φ × the profile direction points outwards.
            let a = k as u32 * columns + s;
            let (b, c, d) = (a + 1, a + 1 + columns, a + columns);
            if lower.at.x > 0.0 {
                indices.extend([a, b, c]);
            }
            if upper.at.x > 0.0 {
                indices.extend([a, c, d]);
            }
        }
    }
    (vertices, indices)
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;

    /// Checks what every primitive promises and returns (min, max, enclosed volume).
    fn check(name: &str, (vertices, indices): &(Vec<Vertex>, Vec<u32>), inside: impl Fn(Vec3) -> Vec3) -> f32 {
        assert!(indices.len() % 3 == 0 && !indices.is_empty(), "{name}: a triangle list");
        let p = |i: u32| Vec3::from(vertices[i as usize].position);
        for v in vertices {
            let n = Vec3::from(v.normal);
            assert!((n.length() - 1.0).abs() < 1e-5, "{name}: normal {n} is not unit");
            // Outward: away from the nearest point of the shape's core (centre or axis).
            let x = Vec3::from(v.position);
            assert!(n.dot(x - inside(x)) > 0.0, "{name}: normal {n} at {x} points inwards");
        }
        // Closed and consistently wound: every edge (vertices welded by position) is used
        // exactly once in each direction.
        let key = |v: Vec3| (v * 1e4).round().as_ivec3().to_array();
        let mut edges: HashMap<([i32; 3], [i32; 3]), i32> = HashMap::new();
        let mut volume = 0.0;
        for t in indices.chunks_exact(3) {
            let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
            let geometric = (b - a).cross(c - a);
            assert!(geometric.length() > 1e-9, "{name}: degenerate triangle {t:?}");
            let shading = Vec3::from(vertices[t[0] as usize].normal)
                + Vec3::from(vertices[t[1] as usize].normal)
                + Vec3::from(vertices[t[2] as usize].normal);
            assert!(geometric.dot(shading) > 0.0, "{name}: triangle {t:?} is wound against its normals");
            for (u, v) in [(a, b), (b, c), (c, a)] {
                *edges.entry((key(u), key(v))).or_default() += 1;
            }
            volume += a.dot(b.cross(c)) / 6.0;
        }
        for (&(u, v), &count) in &edges {
            assert_eq!(count, 1, "{name}: edge {u:?}→{v:?} used {count} times");
            assert_eq!(edges.get(&(v, u)), Some(&1), "{name}: edge {u:?}→{v:?} has no opposite: not closed");
        }
        volume
    }

    fn bounds((vertices, _): &(Vec<Vertex>, Vec<u32>)) -> (Vec3, Vec3) {
        vertices.iter().fold((Vec3::MAX, Vec3::MIN), |(lo, hi), v| {
            (lo.min(Vec3::from(v.position)), hi.max(Vec3::from(v.position)))
        })
    }

    fn assert_bounds(name: &str, mesh: &(Vec<Vertex>, Vec<u32>), lo: Vec3, hi: Vec3) {
        let (got_lo, got_hi) = bounds(mesh);
        assert!(got_lo.abs_diff_eq(lo, 1e-5) && got_hi.abs_diff_eq(hi, 1e-5), "{name}: bounds {got_lo}..{got_hi}");
    }

    fn assert_volume(name: &str, got: f32, want: f32, tolerance: f32) {
        assert!((got - want).abs() <= tolerance * want, "{name}: volume {got}, expected about {want}");
    }

    #[test]
    fn cuboid_is_closed_with_outward_normals() {
        let h = Vec3::new(0.5, 1.0, 2.0);
        let mesh = cuboid(h);
        assert_eq!((mesh.0.len(), mesh.1.len()), (24, 36));
        let volume = check("cuboid", &mesh, |_| Vec3::ZERO);
        assert_bounds("cuboid", &mesh, -h, h);
        assert_volume("cuboid", volume, 8.0 * h.x * h.y * h.z, 1e-5);
    }

    #[test]
    fn boxes_are_cuboids_moved_to_their_centres() {
        let (a, b) =
            ((Vec3::new(1.0, 0.0, 0.0), Vec3::splat(0.5)), (Vec3::new(-2.0, 1.0, 0.0), Vec3::new(0.25, 0.5, 1.0)));
        let mesh = boxes(&[a, b]);
        assert_eq!((mesh.0.len(), mesh.1.len()), (48, 72));
        // Each half is a closed box around its own centre.
        let half = |k: usize| {
            (
                mesh.0[24 * k..24 * (k + 1)].to_vec(),
                mesh.1[36 * k..36 * (k + 1)].iter().map(|i| i - 24 * k as u32).collect(),
            )
        };
        for (k, (centre, h)) in [a, b].into_iter().enumerate() {
            let part = half(k);
            let volume = check("box", &part, |_| centre);
            assert_bounds("box", &part, centre - h, centre + h);
            assert_volume("box", volume, 8.0 * h.x * h.y * h.z, 1e-5);
        }
    }

    #[test]
    fn sphere_is_closed_with_outward_normals() {
        let mesh = uv_sphere(0.7, 16, 8);
        let volume = check("sphere", &mesh, |_| Vec3::ZERO);
        for v in &mesh.0 {
            assert!((Vec3::from(v.position).length() - 0.7).abs() < 1e-5, "on the sphere");
        }
        assert_bounds("sphere", &mesh, Vec3::splat(-0.7), Vec3::splat(0.7));
        // A polyhedron inscribed in the sphere: a little smaller.
        assert_volume("sphere", volume, 4.0 / 3.0 * PI * 0.7f32.powi(3), 0.15);
        // The smallest allowed.
        check("coarse sphere", &uv_sphere(1.0, 0, 0), |_| Vec3::ZERO);
    }

    #[test]
    fn capsule_is_closed_with_outward_normals_and_stands_on_the_origin() {
        let (r, h) = (0.3, 1.8);
        let mesh = capsule(r, h, 16);
        let axis = |x: Vec3| Vec3::new(0.0, x.y.clamp(r, h - r), 0.0);
        let volume = check("capsule", &mesh, axis);
        assert_bounds("capsule", &mesh, Vec3::new(-r, 0.0, -r), Vec3::new(r, h, r));
        assert_volume("capsule", volume, PI * r * r * (h - 2.0 * r) + 4.0 / 3.0 * PI * r.powi(3), 0.1);
        // Height below 2r: a sphere on the ground.
        let ball = capsule(0.5, 0.2, 12);
        check("short capsule", &ball, |_| Vec3::new(0.0, 0.5, 0.0));
        assert_bounds("short capsule", &ball, Vec3::new(-0.5, 0.0, -0.5), Vec3::new(0.5, 1.0, 0.5));
    }

    #[test]
    fn cylinder_is_closed_with_outward_normals_and_stands_on_the_origin() {
        let (r, h) = (0.25, 0.1);
        let mesh = cylinder(r, h, 32);
        // Radial side normals and vertical cap normals all point away from the centre.
        let volume = check("cylinder", &mesh, |_| Vec3::new(0.0, h / 2.0, 0.0));
        assert_bounds("cylinder", &mesh, Vec3::new(-r, 0.0, -r), Vec3::new(r, h, r));
        assert_volume("cylinder", volume, PI * r * r * h, 0.01);
    }
}
