//! A tiny glTF writer: one buffer of accessors, documents as JSON values, embedded data URIs.

use std::path::{Path, PathBuf};

use serde_json::{json, Value};

/// Standard base64 with padding, as a glTF `data:` URI embeds bytes.
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let n = chunk.iter().enumerate().fold(0u32, |n, (i, &b)| n | u32::from(b) << (16 - 8 * i));
        for i in 0..4 {
            out.push(if i <= chunk.len() { ALPHABET[(n >> (18 - 6 * i) & 63) as usize] as char } else { '=' });
        }
    }
    out
}

/// `bytes` as a buffer's `data:` URI.
pub fn data_uri(bytes: &[u8]) -> String {
    format!("data:application/octet-stream;base64,{}", base64(bytes))
}

/// A PNG as an image's `data:` URI.
pub fn png_data_uri(png: &[u8]) -> String {
    format!("data:image/png;base64,{}", base64(png))
}

/// A small PNG (RGBA8) with the given pixels, row-major from the top-left.
pub fn png(width: u32, height: u32, rgba: &[u8]) -> Vec<u8> {
    let img = image::RgbaImage::from_raw(width, height, rgba.to_vec()).expect("width × height × 4 bytes");
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).expect("PNG encoding into memory");
    out.into_inner()
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
        let view = self.view(bytes);
        let mut acc = json!({"bufferView": view, "componentType": component, "count": count, "type": ty});
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
        self.push(&bytes, FLOAT, v.len(), "VEC3", json!({"min": min, "max": max}))
    }
    pub fn vec2(&mut self, v: &[[f32; 2]]) -> usize {
        let bytes: Vec<u8> = v.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
        self.push(&bytes, FLOAT, v.len(), "VEC2", json!({}))
    }
    pub fn u8s(&mut self, v: &[u8]) -> usize {
        self.push(v, UNSIGNED_BYTE, v.len(), "SCALAR", json!({}))
    }
    pub fn u16s(&mut self, v: &[u16]) -> usize {
        let bytes: Vec<u8> = v.iter().flat_map(|f| f.to_le_bytes()).collect();
        self.push(&bytes, UNSIGNED_SHORT, v.len(), "SCALAR", json!({}))
    }
    pub fn u32s(&mut self, v: &[u32]) -> usize {
        let bytes: Vec<u8> = v.iter().flat_map(|f| f.to_le_bytes()).collect();
        self.push(&bytes, UNSIGNED_INT, v.len(), "SCALAR", json!({}))
    }
    /// Any accessor over `bytes` (`component` a glTF componentType, `ty` "VEC3" etc.).
    pub fn typed(&mut self, bytes: &[u8], component: u32, count: usize, ty: &str, normalized: bool) -> usize {
        let extra = if normalized { json!({"normalized": true}) } else { json!({}) };
        self.push(bytes, component, count, ty, extra)
    }
    /// Raw bytes as a bufferView only (for images); returns the view index.
    pub fn view(&mut self, bytes: &[u8]) -> usize {
        // Accessor offsets must be multiples of the component size; 4 suits them all.
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

/// glTF componentType values.
pub const UNSIGNED_BYTE: u32 = 5121;
pub const UNSIGNED_SHORT: u32 = 5123;
pub const UNSIGNED_INT: u32 = 5125;
pub const FLOAT: u32 = 5126;

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

/// Writes `doc` as `dir/name` (pretty-printed, so a failing test's file can be read) and returns the path.
pub fn write(dir: &Path, name: &str, doc: &Value) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec_pretty(doc).expect("JSON")).expect("write the glTF file");
    path
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_pads_each_length() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"h"), "aA==");
        assert_eq!(base64(b"he"), "aGU=");
        assert_eq!(base64(b"hel"), "aGVs");
        assert_eq!(base64(b"hello"), "aGVsbG8=");
        assert_eq!(base64(&[0, 255, 254, 1]), "AP/+AQ==");
    }

    #[test]
    fn views_are_aligned_to_four_bytes() {
        let mut bin = Bin::default();
        bin.u8s(&[1, 2, 3]);
        bin.vec2(&[[1.0, 2.0]]);
        assert_eq!(bin.views[1]["byteOffset"], 4);
        assert_eq!(bin.data.len(), 12);
    }
}
