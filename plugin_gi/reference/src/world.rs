//! The level as senders: its triangles cut into patches fixed in the world, each patch's albedo
//! as the G-buffer has it, and which patches the lamp lights (its frustum, its side, a ray for
//! its shadow).

use engine::glam::{Vec3, Vec4};
use engine::scene::{Material, Reflection, Scene};
use parry3d::query::{Ray, RayCast, RayCullingMode};
use parry3d::shape::TriMesh;
use rayon::prelude::*;

use crate::lamp::Lamp;
use crate::occlusion::OcclusionMap;
use crate::patch::{LitPatch, Patch};
use crate::texture::{slot_uv, LinearTexture};
use crate::transport::LitPatches;
use crate::visibility::Occluders;

/// The longest edge of a patch unless told otherwise (metres).
pub const DEFAULT_MAX_EDGE: f32 = 0.02;

/// How far the end of a shadow ray stands off its patch, towards the lamp (metres).
pub const SHADOW_OFFSET: f32 = 1e-3;

/// One triangle of the level, as its mesh has it.
#[derive(Clone, Debug)]
struct Triangle {
    corners: [Vec3; 3],
    uv: [[f32; 2]; 3],
    uv1: [[f32; 2]; 3],
    color: [Vec4; 3],
    material: usize,
    /// Drawn from both sides (its material's `double_sided`).
    double_sided: bool,
}

/// The level's geometry and materials, ready to cut into patches and to cast shadow rays into.
pub struct World {
    triangles: Vec<Triangle>,
    materials: Vec<Material>,
    /// Per scene texture: decoded from sRGB (base colour) and as is (metallic-roughness), where
    /// some material uses it that way.
    srgb: Vec<Option<LinearTexture>>,
    linear: Vec<Option<LinearTexture>>,
    /// The triangles whose material is single-sided (their back faces let light through, as
    /// they are culled in every view), and the double-sided ones.
    single_sided: Option<TriMesh>,
    double_sided: Option<TriMesh>,
}

/// How many times a triangle's edges are cut for patches of at most `max_edge`: n, making n²
/// congruent sub-triangles.
pub fn subdivisions(corners: &[Vec3; 3], max_edge: f32) -> u32 {
    let [a, b, c] = *corners;
    let longest = (b - a).length().max((c - b).length()).max((a - c).length());
    ((longest / max_edge).ceil() as u32).max(1)
}

/// A patch the lamp frustum's edge crosses takes its light from this many² points.
pub const EDGE_SAMPLES: u32 = 8;

/// The barycentric centroids (u along b − a, v along c − a) of the n² sub-triangles of a
/// triangle, in [`TriangleFrame::row`]'s order.
fn sub_centroids(n: u32, mut f: impl FnMut(f32, f32)) {
    let m = n as f32;
    for i in 0..n {
        for j in 0..n - i {
            f((i as f32 + 1.0 / 3.0) / m, (j as f32 + 1.0 / 3.0) / m);
            if j + 1 < n - i {
                f((i as f32 + 2.0 / 3.0) / m, (j as f32 + 2.0 / 3.0) / m);
            }
        }
    }
}

/// Rows of sub-triangles handed to one task: a large floor is cut into many.
const ROWS_PER_TASK: u32 = 32;

impl World {
    pub fn new(scene: &Scene) -> Self {
        let default = Material::default();
        let material = |i: usize| scene.materials.get(i).unwrap_or(&default);
        let mut triangles = Vec::with_capacity(scene.triangle_count());
        for mesh in &scene.meshes {
            let double_sided = material(mesh.material).double_sided;
            for t in mesh.indices.chunks_exact(3) {
                let Some(v) = t.iter().map(|&i| mesh.vertices.get(i as usize)).collect::<Option<Vec<_>>>() else {
                    continue;
                };
                triangles.push(Triangle {
                    corners: [0, 1, 2].map(|k| Vec3::from(v[k].position)),
                    uv: [0, 1, 2].map(|k| v[k].uv),
                    uv1: [0, 1, 2].map(|k| v[k].uv1),
                    color: [0, 1, 2].map(|k| Vec4::from(v[k].color)),
                    material: if mesh.material < scene.materials.len() { mesh.material } else { usize::MAX },
                    double_sided,
                });
            }
        }
        let uses = |i: usize, linear: bool| {
            scene.materials.iter().any(|m| {
                let is = |t: &engine::scene::TextureRef| t.texture == i;
                if linear {
                    m.metallic_roughness_texture().is_some_and(is)
                } else {
                    m.base_color_texture.as_ref().is_some_and(is)
                }
            })
        };
        let decode = |linear: bool| {
            scene
                .textures
                .iter()
                .enumerate()
                .map(|(i, t)| uses(i, linear).then(|| LinearTexture::decode(t, !linear)))
                .collect::<Vec<_>>()
        };
        let mesh = |double: bool| {
            let picked: Vec<&Triangle> = triangles.iter().filter(|t| t.double_sided == double).collect();
            let vertices: Vec<Vec3> = picked.iter().flat_map(|t| t.corners).collect();
            let indices: Vec<[u32; 3]> = (0..picked.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
            (!indices.is_empty()).then(|| TriMesh::new(vertices, indices).ok()).flatten()
        };
        let (single_sided, double_sided) = (mesh(false), mesh(true));
        Self {
            materials: scene.materials.clone(),
            srgb: decode(false),
            linear: decode(true),
            triangles,
            single_sided,
            double_sided,
        }
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Each triangle's corners and whether it is drawn from both sides, in [`Patch::triangle`]'s
    /// numbering.
    /// The level's triangles as occluders, for visibility between senders and receivers.
    pub fn occluders(&self) -> Occluders {
        Occluders::new(self.triangles.iter().map(|t| (t.corners, t.double_sided)))
    }

    /// Every patch of the level for patches of at most `max_edge`, triangle by triangle: for
    /// tests and small scenes (a level has millions).
    pub fn patches(&self, max_edge: f32) -> Vec<Patch> {
        let mut out = Vec::new();
        for (i, t) in self.triangles.iter().enumerate() {
            let n = subdivisions(&t.corners, max_edge);
            if let Some(frame) = TriangleFrame::of(t, i as u32, n) {
                for row in 0..n {
                    frame.row(row, |patch, _, _| out.push(patch));
                }
            }
        }
        out
    }

    /// The patches `lamp` lights, with their flux: triangles wholly outside the lamp's frustum or
    /// facing away from it are skipped whole; of the others every patch with light on it and a
    /// clear line to the lamp. In a fixed order (triangles, then rows), whatever the threads.
    pub fn lit_patches(&self, lamp: &Lamp, max_edge: f32) -> Vec<LitPatch> {
        self.lit_patches_with(lamp, max_edge, true)
    }

    /// [`World::lit_patches`], with or without the occlusion map that spares rays.
    fn lit_patches_with(&self, lamp: &Lamp, max_edge: f32, occlusion_map: bool) -> Vec<LitPatch> {
        assert!(max_edge > 0.0, "patches have a size");
        if !lamp.is_on() {
            return Vec::new();
        }
        // (triangle, its subdivisions, first row) for every triangle that may be lit.
        let tasks: Vec<(u32, u32, u32)> = self
            .triangles
            .par_iter()
            .enumerate()
            .filter(|(_, t)| self.may_be_lit(t, lamp))
            .flat_map_iter(|(i, t)| {
                let n = subdivisions(&t.corners, max_edge);
                (0..n).step_by(ROWS_PER_TASK as usize).map(move |row| (i as u32, n, row))
            })
            .collect();
        // Triangles a shadow ray stops at: double-sided ones, and single-sided ones facing the lamp.
        let occluders = self.triangles.iter().filter(|t| {
            let [a, b, c] = t.corners;
            t.double_sided || (b - a).cross(c - a).dot(lamp.position - a) > 0.0
        });
        let shadows = OcclusionMap::new(lamp.view_proj, occluders.filter(|_| occlusion_map).map(|t| t.corners));
        let lit: Vec<Vec<LitPatch>> = tasks
            .par_iter()
            .map(|&(i, n, first)| {
                let t = &self.triangles[i as usize];
                let mut out = Vec::new();
                let Some(frame) = TriangleFrame::of(t, i, n) else { return out };
                for row in first..(first + ROWS_PER_TASK).min(n) {
                    frame.row(row, |patch, u, v| {
                        if let Some(p) = self.light(t, patch, u, v, lamp, &shadows) {
                            out.push(p);
                        }
                    });
                }
                out
            })
            .collect();
        lit.concat()
    }

    /// [`World::lit_patches`] ready to light receivers.
    pub fn lit(&self, lamp: &Lamp, max_edge: f32) -> LitPatches {
        LitPatches::new(&self.lit_patches(lamp, max_edge), max_edge)
    }

    /// Whether some of `t` may be lit: not wholly beyond one side of the frustum (or behind the
    /// lamp), and facing the lamp unless double-sided.
    fn may_be_lit(&self, t: &Triangle, lamp: &Lamp) -> bool {
        let [a, b, c] = t.corners;
        let normal = (b - a).cross(c - a);
        let side = normal.dot(lamp.position - a);
        if side == 0.0 || (side < 0.0 && !t.double_sided) {
            return false;
        }
        let clip = t.corners.map(|p| lamp.view_proj * p.extend(1.0));
        let all = |f: &dyn Fn(Vec4) -> bool| clip.iter().all(|&c| f(c));
        !(all(&|c| c.w <= 0.0)
            || all(&|c| c.x > c.w)
            || all(&|c| c.x < -c.w)
            || all(&|c| c.y > c.w)
            || all(&|c| c.y < -c.w))
    }

    /// The light `patch` (at barycentric `u`, `v` of `t`) reflects, if any.
    fn light(
        &self,
        t: &Triangle,
        patch: Patch,
        u: f32,
        v: f32,
        lamp: &Lamp,
        shadows: &OcclusionMap,
    ) -> Option<LitPatch> {
        let to_lamp = lamp.position - patch.centre;
        let side = patch.normal.dot(to_lamp);
        let normal = if side >= 0.0 { patch.normal } else { -patch.normal };
        if side == 0.0 || (side < 0.0 && !t.double_sided) {
            return None;
        }
        // I·cos/d², at the centre, or averaged over the patch where the frustum's edge crosses it
        // (the centre alone would switch the whole patch on or off as the edge sweeps by).
        let at = |x: Vec3| {
            let l = lamp.position - x;
            let d2 = l.length_squared();
            lamp.intensity_towards(x) * (normal.dot(l).max(0.0) / (d2 * d2.sqrt()))
        };
        let inside = lamp.in_frustum(patch.centre);
        let light = if patch.corners.iter().all(|&c| lamp.in_frustum(c) == inside) {
            at(patch.centre)
        } else {
            let [a, b, c] = patch.corners;
            let mut sum = Vec3::ZERO;
            sub_centroids(EDGE_SAMPLES, |u, v| sum += at(a + (b - a) * u + (c - a) * v));
            sum / (EDGE_SAMPLES * EDGE_SAMPLES) as f32
        };
        if light.max_element() <= 0.0 || shadows.hides(patch.centre) {
            return None;
        }
        let rho = self.albedo(t, u, v)?;
        if rho.max_element() <= 0.0 || !self.visible(lamp.position, patch.centre + normal * SHADOW_OFFSET) {
            return None;
        }
        Some(LitPatch { patch, normal, flux: rho * light * patch.area })
    }

    /// Whether the segment from the lamp to `q` is clear: no double-sided triangle on it, and no
    /// single-sided one it meets from the front.
    pub fn visible(&self, lamp: Vec3, q: Vec3) -> bool {
        let ray = Ray::new(lamp, q - lamp);
        let blocked = |mesh: &Option<TriMesh>, culling: Option<RayCullingMode>| {
            mesh.as_ref().is_some_and(|m| match culling {
                None => m.cast_local_ray(&ray, 1.0, false).is_some(),
                Some(c) => m.cast_local_ray_with_culling(&ray, 1.0, c).is_some(),
            })
        };
        !blocked(&self.double_sided, None) && !blocked(&self.single_sided, Some(RayCullingMode::IgnoreBackfaces))
    }

    /// The diffuse albedo ρ at barycentric `u`, `v` of `t` as the G-buffer computes it
    /// (`surface_base_color` and `surface_reflection`): base colour × base colour texture ×
    /// vertex colour, × (1 − metallic) for the metallic-roughness BRDF. None where an
    /// alpha-tested material cuts the surface out.
    fn albedo(&self, t: &Triangle, u: f32, v: f32) -> Option<Vec3> {
        let default = Material::default();
        let m = self.materials.get(t.material).unwrap_or(&default);
        let lerp2 = |x: [[f32; 2]; 3]| [0, 1].map(|k| x[0][k] + u * (x[1][k] - x[0][k]) + v * (x[2][k] - x[0][k]));
        let (uv0, uv1) = (lerp2(t.uv), lerp2(t.uv1));
        let sample = |textures: &[Option<LinearTexture>], slot: &engine::scene::TextureRef| {
            textures
                .get(slot.texture)
                .and_then(Option::as_ref)
                .map_or(Vec4::ONE, |tex| Vec4::from(tex.sample(slot_uv(slot, uv0, uv1), &slot.sampler)))
        };
        let color = t.color[0] + u * (t.color[1] - t.color[0]) + v * (t.color[2] - t.color[0]);
        let mut base = Vec4::from(m.base_color) * color;
        if let Some(slot) = &m.base_color_texture {
            base *= sample(&self.srgb, slot);
        }
        if m.alpha_cutoff().is_some_and(|cutoff| base.w < cutoff) {
            return None;
        }
        let rho = base.truncate();
        Some(match &m.reflection {
            Reflection::Lambertian => rho,
            Reflection::MetallicRoughness { metallic, texture, .. } => {
                let b = texture.as_ref().map_or(1.0, |slot| sample(&self.linear, slot).z);
                (1.0 - (metallic * b).clamp(0.0, 1.0)) * rho
            }
        })
    }
}

/// A triangle's edges and patch size, to cut it into n² congruent sub-triangles: row i holds
/// the "up" triangles (i, j), (i+1, j), (i, j+1) for j < n − i and the "down" ones (i+1, j),
/// (i+1, j+1), (i, j+1) for j < n − i − 1, the point (i, j) being a + (i/n)(b − a) + (j/n)(c − a).
struct TriangleFrame {
    a: Vec3,
    e1: Vec3,
    e2: Vec3,
    normal: Vec3,
    area: f32,
    n: u32,
    index: u32,
}

impl TriangleFrame {
    fn of(t: &Triangle, index: u32, n: u32) -> Option<Self> {
        let [a, b, c] = t.corners;
        let (e1, e2) = (b - a, c - a);
        let cross = e1.cross(e2);
        let length = cross.length();
        if length <= 0.0 || !length.is_finite() {
            return None;
        }
        let area = 0.5 * length / (n as f32 * n as f32);
        Some(Self { a, e1, e2, normal: cross / length, area, n, index })
    }

    fn point(&self, u: f32, v: f32) -> Vec3 {
        self.a + self.e1 * u + self.e2 * v
    }

    /// The sub-triangles of row `i`, each with the barycentric coordinates of its centre.
    fn row(&self, i: u32, mut f: impl FnMut(Patch, f32, f32)) {
        let n = self.n as f32;
        let at = |i: u32, j: u32| self.point(i as f32 / n, j as f32 / n);
        let mut emit = |corners: [Vec3; 3], u: f32, v: f32| {
            let patch =
                Patch { corners, centre: self.point(u, v), normal: self.normal, area: self.area, triangle: self.index };
            f(patch, u, v);
        };
        for j in 0..self.n - i {
            emit([at(i, j), at(i + 1, j), at(i, j + 1)], (i as f32 + 1.0 / 3.0) / n, (j as f32 + 1.0 / 3.0) / n);
            if j + 1 < self.n - i {
                emit(
                    [at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)],
                    (i as f32 + 2.0 / 3.0) / n,
                    (j as f32 + 2.0 / 3.0) / n,
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::start_view::{initial_view, ViewOverrides};

    #[test]
    fn the_occlusion_map_only_spares_rays_it_never_changes_what_is_lit() {
        let cellar = concat!(env!("CARGO_MANIFEST_DIR"), "/../../levels/cellar");
        let level = engine::scene::load_level(std::path::Path::new(cellar)).unwrap();
        let view = initial_view(&level, &ViewOverrides::default());
        let world = World::new(&level.scene);
        let lamp = Lamp::new(&view.headlamp, &view.camera, 4.0 / 3.0);
        let (with, without) = (world.lit_patches_with(&lamp, 0.1, true), world.lit_patches_with(&lamp, 0.1, false));
        assert!(with.len() > 10_000, "{} lit", with.len());
        assert!(with == without, "{} lit patches with the map, {} without", with.len(), without.len());
    }
}
