//! The geometric moves of the character's capsule through the level: slide, step up, follow
//! the ground down, and the probes for ground and headroom.

use glam::Vec3;
use rapier3d::control::{CharacterLength, KinematicCharacterController};
use rapier3d::geometry::{BoundingVolume, Capsule, ContactManifold, Shape};
use rapier3d::math::Pose;
use rapier3d::parry::query::ShapeCastOptions;

use crate::level_collision::LevelCollision;

/// Gap rapier keeps between the swept capsule and the level. The swept capsule is the nominal
/// one shrunk by this much (radius, bottom and top), so the nominal capsule ends up touching:
/// feet on the floor, `radius` from walls.
pub(crate) const SKIN: f32 = 0.01;
/// Straight casts (up, down, forward) stop at half the skin, so that a surface the capsule
/// rests against (a skin away) and moves parallel to is never taken for one in its way; the
/// move then backs off to a full skin.
const CAST_GAP: f32 = 0.5 * SKIN;
/// Ground this far below the feet (beyond the skin) still counts as stood on.
const GROUND_TOLERANCE: f32 = 0.02;
/// A step needs a tread at least this deep beyond the capsule's radius: the capsule's centre
/// must be able to get over it.
const MIN_TREAD_DEPTH: f32 = 0.05;
/// Stepping up may leave the capsule's rounded bottom resting on the step's nosing with the
/// contact this far from straight below. Slow steps need it large: at speed v the capsule gets
/// v·dt past the riser in the stepping tick, asin(1 − v·dt / radius) from vertical.
const MAX_STEP_PERCH_DEG: f32 = 85.0;
/// A contact whose normal is within ~2.6° of its triangle's is on the face, not an edge.
const FACE_CONTACT_COS: f32 = 0.999;

/// Where a move ended and the surfaces (unit normals, pointing out of them) it ran into.
pub(crate) struct Sweep {
    pub feet: Vec3,
    pub hits: Vec<Vec3>,
}

/// The capsule of one height in one level, with the character's slope limit.
pub(crate) struct Mover<'a> {
    level: &'a LevelCollision,
    /// The swept shape: the nominal capsule minus the skin.
    shape: Capsule,
    /// Nominal radius.
    radius: f32,
    half_height: f32,
    max_slope: f32,
    /// cos(max_slope): a surface is walkable when its normal's y is at least this.
    min_ground_normal_y: f32,
}

impl<'a> Mover<'a> {
    /// A capsule of `radius` and `height` (feet to top). Clamps to a valid shape: a bad config
    /// must not reach parry.
    pub fn new(level: &'a LevelCollision, radius: f32, height: f32, max_slope_deg: f32) -> Self {
        // `max` also replaces NaN.
        let radius = radius.max(2.0 * SKIN);
        let height = height.max(2.0 * radius);
        let max_slope = max_slope_deg.clamp(0.0, 89.0).to_radians();
        Self {
            level,
            shape: Capsule::new_y(0.5 * height - radius, radius - SKIN),
            radius,
            half_height: 0.5 * height,
            max_slope,
            min_ground_normal_y: libm::cosf(max_slope),
        }
    }

    fn pose(&self, feet: Vec3) -> Pose {
        Pose::from_translation(feet + Vec3::Y * self.half_height)
    }

    pub fn is_walkable(&self, normal: Vec3) -> bool {
        normal.y >= self.min_ground_normal_y
    }

    /// Moves by `translation`, sliding along what is in the way (rapier's controller, with
    /// its slope rules; its autostep and snap-to-ground are replaced by [`Self::step_up`] and
    /// [`Self::follow_ground_down`]).
    pub fn slide(&self, feet: Vec3, translation: Vec3) -> Sweep {
        let controller = KinematicCharacterController {
            up: Vec3::Y,
            offset: CharacterLength::Absolute(SKIN),
            slide: true,
            autostep: None,
            max_slope_climb_angle: self.max_slope,
            min_slope_slide_angle: self.max_slope,
            snap_to_ground: None,
            ..KinematicCharacterController::default()
        };
        let mut hits = Vec::new();
        // rapier's dt only scales the motion of kinematic platforms, of which there are none.
        let movement = controller.move_shape(
            1.0,
            &self.level.query_pipeline(),
            &self.shape,
            &self.pose(feet),
            translation,
            |collision| hits.push(collision.hit.normal1),
        );
        let end = feet + movement.translation;
        // parry's shape cast can miss an edge that meets the capsule exactly where a hemisphere
        // joins the cylinder (a roof edge at head height minus the radius), letting the move
        // end centimetres inside it. Never end a move inside the level when it began outside.
        if !self.fits(end) && self.fits(feet) {
            return Sweep { feet, hits };
        }
        Sweep { feet: end, hits }
    }

    /// How far the capsule can move along the unit `dir`, up to `max`, keeping a skin from
    /// what it meets. None when nothing is in the way.
    fn room(&self, feet: Vec3, dir: Vec3, max: f32) -> Option<f32> {
        self.cast(feet, dir, max).map(|(distance, _)| distance)
    }

    /// [`Self::room`], with the normal of the surface met (pointing out of it, towards the
    /// capsule).
    fn cast(&self, feet: Vec3, dir: Vec3, max: f32) -> Option<(f32, Vec3)> {
        let options = ShapeCastOptions {
            max_time_of_impact: max + (SKIN - CAST_GAP),
            target_distance: CAST_GAP,
            stop_at_penetration: false,
            compute_impact_geometry_on_penetration: true,
        };
        let (_, hit) = self.level.query_pipeline().cast_shape(&self.pose(feet), dir, &self.shape, options)?;
        Some(((hit.time_of_impact - (SKIN - CAST_GAP)).clamp(0.0, max), hit.normal1))
    }

    /// Quake's step: when a walk by `translation` (horizontal) from `start` was stopped at
    /// `blocked_at`, go up (at most `step_height`), across, and down onto ground. None when the
    /// obstacle is not a step.
    ///
    /// It is a step when, raised by the step height where the walk was stopped, the capsule
    /// can move on far enough to get its centre over a tread. Only then is the move made, and
    /// its landing may leave the capsule's rounded bottom perched on the step's nosing (at
    /// walking speed one tick takes it only centimetres past the riser), a contact steeper than
    /// the slope limit that the next ticks roll up onto the tread. Without the tread check,
    /// that allowance would let the capsule ratchet up any edge, perch by perch.
    pub fn step_up(&self, start: Vec3, blocked_at: Vec3, translation: Vec3, step_height: f32) -> Option<Sweep> {
        let dir = Vec3::new(translation.x, 0.0, translation.z).try_normalize()?;
        let perch_normal_y = libm::cosf(MAX_STEP_PERCH_DEG.to_radians());

        let up = self.room(blocked_at, Vec3::Y, step_height).unwrap_or(step_height);
        let raised = blocked_at + Vec3::Y * up;
        let reach = self.radius + MIN_TREAD_DEPTH;
        if up <= 0.0 || self.room(raised, dir, reach).is_some() {
            return None;
        }
        let over_tread = raised + dir * reach;
        let tread = over_tread - Vec3::Y * self.room(over_tread, Vec3::NEG_Y, up)?;
        if !self.touches_ground(tread, perch_normal_y) {
            return None;
        }

        let up = self.room(start, Vec3::Y, step_height).unwrap_or(step_height);
        let across = self.slide(start + Vec3::Y * up, translation);
        let landed = across.feet - Vec3::Y * self.room(across.feet, Vec3::NEG_Y, up)?;
        self.touches_ground(landed, perch_normal_y).then_some(Sweep { feet: landed, hits: across.hits })
    }

    /// Keeps the feet on the ground while walking: drops onto ground up to `max_drop` below
    /// (down a ramp or a step). Walking off a step, the capsule rolls over the nosing on its
    /// rounded bottom until that contact gets too steep to stand on; it then rolls off, away
    /// from the edge, and drops onto the ground below. Stays put when there is no ground within
    /// reach (walking off a ledge: the fall begins).
    pub fn follow_ground_down(&self, feet: Vec3, max_drop: f32) -> Vec3 {
        let Some((drop, normal)) = self.cast(feet, Vec3::NEG_Y, max_drop) else { return feet };
        let lowered = feet - Vec3::Y * drop;
        if self.on_ground(lowered) {
            return lowered;
        }
        // Off the nosing: the contact normal leans away from the edge by asin(|horizontal|);
        // the centre is that fraction of the swept radius past it and must get a radius (plus
        // the gap) past it. A horizontal move: rapier's slide of a straight drop would lose
        // the sideways motion in its decomposition near flat ground.
        let Some(away) = Vec3::new(normal.x, 0.0, normal.z).try_normalize() else { return feet };
        let past_edge = (self.radius - SKIN) * Vec3::new(normal.x, 0.0, normal.z).length();
        let off = self.slide(lowered, away * (self.radius + CAST_GAP - past_edge)).feet;
        match self.room(off, Vec3::NEG_Y, max_drop - drop) {
            Some(drop) if self.on_ground(off - Vec3::Y * drop) => off - Vec3::Y * drop,
            _ => feet,
        }
    }

    /// Whether the feet touch walkable ground: a face, edge or corner whose contact normal is
    /// within the slope limit.
    pub fn on_ground(&self, feet: Vec3) -> bool {
        self.touches_ground(feet, self.min_ground_normal_y)
    }

    /// Whether the capsule touches a walkable face, or an edge or corner whose contact normal
    /// has a y of at least `min_edge_normal_y` (the rounded bottom perched on it). Contact
    /// manifolds (one per triangle touched) rather than a downward sweep, which would report
    /// only the first thing hit, maybe a wall the capsule brushes.
    fn touches_ground(&self, feet: Vec3, min_edge_normal_y: f32) -> bool {
        let pose = self.pose(feet);
        let prediction = SKIN + GROUND_TOLERANCE;
        let aabb = self.shape.compute_aabb(&pose).loosened(prediction);
        let queries = self.level.query_pipeline();
        let mut manifolds: Vec<ContactManifold> = Vec::new();
        let found = queries.intersect_aabb_conservative(aabb).any(|(_, collider)| {
            let Some(mesh) = collider.shape().as_trimesh() else { return false };
            manifolds.clear();
            // An unsupported shape pair leaves no manifold: no ground, rather than a panic.
            let _ = self.level.contact_dispatcher().contact_manifolds(
                &pose.inv_mul(collider.position()),
                &self.shape,
                mesh,
                prediction,
                &mut manifolds,
                &mut None,
            );
            manifolds.iter().any(|m| {
                // local_n1 points from the capsule to the ground; the pose has no rotation.
                let contact_normal = -m.local_n1;
                let Some(face) = mesh.triangle(m.subshape2).normal() else { return false };
                // A contact normal that is not the triangle's is on one of its edges or corners.
                let on_face = contact_normal.dot(face).abs() >= FACE_CONTACT_COS;
                let supports =
                    if on_face { self.is_walkable(contact_normal) } else { contact_normal.y >= min_edge_normal_y };
                supports && m.points.iter().any(|p| p.dist <= prediction)
            })
        });
        found
    }

    /// Whether the capsule fits at `feet` without touching the level.
    pub fn fits(&self, feet: Vec3) -> bool {
        let queries = self.level.query_pipeline();
        let blocked = queries.intersect_shape(self.pose(feet), &self.shape).next().is_some();
        !blocked
    }
}

/// The level's capsule query is written here, beside the capsule it asks about: the level's
/// own module stays below the sweep, which moves through it.
impl LevelCollision {
    /// Whether an upright capsule of `radius` and `height` (feet to top) standing at `feet`
    /// touches nothing of the level.
    pub fn capsule_fits(&self, feet: Vec3, radius: f32, height: f32) -> bool {
        Mover::new(self, radius, height, 45.0).fits(feet)
    }
}
