//! The parts of a glTF file Headlamp does not use, named so that `headlamp check` (and the log
//! when a level loads) says what is ignored instead of rendering it differently in silence.
//!
//! Read and drawn, so not listed: base colour and emissive factors and textures, every
//! sampler (wrap modes, nearest/linear, mipmap modes), `KHR_texture_transform`,
//! `KHR_materials_emissive_strength`, `TEXCOORD_0`/`_1`, `COLOR_0`, alphaMode MASK, and
//! doubleSided (single-sided materials have their back faces culled). Texture coordinate sets
//! past 1 are warned about where a material asks for one (see the loader).

use gltf::material::AlphaMode;
use gltf::Document;

use crate::BLEND_CUTOFF;

/// Extensions the loader reads.
const SUPPORTED_EXTENSIONS: &[&str] =
    &["KHR_lights_punctual", "KHR_texture_transform", "KHR_materials_emissive_strength"];

/// One line per ignored feature, naming the material that uses it.
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
        if m.alpha_mode() == AlphaMode::Blend {
            out.push(format!(
                "{name}: alphaMode BLEND (partial transparency) is not supported; drawn as MASK with \
                 alphaCutoff {BLEND_CUTOFF}: alpha below it is a hole (for the camera, the lamp's shadows and \
                 the GI), the rest opaque"
            ));
        }
        if m.normal_texture().is_some() {
            out.push(format!("{name}: normal maps are not supported; the geometry's normals are used"));
        }
        if m.occlusion_texture().is_some() {
            out.push(format!("{name}: occlusion textures are not supported; ignored"));
        }
    }
    out
}
