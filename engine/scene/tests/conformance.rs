//! The project's glTF conformance samples (crate `gltf-conformance`), loaded as a user's file
//! would be. Expectations come from the samples' declared constants; where a node transform is
//! involved, world positions are also worked out by hand here, independently of glam.

mod common;

use common::{close, tri_normal, TempDir};
use glam::{Quat, Vec3};
use gltf_conformance as samples;
use scene::{load_level, AlphaMode, Filter, Level, Material, Mesh, Projection, Sampler, Texture, Vertex, Wrap};

/// Writes the sample `file` (a name in [`samples::SAMPLES`]) and loads it as a bare-file level.
fn load(file: &str) -> Level {
    let (_, sample) = samples::SAMPLES.iter().find(|(name, _)| *name == file).expect("a sample of that name");
    let dir = TempDir::new("conformance");
    load_level(&samples::write(dir.path(), file, &sample())).unwrap()
}

fn mesh<'a>(level: &'a Level, name: &str) -> &'a Mesh {
    level.scene.meshes.iter().find(|m| m.name == name).unwrap_or_else(|| panic!("no mesh {name}"))
}

/// The vertex of `mesh` at `position` with `normal` (a cube corner is in three faces).
fn vertex_at(mesh: &Mesh, position: [f32; 3], normal: [f32; 3]) -> &Vertex {
    let near = |a: [f32; 3], b: [f32; 3]| (Vec3::from(a) - Vec3::from(b)).length() < 1e-5;
    mesh.vertices.iter().find(|v| near(v.position, position) && near(v.normal, normal)).unwrap()
}

/// The texel a uv falls in (nearest, clamped); glTF's uv (0, 0) is the image's top-left.
fn texel(t: &Texture, uv: [f32; 2]) -> [u8; 4] {
    let x = ((uv[0] * t.width as f32) as u32).min(t.width - 1);
    let y = ((uv[1] * t.height as f32) as u32).min(t.height - 1);
    let i = 4 * (y * t.width + x) as usize;
    t.rgba8[i..i + 4].try_into().unwrap()
}

const RED: [u8; 4] = [255, 0, 0, 255];
const GREEN: [u8; 4] = [0, 255, 0, 255];
const BLUE: [u8; 4] = [0, 0, 255, 255];
const WHITE: [u8; 4] = [255; 4];

#[test]
fn every_sample_loads_as_a_level_without_warnings() {
    for (file, _) in samples::SAMPLES {
        let level = load(file);
        assert_eq!(level.warnings, vec![], "{file}");
        assert_eq!(level.name, file.trim_end_matches(".gltf"));
        assert!(level.root.is_none(), "{file} is a bare file");
        assert!(level.scene.triangle_count() > 0, "{file}");
    }
}

#[test]
fn red_box_composes_the_root_matrix_with_its_child() {
    let level = load("red_box.gltf");
    let scene = &level.scene;
    assert_eq!(scene.meshes.len(), 1);
    let m = &scene.meshes[0];
    assert_eq!((m.vertices.len(), m.indices.len()), (24, 36));
    assert_eq!(scene.triangle_count(), 12);
    assert_eq!(scene.materials.len(), 1);
    assert_eq!(scene.materials[m.material].base_color, samples::RED);
    // The child scales the unit cube to 1 × 3 × 1 and moves it 2 up its Y; the root's matrix
    // turns +Y to -Z (and +Z to +Y): 1 × 1 × 3 centred on (0, 0, -2).
    let centre = Vec3::new(0.0, 0.0, -2.0);
    let b = scene.bounds();
    close(b.min, [-0.5, -0.5, -3.5]);
    close(b.max, [0.5, 0.5, -0.5]);
    // Every triangle's winding agrees with its normal, and the normal points outward.
    for t in 0..12 {
        let v = &m.vertices[m.indices[3 * t] as usize];
        let n = Vec3::from(v.normal);
        assert!(tri_normal(m, t).dot(n) > 0.99, "triangle {t}");
        assert!((Vec3::from(v.position) - centre).dot(n) > 0.0, "normal of triangle {t} points outward");
    }
    // The cube's +Y face ends up facing -Z.
    assert_eq!(m.vertices.iter().filter(|v| (Vec3::from(v.normal) - Vec3::NEG_Z).length() < 1e-5).count(), 4);
}

#[test]
fn cameras_take_their_pose_and_projection_from_their_nodes() {
    let level = load("cameras.gltf");
    let scene = &level.scene;
    assert_eq!(scene.cameras.len(), 2);

    let c = &scene.cameras[0];
    assert_eq!(c.name, "perspective");
    close(c.position, samples::PERSPECTIVE_AT);
    let want = Projection::Perspective { yfov: 0.7, aspect: Some(1.5), znear: 0.05, zfar: Some(50.0) };
    assert_eq!(c.projection, want);
    // Turned 30° left about +Y: -Z becomes (-sin 30°, 0, -cos 30°).
    close(c.forward(), [-0.5, 0.0, -0.75f32.sqrt()]);
    close(c.rotation * Vec3::Y, Vec3::Y);
    // It looks at the quad's centre: (0.5, 0.5, 0) turned -45° about X.
    let quad_centre = Vec3::new(0.5, 0.5 * 0.5f32.sqrt(), -0.5 * 0.5f32.sqrt());
    let to_quad = quad_centre - c.position;
    assert!(to_quad.reject_from(c.forward()).length() < 0.01, "the quad is off the view axis");

    let c = &scene.cameras[1];
    assert_eq!(c.name, "orthographic");
    close(c.position, samples::ORTHOGRAPHIC_AT);
    assert_eq!(c.projection, Projection::Orthographic { xmag: 0.8, ymag: 0.6, znear: 0.01, zfar: 10.0 });
    // Turned -90° about X: it looks down, its up along -Z.
    close(c.forward(), Vec3::NEG_Y);
    close(c.rotation * Vec3::Y, Vec3::NEG_Z);

    // The quad (facing +Z) is turned by the node's quaternion, -45° about X.
    let m = &scene.meshes[0];
    assert_eq!(m.indices.len(), 6);
    assert_eq!(m.vertices.len(), 6, "no normals: flat normals, vertices un-shared");
    let q = Quat::from_array(samples::QUAD_ROTATION);
    for v in &m.vertices {
        close(v.normal, q * Vec3::Z);
        close(v.normal, [0.0, 0.5f32.sqrt(), 0.5f32.sqrt()]);
    }
    close(m.vertices[2].position, [1.0, 0.5f32.sqrt(), -(0.5f32.sqrt())]);
    assert_eq!(scene.materials[m.material], Material::gltf_default());
}

#[test]
fn vertex_colours_are_read_in_every_encoding() {
    let level = load("vertex_colours.gltf");
    let scene = &level.scene;
    assert_eq!(scene.meshes.len(), samples::COLOUR_ENCODINGS.len(), "one mesh per primitive");
    for (k, (component, ty)) in samples::COLOUR_ENCODINGS.into_iter().enumerate() {
        let m = mesh(&level, &format!("colours#{k}"));
        let colours: Vec<[f32; 4]> = m.vertices.iter().map(|v| v.color).collect();
        for (i, (got, want)) in colours.iter().zip(samples::CORNER_COLOURS).enumerate() {
            // RGB only: alpha 1.
            let alpha = if ty == "VEC4" { f32::from(want[3]) / 255.0 } else { 1.0 };
            let want = [want[0], want[1], want[2]].map(|c| f32::from(c) / 255.0);
            let want = [want[0], want[1], want[2], alpha];
            let error = got.iter().zip(want).map(|(g, w)| (g - w).abs()).fold(0.0, f32::max);
            assert!(error < 1e-6, "primitive {k} ({component} {ty}) vertex {i}: {got:?}, expected {want:?}");
        }
        for (i, a) in colours.iter().enumerate() {
            assert!(colours[i + 1..].iter().all(|b| b != a), "primitive {k}: the corners' colours are distinct");
        }
    }
    // A few by hand: a red corner, green with its alpha dropped (VEC3), blue with alpha 0 (VEC4).
    assert_eq!(mesh(&level, "colours#0").vertices[0].color, [1.0, 0.0, 0.0, 1.0]);
    assert_eq!(mesh(&level, "colours#3").vertices[1].color, [0.0, 1.0, 0.0, 1.0]);
    assert_eq!(mesh(&level, "colours#4").vertices[2].color, [0.0, 0.0, 1.0, 0.0]);
    // One material for all; OPAQUE, so the alphas are kept but not used.
    assert_eq!(scene.materials.len(), 1);
    assert_eq!(scene.materials[0].base_color, samples::GREY);
    assert_eq!(scene.materials[0].alpha_mode, AlphaMode::Opaque);
}

#[test]
fn textured_box_keeps_its_texture_and_sampler() {
    let level = load("textured_box.gltf");
    let scene = &level.scene;
    let tex = scene.materials[0].base_color_texture.unwrap();
    // magFilter LINEAR, minFilter NEAREST_MIPMAP_LINEAR, wrapS REPEAT, wrapT MIRRORED_REPEAT.
    let want = Sampler {
        wrap_u: Wrap::Repeat,
        wrap_v: Wrap::MirroredRepeat,
        mag_filter: Filter::Linear,
        min_filter: Filter::Nearest,
        mipmap_filter: Some(Filter::Linear),
    };
    assert_eq!(tex.sampler, want);
    assert_eq!(tex.tex_coord, 0);
    let image = &scene.textures[tex.texture];
    assert_eq!((image.width, image.height), (2, 2));
    assert_eq!(image.rgba8, [RED, GREEN, BLUE, WHITE].as_flattened(), "rows from the top, not flipped");
    // Upright on every side: each face's top-left corner seen from outside shows the image's
    // top-left (red), its bottom-right the bottom-right (white).
    let m = &scene.meshes[0];
    let faces = [
        ([0.0, 0.0, 1.0], [-0.5, 0.5, 0.5], [0.5, -0.5, 0.5]),
        ([1.0, 0.0, 0.0], [0.5, 0.5, 0.5], [0.5, -0.5, -0.5]),
        ([0.0, 0.0, -1.0], [0.5, 0.5, -0.5], [-0.5, -0.5, -0.5]),
        ([-1.0, 0.0, 0.0], [-0.5, 0.5, -0.5], [-0.5, -0.5, 0.5]),
        ([0.0, 1.0, 0.0], [-0.5, 0.5, -0.5], [0.5, 0.5, 0.5]),
    ];
    for (normal, top_left, bottom_right) in faces {
        assert_eq!(texel(image, vertex_at(m, top_left, normal).uv), RED, "face {normal:?}");
        assert_eq!(texel(image, vertex_at(m, bottom_right, normal).uv), WHITE, "face {normal:?}");
    }
}

#[test]
fn texture_coordinates_reach_the_vertices_with_the_origin_at_the_top_left() {
    let level = load("texture_coordinates.gltf");
    let scene = &level.scene;
    let m = &scene.meshes[0];
    assert_eq!(m.vertices.len(), 4);
    for (v, (position, uv)) in m.vertices.iter().zip(samples::TEXCOORD_CORNERS) {
        close(v.position, position);
        assert_eq!(v.uv, uv);
    }
    // Seen from +Z (where its camera is), each corner shows the image's corner on the same side.
    let tex = scene.materials[m.material].base_color_texture.unwrap();
    let image = &scene.textures[tex.texture];
    for v in &m.vertices {
        let want = match (v.position[0] < 0.0, v.position[1] > 0.0) {
            (true, true) => RED,
            (false, true) => GREEN,
            (true, false) => BLUE,
            (false, false) => WHITE,
        };
        assert_eq!(texel(image, v.uv), want, "corner at {:?}", v.position);
    }
    for t in 0..2 {
        assert!(tri_normal(m, t).dot(Vec3::Z) > 0.99, "triangle {t} faces the camera");
    }
    assert_eq!(tex.sampler.mag_filter, Filter::Nearest);
    assert_eq!((tex.sampler.wrap_u, tex.sampler.wrap_v), (Wrap::ClampToEdge, Wrap::ClampToEdge));
    let c = &scene.cameras[0];
    close(c.position, [0.0, 0.0, samples::TEXCOORD_CAMERA_DISTANCE]);
    close(c.forward(), Vec3::NEG_Z);
    assert!(matches!(c.projection, Projection::Perspective { yfov, .. } if ((yfov / 2.0).tan() - 0.5).abs() < 1e-6));
}

#[test]
fn orientation_turns_scales_and_mirrors_as_the_spec_says() {
    let level = load("orientation.gltf");
    assert_eq!(level.scene.meshes.len(), 5);
    // The arrow (0,0,0), (1,0,0), (0,2,0) facing +Z, placed by hand.
    type Triangle = [[f32; 3]; 3];
    let cases: [(&str, Triangle, [f32; 3]); 5] = [
        // 90° about +Z: +X → +Y, +Y → -X; then +5 X.
        ("quaternion", [[5.0, 0.0, 0.0], [5.0, 1.0, 0.0], [3.0, 0.0, 0.0]], [0.0, 0.0, 1.0]),
        // 90° about +X: +Y → +Z, +Z → -Y; then +5 Y.
        ("matrix", [[0.0, 5.0, 0.0], [1.0, 5.0, 0.0], [0.0, 5.0, 2.0]], [0.0, -1.0, 0.0]),
        // X doubled, then 90° about +Y: +X → -Z, +Z → +X; then +5 Z.
        ("scaled", [[0.0, 0.0, 5.0], [0.0, 0.0, 3.0], [0.0, 2.0, 5.0]], [1.0, 0.0, 0.0]),
        // X negated, then -5 X: the face still faces +Z, its winding reversed to match.
        ("mirrored", [[-5.0, 0.0, 0.0], [-6.0, 0.0, 0.0], [-5.0, 2.0, 0.0]], [0.0, 0.0, 1.0]),
        // +1 X in a parent turned 90° about +Z and moved -5 Y.
        ("child", [[0.0, -4.0, 0.0], [0.0, -3.0, 0.0], [-2.0, -4.0, 0.0]], [0.0, 0.0, 1.0]),
    ];
    for (name, positions, normal) in cases {
        let m = mesh(&level, name);
        assert_eq!(m.vertices.len(), 3, "{name}");
        for (v, p) in m.vertices.iter().zip(positions) {
            close(v.position, p);
            close(v.normal, normal);
        }
        assert!(tri_normal(m, 0).dot(Vec3::from(normal)) > 0.99, "{name}: winding agrees with the normal");
    }
}

#[test]
fn several_meshes_and_a_primitive_without_indices() {
    let level = load("simple_meshes.gltf");
    let scene = &level.scene;
    let names: Vec<&str> = scene.meshes.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["triangle", "triangle", "unindexed"], "one mesh per node, in node order");
    assert_eq!(scene.triangle_count(), 4);
    // The second node instances the first's mesh 2 along X.
    for (v, p) in scene.meshes[1].vertices.iter().zip(samples::TRI) {
        close(v.position, Vec3::from(p) + Vec3::new(2.0, 0.0, 0.0));
    }
    // No indices: the positions are the triangle list, in order.
    let m = &scene.meshes[2];
    assert_eq!(m.indices, (0..6).collect::<Vec<u32>>());
    assert_eq!(m.vertices.len(), 6);
    for (v, p) in m.vertices.iter().zip(samples::UNINDEXED) {
        close(v.position, Vec3::from(p) + Vec3::new(4.0, 0.0, 0.0));
        close(v.normal, Vec3::Z);
    }
    // No materials: every primitive gets the spec's default one, converted once.
    assert_eq!(scene.materials, [Material::gltf_default()]);
    assert!(scene.meshes.iter().all(|m| m.material == 0));
}
