use glam::{Mat4, Quat, Vec3};

/// One vertex as the renderer uploads it: world-space position and unit normal, two texture
/// coordinate sets and a colour.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    /// Texture coordinate set 0 (glTF `TEXCOORD_0`), (0, 0) when the file has none.
    pub uv: [f32; 2],
    /// Texture coordinate set 1 (glTF `TEXCOORD_1`), (0, 0) when the file has none.
    pub uv1: [f32; 2],
    /// Linear RGBA multiplying the material's base colour (glTF `COLOR_0`); white when absent.
    pub color: [f32; 4],
}

impl Vertex {
    /// A vertex with no second uv set and a white colour.
    pub fn new(position: [f32; 3], normal: [f32; 3], uv: [f32; 2]) -> Self {
        Self { position, normal, uv, uv1: [0.0; 2], color: [1.0; 4] }
    }
}

impl Default for Vertex {
    /// At the origin, no normal, uvs (0, 0), white.
    fn default() -> Self {
        Self::new([0.0; 3], [0.0; 3], [0.0; 2])
    }
}

/// A triangle list in world space drawn with one material.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub name: String,
    pub vertices: Vec<Vertex>,
    /// Triangle list; always present (non-indexed input gets 0..n).
    pub indices: Vec<u32>,
    /// Index into `Scene::materials`.
    pub material: usize,
}

/// How texture coordinates outside [0, 1] are mapped (glTF sampler `wrapS`/`wrapT`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Wrap {
    #[default]
    Repeat,
    ClampToEdge,
    MirroredRepeat,
}

/// Texel filtering: the nearest texel, or a linear blend of the nearest ones.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Filter {
    Nearest,
    #[default]
    Linear,
}

/// How a texture is sampled (a glTF sampler). Every texture has a full mip chain on the GPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Sampler {
    /// Along u (glTF `wrapS`).
    pub wrap_u: Wrap,
    /// Along v (glTF `wrapT`).
    pub wrap_v: Wrap,
    /// When a texel covers more than a pixel.
    pub mag_filter: Filter,
    /// Within a mip level when a texel covers less than a pixel.
    pub min_filter: Filter,
    /// Between mip levels; None samples the full-size image only (glTF `minFilter` NEAREST or
    /// LINEAR, which have no mipmapping).
    pub mipmap_filter: Option<Filter>,
}

impl Default for Sampler {
    /// Repeat, trilinear: what glTF leaves to the implementation when a sampler says nothing.
    fn default() -> Self {
        Self {
            wrap_u: Wrap::Repeat,
            wrap_v: Wrap::Repeat,
            mag_filter: Filter::Linear,
            min_filter: Filter::Linear,
            mipmap_filter: Some(Filter::Linear),
        }
    }
}

/// An affine map of texture coordinates (glTF `KHR_texture_transform`): uv' = T·R·S·uv, scale
/// first, then a rotation by `rotation` radians (counter-clockwise in uv, i.e. the image turns
/// clockwise), then the offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureTransform {
    pub offset: [f32; 2],
    pub rotation: f32,
    pub scale: [f32; 2],
}

impl TextureTransform {
    pub const IDENTITY: Self = Self { offset: [0.0; 2], rotation: 0.0, scale: [1.0; 2] };

    /// The map as the two rows of a 2×3 matrix acting on (u, v, 1).
    pub fn matrix(&self) -> [[f32; 3]; 2] {
        let (sin, cos) = self.rotation.sin_cos();
        let [sx, sy] = self.scale;
        let [ox, oy] = self.offset;
        [[cos * sx, sin * sy, ox], [-sin * sx, cos * sy, oy]]
    }

    /// Maps one texture coordinate.
    pub fn apply(&self, uv: [f32; 2]) -> [f32; 2] {
        let [r0, r1] = self.matrix();
        [r0[0] * uv[0] + r0[1] * uv[1] + r0[2], r1[0] * uv[0] + r1[1] * uv[1] + r1[2]]
    }
}

impl Default for TextureTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

/// A material's use of a texture: which image, sampled how, at which transformed uv set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureRef {
    /// Index into `Scene::textures`.
    pub texture: usize,
    pub sampler: Sampler,
    /// The vertex uv set: 0 ([`Vertex::uv`]) or 1 ([`Vertex::uv1`]).
    pub tex_coord: u32,
    /// Applied to that uv set before sampling.
    pub transform: TextureTransform,
}

impl TextureRef {
    /// Texture `texture` with the default sampler, uv set 0, untransformed.
    pub fn new(texture: usize) -> Self {
        Self { texture, sampler: Sampler::default(), tex_coord: 0, transform: TextureTransform::IDENTITY }
    }
}

/// How a material's base colour alpha is used (glTF `alphaMode`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum AlphaMode {
    /// Alpha is ignored.
    #[default]
    Opaque,
    /// Fragments with alpha below `cutoff` are not there: holes in every view, the lamp's
    /// shadows and the GI included.
    Mask { cutoff: f32 },
    /// Partial transparency, which this deferred renderer does not have: drawn as
    /// [`AlphaMode::Mask`] with cutoff [`BLEND_CUTOFF`] (see [`Material::alpha_cutoff`]).
    Blend,
}

/// The cutoff an [`AlphaMode::Blend`] material is drawn with.
pub const BLEND_CUTOFF: f32 = 0.5;

/// How a surface reflects direct light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reflection {
    /// Diffuse only: radiance ρ/π × irradiance, ρ the base colour (OBJ's model, the engine's
    /// default, dynamic instances).
    Lambertian,
    /// glTF 2.0's metallic-roughness BRDF (the spec's Appendix B): a diffuse lobe of albedo
    /// (1 − metallic)·base colour weighted by 1 − F, plus a GGX specular lobe whose Fresnel F
    /// starts at 0.04 for dielectrics and at the base colour for metals. The two factors are
    /// multiplied by the texture's blue (metallic) and green (roughness) channels.
    MetallicRoughness {
        metallic: f32,
        /// Perceptual roughness; α = roughness².
        roughness: f32,
        /// Linear (not sRGB) image: B = metallic, G = roughness.
        texture: Option<TextureRef>,
    },
}

impl Reflection {
    /// glTF's defaults when a material says nothing: metallic 1, roughness 1, no texture.
    pub const GLTF_DEFAULT: Self = Self::MetallicRoughness { metallic: 1.0, roughness: 1.0, texture: None };
}

/// A material: the base colour is `base_color × texture × vertex colour` (all linear), how it
/// reflects light `reflection`, the emitted radiance `emissive × emissive texture`.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    /// Linear RGBA factor.
    pub base_color: [f32; 4],
    /// Multiplies `base_color`; the image is stored sRGB-encoded.
    pub base_color_texture: Option<TextureRef>,
    /// Emitted radiance, linear (W·sr⁻¹·m⁻²); glTF's `emissiveFactor` × `emissiveStrength`.
    pub emissive: [f32; 3],
    /// Multiplies `emissive` (rgb); the image is stored sRGB-encoded.
    pub emissive_texture: Option<TextureRef>,
    pub alpha_mode: AlphaMode,
    /// Lambertian, or glTF's metallic-roughness BRDF.
    pub reflection: Reflection,
    /// Drawn from both sides (the back side's normal reversed); false culls back faces (those
    /// winding clockwise as seen), in every view.
    pub double_sided: bool,
}

impl Material {
    /// glTF 2.0's default material, for primitives without one: base colour 1 (white),
    /// metallic 1, roughness 1, no emission, opaque, single-sided.
    pub fn gltf_default() -> Self {
        Self {
            name: "default".into(),
            base_color: [1.0; 4],
            reflection: Reflection::GLTF_DEFAULT,
            double_sided: false,
            ..Self::default()
        }
    }

    /// The metallic-roughness texture, if the material reflects by that model and has one.
    pub fn metallic_roughness_texture(&self) -> Option<&TextureRef> {
        match &self.reflection {
            Reflection::MetallicRoughness { texture, .. } => texture.as_ref(),
            Reflection::Lambertian => None,
        }
    }

    /// Every texture the material samples.
    pub fn textures(&self) -> impl Iterator<Item = &TextureRef> {
        [self.base_color_texture.as_ref(), self.emissive_texture.as_ref(), self.metallic_roughness_texture()]
            .into_iter()
            .flatten()
    }

    /// The alpha below which a fragment is discarded; None for opaque materials.
    pub fn alpha_cutoff(&self) -> Option<f32> {
        match self.alpha_mode {
            AlphaMode::Opaque => None,
            AlphaMode::Mask { cutoff } => Some(cutoff),
            AlphaMode::Blend => Some(BLEND_CUTOFF),
        }
    }
}

impl Default for Material {
    /// The engine's (and OBJ's) default: Lambertian, albedo 0.8 grey, no emission, opaque, drawn
    /// from both sides. glTF files use [`Material::gltf_default`] instead.
    fn default() -> Self {
        Self {
            name: "default".into(),
            base_color: [0.8, 0.8, 0.8, 1.0],
            base_color_texture: None,
            emissive: [0.0; 3],
            emissive_texture: None,
            alpha_mode: AlphaMode::Opaque,
            reflection: Reflection::Lambertian,
            double_sided: true,
        }
    }
}

/// An 8-bit RGBA image, sRGB-encoded, row-major from the top-left.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub rgba8: Vec<u8>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Vertical field of view in radians; `aspect` None means "the viewport's".
    Perspective { yfov: f32, aspect: Option<f32>, znear: f32, zfar: Option<f32> },
    /// Half extents of the view volume in metres.
    Orthographic { xmag: f32, ymag: f32, znear: f32, zfar: f32 },
}

/// A camera found in a file: a world-space pose (looking down its local -Z, +Y up) and a projection.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneCamera {
    pub name: String,
    pub position: Vec3,
    pub rotation: Quat,
    pub projection: Projection,
}

impl SceneCamera {
    pub fn forward(&self) -> Vec3 {
        self.rotation * Vec3::NEG_Z
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Radiates `intensity` W/sr (glTF: candela, taken 1:1 as radiometric units) in every direction.
    Point,
    /// A point light limited to a cone around `direction`; angles in radians from the axis.
    Spot { inner_cone: f32, outer_cone: f32 },
    /// Irradiance `intensity` W/m² (glTF: lux) arriving along `direction`.
    Directional,
}

/// A punctual light (glTF `KHR_lights_punctual` or level.toml).
#[derive(Clone, Debug, PartialEq)]
pub struct PunctualLight {
    pub name: String,
    pub kind: LightKind,
    pub position: Vec3,
    /// Unit direction the light points towards (local -Z of its node).
    pub direction: Vec3,
    /// Linear RGB colour, multiplied by `intensity`.
    pub color: [f32; 3],
    pub intensity: f32,
    /// Distance beyond which the light has no effect; None = infinite.
    pub range: Option<f32>,
}

/// A node's `extras` from glTF (arbitrary JSON the level author attached), with its world transform.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeExtras {
    pub node_name: String,
    pub world: Mat4,
    pub extras: serde_json::Value,
}

/// Axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb { min: Vec3::splat(f32::INFINITY), max: Vec3::splat(f32::NEG_INFINITY) };

    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x
    }
    pub fn grow(&mut self, p: Vec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }
    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }
    pub fn size(&self) -> Vec3 {
        self.max - self.min
    }
}

/// Everything loaded from one scene file, geometry already in world space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub cameras: Vec<SceneCamera>,
    pub lights: Vec<PunctualLight>,
    pub extras: Vec<NodeExtras>,
}

impl Scene {
    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for m in &self.meshes {
            for v in &m.vertices {
                b.grow(Vec3::from(v.position));
            }
        }
        b
    }
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.indices.len() / 3).sum()
    }
}
