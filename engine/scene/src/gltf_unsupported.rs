//! The parts of a glTF file Headlamp does not use, named so that `headlamp check` (and the log
//! when a level loads) says what is ignored instead of rendering it differently in silence.

use gltf::material::AlphaMode;
use gltf::mesh::Semantic;
use gltf::texture::{MagFilter, WrappingMode};
use gltf::Document;

/// Extensions the loader reads.
const SUPPORTED_EXTENSIONS: &[&str] = &["KHR_lights_punctual"];

/// One line per ignored feature, naming the material, texture or primitive that uses it.
pub(crate) fn unsupported_features(doc: &Document) -> Vec<String> {
    let mut out = Vec::new();
    for ext in doc.extensions_used().filter(|e| !SUPPORTED_EXTENSIONS.contains(e)) {
        out.push(format!("extension {ext} is not supported; ignored"));
    }
    for m in doc.materials() {
        let name = match (m.index(), m.name()) {
            (Some(i), Some(n)) => format!("material {i} ('{n}')"),
            (Some(i), None) => format!("material {i}"),
            (None, _) => continue,
        };
        match m.alpha_mode() {
            AlphaMode::Opaque => {}
            AlphaMode::Mask => out.push(format!("{name}: alphaMode MASK is not supported; drawn opaque")),
            AlphaMode::Blend => out.push(format!("{name}: alphaMode BLEND is not supported; drawn opaque")),
        }
        if m.emissive_texture().is_some() {
            out.push(format!("{name}: emissive textures are not supported; the emissive factor is used alone"));
        }
        if m.normal_texture().is_some() {
            out.push(format!("{name}: normal maps are not supported; the geometry's normals are used"));
        }
    }
    for t in doc.textures() {
        let s = t.sampler();
        let wraps = [s.wrap_s(), s.wrap_t()];
        if wraps.iter().any(|w| *w != WrappingMode::Repeat) {
            out.push(format!("texture {}: wrap modes {wraps:?} are not supported; it repeats", t.index()));
        }
        if s.mag_filter() == Some(MagFilter::Nearest) {
            out.push(format!("texture {}: nearest filtering is not supported; it is filtered linearly", t.index()));
        }
    }
    for mesh in doc.meshes() {
        for prim in mesh.primitives() {
            if prim.attributes().any(|(semantic, _)| semantic == Semantic::Colors(0)) {
                out.push(format!(
                    "mesh {} primitive {}: vertex colours (COLOR_0) are not supported; ignored",
                    mesh.index(),
                    prim.index()
                ));
            }
        }
    }
    out
}
