//! glTF 2.0 (.gltf with external or embedded buffers, and .glb) to a world-space [`Scene`].
//!
//! The `gltf` crate parses and validates the JSON (every index reference is checked there);
//! everything that touches bytes (GLB container, buffers, accessors, images) is done with
//! explicit bounds checks in this crate, so malformed files are errors, not panics.

use std::collections::HashMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use glam::{Mat3, Mat4, Quat, Vec3};
use gltf::camera::Projection as GltfProjection;
use gltf::khr_lights_punctual::Kind as GltfLightKind;
use gltf::material::AlphaMode as GltfAlphaMode;
use gltf::mesh::{Mode, Semantic};
use gltf::texture::{MagFilter, MinFilter, WrappingMode};
use gltf::{Document, Node};

use crate::error::{one_line, LoadError, LoadErrorKind};
use crate::geometry::{bake, rigid_pose, RawTriangles};
use crate::gltf_accessor::{read_colors, read_indices, read_vectors, view_bytes};
use crate::gltf_container::{is_glb, parse_uri, split_glb, UriTarget};
use crate::gltf_unsupported::unsupported_features;
use crate::image_loader::{decode_texture, file_label};
use crate::limits::{MAX_FILE_BYTES, MAX_TRIANGLES};
use crate::sources::Sources;
use crate::{
    AlphaMode, Filter, LightKind, Material, Mesh, NodeExtras, Projection, PunctualLight, Reflection, Sampler, Scene,
    SceneCamera, TextureRef, TextureTransform, Wrap,
};

/// Loads a .gltf or .glb file (the container is recognised by its bytes, not its extension).
///
/// The default scene is used (else scene 0, else every root node); meshes are baked to world
/// space (with `TEXCOORD_0`/`_1` and `COLOR_0`), cameras and `KHR_lights_punctual` lights get
/// world poses, node `extras` are kept. Materials keep base colour, metallic-roughness and
/// emissive factors and textures (samplers, `KHR_texture_transform`,
/// `KHR_materials_emissive_strength`), alpha mode and sidedness; a primitive without a material gets [`Material::gltf_default`].
pub fn load_gltf(path: &Path) -> Result<Scene, LoadError> {
    load_gltf_with(path, &mut Sources::new(None))
}

pub(crate) fn load_gltf_with(path: &Path, sources: &mut Sources) -> Result<Scene, LoadError> {
    let bytes = sources.read(path)?;
    let (json, blob) = if is_glb(&bytes) {
        let glb = split_glb(&bytes).map_err(|e| LoadError::gltf(path, e))?;
        (glb.json, glb.bin)
    } else {
        (&bytes[..], None)
    };
    let root: gltf::json::Root = gltf::json::deserialize::from_slice(json)
        .map_err(|e| LoadError::gltf(path, format!("not valid glTF JSON: {e}")))?;
    check_attribute_indices(&root).map_err(|e| LoadError::gltf(path, e))?;
    // The crate's validator indexes the POSITION accessor unchecked (guarded above); the
    // catch is a last line of defence against similar slips in third-party code.
    let doc = catch_unwind(AssertUnwindSafe(|| Document::from_json(root)))
        .map_err(|_| LoadError::gltf(path, "the glTF validator gave up on this file"))?
        .map_err(|e| LoadError::gltf(path, describe_invalid(&e)))?;

    for feature in unsupported_features(&doc) {
        sources.warn(path, None, feature);
    }
    let buffers = load_buffers(&doc, blob, path, sources)?;
    let mut builder = Builder {
        path,
        base: path.parent().unwrap_or(Path::new("")),
        doc: &doc,
        buffers,
        sources,
        scene: Scene::default(),
        materials: HashMap::new(),
        textures: HashMap::new(),
        triangles: 0,
    };
    builder.walk()?;
    Ok(builder.scene)
}

/// Every primitive attribute must name an existing accessor: `gltf-json` 1.4's validator
/// looks the POSITION accessor up without a bounds check and would panic.
fn check_attribute_indices(root: &gltf::json::Root) -> Result<(), String> {
    // The crate's `image.source()` unwraps these (both are spec violations).
    for (i, image) in root.images.iter().enumerate() {
        match (&image.uri, &image.buffer_view, &image.mime_type) {
            (None, None, _) => return Err(format!("images[{i}] has neither a uri nor a bufferView")),
            (None, Some(_), None) => return Err(format!("images[{i}] is in a bufferView but has no mimeType")),
            _ => {}
        }
    }
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            for (semantic, index) in &prim.attributes {
                if index.value() >= root.accessors.len() {
                    return Err(format!(
                        "meshes[{m}].primitives[{p}].attributes[{semantic:?}]: accessor {} does not exist ({} accessors)",
                        index.value(),
                        root.accessors.len()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Summarises the crate's validation report (which can list hundreds of problems) in one line.
fn describe_invalid(e: &gltf::Error) -> String {
    match e {
        gltf::Error::Validation(list) => {
            let shown: Vec<String> = list.iter().take(4).map(|(path, err)| format!("{path}: {err}")).collect();
            let more = list.len().saturating_sub(shown.len());
            let tail = if more > 0 { format!(" (and {more} more)") } else { String::new() };
            format!("{}{tail}", shown.join("; "))
        }
        other => one_line(other),
    }
}

/// Loads every buffer's bytes: the GLB BIN chunk, a data: URI, or a file beside the glTF.
fn load_buffers(
    doc: &Document,
    blob: Option<&[u8]>,
    path: &Path,
    sources: &mut Sources,
) -> Result<Vec<Vec<u8>>, LoadError> {
    let base = path.parent().unwrap_or(Path::new(""));
    let mut out = Vec::with_capacity(doc.buffers().len());
    for buffer in doc.buffers() {
        let i = buffer.index();
        let want = buffer.length();
        if want as u64 > MAX_FILE_BYTES {
            return Err(LoadError::too_large(
                path,
                format!("buffer {i} declares {want} bytes (limit {MAX_FILE_BYTES})"),
            ));
        }
        let mut data = match buffer.source() {
            gltf::buffer::Source::Bin => blob
                .ok_or_else(|| {
                    LoadError::gltf(path, format!("buffer {i} refers to the GLB binary chunk, but there is none"))
                })?
                .to_vec(),
            gltf::buffer::Source::Uri(uri) => {
                match parse_uri(uri).map_err(|e| LoadError::gltf(path, format!("buffer {i}: {e}")))? {
                    UriTarget::Embedded(bytes) => bytes,
                    UriTarget::File(rel) => {
                        let file = sources.resolve(path, base, &rel)?;
                        sources.read(&file)?
                    }
                }
            }
        };
        if data.len() < want {
            return Err(LoadError::gltf(
                path,
                format!("buffer {i} has {} bytes but its byteLength is {want}", data.len()),
            ));
        }
        // The BIN chunk may carry up to 3 bytes of padding; views must fit the declared length.
        data.truncate(want);
        out.push(data);
    }
    Ok(out)
}

struct Builder<'a> {
    path: &'a Path,
    base: &'a Path,
    doc: &'a Document,
    buffers: Vec<Vec<u8>>,
    sources: &'a mut Sources,
    scene: Scene,
    /// glTF material index (None = the default material) → index in `scene.materials`.
    materials: HashMap<Option<usize>, usize>,
    /// glTF image index → index in `scene.textures`.
    textures: HashMap<usize, usize>,
    triangles: usize,
}

impl Builder<'_> {
    fn corrupt(&self, msg: impl std::fmt::Display) -> LoadError {
        LoadError::gltf(self.path, msg)
    }

    fn at(&self, kind: LoadErrorKind) -> LoadError {
        LoadError::new(self.path, kind)
    }

    /// Walks the chosen node trees depth-first, in file order, without recursion (a deep or
    /// cyclic hierarchy must not overflow the stack).
    fn walk(&mut self) -> Result<(), LoadError> {
        let doc = self.doc;
        let roots: Vec<Node> = match doc.default_scene().or_else(|| doc.scenes().next()) {
            Some(scene) => scene.nodes().collect(),
            None => {
                let mut is_child = vec![false; doc.nodes().len()];
                for node in doc.nodes() {
                    for child in node.children() {
                        is_child[child.index()] = true;
                    }
                }
                doc.nodes().filter(|n| !is_child[n.index()]).collect()
            }
        };
        let mut visited = vec![false; doc.nodes().len()];
        let mut stack: Vec<(Node, Mat4)> = roots.into_iter().rev().map(|n| (n, Mat4::IDENTITY)).collect();
        while let Some((node, parent)) = stack.pop() {
            let idx = node.index();
            if std::mem::replace(&mut visited[idx], true) {
                return Err(self.corrupt(format!("node {idx} is reached twice (a cycle, or a node with two parents)")));
            }
            let world = parent * self.local_transform(&node)?;
            if !world.is_finite() {
                return Err(self.corrupt(format!("node {idx}: world transform overflows")));
            }
            self.visit(&node, &world)?;
            let children: Vec<Node> = node.children().collect();
            stack.extend(children.into_iter().rev().map(|c| (c, world)));
        }
        Ok(())
    }

    fn local_transform(&self, node: &Node) -> Result<Mat4, LoadError> {
        let idx = node.index();
        let m = match node.transform() {
            gltf::scene::Transform::Matrix { matrix } => Mat4::from_cols_array_2d(&matrix),
            gltf::scene::Transform::Decomposed { translation, rotation, scale } => {
                let q = Quat::from_array(rotation);
                let q = q.try_normalize_quat().ok_or_else(|| {
                    self.corrupt(format!("node {idx}: rotation {rotation:?} is not a usable quaternion"))
                })?;
                Mat4::from_scale_rotation_translation(Vec3::from(scale), q, Vec3::from(translation))
            }
        };
        if !m.is_finite() {
            return Err(self.corrupt(format!("node {idx}: transform has non-finite values")));
        }
        Ok(m)
    }

    fn visit(&mut self, node: &Node, world: &Mat4) -> Result<(), LoadError> {
        if let Some(mesh) = node.mesh() {
            for prim in mesh.primitives() {
                self.primitive(node, &mesh, &prim, world)?;
            }
        }
        if let Some(camera) = node.camera() {
            let cam = self.camera(node, &camera, world)?;
            self.scene.cameras.push(cam);
        }
        if let Some(light) = node.light() {
            let light = self.light(node, &light, world)?;
            self.scene.lights.push(light);
        }
        if let Some(raw) = node.extras() {
            let extras: serde_json::Value = serde_json::from_str(raw.get())
                .map_err(|e| self.corrupt(format!("node {}: extras: {e}", node.index())))?;
            if !extras.is_null() {
                self.scene.extras.push(NodeExtras { node_name: node_name(node), world: *world, extras });
            }
        }
        Ok(())
    }

    fn primitive(
        &mut self,
        node: &Node,
        mesh: &gltf::Mesh,
        prim: &gltf::Primitive,
        world: &Mat4,
    ) -> Result<(), LoadError> {
        let mesh_name = mesh.name().map(str::to_owned).unwrap_or_else(|| format!("mesh{}", mesh.index()));
        let label = match mesh.name() {
            Some(name) => format!("mesh {} ('{name}') primitive {}", mesh.index(), prim.index()),
            None => format!("mesh {} primitive {}", mesh.index(), prim.index()),
        };
        let mode = prim.mode();
        if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
            self.sources.warn(
                self.path,
                None,
                format!("{label}: skipping {mode:?} primitive (only triangles are drawn)"),
            );
            return Ok(());
        }
        let Some(pos_acc) = prim.get(&Semantic::Positions) else {
            self.sources.warn(self.path, None, format!("{label}: skipping primitive without POSITION"));
            return Ok(());
        };
        let with_label = |k: LoadErrorKind| match k {
            LoadErrorKind::CorruptGltf(m) => LoadErrorKind::CorruptGltf(format!("{label}: {m}")),
            LoadErrorKind::TooLarge(m) => LoadErrorKind::TooLarge(format!("{label}: {m}")),
            other => other,
        };
        let positions = read_vectors::<3>(&pos_acc, &self.buffers, "POSITION").map_err(|k| self.at(with_label(k)))?;
        let n = positions.len();
        if let Some(i) = positions.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(self.corrupt(format!("{label}: vertex {i} has a non-finite position {:?}", positions[i])));
        }
        let normals = match prim.get(&Semantic::Normals) {
            Some(acc) => Some(read_vectors::<3>(&acc, &self.buffers, "NORMAL").map_err(|k| self.at(with_label(k)))?),
            None => None,
        };
        let read_uvs = |set: u32, what: &str| match prim.get(&Semantic::TexCoords(set)) {
            Some(acc) => read_vectors::<2>(&acc, &self.buffers, what).map(Some).map_err(|k| self.at(with_label(k))),
            None => Ok(None),
        };
        let uvs = read_uvs(0, "TEXCOORD_0")?;
        let mut uvs1 = read_uvs(1, "TEXCOORD_1")?;
        let colors = match prim.get(&Semantic::Colors(0)) {
            Some(acc) => Some(read_colors(&acc, &self.buffers, "COLOR_0").map_err(|k| self.at(with_label(k)))?),
            None => None,
        };
        for (what, len) in [
            ("NORMAL", normals.as_ref().map(Vec::len)),
            ("TEXCOORD_0", uvs.as_ref().map(Vec::len)),
            ("TEXCOORD_1", uvs1.as_ref().map(Vec::len)),
            ("COLOR_0", colors.as_ref().map(Vec::len)),
        ] {
            if let Some(len) = len.filter(|&l| l != n) {
                return Err(self.corrupt(format!("{label}: {what} has {len} elements but POSITION has {n}")));
            }
        }
        if let Some((i, c)) =
            colors.iter().flatten().enumerate().find(|(_, c)| !c.iter().all(|v| v.is_finite() && *v >= 0.0))
        {
            return Err(
                self.corrupt(format!("{label}: vertex {i} has COLOR_0 {c:?}; colours must be finite and non-negative"))
            );
        }
        let indices = match prim.indices() {
            Some(acc) => read_indices(&acc, &self.buffers).map_err(|k| self.at(with_label(k)))?,
            None => (0..n as u32).collect(),
        };
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= n) {
            return Err(self.corrupt(format!("{label}: index {bad} out of range ({n} vertices)")));
        }
        let indices = match to_triangle_list(mode, indices) {
            (list, 0) => list,
            (list, dropped) => {
                let message = format!("{label}: ignoring {dropped} trailing indices that do not form a triangle");
                self.sources.warn(self.path, None, message);
                list
            }
        };
        if indices.is_empty() {
            return Ok(());
        }
        self.triangles += indices.len() / 3;
        if self.triangles > MAX_TRIANGLES {
            return Err(LoadError::too_large(self.path, format!("scene has more than {MAX_TRIANGLES} triangles")));
        }

        let material = self.material(prim.material())?;
        let uses_uv1 = self.scene.materials[material].textures().any(|t| t.tex_coord == 1);
        if uses_uv1 && uvs1.is_none() {
            let message =
                format!("{label}: its material's textures read TEXCOORD_1, which it lacks; TEXCOORD_0 is used");
            self.sources.warn(self.path, None, message);
            uvs1.clone_from(&uvs);
        }
        let raw = RawTriangles { positions, normals, uvs, uvs1, colors, indices };
        let (vertices, indices) =
            bake(&raw, world).map_err(|e| self.corrupt(format!("{label} (node {}): {e}", node.index())))?;
        let name = if mesh.primitives().len() > 1 { format!("{mesh_name}#{}", prim.index()) } else { mesh_name };
        self.scene.meshes.push(Mesh { name, vertices, indices, material });
        Ok(())
    }

    /// Index of the scene material for a glTF material, converting it on first use (so unused
    /// materials, and their textures, are never decoded).
    fn material(&mut self, m: gltf::Material) -> Result<usize, LoadError> {
        if let Some(&i) = self.materials.get(&m.index()) {
            return Ok(i);
        }
        let material = match m.index() {
            None => Material::gltf_default(),
            Some(idx) => {
                let pbr = m.pbr_metallic_roughness();
                let base_color = pbr.base_color_factor();
                let factor = m.emissive_factor();
                if !base_color.iter().chain(&factor).all(|c| c.is_finite() && *c >= 0.0) {
                    return Err(self.corrupt(format!("material {idx}: colour factors must be finite and non-negative")));
                }
                let strength = m.emissive_strength().unwrap_or(1.0);
                if !(strength.is_finite() && strength >= 0.0) {
                    return Err(self.corrupt(format!(
                        "material {idx}: KHR_materials_emissive_strength {strength} must be finite and non-negative"
                    )));
                }
                let base_color_texture = match pbr.base_color_texture() {
                    Some(info) => Some(self.texture_ref(idx, "base colour", &info)?),
                    None => None,
                };
                let emissive_texture = match m.emissive_texture() {
                    Some(info) => Some(self.texture_ref(idx, "emissive", &info)?),
                    None => None,
                };
                let (metallic, roughness) = (pbr.metallic_factor(), pbr.roughness_factor());
                for (name, value) in [("metallicFactor", metallic), ("roughnessFactor", roughness)] {
                    if !(0.0..=1.0).contains(&value) {
                        return Err(self.corrupt(format!("material {idx}: {name} {value} must be between 0 and 1")));
                    }
                }
                let texture = match pbr.metallic_roughness_texture() {
                    Some(info) => Some(self.texture_ref(idx, "metallic-roughness", &info)?),
                    None => None,
                };
                let alpha_mode = match m.alpha_mode() {
                    GltfAlphaMode::Opaque => AlphaMode::Opaque,
                    GltfAlphaMode::Mask => {
                        let cutoff = m.alpha_cutoff().unwrap_or(0.5);
                        if !(cutoff.is_finite() && cutoff >= 0.0) {
                            return Err(self.corrupt(format!(
                                "material {idx}: alphaCutoff {cutoff} must be finite and non-negative"
                            )));
                        }
                        AlphaMode::Mask { cutoff }
                    }
                    GltfAlphaMode::Blend => AlphaMode::Blend,
                };
                Material {
                    name: m.name().map(str::to_owned).unwrap_or_else(|| format!("material{idx}")),
                    base_color,
                    base_color_texture,
                    emissive: factor.map(|c| c * strength),
                    emissive_texture,
                    alpha_mode,
                    reflection: Reflection::MetallicRoughness { metallic, roughness, texture },
                    double_sided: m.double_sided(),
                }
            }
        };
        self.scene.materials.push(material);
        let i = self.scene.materials.len() - 1;
        self.materials.insert(m.index(), i);
        Ok(i)
    }

    /// A material's texture slot (`what`: "base colour", "emissive"): its image, sampler, uv
    /// set and `KHR_texture_transform` (whose `texCoord` overrides the slot's own).
    fn texture_ref(
        &mut self,
        material: usize,
        what: &str,
        info: &gltf::texture::Info,
    ) -> Result<TextureRef, LoadError> {
        let transform = info.texture_transform();
        let mut tex_coord = transform.as_ref().and_then(|t| t.tex_coord()).unwrap_or(info.tex_coord());
        if tex_coord > 1 {
            let message = format!(
                "material {material}: {what} texture uses TEXCOORD_{tex_coord}; only TEXCOORD_0 and TEXCOORD_1 \
                 are read, TEXCOORD_0 is used instead"
            );
            self.sources.warn(self.path, None, message);
            tex_coord = 0;
        }
        let transform = match transform {
            Some(t) => {
                let transform = TextureTransform { offset: t.offset(), rotation: t.rotation(), scale: t.scale() };
                let values = transform.offset.iter().chain(&transform.scale).chain([&transform.rotation]);
                if !values.into_iter().all(|v| v.is_finite()) {
                    return Err(self.corrupt(format!(
                        "material {material}: {what} texture's KHR_texture_transform {transform:?} has \
                         non-finite values"
                    )));
                }
                transform
            }
            None => TextureTransform::IDENTITY,
        };
        let texture = info.texture();
        let sampler = convert_sampler(&texture.sampler());
        let texture = self.texture(texture.source())?;
        Ok(TextureRef { texture, sampler, tex_coord, transform })
    }

    /// Index of the scene texture for a glTF image, decoding it on first use.
    fn texture(&mut self, image: gltf::Image) -> Result<usize, LoadError> {
        let idx = image.index();
        if let Some(&t) = self.textures.get(&idx) {
            return Ok(t);
        }
        let what = format!("image {idx}");
        let texture = match image.source() {
            gltf::image::Source::View { view, .. } => {
                let bytes = view_bytes(&view, &self.buffers).map_err(|k| self.at(k))?;
                let name = image.name().map(str::to_owned).unwrap_or_else(|| format!("image{idx}"));
                decode_texture(bytes, self.path, &what, name)?
            }
            gltf::image::Source::Uri { uri, .. } => {
                match parse_uri(uri).map_err(|e| self.corrupt(format!("{what}: {e}")))? {
                    UriTarget::Embedded(bytes) => {
                        let name = image.name().map(str::to_owned).unwrap_or_else(|| format!("image{idx}"));
                        decode_texture(&bytes, self.path, &what, name)?
                    }
                    UriTarget::File(rel) => {
                        let file = self.sources.resolve(self.path, self.base, &rel)?;
                        let bytes = self.sources.read(&file)?;
                        let name = image.name().map(str::to_owned).unwrap_or_else(|| file_label(&file));
                        decode_texture(&bytes, &file, "", name)?
                    }
                }
            }
        };
        self.sources.hold_texture(self.path, &texture)?;
        self.scene.textures.push(texture);
        let t = self.scene.textures.len() - 1;
        self.textures.insert(idx, t);
        Ok(t)
    }

    fn camera(&self, node: &Node, camera: &gltf::Camera, world: &Mat4) -> Result<SceneCamera, LoadError> {
        let label = format!("camera {} (node {})", camera.index(), node.index());
        let bad = |what: &str| self.corrupt(format!("{label}: {what}"));
        let (position, rotation) = rigid_pose(world).ok_or_else(|| bad("node transform is degenerate"))?;
        let projection = match camera.projection() {
            GltfProjection::Perspective(p) => {
                let (yfov, znear) = (p.yfov(), p.znear());
                if !(yfov > 0.0 && yfov < std::f32::consts::PI) {
                    return Err(bad(&format!("yfov {yfov} is not in (0, pi)")));
                }
                if !(znear > 0.0 && znear.is_finite()) {
                    return Err(bad(&format!("znear {znear} must be positive")));
                }
                if let Some(a) = p.aspect_ratio().filter(|a| !(*a > 0.0 && a.is_finite())) {
                    return Err(bad(&format!("aspectRatio {a} must be positive")));
                }
                if let Some(f) = p.zfar().filter(|f| !(*f > znear && f.is_finite())) {
                    return Err(bad(&format!("zfar {f} must be greater than znear {znear}")));
                }
                Projection::Perspective { yfov, aspect: p.aspect_ratio(), znear, zfar: p.zfar() }
            }
            GltfProjection::Orthographic(o) => {
                let (xmag, ymag, znear, zfar) = (o.xmag(), o.ymag(), o.znear(), o.zfar());
                if !(xmag != 0.0 && ymag != 0.0 && xmag.is_finite() && ymag.is_finite()) {
                    return Err(bad(&format!("xmag {xmag} and ymag {ymag} must be non-zero")));
                }
                if !(znear >= 0.0 && zfar > znear && zfar.is_finite()) {
                    return Err(bad(&format!("znear {znear} / zfar {zfar} must satisfy 0 <= znear < zfar")));
                }
                Projection::Orthographic { xmag, ymag, znear, zfar }
            }
        };
        let name =
            camera.name().or(node.name()).map(str::to_owned).unwrap_or_else(|| format!("camera{}", camera.index()));
        Ok(SceneCamera { name, position, rotation, projection })
    }

    fn light(
        &self,
        node: &Node,
        light: &gltf::khr_lights_punctual::Light,
        world: &Mat4,
    ) -> Result<PunctualLight, LoadError> {
        let label = format!("light {} (node {})", light.index(), node.index());
        let bad = |what: String| self.corrupt(format!("{label}: {what}"));
        let (color, intensity, range) = (light.color(), light.intensity(), light.range());
        if !color.iter().all(|c| c.is_finite() && *c >= 0.0) {
            return Err(bad(format!("colour {color:?} must be finite and non-negative")));
        }
        if !(intensity >= 0.0 && intensity.is_finite()) {
            return Err(bad(format!("intensity {intensity} must be finite and non-negative")));
        }
        if let Some(r) = range.filter(|r| !(*r > 0.0 && r.is_finite())) {
            return Err(bad(format!("range {r} must be positive")));
        }
        let kind = match light.kind() {
            GltfLightKind::Point => LightKind::Point,
            GltfLightKind::Directional => LightKind::Directional,
            GltfLightKind::Spot { inner_cone_angle: inner, outer_cone_angle: outer } => {
                // Equal angles (a hard-edged cone) are what Blender exports with zero blend.
                if !(inner >= 0.0 && inner <= outer && outer <= std::f32::consts::FRAC_PI_2 + 1e-6) {
                    return Err(bad(format!(
                        "spot cone angles inner {inner} / outer {outer} must satisfy 0 <= inner <= outer <= pi/2"
                    )));
                }
                LightKind::Spot { inner_cone: inner, outer_cone: outer }
            }
        };
        let direction = (Mat3::from_mat4(*world) * Vec3::NEG_Z).try_normalize();
        let direction = match (kind, direction) {
            (_, Some(d)) => d,
            (LightKind::Point, None) => Vec3::NEG_Z,
            (_, None) => return Err(bad("node transform is degenerate, the light has no direction".into())),
        };
        let name = light.name().or(node.name()).map(str::to_owned).unwrap_or_else(|| format!("light{}", light.index()));
        Ok(PunctualLight { name, kind, position: world.w_axis.truncate(), direction, color, intensity, range })
    }
}

/// A glTF sampler; an unset `minFilter` gets trilinear filtering, an unset `magFilter` linear.
fn convert_sampler(s: &gltf::texture::Sampler) -> Sampler {
    let wrap = |w: WrappingMode| match w {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::ClampToEdge,
        WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
    };
    let mag_filter = match s.mag_filter() {
        Some(MagFilter::Nearest) => Filter::Nearest,
        Some(MagFilter::Linear) | None => Filter::Linear,
    };
    let (min_filter, mipmap_filter) = match s.min_filter() {
        Some(MinFilter::Nearest) => (Filter::Nearest, None),
        Some(MinFilter::Linear) => (Filter::Linear, None),
        Some(MinFilter::NearestMipmapNearest) => (Filter::Nearest, Some(Filter::Nearest)),
        Some(MinFilter::LinearMipmapNearest) => (Filter::Linear, Some(Filter::Nearest)),
        Some(MinFilter::NearestMipmapLinear) => (Filter::Nearest, Some(Filter::Linear)),
        Some(MinFilter::LinearMipmapLinear) | None => (Filter::Linear, Some(Filter::Linear)),
    };
    Sampler { wrap_u: wrap(s.wrap_s()), wrap_v: wrap(s.wrap_t()), mag_filter, min_filter, mipmap_filter }
}

fn node_name(node: &Node) -> String {
    node.name().map(str::to_owned).unwrap_or_else(|| format!("node{}", node.index()))
}

/// Converts strips and fans to a triangle list (glTF 2.0 §3.7.2.1 vertex orders), returning
/// the list and how many trailing indices of a plain list were left over.
fn to_triangle_list(mode: Mode, idx: Vec<u32>) -> (Vec<u32>, usize) {
    match mode {
        Mode::TriangleStrip => {
            let tris = idx.len().saturating_sub(2);
            let mut out = Vec::with_capacity(tris * 3);
            for i in 0..tris {
                // Every other triangle swaps two vertices so all keep the strip's winding.
                let (a, b, c) = if i % 2 == 0 { (i, i + 1, i + 2) } else { (i, i + 2, i + 1) };
                out.extend([idx[a], idx[b], idx[c]]);
            }
            (out, 0)
        }
        Mode::TriangleFan => {
            let tris = idx.len().saturating_sub(2);
            let mut out = Vec::with_capacity(tris * 3);
            for i in 0..tris {
                out.extend([idx[i + 1], idx[i + 2], idx[0]]);
            }
            (out, 0)
        }
        _ => {
            let rem = idx.len() % 3;
            let mut idx = idx;
            idx.truncate(idx.len() - rem);
            (idx, rem)
        }
    }
}

trait TryNormalizeQuat: Sized {
    fn try_normalize_quat(self) -> Option<Self>;
}

impl TryNormalizeQuat for Quat {
    /// Exporters write slightly non-unit quaternions; a zero or non-finite one is corrupt.
    fn try_normalize_quat(self) -> Option<Self> {
        let len = self.length();
        (len.is_finite() && len > 1e-6).then(|| self / len)
    }
}
