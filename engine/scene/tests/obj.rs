//! OBJ + MTL loading.

mod common;

use common::*;
use glam::Vec3;
use scene::{load_obj, load_scene_file, Material};

const QUAD_OBJ: &str = "\
mtllib quad.mtl
o Floor
v 0 0 0
v 1 0 0
v 1 0 -1
v 0 0 -1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 1 0
usemtl wood
f 1/1/1 2/2/1 3/3/1 4/4/1
";

#[test]
fn obj_with_mtl_colour_and_texture() {
    let dir = TempDir::new("objmtl");
    dir.write("tex/wood.png", png(2, 2, &[10, 20, 30, 255, 40, 50, 60, 255, 70, 80, 90, 255, 100, 110, 120, 255]));
    dir.write("quad.mtl", "newmtl wood\nKd 0.5 0.25 0.125\nKe 1 2 3\nmap_Kd -s 1 1 1 tex/wood.png\n");
    let path = dir.write("quad.obj", QUAD_OBJ);
    let scene = load_obj(&path).unwrap();
    assert_eq!(scene.meshes.len(), 1);
    let m = &scene.meshes[0];
    assert_eq!(m.name, "Floor");
    assert_eq!(m.indices.len(), 6, "quad triangulated");
    assert_eq!(m.vertices.len(), 4, "normals present: vertices shared (single index)");
    for v in &m.vertices {
        close(v.normal, Vec3::Y);
    }
    // V flipped: vt (1,1) at vertex 3 becomes uv (1,0).
    let v3 = m.vertices.iter().find(|v| v.position == [1.0, 0.0, -1.0]).unwrap();
    assert_eq!(v3.uv, [1.0, 0.0]);
    let v1 = m.vertices.iter().find(|v| v.position == [0.0, 0.0, 0.0]).unwrap();
    assert_eq!(v1.uv, [0.0, 1.0]);
    // Front faces point up, along the normals.
    close(tri_normal(m, 0), Vec3::Y);

    let mat = &scene.materials[m.material];
    assert_eq!(mat.name, "wood");
    assert_eq!(mat.base_color, [0.5, 0.25, 0.125, 1.0]);
    assert_eq!(mat.emissive, [1.0, 2.0, 3.0]);
    let tex = &scene.textures[mat.base_color_texture.unwrap().texture];
    assert_eq!((tex.width, tex.height), (2, 2));
    assert_eq!(tex.name, "wood.png");
    assert_eq!(&tex.rgba8[..4], &[10, 20, 30, 255]);
}

#[test]
fn obj_without_normals_gets_flat_normals() {
    let dir = TempDir::new("objflat");
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\n";
    let scene = load_obj(&dir.write("tet.OBJ", obj)).unwrap();
    let m = &scene.meshes[0];
    assert_eq!(m.vertices.len(), 6);
    close(m.vertices[0].normal, Vec3::Z);
    close(m.vertices[3].normal, Vec3::Y);
    for t in 0..2 {
        close(tri_normal(m, t), m.vertices[3 * t].normal);
    }
    assert_eq!(scene.materials[m.material], Material::default());
    // Dispatch by extension is case-insensitive.
    assert_eq!(load_scene_file(&dir.path().join("tet.OBJ")).unwrap(), scene);
}

#[test]
fn missing_mtl_falls_back_to_default_material() {
    let dir = TempDir::new("objnomtl");
    let obj = "mtllib gone.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let scene = load_obj(&dir.write("a.obj", obj)).unwrap();
    assert_eq!(scene.materials, [Material::default()]);
    assert_eq!(scene.meshes[0].material, 0);
}

#[test]
fn single_value_kd_and_texture_without_kd() {
    let dir = TempDir::new("objkd");
    dir.write("w.png", png(1, 1, &[1, 2, 3, 255]));
    dir.write("m.mtl", "newmtl grey\nKd 0.3\nnewmtl tex\nmap_Kd w.png\nd 0.5\n");
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\nusemtl tex\nf 1 2 3\n";
    let scene = load_obj(&dir.write("a.obj", obj)).unwrap();
    assert_eq!(scene.meshes.len(), 2);
    let grey = &scene.materials[scene.meshes[0].material];
    assert_eq!(grey.base_color, [0.3, 0.3, 0.3, 1.0]);
    let tex = &scene.materials[scene.meshes[1].material];
    assert_eq!(tex.base_color, [1.0, 1.0, 1.0, 0.5], "map_Kd without Kd: texture unscaled");
    assert!(tex.base_color_texture.is_some());
}
