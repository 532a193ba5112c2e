//! The Khronos sample files the design names as conformance inputs.

mod common;

use common::close;
use glam::{Quat, Vec3};
use scene::{load_gltf, load_level, Filter, Material, Projection, Sampler, Wrap};

const BOX: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/testdata/khronos/Box.gltf");
const CAMERAS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/testdata/khronos/Cameras.gltf");
const BOX_VERTEX_COLORS: &str =
    concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/testdata/khronos/BoxVertexColors.gltf");
const BOX_TEXTURED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/testdata/khronos/BoxTextured.gltf");

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
    assert_eq!(scene.materials[m.material], Material::gltf_default());
}

#[test]
fn bare_gltf_file_is_a_level() {
    let level = load_level(BOX.as_ref()).unwrap();
    assert_eq!(level.name, "Box");
    assert!(level.root.is_none());
    assert_eq!(level.scene.triangle_count(), 12);
}

#[test]
fn box_vertex_colors_keeps_its_colours_and_warns_about_nothing() {
    let level = load_level(BOX_VERTEX_COLORS.as_ref()).unwrap();
    assert_eq!(level.warnings, vec![]);
    let scene = &level.scene;
    let colours: Vec<[f32; 4]> = scene.meshes.iter().flat_map(|m| m.vertices.iter().map(|v| v.color)).collect();
    let mut distinct: Vec<[u32; 4]> = colours.iter().map(|c| c.map(f32::to_bits)).collect();
    distinct.sort();
    distinct.dedup();
    assert_eq!(distinct.len(), 7, "COLOR_0 read: the file's 7 distinct RGBA colours");
    assert!(colours.iter().all(|c| c.iter().all(|v| (0.0..=1.0).contains(v))), "{colours:?}");
    assert!(colours.iter().any(|c| c[0] > 0.99 && c[1] < 0.01), "a red corner");
    // VEC4: the (near-zero) alphas are kept; the material is OPAQUE, so they are not used.
    assert!(colours.iter().any(|c| c[3] < 0.01));
    assert_eq!(scene.materials[scene.meshes[0].material].base_color, [0.8, 0.8, 0.8, 1.0]);
}

#[test]
fn box_textured_keeps_its_sampler() {
    let level = load_level(BOX_TEXTURED.as_ref()).unwrap();
    assert_eq!(level.warnings, vec![]);
    let texture = level.scene.materials[0].base_color_texture.unwrap();
    // magFilter LINEAR, minFilter NEAREST_MIPMAP_LINEAR, REPEAT both ways.
    let want = Sampler {
        wrap_u: Wrap::Repeat,
        wrap_v: Wrap::Repeat,
        mag_filter: Filter::Linear,
        min_filter: Filter::Nearest,
        mipmap_filter: Some(Filter::Linear),
    };
    assert_eq!(texture.sampler, want);
}
