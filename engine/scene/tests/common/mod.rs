//! Helpers shared by the integration tests: scratch folders, and a tiny glTF writer.
#![allow(dead_code)] // each test binary uses a different subset

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use serde_json::{json, Value};

/// A fresh folder under the system temp dir, removed on drop.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(tag: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("headlamp-scene-{}-{tag}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }
    pub fn path(&self) -> &Path {
        &self.0
    }
    /// Writes `bytes` to `name` (sub-folders created) and returns the full path.
    pub fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let p = self.0.join(name);
        if let Some(parent) = p.parent() {
            std::fs::create_dir_all(parent).unwrap();
        }
        std::fs::write(&p, bytes).unwrap();
        p
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

pub use scene::encode_base64 as base64;

pub fn data_uri(bytes: &[u8]) -> String {
    format!("data:application/octet-stream;base64,{}", base64(bytes))
}

/// Accumulates binary data and the bufferViews/accessors describing it (one buffer, index 0).
#[derive(Default)]
pub struct Bin {
    pub data: Vec<u8>,
    pub views: Vec<Value>,
    pub accessors: Vec<Value>,
}

impl Bin {
    fn push(&mut self, bytes: &[u8], component: u32, count: usize, ty: &str, extra: Value) -> usize {
        while !self.data.len().is_multiple_of(4) {
            self.data.push(0);
        }
        self.views.push(json!({"buffer": 0, "byteOffset": self.data.len(), "byteLength": bytes.len()}));
        self.data.extend_from_slice(bytes);
        let mut acc =
            json!({"bufferView": self.views.len() - 1, "componentType": component, "count": count, "type": ty});
        if let (Value::Object(a), Value::Object(e)) = (&mut acc, extra) {
            a.extend(e);
        }
        self.accessors.push(acc);
        self.accessors.len() - 1
    }

    /// VEC3/VEC2 float data (POSITION gets min/max as the spec requires).
    pub fn vec3(&mut self, v: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = v.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for p in v {
            for i in 0..3 {
                min[i] = min[i].min(p[i]);
                max[i] = max[i].max(p[i]);
            }
        }
        self.push(&bytes, 5126, v.len(), "VEC3", json!({"min": min, "max": max}))
    }
    pub fn vec2(&mut self, v: &[[f32; 2]]) -> usize {
        let bytes: Vec<u8> = v.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
        self.push(&bytes, 5126, v.len(), "VEC2", json!({}))
    }
    pub fn u8s(&mut self, v: &[u8]) -> usize {
        self.push(v, 5121, v.len(), "SCALAR", json!({}))
    }
    pub fn u16s(&mut self, v: &[u16]) -> usize {
        let bytes: Vec<u8> = v.iter().flat_map(|f| f.to_le_bytes()).collect();
        self.push(&bytes, 5123, v.len(), "SCALAR", json!({}))
    }
    pub fn u32s(&mut self, v: &[u32]) -> usize {
        let bytes: Vec<u8> = v.iter().flat_map(|f| f.to_le_bytes()).collect();
        self.push(&bytes, 5125, v.len(), "SCALAR", json!({}))
    }
    /// Any accessor over `bytes` (`component` a glTF componentType, `ty` "VEC3" etc.).
    pub fn typed(&mut self, bytes: &[u8], component: u32, count: usize, ty: &str, normalized: bool) -> usize {
        let extra = if normalized { json!({"normalized": true}) } else { json!({}) };
        self.push(bytes, component, count, ty, extra)
    }
    /// Raw bytes as a bufferView only (for images); returns the view index.
    pub fn view(&mut self, bytes: &[u8]) -> usize {
        while !self.data.len().is_multiple_of(4) {
            self.data.push(0);
        }
        self.views.push(json!({"buffer": 0, "byteOffset": self.data.len(), "byteLength": bytes.len()}));
        self.data.extend_from_slice(bytes);
        self.views.len() - 1
    }

    /// A complete document around `rest` (nodes, meshes, ...), the buffer embedded as base64.
    pub fn gltf(&self, rest: Value) -> Value {
        self.gltf_with_buffer(rest, json!({"byteLength": self.data.len(), "uri": data_uri(&self.data)}))
    }

    pub fn gltf_with_buffer(&self, rest: Value, buffer: Value) -> Value {
        let mut doc = json!({
            "asset": {"version": "2.0"},
            "buffers": [buffer],
            "bufferViews": self.views,
            "accessors": self.accessors,
        });
        if let (Value::Object(d), Value::Object(r)) = (&mut doc, rest) {
            d.extend(r);
        }
        doc
    }
}

/// A GLB container of a document and its BIN chunk.
pub fn glb(json: &Value, bin: &[u8]) -> Vec<u8> {
    scene::pack_glb(&serde_json::to_vec(json).unwrap(), bin)
}

/// One triangle in the XY plane facing +Z (counter-clockwise), as positions.
pub const TRI: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// A unit quad in the XY plane facing +Z.
pub const QUAD: [[f32; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
pub const QUAD_INDICES: [u32; 6] = [0, 1, 2, 0, 2, 3];

/// A one-node, one-mesh document from a primitive's JSON.
pub fn single_primitive(bin: &Bin, primitive: Value) -> Value {
    bin.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [primitive]}],
    }))
}

pub fn write_json(dir: &TempDir, name: &str, doc: &Value) -> PathBuf {
    dir.write(name, serde_json::to_vec_pretty(doc).unwrap())
}

/// Asserts two vectors agree to 1e-4.
pub fn close(a: impl Into<glam::Vec3>, b: impl Into<glam::Vec3>) {
    let (a, b) = (a.into(), b.into());
    assert!((a - b).abs().max_element() < 1e-4, "{a} != {b}");
}

/// A small PNG (RGBA8) with the given pixels, row-major.
pub fn png(width: u32, height: u32, rgba: &[u8]) -> Vec<u8> {
    let img = image::RgbaImage::from_raw(width, height, rgba.to_vec()).unwrap();
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

/// Geometric normal of triangle `t` of a mesh (from positions, in index order).
pub fn tri_normal(mesh: &scene::Mesh, t: usize) -> glam::Vec3 {
    let p = |k: usize| glam::Vec3::from(mesh.vertices[mesh.indices[3 * t + k] as usize].position);
    (p(1) - p(0)).cross(p(2) - p(0)).normalize()
}
