//! glTF loading: hierarchy, buffers (embedded, external, GLB), indices, normals, materials,
//! textures, cameras, lights, extras; vertex colours, the second uv set, samplers, alpha modes,
//! sidedness, emissive textures and strength, texture transforms.

mod common;

use common::*;
use glam::{Quat, Vec3};
use scene::{
    load_gltf, load_level, load_scene_file, AlphaMode, Filter, LightKind, Material, Projection, Reflection, Sampler,
    Scene, TextureTransform, Wrap,
};
use serde_json::{json, Value};

const S: f32 = std::f32::consts::FRAC_1_SQRT_2;

#[test]
fn hierarchy_composes_trs_parent_and_matrix_child() {
    let dir = TempDir::new("hier");
    let mut bin = Bin::default();
    // A tilted triangle with its true normal (0,-1,1)/√2.
    let pos = bin.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 1.0]]);
    let nrm = bin.vec3(&[[0.0, -S, S]; 3]);
    // Child: translate (1,0,0) then non-uniform scale (1,3,1), column-major.
    let child = [1.0, 0.0, 0.0, 0.0, 0.0, 3.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0];
    let doc = bin.gltf(json!({
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"name": "parent", "translation": [1.0, 2.0, 3.0], "rotation": [0.0, S, 0.0, S], "scale": [2.0, 2.0, 2.0], "children": [1]},
            {"name": "child", "matrix": child, "mesh": 0}
        ],
        "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm}}]}],
    }));
    let scene = load_gltf(&write_json(&dir, "h.gltf", &doc)).unwrap();
    assert_eq!(scene.meshes.len(), 1);
    let m = &scene.meshes[0];
    assert_eq!(m.name, "tri");
    assert_eq!(m.indices, [0, 1, 2]);
    // (0,1,1) → child (1,3,1) → scale 2 (2,6,2) → rotY90 (2,6,-2) → translate (3,8,1).
    close(m.vertices[2].position, [3.0, 8.0, 1.0]);
    close(m.vertices[0].position, [1.0, 2.0, 1.0]);
    // Inverse-transpose: (0,-1,1) → (0,-1/3,1) ∝ (0,-1,3) → rotY90 → (3,-1,0)/√10.
    let expected = Vec3::new(3.0, -1.0, 0.0).normalize();
    for v in &m.vertices {
        close(v.normal, expected);
    }
    // And that matches the baked triangle's own orientation.
    assert!(tri_normal(m, 0).dot(expected) > 0.999);
}

#[test]
fn base64_embedded_buffer_and_u16_indices() {
    let dir = TempDir::new("b64");
    let mut bin = Bin::default();
    let pos = bin.vec3(&QUAD);
    let idx = bin.u16s(&[0, 1, 2, 0, 2, 3]);
    let doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos}, "indices": idx}));
    let scene = load_gltf(&write_json(&dir, "q.gltf", &doc)).unwrap();
    assert_eq!(scene.triangle_count(), 2);
    let m = &scene.meshes[0];
    // No normals: flat shading un-shares the vertices.
    assert_eq!(m.vertices.len(), 6);
    assert_eq!(m.indices, [0, 1, 2, 3, 4, 5]);
    close(m.vertices[2].position, QUAD[2]);
    close(m.vertices[5].position, QUAD[3]);
}

#[test]
fn u8_and_u32_indices() {
    let dir = TempDir::new("idx");
    for kind in ["u8", "u32"] {
        let mut bin = Bin::default();
        let pos = bin.vec3(&QUAD);
        let nrm = bin.vec3(&[[0.0, 0.0, 1.0]; 4]);
        let idx = if kind == "u8" { bin.u8s(&[0, 1, 2, 0, 2, 3]) } else { bin.u32s(&QUAD_INDICES) };
        let doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos, "NORMAL": nrm}, "indices": idx}));
        let scene = load_gltf(&write_json(&dir, &format!("{kind}.gltf"), &doc)).unwrap();
        let m = &scene.meshes[0];
        assert_eq!(m.indices, QUAD_INDICES, "{kind}");
        assert_eq!(m.vertices.len(), 4, "{kind}: normals given, vertices stay shared");
        close(m.vertices[2].position, QUAD[2]);
    }
}

#[test]
fn non_indexed_primitive() {
    let dir = TempDir::new("nonidx");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let nrm = bin.vec3(&[[0.0, 0.0, 1.0]; 3]);
    let uv = bin.vec2(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    let doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}}));
    let scene = load_gltf(&write_json(&dir, "t.gltf", &doc)).unwrap();
    let m = &scene.meshes[0];
    assert_eq!(m.indices, [0, 1, 2]);
    assert_eq!(m.vertices[1].uv, [1.0, 0.0]);
    assert_eq!(m.vertices[2].uv, [0.0, 1.0]);
}

#[test]
fn missing_normals_give_flat_normals_perpendicular_to_each_triangle() {
    let dir = TempDir::new("flat");
    let mut bin = Bin::default();
    // Two triangles of a tent: different planes.
    let pos = bin.vec3(&[
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.5, 1.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [0.5, 1.0, 1.0],
    ]);
    let doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos}}));
    let scene = load_gltf(&write_json(&dir, "tent.gltf", &doc)).unwrap();
    let m = &scene.meshes[0];
    assert_eq!(m.vertices.len(), 6);
    for t in 0..2 {
        let geometric = tri_normal(m, t);
        for k in 0..3 {
            let v = &m.vertices[m.indices[3 * t + k] as usize];
            close(v.normal, geometric);
            let p0 = Vec3::from(m.vertices[m.indices[3 * t] as usize].position);
            let p1 = Vec3::from(m.vertices[m.indices[3 * t + 1] as usize].position);
            assert!(Vec3::from(v.normal).dot(p1 - p0).abs() < 1e-5);
        }
    }
    // Missing TEXCOORD_0 → zeros.
    assert!(m.vertices.iter().all(|v| v.uv == [0.0, 0.0]));
}

#[test]
fn primitives_without_material_share_one_default_material() {
    let dir = TempDir::new("defmat");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let doc = bin.gltf(json!({
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"mesh": 0, "translation": [5.0, 0.0, 0.0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos}}, {"attributes": {"POSITION": pos}, "material": 0}]}],
        "materials": [{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.0, 0.0, 1.0]}, "emissiveFactor": [0.5, 0.25, 0.0]}],
    }));
    let scene = load_gltf(&write_json(&dir, "m.gltf", &doc)).unwrap();
    assert_eq!(scene.meshes.len(), 4, "two nodes instancing a two-primitive mesh");
    assert_eq!(scene.materials.len(), 2, "default added once, red once");
    let default = &scene.materials[scene.meshes[0].material];
    assert_eq!(*default, Material::gltf_default());
    assert_eq!(scene.meshes[0].material, scene.meshes[2].material);
    let red = &scene.materials[scene.meshes[1].material];
    assert_eq!(red.name, "red");
    assert_eq!(red.base_color, [1.0, 0.0, 0.0, 1.0]);
    assert_eq!(red.emissive, [0.5, 0.25, 0.0]);
    close(scene.meshes[2].vertices[1].position, [6.0, 0.0, 0.0]);
}

#[test]
fn glb_container() {
    let dir = TempDir::new("glb");
    let mut bin = Bin::default();
    let pos = bin.vec3(&QUAD);
    let idx = bin.u16s(&[0, 1, 2, 0, 2, 3]);
    let doc = bin.gltf_with_buffer(
        json!({"scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}]}),
        json!({"byteLength": bin.data.len()}),
    );
    let path = dir.write("q.glb", glb(&doc, &bin.data));
    let scene = load_gltf(&path).unwrap();
    assert_eq!(scene.triangle_count(), 2);
    // The extension check is case-insensitive, and the loader is chosen by it.
    let upper = dir.write("Q.GLB", glb(&doc, &bin.data));
    assert_eq!(load_scene_file(&upper).unwrap(), scene);
}

#[test]
fn external_bin_buffer_with_percent_encoded_name() {
    let dir = TempDir::new("extbin");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    dir.write("my geo.bin", &bin.data);
    let doc = bin.gltf_with_buffer(
        json!({"scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": pos}}]}]}),
        json!({"byteLength": bin.data.len(), "uri": "my%20geo.bin"}),
    );
    let scene = load_gltf(&write_json(&dir, "ext.gltf", &doc)).unwrap();
    close(scene.meshes[0].vertices[1].position, TRI[1]);
}

#[test]
fn strips_and_fans_become_lists_with_front_faces_kept() {
    let dir = TempDir::new("strip");
    let mut bin = Bin::default();
    // Strip order for the quad: 0,1,3,2 (bottom-left, bottom-right, top-left, top-right).
    let strip = bin.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]);
    let fan = bin.vec3(&QUAD);
    let points = bin.vec3(&TRI);
    let doc = bin.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": strip}, "mode": 5},
            {"attributes": {"POSITION": fan}, "mode": 6},
            {"attributes": {"POSITION": points}, "mode": 0}
        ]}],
    }));
    let scene = load_gltf(&write_json(&dir, "s.gltf", &doc)).unwrap();
    assert_eq!(scene.meshes.len(), 2, "POINTS skipped");
    for m in &scene.meshes {
        assert_eq!(m.indices.len(), 6);
        for t in 0..2 {
            close(tri_normal(m, t), Vec3::Z);
        }
    }
}

#[test]
fn mirroring_transform_flips_winding() {
    let dir = TempDir::new("mirror");
    let mut bin = Bin::default();
    let pos = bin.vec3(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]]); // faces +Y
    let nrm = bin.vec3(&[[0.0, 1.0, 0.0]; 3]);
    let doc = bin.gltf(json!({
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [
            {"mesh": 0, "scale": [-1.0, 1.0, 1.0]},
            {"mesh": 0, "scale": [1.0, -1.0, 1.0]}
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm}}]}],
    }));
    let scene = load_gltf(&write_json(&dir, "mirror.gltf", &doc)).unwrap();
    // Mirrored in X: still faces +Y, winding reversed to stay CCW.
    close(scene.meshes[0].vertices[0].normal, Vec3::Y);
    close(tri_normal(&scene.meshes[0], 0), Vec3::Y);
    // Mirrored in Y: now faces -Y.
    close(scene.meshes[1].vertices[0].normal, Vec3::NEG_Y);
    close(tri_normal(&scene.meshes[1], 0), Vec3::NEG_Y);
}

#[test]
fn cameras_perspective_and_orthographic_with_world_pose() {
    let dir = TempDir::new("cam");
    let bin = Bin::default();
    let q = Quat::from_rotation_y(0.5);
    let doc = bin.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"translation": [0.0, 1.0, 0.0], "scale": [2.0, 2.0, 2.0], "children": [1, 2]},
            {"name": "eye", "camera": 0, "translation": [0.0, 0.0, 5.0], "rotation": [q.x, q.y, q.z, q.w]},
            {"camera": 1}
        ],
        "cameras": [
            {"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1, "zfar": 50.0}},
            {"type": "orthographic", "name": "top", "orthographic": {"xmag": 3.0, "ymag": 2.0, "znear": 0.5, "zfar": 20.0}}
        ],
    }));
    let scene = load_gltf(&write_json(&dir, "c.gltf", &doc)).unwrap();
    assert_eq!(scene.cameras.len(), 2);
    let c = &scene.cameras[0];
    assert_eq!(c.name, "eye");
    close(c.position, [0.0, 1.0, 10.0]);
    assert!(c.rotation.angle_between(q) < 1e-4, "scale stripped, rotation kept");
    close(c.forward(), q * Vec3::NEG_Z);
    assert_eq!(c.projection, Projection::Perspective { yfov: 0.8, aspect: Some(1.5), znear: 0.1, zfar: Some(50.0) });
    let o = &scene.cameras[1];
    assert_eq!(o.name, "top");
    close(o.position, [0.0, 1.0, 0.0]);
    assert_eq!(o.projection, Projection::Orthographic { xmag: 3.0, ymag: 2.0, znear: 0.5, zfar: 20.0 });
}

#[test]
fn punctual_lights_with_world_position_and_direction() {
    let dir = TempDir::new("lights");
    let bin = Bin::default();
    let down = [-S, 0.0, 0.0, S]; // -90° about X: local -Z → world -Y
    let doc = bin.gltf(json!({
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "name": "bulb", "color": [1.0, 0.5, 0.25], "intensity": 10.0, "range": 5.0},
            {"type": "spot", "intensity": 4.0, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
            {"type": "directional", "intensity": 3.0}
        ]}},
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"translation": [0.0, 3.0, 0.0], "children": [1, 2, 3]},
            {"translation": [1.0, 0.0, 0.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "spot node", "rotation": down, "extensions": {"KHR_lights_punctual": {"light": 1}}},
            {"rotation": [0.0, S, 0.0, S], "extensions": {"KHR_lights_punctual": {"light": 2}}}
        ],
    }));
    let scene = load_gltf(&write_json(&dir, "l.gltf", &doc)).unwrap();
    assert_eq!(scene.lights.len(), 3);
    let [point, spot, sun] = [&scene.lights[0], &scene.lights[1], &scene.lights[2]];
    assert_eq!(point.name, "bulb");
    assert_eq!(point.kind, LightKind::Point);
    close(point.position, [1.0, 3.0, 0.0]);
    assert_eq!(point.color, [1.0, 0.5, 0.25]);
    assert_eq!(point.intensity, 10.0);
    assert_eq!(point.range, Some(5.0));

    assert_eq!(spot.name, "spot node");
    assert_eq!(spot.kind, LightKind::Spot { inner_cone: 0.2, outer_cone: 0.5 });
    close(spot.position, [0.0, 3.0, 0.0]);
    close(spot.direction, Vec3::NEG_Y);
    assert_eq!(spot.range, None);

    assert_eq!(sun.kind, LightKind::Directional);
    close(sun.direction, Vec3::NEG_X); // -Z turned 90° left about Y
    assert_eq!(sun.intensity, 3.0);
}

#[test]
fn node_extras_are_kept_with_world_matrix() {
    let dir = TempDir::new("extras");
    let bin = Bin::default();
    let doc = bin.gltf(json!({
        "scenes": [{"nodes": [0, 2]}],
        "nodes": [
            {"name": "room", "translation": [0.0, 0.0, -2.0], "children": [1]},
            {"name": "grunt spawn", "translation": [1.0, 0.0, 0.0], "extras": {"enemy": "grunt", "hp": 3}},
            {"name": "plain", "extras": null}
        ],
    }));
    let scene = load_gltf(&write_json(&dir, "x.gltf", &doc)).unwrap();
    assert_eq!(scene.extras.len(), 1);
    let e = &scene.extras[0];
    assert_eq!(e.node_name, "grunt spawn");
    assert_eq!(e.extras, json!({"enemy": "grunt", "hp": 3}));
    close(e.world.w_axis.truncate(), [1.0, 0.0, -2.0]);
}

#[test]
fn base_color_textures_from_data_uri_and_buffer_view_deduped_by_image() {
    let dir = TempDir::new("tex");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let uv = bin.vec2(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    let red_green = png(2, 1, &[255, 0, 0, 255, 0, 255, 0, 128]);
    let blue = png(1, 1, &[0, 0, 255, 255]);
    let view = bin.view(&blue);
    let doc = bin.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "material": 0},
            {"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "material": 1},
            {"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "material": 2}
        ]}],
        "materials": [
            {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
            {"pbrMetallicRoughness": {"baseColorTexture": {"index": 1}, "baseColorFactor": [0.5, 0.5, 0.5, 1.0]}},
            {"pbrMetallicRoughness": {"baseColorTexture": {"index": 2}}}
        ],
        "textures": [{"source": 0}, {"source": 0}, {"source": 1}],
        "images": [
            {"uri": format!("data:image/png;base64,{}", base64(&red_green))},
            {"name": "blue", "bufferView": view, "mimeType": "image/png"}
        ],
    }));
    let scene = load_gltf(&write_json(&dir, "tex.gltf", &doc)).unwrap();
    assert_eq!(scene.textures.len(), 2, "image 0 used twice, decoded once");
    let t0 = &scene.textures[scene.materials[0].base_color_texture.unwrap().texture];
    assert_eq!((t0.width, t0.height), (2, 1));
    assert_eq!(t0.rgba8, [255, 0, 0, 255, 0, 255, 0, 128]);
    assert_eq!(scene.materials[1].base_color_texture, scene.materials[0].base_color_texture);
    assert_eq!(scene.materials[1].base_color, [0.5, 0.5, 0.5, 1.0]);
    let t1 = &scene.textures[scene.materials[2].base_color_texture.unwrap().texture];
    assert_eq!(t1.name, "blue");
    assert_eq!(t1.rgba8, [0, 0, 255, 255]);
}

#[test]
fn all_root_nodes_are_used_when_there_are_no_scenes() {
    let dir = TempDir::new("noscene");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let doc = bin.gltf(json!({
        "nodes": [{"mesh": 0, "children": [1]}, {"mesh": 0, "translation": [0.0, 0.0, 1.0]}, {"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos}}]}],
    }));
    let scene = load_gltf(&write_json(&dir, "n.gltf", &doc)).unwrap();
    assert_eq!(scene.meshes.len(), 3);
}

/// A 1×1 white PNG as a data URI: an image every material test below can point at.
fn white_png_uri() -> String {
    format!("data:image/png;base64,{}", base64(&png(1, 1, &[255; 4])))
}

fn le_bytes_u16(v: &[u16]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

#[test]
fn vertex_colours_from_float_vec3_and_normalized_u8_u16_accessors_reach_every_vertex() {
    let dir = TempDir::new("colours");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let nrm = bin.vec3(&[[0.0, 0.0, 1.0]; 3]);
    let float3 = bin.vec3(&[[1.0, 0.5, 0.25], [0.0, 1.0, 0.0], [0.0, 0.0, 2.0]]);
    let u8x4 = bin.typed(&[255, 0, 0, 255, 0, 51, 0, 102, 0, 0, 255, 0], 5121, 3, "VEC4", true);
    let u16x4 =
        bin.typed(&le_bytes_u16(&[65535, 0, 13107, 65535, 0, 65535, 0, 0, 0, 0, 0, 32768]), 5123, 3, "VEC4", true);
    let u16x3 = bin.typed(&le_bytes_u16(&[0, 65535, 0, 65535, 65535, 65535, 0, 0, 0]), 5123, 3, "VEC3", true);
    let doc = bin.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": pos, "NORMAL": nrm, "COLOR_0": float3}},
            {"attributes": {"POSITION": pos, "NORMAL": nrm, "COLOR_0": u8x4}},
            {"attributes": {"POSITION": pos, "NORMAL": nrm, "COLOR_0": u16x4}},
            {"attributes": {"POSITION": pos, "NORMAL": nrm, "COLOR_0": u16x3}},
            // No normals: flat shading un-shares the vertices, each keeps its colour.
            {"attributes": {"POSITION": pos, "COLOR_0": float3}},
            {"attributes": {"POSITION": pos, "NORMAL": nrm}}
        ]}],
    }));
    let scene = load_gltf(&write_json(&dir, "c.gltf", &doc)).unwrap();
    let colours = |m: usize| scene.meshes[m].vertices.iter().map(|v| v.color).collect::<Vec<_>>();
    assert_eq!(colours(0), [[1.0, 0.5, 0.25, 1.0], [0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 2.0, 1.0]], "float VEC3: alpha 1");
    assert_eq!(colours(1), [[1.0, 0.0, 0.0, 1.0], [0.0, 0.2, 0.0, 0.4], [0.0, 0.0, 1.0, 0.0]], "u8 VEC4 / 255");
    assert_eq!(colours(2), [[1.0, 0.0, 0.2, 1.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 32768.0 / 65535.0]]);
    assert_eq!(colours(3), [[0.0, 1.0, 0.0, 1.0], [1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 1.0]], "u16 VEC3 / 65535");
    assert_eq!(colours(4), colours(0));
    assert_eq!(colours(5), [[1.0; 4]; 3], "no COLOR_0: white");

    // Integer colours must be normalized, and colours non-negative.
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let raw = bin.typed(&[255; 12], 5121, 3, "VEC4", false);
    let negative = bin.vec3(&[[1.0, -0.5, 0.0]; 3]);
    for (name, colour, needle) in
        [("raw", raw, "expected float or normalized"), ("neg", negative, "vertex 0 has COLOR_0")]
    {
        let doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos, "COLOR_0": colour}}));
        let err = load_gltf(&write_json(&dir, &format!("{name}.gltf"), &doc)).unwrap_err().to_string();
        assert!(err.contains("COLOR_0") && err.contains(needle), "{name}: {err}");
    }
}

#[test]
fn a_primitive_without_material_gets_the_specs_default_material() {
    let dir = TempDir::new("specdefault");
    let mut bin = Bin::default();
    let pos = bin.vec3(&QUAD);
    let doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos}}));
    let scene = load_gltf(&write_json(&dir, "d.gltf", &doc)).unwrap();
    let m = &scene.materials[scene.meshes[0].material];
    // glTF 2.0 §3.9.6: base colour 1, metallic 1, roughness 1, no emission, opaque,
    // single-sided.
    assert_eq!(m.base_color, [1.0; 4]);
    assert_eq!(m.reflection, Reflection::MetallicRoughness { metallic: 1.0, roughness: 1.0, texture: None });
    assert_eq!((m.emissive, m.alpha_mode, m.double_sided), ([0.0; 3], AlphaMode::Opaque, false));
    assert!(m.base_color_texture.is_none() && m.emissive_texture.is_none());
    // OBJ keeps its own default (0.8 grey, Lambertian, both sides).
    assert_eq!((Material::default().base_color, Material::default().double_sided), ([0.8, 0.8, 0.8, 1.0], true));
    assert_eq!(Material::default().reflection, Reflection::Lambertian);
}

#[test]
fn metallic_and_roughness_factors_default_to_one_and_must_lie_in_0_1() {
    let dir = TempDir::new("metalrough");
    let mut bin = Bin::default();
    let pos = bin.vec3(&QUAD);
    let with = |pbr: Value| {
        let mut doc = single_primitive(&bin, json!({"attributes": {"POSITION": pos}, "material": 0}));
        doc["materials"] = json!([{ "pbrMetallicRoughness": pbr }]);
        load_gltf(&write_json(&dir, "m.gltf", &doc))
    };
    let reflection = |scene: Scene| scene.materials[0].reflection;
    assert_eq!(reflection(with(json!({})).unwrap()), Reflection::GLTF_DEFAULT);
    let stated = with(json!({"metallicFactor": 0.0, "roughnessFactor": 0.4})).unwrap();
    assert_eq!(reflection(stated), Reflection::MetallicRoughness { metallic: 0.0, roughness: 0.4, texture: None });
    for (key, value) in [("metallicFactor", 1.5), ("roughnessFactor", -0.1)] {
        let err = with(json!({ key: value })).unwrap_err().to_string();
        assert!(err.contains("m.gltf") && err.contains(key) && err.contains("between 0 and 1"), "{err}");
    }
}

#[test]
fn samplers_wrap_and_filter_modes_reach_each_texture_use() {
    let dir = TempDir::new("samplers");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let uv = bin.vec2(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    let (clamp, mirror, repeat) = (33071, 33648, 10497);
    let (nearest, linear) = (9728, 9729);
    let samplers = json!([
        {"wrapS": clamp, "wrapT": mirror, "magFilter": nearest, "minFilter": nearest},
        {"wrapS": mirror, "wrapT": repeat, "magFilter": linear, "minFilter": linear},
        {"minFilter": 9984},
        {"minFilter": 9985},
        {"minFilter": 9986},
        {"minFilter": 9987}
    ]);
    let mut textures = vec![json!({"source": 0})];
    textures.extend((0..6).map(|s| json!({"source": 0, "sampler": s})));
    let materials: Vec<_> =
        (0..7).map(|t| json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": t}}})).collect();
    let primitives: Vec<_> =
        (0..7).map(|m| json!({"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "material": m})).collect();
    let doc = bin.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": primitives}],
        "materials": materials,
        "textures": textures,
        "samplers": samplers,
        "images": [{"uri": white_png_uri()}],
    }));
    let scene = load_gltf(&write_json(&dir, "s.gltf", &doc)).unwrap();
    assert_eq!(scene.textures.len(), 1, "one image, sampled seven ways");
    let got: Vec<Sampler> = scene.materials.iter().map(|m| m.base_color_texture.unwrap().sampler).collect();
    let (n, l) = (Filter::Nearest, Filter::Linear);
    let sampler = |wrap_u, wrap_v, mag_filter, min_filter, mipmap_filter| Sampler {
        wrap_u,
        wrap_v,
        mag_filter,
        min_filter,
        mipmap_filter,
    };
    let r = Wrap::Repeat;
    assert_eq!(
        got,
        [
            Sampler::default(),
            sampler(Wrap::ClampToEdge, Wrap::MirroredRepeat, n, n, None),
            sampler(Wrap::MirroredRepeat, r, l, l, None),
            sampler(r, r, l, n, Some(n)),
            sampler(r, r, l, l, Some(n)),
            sampler(r, r, l, n, Some(l)),
            sampler(r, r, l, l, Some(l)),
        ]
    );
    assert_eq!(Sampler::default(), sampler(r, r, l, l, Some(l)), "no sampler: repeat, trilinear");
}

#[test]
fn alpha_modes_cutoffs_and_sidedness() {
    let dir = TempDir::new("alpha");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let materials = json!([
        {},
        {"alphaMode": "MASK"},
        {"alphaMode": "MASK", "alphaCutoff": 0.25, "doubleSided": true},
        {"alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 0.3]}}
    ]);
    let primitives: Vec<_> = (0..4).map(|m| json!({"attributes": {"POSITION": pos}, "material": m})).collect();
    let doc = bin.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": primitives}],
        "materials": materials,
    }));
    let scene = load_gltf(&write_json(&dir, "a.gltf", &doc)).unwrap();
    let got: Vec<_> =
        scene.materials.iter().map(|m| (m.alpha_mode, m.alpha_cutoff(), m.double_sided, m.base_color[3])).collect();
    assert_eq!(
        got,
        [
            (AlphaMode::Opaque, None, false, 1.0),
            (AlphaMode::Mask { cutoff: 0.5 }, Some(0.5), false, 1.0),
            (AlphaMode::Mask { cutoff: 0.25 }, Some(0.25), true, 1.0),
            // BLEND is drawn as MASK at 0.5.
            (AlphaMode::Blend, Some(0.5), false, 0.3),
        ]
    );
}

#[test]
fn emissive_textures_and_strength_multiply_the_emissive_factor() {
    let dir = TempDir::new("emissive");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let strength = |s: f32| json!({"KHR_materials_emissive_strength": {"emissiveStrength": s}});
    let materials = json!([
        {"emissiveFactor": [1.0, 0.5, 0.25], "emissiveTexture": {"index": 0}, "extensions": strength(4.0)},
        {"emissiveFactor": [1.0, 1.0, 1.0]}
    ]);
    let doc = bin.gltf(json!({
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": pos}, "material": 0},
            {"attributes": {"POSITION": pos}, "material": 1}
        ]}],
        "materials": materials,
        "textures": [{"source": 0}],
        "images": [{"uri": white_png_uri()}],
    }));
    let path = write_json(&dir, "e.gltf", &doc);
    let scene = load_gltf(&path).unwrap();
    let (lit, plain) = (&scene.materials[0], &scene.materials[1]);
    assert_eq!(lit.emissive, [4.0, 2.0, 1.0], "factor × emissiveStrength");
    let texture = lit.emissive_texture.expect("the emissive texture is kept");
    assert_eq!((texture.texture, texture.tex_coord, texture.transform), (0, 0, TextureTransform::IDENTITY));
    assert!(lit.base_color_texture.is_none());
    assert_eq!((plain.emissive, plain.emissive_texture), ([1.0; 3], None));

    let mut doc = doc;
    doc["materials"][0]["extensions"] = strength(-1.0);
    let err = load_gltf(&write_json(&dir, "neg.gltf", &doc)).unwrap_err().to_string();
    assert!(err.contains("material 0: KHR_materials_emissive_strength -1"), "{err}");
}

#[test]
fn texture_transforms_and_the_second_uv_set_reach_the_material_and_vertices() {
    let dir = TempDir::new("transform");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let uv0 = bin.vec2(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    let uv1 = bin.vec2(&[[0.5, 0.5], [0.25, 0.5], [0.5, 0.75]]);
    let transform =
        json!({"offset": [0.5, 0.25], "rotation": std::f32::consts::FRAC_PI_2, "scale": [2.0, 3.0], "texCoord": 1});
    let materials = json!([
        {
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": transform}}},
            "emissiveTexture": {"index": 0, "texCoord": 1}
        },
        // The extension without texCoord keeps the textureInfo's.
        {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1, "extensions": {"KHR_texture_transform": {"scale": [2.0, 2.0]}}}}}
    ]);
    let doc = bin.gltf(json!({
        "extensionsUsed": ["KHR_texture_transform"],
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": pos, "TEXCOORD_0": uv0, "TEXCOORD_1": uv1}, "material": 0},
            {"attributes": {"POSITION": pos, "TEXCOORD_0": uv0, "TEXCOORD_1": uv1}, "material": 1}
        ]}],
        "materials": materials,
        "textures": [{"source": 0}],
        "images": [{"uri": white_png_uri()}],
    }));
    let level = load_level(&write_json(&dir, "t.gltf", &doc)).unwrap();
    assert_eq!(level.warnings, vec![], "everything here is read");
    let scene = &level.scene;
    let v = &scene.meshes[0].vertices;
    assert_eq!([v[0].uv1, v[1].uv1, v[2].uv1], [[0.5, 0.5], [0.25, 0.5], [0.5, 0.75]]);
    assert_eq!([v[0].uv, v[1].uv, v[2].uv], [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);

    let base = scene.materials[0].base_color_texture.unwrap();
    assert_eq!(base.tex_coord, 1, "the extension's texCoord overrides the textureInfo's");
    assert_eq!(base.transform.offset, [0.5, 0.25]);
    assert_eq!(base.transform.scale, [2.0, 3.0]);
    assert!((base.transform.rotation - std::f32::consts::FRAC_PI_2).abs() < 1e-7);
    // uv' = T·R·S·uv: scale (2, 3), rotate 90° (u' = v, v' = -u), then offset.
    let apply = |uv| glam::Vec2::from(base.transform.apply(uv));
    assert!((apply([1.0, 0.0]) - glam::Vec2::new(0.5, -1.75)).length() < 1e-6, "{}", apply([1.0, 0.0]));
    assert!((apply([0.0, 1.0]) - glam::Vec2::new(3.5, 0.25)).length() < 1e-6, "{}", apply([0.0, 1.0]));
    let emissive = scene.materials[0].emissive_texture.unwrap();
    assert_eq!((emissive.tex_coord, emissive.transform), (1, TextureTransform::IDENTITY));
    let second = scene.materials[1].base_color_texture.unwrap();
    assert_eq!((second.tex_coord, second.transform.scale, second.transform.offset), (1, [2.0, 2.0], [0.0, 0.0]));
}

#[test]
fn a_missing_second_uv_set_and_sets_past_1_are_warnings() {
    let dir = TempDir::new("uvsets");
    let mut bin = Bin::default();
    let pos = bin.vec3(&TRI);
    let uv0 = bin.vec2(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    let doc = bin.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": pos, "TEXCOORD_0": uv0}, "material": 0},
            {"attributes": {"POSITION": pos, "TEXCOORD_0": uv0}, "material": 1}
        ]}],
        "materials": [
            {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}}},
            {"emissiveTexture": {"index": 0, "texCoord": 2}}
        ],
        "textures": [{"source": 0}],
        "images": [{"uri": white_png_uri()}],
    }));
    let level = load_level(&write_json(&dir, "u.gltf", &doc)).unwrap();
    let lines: Vec<String> = level.warnings.iter().map(ToString::to_string).collect();
    for needle in [
        "mesh 0 primitive 0: its material's textures read TEXCOORD_1, which it lacks; TEXCOORD_0 is used",
        "material 1: emissive texture uses TEXCOORD_2; only TEXCOORD_0 and TEXCOORD_1 are read",
    ] {
        assert!(lines.iter().any(|l| l.contains(needle)), "no '{needle}' in {lines:#?}");
    }
    assert_eq!(lines.len(), 2, "{lines:#?}");
    let v = &level.scene.meshes[0].vertices;
    assert!(v.iter().all(|v| v.uv1 == v.uv), "TEXCOORD_0 stands in for the missing TEXCOORD_1");
    assert_eq!(level.scene.materials[1].emissive_texture.unwrap().tex_coord, 0);
}
