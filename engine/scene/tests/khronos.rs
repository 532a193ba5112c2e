//! The Khronos sample files the design names as conformance inputs.

mod common;

use common::close;
use glam::{Quat, Vec3};
use scene::{load_gltf, load_level, Material, Projection};

const BOX: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/testdata/khronos/Box.gltf");
const CAMERAS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/testdata/khronos/Cameras.gltf");

#[test]
fn box_gltf() {
    let scene = load_gltf(BOX.as_ref()).unwrap();
    assert_eq!(scene.meshes.len(), 1);
    let m = &scene.meshes[0];
    assert_eq!(m.indices.len(), 36);
    assert_eq!(m.vertices.len(), 24);
    assert_eq!(scene.materials.len(), 1);
    let mat = &scene.materials[m.material];
    assert!((mat.base_color[0] - 0.8).abs() < 1e-6);
    assert_eq!(&mat.base_color[1..], &[0.0, 0.0, 1.0]);
    // The root matrix swaps Y and Z; the unit box stays a unit box.
    let b = scene.bounds();
    close(b.min, Vec3::splat(-0.5));
    close(b.max, Vec3::splat(0.5));
    // Every triangle's winding agrees with its normals (outward faces).
    for t in 0..12 {
        let n = Vec3::from(m.vertices[m.indices[3 * t] as usize].normal);
        assert!(common::tri_normal(m, t).dot(n) > 0.99, "triangle {t}");
        let centre = Vec3::from(m.vertices[m.indices[3 * t] as usize].position);
        assert!(centre.dot(n) > 0.0, "normal of triangle {t} points outward");
    }
}

#[test]
fn cameras_gltf() {
    let scene = load_gltf(CAMERAS.as_ref()).unwrap();
    assert_eq!(scene.cameras.len(), 2);
    let c = &scene.cameras[0];
    close(c.position, [0.5, 0.5, 3.0]);
    assert!(matches!(c.projection, Projection::Perspective { yfov, .. } if (yfov - 0.7).abs() < 1e-6));
    close(c.forward(), Vec3::NEG_Z);
    assert!(matches!(scene.cameras[1].projection, Projection::Orthographic { .. }));

    // The quad (facing +Z) is rotated by the node quaternion (about -45° around X).
    let m = &scene.meshes[0];
    assert_eq!(m.indices.len(), 6);
    assert_eq!(m.vertices.len(), 6, "no normals: flat normals, vertices un-shared");
    let q = Quat::from_xyzw(-0.383, 0.0, 0.0, 0.924).normalize();
    let expected = q * Vec3::Z;
    for v in &m.vertices {
        close(v.normal, expected);
    }
    close(m.vertices[2].position, q * Vec3::Y);
    assert_eq!(scene.materials[m.material], Material::default());
}

#[test]
fn bare_gltf_file_is_a_level() {
    let level = load_level(BOX.as_ref()).unwrap();
    assert_eq!(level.name, "Box");
    assert!(level.root.is_none());
    assert_eq!(level.scene.triangle_count(), 12);
}
