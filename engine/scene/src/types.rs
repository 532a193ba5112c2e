use glam::{Mat4, Quat, Vec3};

/// One vertex as the renderer uploads it: world-space position and unit normal, texture coordinate.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
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

/// A Lambertian material: the diffuse albedo is `base_color * texture` (both linear).
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    /// Linear RGBA factor.
    pub base_color: [f32; 4],
    /// Index into `Scene::textures`, sampled with the vertex uv; stored sRGB-encoded.
    pub base_color_texture: Option<usize>,
    /// Emitted radiance, linear (W·sr⁻¹·m⁻²).
    pub emissive: [f32; 3],
}

impl Default for Material {
    fn default() -> Self {
        Self { name: "default".into(), base_color: [0.8, 0.8, 0.8, 1.0], base_color_texture: None, emissive: [0.0; 3] }
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
