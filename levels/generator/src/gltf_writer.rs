//! Serialises the level as text glTF 2.0 with one external binary buffer.
//!
//! Layout of the buffer: for each mesh in material order, tightly packed POSITION (VEC3 f32),
//! NORMAL (VEC3 f32), TEXCOORD_0 (VEC2 f32) and u32 indices, each in its own bufferView. Every
//! block is a multiple of 4 bytes long, so every bufferView starts 4-byte aligned.
//!
//! A textured material's base colour texture (and a wet floor's metallic-roughness texture) is
//! an external PNG beside the scene file (`images[].uri`), sampled with repeat wrapping and
//! trilinear filtering; a level without textured materials writes no `images`, `samplers` or
//! `textures` at all. Every material states its metallic and roughness factors.

use crate::geometry::MeshBuffers;
use crate::layout::{Level, LightKind};
use crate::materials::Material;
use crate::textures::TextureKind;
use serde_json::{json, Map, Value};

const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const TRIANGLES: u32 = 4;

const LINEAR: u32 = 9729;
const LINEAR_MIPMAP_LINEAR: u32 = 9987;
const REPEAT: u32 = 10497;

pub struct GltfOutput {
    pub json: String,
    pub bin: Vec<u8>,
    /// The textures the materials use, in the order of `images`.
    pub textures: Vec<TextureKind>,
}

/// An f32 as a JSON number with its shortest round-tripping decimal form (so 0.1f32 is written as
/// `0.1`, which parses back to exactly the same f32).
fn num32(x: f32) -> Value {
    let v: f64 = x.to_string().parse().expect("f32 formats as a number");
    json!(v)
}

fn vec32<const N: usize>(v: [f32; N]) -> Value {
    Value::Array(v.iter().map(|&x| num32(x)).collect())
}

/// Quaternion (x, y, z, w) for yaw about +Y followed by pitch about the local +X.
pub fn yaw_pitch_quat(yaw_deg: f64, pitch_deg: f64) -> [f64; 4] {
    let (sy, cy) = (0.5 * yaw_deg.to_radians()).sin_cos();
    let (sp, cp) = (0.5 * pitch_deg.to_radians()).sin_cos();
    // q_yaw * q_pitch with q_yaw = (0, sy, 0, cy), q_pitch = (sp, 0, 0, cp).
    [cy * sp, sy * cp, -sy * sp, cy * cp]
}

/// A node transform: translation, and rotation unless it is the identity.
fn transform(node: &mut Map<String, Value>, position: [f64; 3], yaw_deg: f64, pitch_deg: f64) {
    if yaw_deg != 0.0 || pitch_deg != 0.0 {
        // Snap rounding noise (6e-17, -0.0) to a clean 0.
        let q = yaw_pitch_quat(yaw_deg, pitch_deg).map(|c| if c.abs() < 1e-9 { 0.0 } else { c as f32 });
        node.insert("rotation".into(), vec32(q));
    }
    node.insert("translation".into(), vec32(position.map(|c| c as f32)));
}

struct BinBuilder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl BinBuilder {
    fn view(&mut self, bytes: &[u8], target: u32) -> usize {
        debug_assert_eq!(self.bin.len() % 4, 0);
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.views.push(json!({
            "buffer": 0,
            "byteOffset": offset,
            "byteLength": bytes.len(),
            "target": target,
        }));
        self.views.len() - 1
    }

    fn accessor(&mut self, accessor: Value) -> usize {
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    fn floats<const N: usize>(&mut self, data: &[[f32; N]], kind: &str) -> usize {
        let bytes: Vec<u8> = data.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
        let view = self.view(&bytes, ARRAY_BUFFER);
        self.accessor(json!({
            "bufferView": view,
            "componentType": FLOAT,
            "count": data.len(),
            "type": kind,
        }))
    }
}

/// Builds the glTF document for `level` with `meshes` (one per material, already merged).
/// `bin_uri` is the buffer's file name relative to the .gltf.
pub fn write(level: &Level, meshes: &[(Material, MeshBuffers)], bin_uri: &str) -> GltfOutput {
    let mut b = BinBuilder { bin: Vec::new(), views: Vec::new(), accessors: Vec::new() };
    let mut gltf_meshes = Vec::new();
    let mut materials = Vec::new();
    let mut nodes = Vec::new();
    let mut textures: Vec<TextureKind> = Vec::new();

    for (material, mesh) in meshes.iter().filter(|(_, m)| !m.is_empty()) {
        let position = b.floats(&mesh.positions, "VEC3");
        let (lo, hi) = mesh.position_bounds();
        b.accessors[position]["min"] = vec32(lo);
        b.accessors[position]["max"] = vec32(hi);
        let normal = b.floats(&mesh.normals, "VEC3");
        let texcoord = b.floats(&mesh.uvs, "VEC2");
        let index_bytes: Vec<u8> = mesh.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let index_view = b.view(&index_bytes, ELEMENT_ARRAY_BUFFER);
        let indices = b.accessor(json!({
            "bufferView": index_view,
            "componentType": UNSIGNED_INT,
            "count": mesh.indices.len(),
            "type": "SCALAR",
        }));

        let [r, g, bl] = material.albedo();
        let mut pbr = json!({
            "baseColorFactor": [r, g, bl, 1.0],
            "metallicFactor": material.metallic(),
            "roughnessFactor": material.roughness(),
        });
        let mut texture_index = |kind: TextureKind| {
            textures.iter().position(|&t| t == kind).unwrap_or_else(|| {
                textures.push(kind);
                textures.len() - 1
            })
        };
        if let Some((kind, _)) = material.texture() {
            pbr["baseColorTexture"] = json!({ "index": texture_index(kind) });
        }
        if let Some(kind) = material.roughness_texture() {
            pbr["metallicRoughnessTexture"] = json!({ "index": texture_index(kind) });
        }
        materials.push(json!({ "name": material.name(), "pbrMetallicRoughness": pbr }));
        gltf_meshes.push(json!({
            "name": material.name(),
            "primitives": [{
                "attributes": { "POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord },
                "indices": indices,
                "material": materials.len() - 1,
                "mode": TRIANGLES,
            }],
        }));
        nodes.push(json!({
            "name": format!("geometry_{}", material.name()),
            "mesh": gltf_meshes.len() - 1,
        }));
    }

    // The overview camera.
    let cam = &level.camera;
    let mut node = Map::new();
    node.insert("name".into(), json!(cam.name));
    node.insert("camera".into(), json!(0));
    transform(&mut node, cam.position, cam.yaw_deg, cam.pitch_deg);
    nodes.push(Value::Object(node));
    let cameras = json!([{
        "name": cam.name,
        "type": "perspective",
        "perspective": { "yfov": cam.yfov, "znear": cam.znear, "zfar": cam.zfar },
    }]);

    // Lights.
    let mut lights = Vec::new();
    for (i, l) in level.lights.iter().enumerate() {
        let mut light = Map::new();
        light.insert("name".into(), json!(l.name));
        light.insert("color".into(), json!(l.color));
        light.insert("intensity".into(), json!(l.intensity));
        light.insert("range".into(), json!(l.range));
        match l.kind {
            LightKind::Point => {
                light.insert("type".into(), json!("point"));
            }
            LightKind::Spot { inner, outer } => {
                light.insert("type".into(), json!("spot"));
                light.insert("spot".into(), json!({ "innerConeAngle": inner, "outerConeAngle": outer }));
            }
        }
        lights.push(Value::Object(light));
        let mut node = Map::new();
        node.insert("name".into(), json!(l.name));
        node.insert("extensions".into(), json!({ "KHR_lights_punctual": { "light": i } }));
        transform(&mut node, l.position, l.yaw_deg, l.pitch_deg);
        nodes.push(Value::Object(node));
    }

    // Gameplay markers: empty nodes with extras.
    for m in &level.markers {
        let mut node = Map::new();
        node.insert("name".into(), json!(m.name));
        node.insert("extras".into(), m.extras.clone());
        transform(&mut node, m.position, m.yaw_deg, 0.0);
        nodes.push(Value::Object(node));
    }

    let mut doc = json!({
        "asset": { "version": "2.0", "generator": "levelgen (Headlamp)" },
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": lights } },
        "scene": 0,
        "scenes": [{ "name": level.name, "nodes": (0..nodes.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
        "meshes": gltf_meshes,
        "materials": materials,
        "cameras": cameras,
        "buffers": [{ "uri": bin_uri, "byteLength": b.bin.len() }],
        "bufferViews": b.views,
        "accessors": b.accessors,
    });
    if !textures.is_empty() {
        let images: Vec<Value> = textures.iter().map(|t| json!({ "name": t.name(), "uri": t.file_name() })).collect();
        let gltf_textures: Vec<Value> =
            (0..textures.len()).map(|i| json!({ "name": textures[i].name(), "sampler": 0, "source": i })).collect();
        doc["images"] = json!(images);
        doc["samplers"] = json!([{
            "magFilter": LINEAR,
            "minFilter": LINEAR_MIPMAP_LINEAR,
            "wrapS": REPEAT,
            "wrapT": REPEAT,
        }]);
        doc["textures"] = json!(gltf_textures);
    }
    let mut json = serde_json::to_string_pretty(&doc).expect("JSON serialisation");
    json.push('\n');
    GltfOutput { json, bin: b.bin, textures }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate;

    fn u(v: &Value) -> usize {
        v.as_u64().unwrap_or_else(|| panic!("not an unsigned integer: {v}")) as usize
    }

    fn f32_at(bin: &[u8], at: usize) -> f32 {
        f32::from_le_bytes(bin[at..at + 4].try_into().unwrap())
    }

    #[test]
    fn gltf_structure_is_consistent_with_the_buffer() {
        for level in crate::all_levels() {
            check_structure(&level);
        }
    }

    fn check_structure(level: &Level) {
        let out = generate(level);
        let doc: Value = serde_json::from_str(&out.gltf).unwrap();
        let bin = &out.bin;
        assert_eq!(doc["asset"]["version"], "2.0");
        assert_eq!(doc["buffers"].as_array().unwrap().len(), 1);
        assert_eq!(doc["buffers"][0]["uri"], "scene.bin");
        assert_eq!(u(&doc["buffers"][0]["byteLength"]), bin.len());

        let views = doc["bufferViews"].as_array().unwrap();
        let mut end = 0;
        for v in views {
            let (off, len) = (u(&v["byteOffset"]), u(&v["byteLength"]));
            assert_eq!(off % 4, 0, "bufferView not 4-byte aligned");
            assert_eq!(off, end, "bufferViews are packed in order");
            assert!(len > 0);
            end = off + len;
        }
        assert_eq!(end, bin.len());

        let accessors = doc["accessors"].as_array().unwrap();
        let mut used_views = vec![0; views.len()];
        for a in accessors {
            let view = &views[u(&a["bufferView"])];
            used_views[u(&a["bufferView"])] += 1;
            let components = match a["type"].as_str().unwrap() {
                "SCALAR" => 1,
                "VEC2" => 2,
                "VEC3" => 3,
                t => panic!("unexpected accessor type {t}"),
            };
            assert!(matches!(u(&a["componentType"]), 5125 | 5126));
            assert!(a.get("byteOffset").is_none());
            assert_eq!(u(&a["count"]) * components * 4, u(&view["byteLength"]));
        }
        assert!(used_views.iter().all(|&n| n == 1), "every view backs exactly one accessor");

        let meshes = doc["meshes"].as_array().unwrap();
        let materials = doc["materials"].as_array().unwrap();
        assert_eq!(meshes.len(), materials.len());
        for (mi, mesh) in meshes.iter().enumerate() {
            assert!(mesh["name"].is_string());
            let prim = &mesh["primitives"][0];
            assert_eq!(mesh["primitives"].as_array().unwrap().len(), 1);
            assert_eq!(u(&prim["material"]), mi);
            assert_eq!(u(&prim["mode"]), 4);
            let attr = &prim["attributes"];
            let pos = &accessors[u(&attr["POSITION"])];
            let nor = &accessors[u(&attr["NORMAL"])];
            let tex = &accessors[u(&attr["TEXCOORD_0"])];
            let idx = &accessors[u(&prim["indices"])];
            assert_eq!((pos["type"].as_str(), nor["type"].as_str()), (Some("VEC3"), Some("VEC3")));
            assert_eq!(tex["type"], "VEC2");
            assert_eq!((idx["type"].as_str(), u(&idx["componentType"])), (Some("SCALAR"), 5125));
            let n = u(&pos["count"]);
            assert_eq!(u(&nor["count"]), n);
            assert_eq!(u(&tex["count"]), n);
            let count = u(&idx["count"]);
            assert_eq!(count % 3, 0);
            // Indices in range; min/max of POSITION match the data exactly.
            let ioff = u(&views[u(&idx["bufferView"])]["byteOffset"]);
            for k in 0..count {
                let i = u32::from_le_bytes(bin[ioff + 4 * k..ioff + 4 * k + 4].try_into().unwrap());
                assert!((i as usize) < n);
            }
            let poff = u(&views[u(&pos["bufferView"])]["byteOffset"]);
            let mut lo = [f32::INFINITY; 3];
            let mut hi = [f32::NEG_INFINITY; 3];
            for v in 0..n {
                for c in 0..3 {
                    let x = f32_at(bin, poff + 12 * v + 4 * c);
                    lo[c] = lo[c].min(x);
                    hi[c] = hi[c].max(x);
                }
            }
            for c in 0..3 {
                assert_eq!(pos["min"][c].as_f64().unwrap() as f32, lo[c]);
                assert_eq!(pos["max"][c].as_f64().unwrap() as f32, hi[c]);
            }
            // Normals are unit length.
            let noff = u(&views[u(&nor["bufferView"])]["byteOffset"]);
            for v in 0..n {
                let l2: f32 = (0..3).map(|c| f32_at(bin, noff + 12 * v + 4 * c).powi(2)).sum();
                assert!((l2 - 1.0).abs() < 1e-5);
            }
            // Every material states both factors (glTF's defaults, metallic 1, would make metals).
            let pbr = &materials[mi]["pbrMetallicRoughness"];
            let metallic = pbr["metallicFactor"].as_f64().unwrap();
            assert!(metallic == 0.0 || metallic == 1.0);
            assert!((0.0..=1.0).contains(&pbr["roughnessFactor"].as_f64().unwrap()));
            let limit = if metallic == 0.0 { 0.85 } else { 1.0 };
            assert!(pbr["baseColorFactor"].as_array().unwrap()[..3].iter().all(|c| c.as_f64().unwrap() <= limit));
        }

        // Nodes: every scene node exists; every mesh, the camera and every light is referenced.
        let nodes = doc["nodes"].as_array().unwrap();
        let scene_nodes: Vec<usize> = doc["scenes"][0]["nodes"].as_array().unwrap().iter().map(u).collect();
        assert_eq!(scene_nodes, (0..nodes.len()).collect::<Vec<_>>());
        let lights = doc["extensions"]["KHR_lights_punctual"]["lights"].as_array().unwrap();
        let mut mesh_refs: Vec<usize> = nodes.iter().filter_map(|n| n.get("mesh")).map(u).collect();
        mesh_refs.sort();
        assert_eq!(mesh_refs, (0..meshes.len()).collect::<Vec<_>>());
        let mut light_refs: Vec<usize> =
            nodes.iter().filter_map(|n| n.pointer("/extensions/KHR_lights_punctual/light")).map(u).collect();
        light_refs.sort();
        assert_eq!(light_refs, (0..lights.len()).collect::<Vec<_>>());
        assert!(nodes.iter().all(|n| n["name"].is_string()));
        let overview = nodes.iter().find(|n| n["name"] == "overview").unwrap();
        assert_eq!(u(&overview["camera"]), 0);
        assert_eq!(doc["cameras"][0]["type"], "perspective");
        if level.id == "cellar" {
            for l in lights {
                assert!(l["intensity"].as_f64().unwrap() <= 0.5, "the Cellar's lights must stay dim");
            }
        }
        assert_eq!(doc["extensionsUsed"], json!(["KHR_lights_punctual"]));
        for key in ["spawn", "pickup", "enemy"] {
            assert!(nodes.iter().any(|n| n["extras"].get(key).is_some()), "no {key} marker");
        }
        assert_eq!(nodes.iter().filter(|n| n["extras"]["spawn"] == "player").count(), 1);
    }

    /// Textured materials name their PNG through one texture each, all with the one repeating
    /// sampler; untextured levels carry no texture arrays at all.
    #[test]
    fn textured_materials_reference_their_pngs() {
        for level in crate::all_levels() {
            let out = generate(&level);
            let doc: Value = serde_json::from_str(&out.gltf).unwrap();
            let materials = doc["materials"].as_array().unwrap();
            let textured: Vec<&Value> =
                materials.iter().filter(|m| m["pbrMetallicRoughness"].get("baseColorTexture").is_some()).collect();
            if textured.is_empty() {
                for key in ["images", "samplers", "textures"] {
                    assert!(doc.get(key).is_none(), "{}: {key}", level.id);
                }
                continue;
            }
            let images = doc["images"].as_array().unwrap();
            let textures = doc["textures"].as_array().unwrap();
            assert_eq!(images.len(), out.textures.len());
            assert!(out.textures.iter().all(|(_, png)| png.starts_with(b"\x89PNG")));
            assert_eq!(textures.len(), images.len());
            let sampler = &doc["samplers"][0];
            assert_eq!((u(&sampler["wrapS"]), u(&sampler["wrapT"])), (10497, 10497));
            for (i, t) in textures.iter().enumerate() {
                assert_eq!((u(&t["sampler"]), u(&t["source"])), (0, i));
                assert_eq!(images[i]["uri"], out.textures[i].0.as_str());
            }
            for (m, _) in &crate::build_meshes(&level) {
                let written = materials.iter().find(|w| w["name"] == m.name()).unwrap();
                let index = written["pbrMetallicRoughness"]["baseColorTexture"]["index"].as_u64();
                match m.texture() {
                    Some((kind, _)) => assert_eq!(out.textures[index.unwrap() as usize].0, kind.file_name(), "{m:?}"),
                    None => assert_eq!(index, None, "{m:?}"),
                }
                let index = written["pbrMetallicRoughness"]["metallicRoughnessTexture"]["index"].as_u64();
                match m.roughness_texture() {
                    Some(kind) => assert_eq!(out.textures[index.unwrap() as usize].0, kind.file_name(), "{m:?}"),
                    None => assert_eq!(index, None, "{m:?}"),
                }
            }
        }
    }

    #[test]
    fn quaternion_matches_yaw_convention() {
        // Yaw +90° turns left: the camera's -Z axis must end up pointing at -X.
        let [x, y, z, w] = yaw_pitch_quat(90.0, 0.0);
        // Rotate v = (0, 0, -1): v' = v + 2w(q×v) + 2q×(q×v).
        let q = [x, y, z];
        let v = [0.0, 0.0, -1.0];
        let c1 = crate::geometry::cross(q, v);
        let c2 = crate::geometry::cross(q, c1);
        let r: Vec<f64> = (0..3).map(|i| v[i] + 2.0 * w * c1[i] + 2.0 * c2[i]).collect();
        assert!((r[0] + 1.0).abs() < 1e-12 && r[1].abs() < 1e-12 && r[2].abs() < 1e-12, "{r:?}");
        // Pitch -90° points straight down.
        let [x, y, z, w] = yaw_pitch_quat(0.0, -90.0);
        let q = [x, y, z];
        let c1 = crate::geometry::cross(q, v);
        let c2 = crate::geometry::cross(q, c1);
        let r: Vec<f64> = (0..3).map(|i| v[i] + 2.0 * w * c1[i] + 2.0 * c2[i]).collect();
        assert!(r[0].abs() < 1e-12 && (r[1] + 1.0).abs() < 1e-12 && r[2].abs() < 1e-12, "{r:?}");
    }
}
