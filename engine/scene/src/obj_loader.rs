//! Wavefront OBJ + MTL to a [`Scene`], through `tobj`.
//!
//! Choices worth knowing:
//! - A *missing* .mtl file is a warning, not an error: the meshes get the default material.
//!   Most tools behave this way and OBJ files travel without their .mtl all the time. A .mtl
//!   that exists but is malformed, or a `map_Kd` texture that cannot be loaded, is an error.
//! - Kd/Ke are taken as linear RGB; `map_Kd` images as sRGB, like every [`Texture`].
//! - Texture V is flipped (OBJ's origin is bottom-left, our textures' top-left).
//! - A material without `Kd` has albedo 0.8 (1.0 under a `map_Kd`), and faces without a
//!   material get [`Material::default`] (0.8 grey): the MTL format defines no default for
//!   `Kd`, and 0.8 is OpenGL's default diffuse reflectance (unlike glTF, whose default
//!   material is white: see [`Material::gltf_default`]). Textures repeat and are filtered
//!   trilinearly; `d` (dissolve) is kept in the base colour's alpha but drawn opaque; every
//!   face is drawn from both sides (OBJ has no notion of a single-sided face).
//! - OBJ has no hierarchy: positions are used as written (metres, +Y up assumed).
//!
//! `tobj` can panic on some malformed input (an over-large negative face index, a colour with
//! fewer than three numbers), so the text is checked first, and the calls are also wrapped
//! in `catch_unwind` as a last line of defence.

use std::cell::RefCell;
use std::collections::HashMap;
use std::io::Cursor;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use glam::Mat4;

use crate::error::{LoadError, LoadErrorKind};
use crate::geometry::{bake, RawTriangles};
use crate::image_loader::{decode_texture, file_label};
use crate::limits::MAX_TRIANGLES;
use crate::sources::Sources;
use crate::{Material, Mesh, Scene, TextureRef};

/// Loads an .obj file and the .mtl libraries it names.
pub fn load_obj(path: &Path) -> Result<Scene, LoadError> {
    load_obj_with(path, &mut Sources::new(None))
}

/// What the material-library callback found; `tobj` only lets it return its own error type.
struct MtlState<'s> {
    sources: &'s mut Sources,
    /// Each loaded library and how many materials it contributed, in tobj's merge order.
    libraries: Vec<(PathBuf, usize)>,
    error: Option<LoadError>,
}

pub(crate) fn load_obj_with(path: &Path, sources: &mut Sources) -> Result<Scene, LoadError> {
    let bytes = sources.read(path)?;
    let text = String::from_utf8_lossy(&bytes);
    check_obj(&text).map_err(|kind| LoadError::new(path, kind))?;
    let base = path.parent().unwrap_or(Path::new(""));

    let state = RefCell::new(MtlState { sources, libraries: Vec::new(), error: None });
    let options = tobj::LoadOptions { single_index: true, triangulate: true, ignore_points: true, ignore_lines: true };
    let loaded = catch_unwind(AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut Cursor::new(text.as_bytes()), &options, |mtl: &Path| {
            load_library(path, base, mtl, &state)
        })
    }));
    let MtlState { sources, libraries, error } = state.into_inner();
    if let Some(e) = error {
        return Err(e);
    }
    let corrupt = |msg: String| LoadError::new(path, LoadErrorKind::CorruptObj(msg));
    let (models, materials) = match loaded {
        Ok(Ok((models, materials))) => (models, materials.unwrap_or_default()),
        Ok(Err(e)) => return Err(corrupt(e.to_string())),
        Err(_) => return Err(corrupt("malformed file (the OBJ parser gave up)".into())),
    };

    let mut builder = Builder {
        path,
        sources,
        libraries,
        materials,
        scene: Scene::default(),
        used: HashMap::new(),
        textures: HashMap::new(),
    };
    let mut triangles = 0usize;
    for (i, model) in models.iter().enumerate() {
        let m = &model.mesh;
        if m.indices.is_empty() {
            continue;
        }
        let name = if model.name.is_empty() { format!("object{i}") } else { model.name.clone() };
        let n = m.positions.len() / 3;
        let positions: Vec<[f32; 3]> = m.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        if let Some(v) = positions.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(corrupt(format!("object '{name}': vertex {v} has a non-finite position {:?}", positions[v])));
        }
        // With single_index, tobj emits normals/uvs only for vertices that have them; a
        // partial set cannot be matched to vertices, so it is dropped.
        let normals = if m.normals.len() == 3 * n {
            Some(m.normals.chunks_exact(3).map(|v| [v[0], v[1], v[2]]).collect())
        } else {
            if !m.normals.is_empty() {
                builder.sources.warn(
                    path,
                    None,
                    format!("object '{name}': only some vertices have normals; using flat normals"),
                );
            }
            None
        };
        let uvs =
            (m.texcoords.len() == 2 * n).then(|| m.texcoords.chunks_exact(2).map(|t| [t[0], 1.0 - t[1]]).collect());
        let mut indices = m.indices.clone();
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= n) {
            return Err(corrupt(format!("object '{name}': index {bad} out of range ({n} vertices)")));
        }
        indices.truncate(indices.len() / 3 * 3);
        triangles += indices.len() / 3;
        if triangles > MAX_TRIANGLES {
            return Err(LoadError::too_large(path, format!("more than {MAX_TRIANGLES} triangles")));
        }
        let raw = RawTriangles { positions, normals, uvs, indices, ..RawTriangles::default() };
        let (vertices, indices) = bake(&raw, &Mat4::IDENTITY).map_err(|e| corrupt(format!("object '{name}': {e}")))?;
        let material = builder.material(m.material_id)?;
        builder.scene.meshes.push(Mesh { name, vertices, indices, material });
    }
    Ok(builder.scene)
}

/// The `tobj` material loader: resolves `mtllib` names against the .obj folder and reads them
/// through [`Sources`]. Errors are parked in `state` (tobj cannot carry them).
fn load_library(obj: &Path, base: &Path, mtl: &Path, state: &RefCell<MtlState>) -> tobj::MTLLoadResult {
    let mut st = state.borrow_mut();
    if st.error.is_some() {
        return Ok(Default::default());
    }
    let written = mtl.to_string_lossy().replace('\\', "/");
    if written.trim().is_empty() {
        st.sources.warn(obj, None, "'mtllib' without a file name; using the default material");
        return Ok(Default::default());
    }
    let missing = |e: &LoadError| matches!(e.kind, LoadErrorKind::NotFound);
    let read = st.sources.resolve(obj, base, &written).and_then(|file| Ok((st.sources.read(&file)?, file)));
    let (bytes, file) = match read {
        Ok(found) => found,
        Err(e) if missing(&e) => {
            st.sources.warn(obj, None, format!("material library '{written}' not found; using the default material"));
            return Ok(Default::default());
        }
        Err(e) => {
            st.error = Some(e);
            return Err(tobj::LoadError::GenericFailure);
        }
    };
    let corrupt = |msg: String| LoadError::new(&file, LoadErrorKind::CorruptMtl(msg));
    let text = match fix_mtl(&String::from_utf8_lossy(&bytes)) {
        Ok(t) => t,
        Err(msg) => {
            st.error = Some(corrupt(msg));
            return Err(tobj::LoadError::GenericFailure);
        }
    };
    match catch_unwind(|| tobj::load_mtl_buf(&mut Cursor::new(text.as_bytes()))) {
        Ok(Ok((mats, names))) => {
            st.libraries.push((file, mats.len()));
            Ok((mats, names))
        }
        Ok(Err(e)) => {
            st.error = Some(corrupt(e.to_string()));
            Err(e)
        }
        Err(_) => {
            st.error = Some(corrupt("malformed file (the MTL parser gave up)".into()));
            Err(tobj::LoadError::GenericFailure)
        }
    }
}

struct Builder<'a> {
    path: &'a Path,
    sources: &'a mut Sources,
    libraries: Vec<(PathBuf, usize)>,
    materials: Vec<tobj::Material>,
    scene: Scene,
    /// tobj material id (None = default) → scene material index.
    used: HashMap<Option<usize>, usize>,
    /// Resolved texture path → scene texture index.
    textures: HashMap<PathBuf, usize>,
}

impl Builder<'_> {
    /// Converts an MTL material on first use; unused materials' textures are never loaded.
    fn material(&mut self, id: Option<usize>) -> Result<usize, LoadError> {
        let id = id.filter(|&i| i < self.materials.len());
        if let Some(&i) = self.used.get(&id) {
            return Ok(i);
        }
        let material = match id {
            None => Material::default(),
            Some(i) => self.convert(i)?,
        };
        self.scene.materials.push(material);
        let index = self.scene.materials.len() - 1;
        self.used.insert(id, index);
        Ok(index)
    }

    /// The .mtl file material `i` came from.
    fn library_of(&self, i: usize) -> &Path {
        let mut end = 0;
        for (file, count) in &self.libraries {
            end += count;
            if i < end {
                return file;
            }
        }
        self.path
    }

    fn convert(&mut self, i: usize) -> Result<Material, LoadError> {
        let m = &self.materials[i];
        let mtl = self.library_of(i).to_path_buf();
        let texture_name = m.diffuse_texture.as_deref().map(map_file_name);
        let rgb = m.diffuse.unwrap_or(if texture_name.is_some() { [1.0; 3] } else { [0.8; 3] });
        let alpha = m.dissolve.unwrap_or(1.0);
        let emissive = m.emissive.unwrap_or([0.0; 3]);
        if !rgb.iter().chain(&emissive).chain([&alpha]).all(|c| c.is_finite() && *c >= 0.0) {
            return Err(LoadError::new(
                &mtl,
                LoadErrorKind::CorruptMtl(format!("material '{}': colours must be finite and non-negative", m.name)),
            ));
        }
        let name = m.name.clone();
        let base_color_texture = match texture_name {
            Some(Some(file)) => Some(TextureRef::new(self.texture(&mtl, &file)?)),
            Some(None) => {
                return Err(LoadError::new(
                    &mtl,
                    LoadErrorKind::CorruptMtl(format!("material '{name}': map_Kd has no file name")),
                ));
            }
            None => None,
        };
        let base_color = [rgb[0], rgb[1], rgb[2], alpha.min(1.0)];
        Ok(Material { name, base_color, base_color_texture, emissive, ..Material::default() })
    }

    /// Loads a `map_Kd` image named in `mtl`, relative to the .mtl's folder (falling back to
    /// the .obj's, where some exporters put textures).
    fn texture(&mut self, mtl: &Path, written: &str) -> Result<usize, LoadError> {
        let mtl_dir = mtl.parent().unwrap_or(Path::new(""));
        let obj_dir = self.path.parent().unwrap_or(Path::new(""));
        let file = match self.sources.resolve(mtl, mtl_dir, written) {
            Ok(file) if file.exists() => file,
            // Only a missing file falls back; a path leaving the level folder is an error.
            Ok(_) | Err(LoadError { kind: LoadErrorKind::NotFound, .. }) if mtl_dir != obj_dir => {
                match self.sources.resolve(mtl, obj_dir, written) {
                    Ok(alt) if alt.exists() => alt,
                    // Reading the primary location below reports "file not found" there.
                    _ => mtl_dir.join(written),
                }
            }
            Ok(file) => file,
            Err(e) => return Err(e),
        };
        if let Some(&t) = self.textures.get(&file) {
            return Ok(t);
        }
        let bytes = self.sources.read(&file)?;
        let texture = decode_texture(&bytes, &file, "", file_label(&file))?;
        self.sources.hold_texture(&file, &texture)?;
        self.scene.textures.push(texture);
        let t = self.scene.textures.len() - 1;
        self.textures.insert(file, t);
        Ok(t)
    }
}

/// The file name in a `map_Kd` statement, skipping options such as `-s 1 1 1` or `-bm 0.5`.
/// Backslashes (Windows exporters) become slashes. None if only options are present.
fn map_file_name(args: &str) -> Option<String> {
    let mut words = args.split_whitespace().peekable();
    while let Some(&w) = words.peek() {
        let fixed = match w {
            "-blendu" | "-blendv" | "-boost" | "-texres" | "-clamp" | "-bm" | "-imfchan" | "-type" | "-cc" => 1,
            "-mm" => 2,
            "-o" | "-s" | "-t" => 0, // one to three numbers, handled below
            _ => break,
        };
        words.next();
        if fixed == 0 {
            for _ in 0..3 {
                if words.peek().is_some_and(|n| n.parse::<f32>().is_ok()) {
                    words.next();
                }
            }
        } else {
            for _ in 0..fixed {
                words.next();
            }
        }
    }
    let rest: Vec<&str> = words.collect();
    (!rest.is_empty()).then(|| rest.join(" ").replace('\\', "/"))
}

/// Checks face indices against the vertices declared so far (tobj can overflow on a large
/// negative index) and refuses absurd triangle counts before tobj allocates for them.
fn check_obj(text: &str) -> Result<(), LoadErrorKind> {
    let (mut v, mut vt, mut vn, mut triangles) = (0usize, 0usize, 0usize, 0usize);
    for (line_no, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => v += 1,
            Some("vt") => vt += 1,
            Some("vn") => vn += 1,
            Some("f") => {
                let mut corners = 0usize;
                for word in words {
                    corners += 1;
                    let parts: Vec<&str> = word.split('/').collect();
                    if parts.len() > 3 || parts[0].is_empty() {
                        return Err(LoadErrorKind::CorruptObj(format!(
                            "line {}: malformed face vertex '{word}'",
                            line_no + 1
                        )));
                    }
                    for (part, (count, what)) in
                        parts.iter().zip([(v, "vertex"), (vt, "texture coordinate"), (vn, "normal")])
                    {
                        if part.is_empty() {
                            continue;
                        }
                        let ok = match part.parse::<i64>() {
                            Ok(i) if i > 0 => i as u64 <= count as u64,
                            Ok(i) if i < 0 => i.unsigned_abs() <= count as u64,
                            _ => false,
                        };
                        if !ok {
                            return Err(LoadErrorKind::CorruptObj(format!(
                                "line {}: {what} index '{part}' out of range ({count} declared so far)",
                                line_no + 1
                            )));
                        }
                    }
                }
                triangles += corners.saturating_sub(2);
                if triangles > MAX_TRIANGLES {
                    return Err(LoadErrorKind::TooLarge(format!("more than {MAX_TRIANGLES} triangles")));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Makes an MTL safe for tobj: `Kd r` (one number, legal: g = b = r) is expanded to `Kd r r r`,
/// since tobj panics on fewer than three numbers; other short colours are errors.
fn fix_mtl(text: &str) -> Result<String, String> {
    let mut out = String::with_capacity(text.len() + 16);
    for (line_no, line) in text.lines().enumerate() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            [key @ ("Ka" | "Kd" | "Ks" | "Ke" | "Tf"), rest @ ..] if rest.len() < 3 => match rest {
                [one] if one.parse::<f32>().is_ok() => out.push_str(&format!("{key} {one} {one} {one}")),
                _ => return Err(format!("line {}: '{key}' needs three numbers (r g b)", line_no + 1)),
            },
            _ => out.push_str(line),
        }
        out.push('\n');
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_kd_options_are_skipped() {
        assert_eq!(map_file_name("wood.png").as_deref(), Some("wood.png"));
        assert_eq!(map_file_name("-s 2 2 1 -bm 0.5 tex\\wood grain.png").as_deref(), Some("tex/wood grain.png"));
        assert_eq!(map_file_name("-o 0.5 wood.png").as_deref(), Some("wood.png"));
        assert_eq!(map_file_name("-clamp on"), None);
    }

    #[test]
    fn face_indices_are_checked() {
        assert!(check_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf -1 -2 -3\n").is_ok());
        assert!(check_obj("v 0 0 0\nf 1 2 3\n").is_err());
        assert!(check_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/-99999999999 2 3\n").is_err());
        assert!(check_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").is_err());
    }

    #[test]
    fn short_colours() {
        assert_eq!(fix_mtl("Kd 0.5\n").unwrap(), "Kd 0.5 0.5 0.5\n");
        assert!(fix_mtl("Kd 0.5 0.5\n").is_err());
    }
}
