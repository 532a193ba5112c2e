//! Helpers shared by the integration tests: scratch folders, the glTF writer, assertions.
#![allow(dead_code, unused_imports)] // each test binary uses a different subset

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use serde_json::Value;

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

// The glTF writer is the conformance crate's, shared with the game's tests.
pub use gltf_conformance::{base64, data_uri, png, single_primitive, Bin, QUAD, QUAD_INDICES, TRI};

/// A GLB container of a document and its BIN chunk.
pub fn glb(json: &Value, bin: &[u8]) -> Vec<u8> {
    scene::pack_glb(&serde_json::to_vec(json).unwrap(), bin)
}

pub fn write_json(dir: &TempDir, name: &str, doc: &Value) -> PathBuf {
    dir.write(name, serde_json::to_vec_pretty(doc).unwrap())
}

/// Asserts two vectors agree to 1e-4.
pub fn close(a: impl Into<glam::Vec3>, b: impl Into<glam::Vec3>) {
    let (a, b) = (a.into(), b.into());
    assert!((a - b).abs().max_element() < 1e-4, "{a} != {b}");
}

/// Geometric normal of triangle `t` of a mesh (from positions, in index order).
pub fn tri_normal(mesh: &scene::Mesh, t: usize) -> glam::Vec3 {
    let p = |k: usize| glam::Vec3::from(mesh.vertices[mesh.indices[3 * t + k] as usize].position);
    (p(1) - p(0)).cross(p(2) - p(0)).normalize()
}
