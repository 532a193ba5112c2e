//! The level's static collision geometry: all its triangles as one rapier triangle mesh.

use glam::Vec3;
use rapier3d::dynamics::{IntegrationParameters, RigidBodySet};
use rapier3d::geometry::{
    BroadPhaseBvh, ColliderBuilder, ColliderSet, ContactData, ContactManifoldData, NarrowPhase, Ray, TriMeshFlags,
};
use rapier3d::parry::query::PersistentQueryDispatcher;
use rapier3d::pipeline::{QueryFilter, QueryPipeline};

use crate::error::CollisionError;

/// A triangle whose doubled area is below this fraction of its longest edge squared has no
/// usable normal at f32 precision (a needle or a point); it is dropped.
const DEGENERATE_RATIO: f32 = 1e-7;

/// Static collision geometry of a level: every triangle of every mesh, in world space.
///
/// Held as rapier's query structures (one fixed collider, no rigid body) so that the character
/// controller and ray casts can use rapier's scene queries directly. Immutable once built.
pub struct LevelCollision {
    /// Empty: the level collider has no parent body, but queries want the set.
    bodies: RigidBodySet,
    colliders: ColliderSet,
    /// Holds the level collider's AABB; scene queries walk it.
    broad_phase: BroadPhaseBvh,
    /// Never stepped; it only provides the query dispatcher.
    narrow_phase: NarrowPhase,
    triangle_count: usize,
    /// Corners of the box around every triangle.
    bounds: (Vec3, Vec3),
}

/// The first surface a ray meets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Distance from the origin along the (normalised) direction, metres.
    pub distance: f32,
    pub point: Vec3,
    /// Unit normal of the surface hit, facing back towards the ray's origin (triangles are
    /// two-sided, so this is the side the ray came from).
    pub normal: Vec3,
}

impl LevelCollision {
    /// Collects every triangle of every mesh in the scene (meshes are already in world space).
    /// Degenerate triangles are dropped; bad data is an error, never a panic.
    pub fn from_scene(scene: &scene::Scene) -> Result<Self, CollisionError> {
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for mesh in &scene.meshes {
            if mesh.indices.len() % 3 != 0 {
                return Err(CollisionError::PartialTriangle {
                    mesh: mesh.name.clone(),
                    index_count: mesh.indices.len(),
                });
            }
            let local_positions: Vec<Vec3> = mesh.vertices.iter().map(|v| Vec3::from(v.position)).collect();
            let local_triangles: Vec<[u32; 3]> = mesh.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
            validate(&local_positions, &local_triangles, Some(&mesh.name))?;

            let count = positions.len() + local_positions.len();
            let base = u32::try_from(positions.len()).map_err(|_| CollisionError::TooManyVertices { count })?;
            u32::try_from(count).map_err(|_| CollisionError::TooManyVertices { count })?;
            positions.extend(local_positions);
            // Indices are below the mesh's vertex count and the total fits in u32: no overflow.
            triangles.extend(local_triangles.iter().map(|t| t.map(|i| base + i)));
        }
        Self::build(positions, triangles)
    }

    /// Builds the collision mesh from world-space positions and a triangle list indexing them.
    /// Degenerate triangles are dropped; bad data is an error, never a panic.
    pub fn from_triangles(positions: &[Vec3], triangles: &[[u32; 3]]) -> Result<Self, CollisionError> {
        validate(positions, triangles, None)?;
        Self::build(positions.to_vec(), triangles.to_vec())
    }

    /// Expects validated input.
    fn build(positions: Vec<Vec3>, mut triangles: Vec<[u32; 3]>) -> Result<Self, CollisionError> {
        triangles.retain(|t| !is_degenerate(t.map(|i| positions[i as usize])));
        if triangles.is_empty() {
            return Err(CollisionError::NoTriangles);
        }
        let triangle_count = triangles.len();
        let used = triangles.iter().flatten().map(|&i| positions[i as usize]);
        let bounds = used.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));

        // FIX_INTERNAL_EDGES (which merges duplicate vertices first) corrects contact normals on
        // edges shared by coplanar triangles, so a capsule sliding over a floor made of many
        // triangles is not reported bumps at their seams. Both steps are deterministic
        // (hash maps are only looked up, never iterated).
        let collider = ColliderBuilder::trimesh_with_flags(positions, triangles, TriMeshFlags::FIX_INTERNAL_EDGES)
            .map_err(|e| CollisionError::Rejected(e.to_string()))?
            .build();
        let aabb = collider.compute_aabb();
        let mut colliders = ColliderSet::new();
        let handle = colliders.insert(collider);
        let mut broad_phase = BroadPhaseBvh::new();
        broad_phase.set_aabb(&IntegrationParameters::default(), handle, aabb);

        Ok(Self {
            bodies: RigidBodySet::new(),
            colliders,
            broad_phase,
            narrow_phase: NarrowPhase::new(),
            triangle_count,
            bounds,
        })
    }

    /// The first surface hit by a ray from `origin` along `dir` (normalised here) within
    /// `max_distance` metres. None when nothing is hit or the input is not usable (zero or
    /// non-finite direction, non-finite origin, negative or NaN distance).
    pub fn cast_ray(&self, origin: Vec3, dir: Vec3, max_distance: f32) -> Option<RayHit> {
        let dir = dir.try_normalize()?;
        if !origin.is_finite() || max_distance.is_nan() || max_distance < 0.0 {
            return None;
        }
        let ray = Ray::new(origin, dir);
        let (_, hit) = self.query_pipeline().cast_ray_and_get_normal(&ray, max_distance.min(f32::MAX), true)?;
        let normal = if hit.normal.dot(dir) > 0.0 { -hit.normal } else { hit.normal };
        Some(RayHit { distance: hit.time_of_impact, point: origin + dir * hit.time_of_impact, normal })
    }

    /// The smallest and largest corner of the box around the level's triangles.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.bounds
    }

    /// Number of triangles in the collision mesh (degenerate input triangles excluded).
    pub fn triangle_count(&self) -> usize {
        self.triangle_count
    }

    /// The dispatcher that computes contact manifolds against the level mesh.
    pub(crate) fn contact_dispatcher(&self) -> &dyn PersistentQueryDispatcher<ContactManifoldData, ContactData> {
        self.narrow_phase.query_dispatcher()
    }

    /// rapier's scene queries over the level.
    pub(crate) fn query_pipeline(&self) -> QueryPipeline<'_> {
        self.broad_phase.as_query_pipeline(
            self.narrow_phase.query_dispatcher(),
            &self.bodies,
            &self.colliders,
            QueryFilter::default(),
        )
    }
}

fn validate(positions: &[Vec3], triangles: &[[u32; 3]], mesh: Option<&str>) -> Result<(), CollisionError> {
    if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
        return Err(CollisionError::NonFinitePosition { mesh: mesh.map(str::to_owned), vertex });
    }
    for (triangle, t) in triangles.iter().enumerate() {
        if let Some(&index) = t.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(CollisionError::IndexOutOfRange {
                mesh: mesh.map(str::to_owned),
                triangle,
                index,
                vertex_count: positions.len(),
            });
        }
    }
    Ok(())
}

fn is_degenerate([a, b, c]: [Vec3; 3]) -> bool {
    let longest_sq = (b - a).length_squared().max((c - b).length_squared()).max((a - c).length_squared());
    let doubled_area = (b - a).cross(c - a).length();
    // NaN: huge coordinates overflowed.
    doubled_area.is_nan() || doubled_area <= DEGENERATE_RATIO * longest_sq
}
