//! A crawler's body: a hunched, pale thing on four long limbs — a spine of swelling segments,
//! a head jutting forward, hind legs and longer forelimbs bent by two-bone IK to where their
//! feet should be. Its pose is a pure function of two consecutive simulation states and the
//! blend between them (plus the tick clock for breathing), so a replay and its headless frames
//! show exactly what the game showed: the walk cycle follows [`Enemy::walked`], the rear-up
//! [`Mind::Alert`], the windup and strike [`Mind::Attack`]'s timer, the flinch
//! [`Enemy::flinch`], the fall [`Mind::Dead`]'s timer.

use std::f32::consts::{FRAC_PI_2, TAU};

use engine::frame::{Instance, MeshId, ViewState};
use engine::glam::{Mat4, Quat, Vec3};
use engine::gpu::Gpu;
use engine::primitives;
use engine::renderer::Renderer;
use engine::scene::IntensityDistribution;

use crate::sim::enemy::{self, Enemy, Mind, GAIT};

/// The body at rest, in the crawler's own frame: feet centre at the origin, facing −Z, +X its
/// right, +Y up, m.
const PELVIS: Vec3 = Vec3::new(0.0, 0.68, 0.28);
const SHOULDERS: Vec3 = Vec3::new(0.0, 1.06, -0.12);
/// The head's centre; its eyes sit at about the simulation's eye height (1.3 m).
const HEAD: Vec3 = Vec3::new(0.0, 1.27, -0.34);
/// Spine segments from the pelvis to the shoulders: where along (0–1) and half extents.
const SPINE: [(f32, Vec3); 4] = [
    (0.0, Vec3::new(0.16, 0.14, 0.19)),
    (0.34, Vec3::new(0.19, 0.17, 0.19)),
    (0.67, Vec3::new(0.21, 0.18, 0.18)),
    (1.0, Vec3::new(0.19, 0.15, 0.15)),
];
const NECK: Vec3 = Vec3::new(0.08, 0.08, 0.12);
const HEAD_SIZE: Vec3 = Vec3::new(0.11, 0.1, 0.15);
/// Eyes in the head's frame, and their radius.
const EYE: Vec3 = Vec3::new(0.05, 0.0, -0.13);
const EYE_RADIUS: f32 = 0.03;

/// A limb: where it joins the body (the hind legs at the pelvis, the forelimbs at the
/// shoulders; left side, mirrored for the right), where its foot rests, the way its middle joint
/// bends, and its two bones.
struct LimbShape {
    root: Vec3,
    rest: Vec3,
    bend: Vec3,
    bone: Bone,
    /// Phase of its walk cycle, radians: diagonal pairs step together (a trot).
    phase: f32,
}

/// The two bones of a limb: lengths and radii, m.
#[derive(Clone, Copy)]
struct Bone {
    upper: f32,
    lower: f32,
    upper_radius: f32,
    lower_radius: f32,
}

const HIND: Bone = Bone { upper: 0.42, lower: 0.42, upper_radius: 0.075, lower_radius: 0.05 };
const FORE: Bone = Bone { upper: 0.6, lower: 0.6, upper_radius: 0.06, lower_radius: 0.04 };

/// Left hind, right hind, left fore, right fore (the right one strikes).
const LIMBS: [LimbShape; 4] = [
    LimbShape {
        root: Vec3::new(-0.15, 0.66, 0.3),
        rest: Vec3::new(-0.24, 0.0, 0.36),
        bend: Vec3::new(-0.3, 0.0, -1.0),
        bone: HIND,
        phase: std::f32::consts::PI,
    },
    LimbShape {
        root: Vec3::new(0.15, 0.66, 0.3),
        rest: Vec3::new(0.24, 0.0, 0.36),
        bend: Vec3::new(0.3, 0.0, -1.0),
        bone: HIND,
        phase: 0.0,
    },
    LimbShape {
        root: Vec3::new(-0.2, 1.0, -0.12),
        rest: Vec3::new(-0.32, 0.0, -0.45),
        bend: Vec3::new(-0.45, 0.2, 1.0),
        bone: FORE,
        phase: 0.0,
    },
    LimbShape {
        root: Vec3::new(0.2, 1.0, -0.12),
        rest: Vec3::new(0.32, 0.0, -0.45),
        bend: Vec3::new(0.45, 0.2, 1.0),
        bone: FORE,
        phase: std::f32::consts::PI,
    },
];
/// Index of the striking forelimb in [`LIMBS`].
pub const STRIKE_LIMB: usize = 3;

/// How high a foot lifts mid-step, m.
const STEP_LIFT: f32 = 0.14;
/// Below this speed (m/s) the stride shrinks towards nothing: shuffling, not striding.
const FULL_STRIDE_SPEED: f32 = 0.6;
/// Ticks the death fall takes.
const FALL_TICKS: f32 = 20.0;

/// Where the body is, in the crawler's frame (see [`PELVIS`]); [`Pose::to_world`] places it.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// The crawler's frame in the world: feet, facing, and the death fall's roll onto its side.
    pub to_world: Mat4,
    /// Spine segment centres, pelvis first, and their half extents (breathing included).
    pub spine: [(Vec3, Vec3); 4],
    /// The torso's rotation (rearing up, lunging).
    pub torso: Quat,
    pub neck: Vec3,
    pub head: Vec3,
    pub head_rotation: Quat,
    /// Per limb of [`LIMBS`]: root, middle joint, foot.
    pub limbs: [[Vec3; 3]; 4],
    /// 0 standing, 1 lying dead.
    pub fallen: f32,
}

impl Pose {
    /// The eyes' centres, in the world.
    pub fn eyes(&self) -> [Vec3; 2] {
        [-1.0, 1.0].map(|side| {
            let local = self.head + self.head_rotation * (EYE * Vec3::new(side, 1.0, 1.0));
            self.to_world.transform_point3(local)
        })
    }

    /// The way the eyes look, in the world (unit).
    pub fn gaze(&self) -> Vec3 {
        self.to_world.transform_vector3(self.head_rotation * Vec3::NEG_Z).normalize()
    }
}

/// A value's progress from `a` to `b`, eased (0 before, 1 after).
fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Ticks in the current state of mind, blended: `cur.timer` counts this tick, so between two
/// ticks in the same mind it runs smoothly; a mind just entered starts at its timer.
fn mind_ticks(prev: &Enemy, cur: &Enemy, t: f32) -> f32 {
    if prev.mind == cur.mind && cur.timer >= prev.timer {
        prev.timer as f32 + (cur.timer - prev.timer) as f32 * t
    } else {
        cur.timer as f32
    }
}

/// Yaw from `a` to `b` the short way round, at `t`.
fn yaw_between(a: f32, b: f32, t: f32) -> f32 {
    let mut d = b - a;
    d -= TAU * ((d + std::f32::consts::PI) / TAU).floor();
    a + d * t
}

/// The walk cycle's phase, radians, blended between ticks across the wrap of [`GAIT`].
fn walk_phase(prev: &Enemy, cur: &Enemy, t: f32) -> f32 {
    let mut d = cur.walked - prev.walked;
    if d < 0.0 {
        d += GAIT;
    }
    TAU * (prev.walked + d * t) / GAIT
}

/// The end of a two-bone chain from `root` reaching for `target` (as far as it can), the middle
/// joint bent towards `bend`: (joint, end).
fn two_bone(root: Vec3, target: Vec3, upper: f32, lower: f32, bend: Vec3) -> (Vec3, Vec3) {
    let to = target - root;
    let reach = to.length().clamp((upper - lower).abs() + 1e-3, upper + lower - 1e-3);
    let dir = to.try_normalize().unwrap_or(Vec3::NEG_Y);
    let end = root + dir * reach;
    // The joint: along the chain by a, out of it by h (the triangle of the two bones).
    let a = (upper * upper - lower * lower + reach * reach) / (2.0 * reach);
    let h = (upper * upper - a * a).max(0.0).sqrt();
    let side = (bend - dir * bend.dot(dir)).try_normalize().unwrap_or_else(|| dir.any_orthonormal_vector());
    (root + dir * a + side * h, end)
}

/// The crawler's pose between `prev` (t = 0) and `cur` (t = 1) at world tick `clock` (the tick
/// plus t; breathing only). `index` staggers the crawlers' breaths.
pub fn pose(prev: &Enemy, cur: &Enemy, t: f32, clock: f32, index: usize) -> Pose {
    let ticks = mind_ticks(prev, cur, t);
    let position = prev.body.position.lerp(cur.body.position, t);
    let yaw = yaw_between(prev.yaw, cur.yaw, t);
    let flinch = (prev.flinch as f32 + (cur.flinch as f32 - prev.flinch as f32) * t) / 12.0;
    let fallen = if cur.mind == Mind::Dead { (ticks / FALL_TICKS).min(1.0).powi(2) } else { 0.0 };

    // Stride: full at walking pace, none standing still.
    let velocity = prev.body.velocity.lerp(cur.body.velocity, t);
    let speed = Vec3::new(velocity.x, 0.0, velocity.z).length();
    let stride = if cur.alive() { (speed / FULL_STRIDE_SPEED).min(1.0) } else { 0.0 };
    let phase = walk_phase(prev, cur, t);

    // Rearing (nose up, radians about the pelvis), the torso's shift (m, +Z back), raised
    // forelimbs (0–1), and the strike's draw and reach (0–1).
    let (mut rear, mut shift, mut raise, mut draw, mut reach) = (0.0, 0.0, 0.0, 0.0, 0.0);
    match cur.mind {
        Mind::Alert => {
            // Up fast, held, down again before it moves in.
            let n = enemy::NOTICE_TICKS as f32;
            let up = smoothstep(0.0, n * 0.33, ticks) * (1.0 - smoothstep(n * 0.6, n, ticks));
            rear = 0.55 * up;
            raise = up;
        }
        Mind::Attack => {
            let (w, r) = (enemy::WINDUP as f32, enemy::RECOVER as f32);
            // Fully drawn back by half the windup, held, then flung out as it lands.
            draw = smoothstep(0.0, 0.5 * w, ticks) * (1.0 - smoothstep(w - 4.0, w, ticks));
            reach = smoothstep(w - 4.0, w, ticks) * (1.0 - smoothstep(w + 6.0, w + r, ticks));
            rear = 0.45 * draw - 0.25 * reach;
            shift = 0.1 * draw - 0.28 * reach;
            raise = 0.4 * draw;
        }
        Mind::Dead => {
            rear = -0.15 * fallen;
        }
        _ => {}
    }
    rear += 0.3 * flinch;
    shift += 0.12 * flinch;

    // The chest heaves on the simulation's calm breathing beat, so a calm crawler is seen
    // breathing as it is heard.
    let beat = (clock + (index as u32 * enemy::BREATH_STAGGER) as f32) / enemy::BREATH_CALM as f32;
    let breath = (TAU * beat).sin() * (1.0 - fallen);
    let bob = Vec3::Y * (0.025 * stride * (2.0 * phase).cos() + 0.008 * breath);
    let torso = Quat::from_rotation_x(rear);
    let place = |p: Vec3| PELVIS + torso * (p - PELVIS) + Vec3::Z * shift + bob;

    let spine = SPINE.map(|(along, size)| {
        // A gentle hump: the middle rides a little above the straight line.
        let hump = Vec3::Y * 0.06 * (along * std::f32::consts::PI).sin();
        let swell = 1.0 + 0.035 * breath;
        (place(PELVIS.lerp(SHOULDERS, along) + hump), size * Vec3::new(swell, swell, 1.0))
    });

    // The head leads: it turns towards what the crawler is after, and into the turn it is making.
    let turning = yaw_between(prev.yaw, cur.yaw, 1.0) - prev.yaw;
    let mut look = 6.0 * turning;
    if !matches!(cur.mind, Mind::Patrol | Mind::Dead) {
        let to = cur.target - position;
        if to.x * to.x + to.z * to.z > 0.04 {
            look += yaw_between(yaw, (-to.x).atan2(-to.z), 1.0) - yaw;
        }
    }
    let look = look.clamp(-0.7, 0.7);
    let head_pitch = 0.25 * raise - 0.3 * flinch - 0.5 * fallen;
    let head_rotation = torso * Quat::from_rotation_y(look) * Quat::from_rotation_x(head_pitch);
    let lunge = Vec3::NEG_Z * 0.22 * reach;
    let head = place(HEAD) + lunge;
    let neck = place(SHOULDERS.lerp(HEAD, 0.55)) + lunge * 0.5;

    let limbs = std::array::from_fn(|i| {
        let shape = &LIMBS[i];
        let fore = i >= 2;
        let root = if fore { place(shape.root) } else { shape.root + bob };
        // Walking: the foot swings forward lifted and pushes back planted.
        let p = phase + shape.phase;
        let mut foot =
            shape.rest + Vec3::new(0.0, STEP_LIFT * stride * p.sin().max(0.0), 0.25 * GAIT * stride * p.cos());
        if fore {
            // Claws up in front of the chest when it rears; the striker drawn back over the
            // shoulder, then flung out to its reach.
            let side = shape.rest.x.signum();
            let up = place(Vec3::new(0.3 * side, 0.8, -0.5));
            foot = foot.lerp(up, raise.min(1.0));
            if i == STRIKE_LIMB {
                let drawn = place(Vec3::new(0.32, 1.6, 0.05));
                let struck = Vec3::new(0.12, 0.95, -enemy::REACH - 0.1);
                foot = foot.lerp(drawn, draw).lerp(struck, reach);
            }
        }
        // Dead: limbs curled in against the body, those of the side it falls on tucked under.
        let curled_x = if shape.rest.x < 0.0 { -0.06 } else { shape.rest.x * 0.9 };
        let curled = Vec3::new(curled_x, if fore { 0.55 } else { 0.35 }, shape.root.z + 0.1);
        let foot = foot.lerp(curled, fallen);
        // Joints bend up when rearing; on the side it falls on, in under the body.
        let tuck = if shape.rest.x < 0.0 { Vec3::X * 1.2 * fallen } else { Vec3::ZERO };
        let bend = shape.bend + Vec3::Y * if fore { raise } else { 0.0 } + tuck;
        let (joint, end) = two_bone(root, foot, shape.bone.upper, shape.bone.lower, bend);
        [root, joint, end]
    });

    // The fall: a roll onto its left side, lifted by the body's half width so it lies on the
    // floor rather than in it.
    let roll = Quat::from_rotation_z((FRAC_PI_2 - 0.1) * fallen);
    let to_world = Mat4::from_rotation_translation(Quat::from_rotation_y(yaw), position)
        * Mat4::from_translation(Vec3::Y * 0.2 * fallen)
        * Mat4::from_quat(roll);
    Pose { to_world, spine, torso, neck, head, head_rotation, limbs, fallen }
}

/// The headlamp as the eyes see it, for eyeshine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LampLight {
    pub position: Vec3,
    /// The beam's axis (unit).
    pub direction: Vec3,
    /// Radiant intensity on the axis, W/sr per channel (0 when off).
    pub intensity: Vec3,
    /// The beam's half-angles as cosines: full within `cos_inner`, nothing beyond `cos_outer`.
    pub cos_inner: f32,
    pub cos_outer: f32,
    /// Where the player's eye is: eyeshine goes back towards the lamp, so it shows only
    /// from near it.
    pub viewer: Vec3,
}

impl LampLight {
    /// No lamp: no eyeshine.
    pub const OFF: Self = Self {
        position: Vec3::ZERO,
        direction: Vec3::NEG_Z,
        intensity: Vec3::ZERO,
        cos_inner: 1.0,
        cos_outer: 0.0,
        viewer: Vec3::ZERO,
    };

    /// The headlamp of `view` (on the camera while worn), seen from its camera.
    pub fn of(view: &ViewState) -> Self {
        let lamp = &view.headlamp;
        let (position, rotation) =
            if lamp.attached { (view.camera.position, view.camera.rotation) } else { (lamp.position, lamp.rotation) };
        let (cos_inner, cos_outer) = match lamp.profile.distribution {
            IntensityDistribution::Spot { inner, outer } => (inner.cos(), outer.cos()),
            // Other profiles: roughly the frustum's inscribed cone, softened.
            _ => ((0.35 * lamp.profile.fov_y).cos(), (0.5 * lamp.profile.fov_y).cos()),
        };
        Self {
            position,
            direction: rotation * Vec3::NEG_Z,
            intensity: if lamp.on { lamp.intensity() } else { Vec3::ZERO },
            cos_inner,
            cos_outer,
            viewer: view.camera.position,
        }
    }
}

/// Returned radiance per irradiance of the eyes' tapetum, sr⁻¹ (a retroreflector's coefficient
/// R_A: far above a white diffuser's 1/π).
const RETROREFLECTION: f32 = 4.0;
/// The tapetum's tint: amber.
const TAPETUM: Vec3 = Vec3::new(1.0, 0.5, 0.12);
/// The retroreflected light's spread about the way back to the lamp, as cosines (full within
/// 2°, gone at 12°).
const RETRO_COS_FULL: f32 = 0.9994;
const RETRO_COS_EDGE: f32 = 0.978;

/// Emitted radiance (W·sr⁻¹·m⁻²) of an eye at `eye` looking along `gaze`: the lamp's irradiance
/// on it (its intensity towards the eye over distance², by how squarely the eye faces the lamp)
/// sent back towards the lamp, seen as much as the viewer stands in that returned light.
pub fn eyeshine(eye: Vec3, gaze: Vec3, lamp: &LampLight) -> Vec3 {
    let to_eye = eye - lamp.position;
    let d2 = to_eye.length_squared().max(0.01);
    let along = to_eye.normalize().dot(lamp.direction);
    let in_beam = smoothstep(lamp.cos_outer, lamp.cos_inner, along);
    let facing = gaze.dot(-to_eye.normalize()).max(0.0);
    let to_viewer = (lamp.viewer - eye).try_normalize().unwrap_or(Vec3::Y);
    let back = smoothstep(RETRO_COS_EDGE, RETRO_COS_FULL, to_viewer.dot(-to_eye.normalize()));
    let irradiance = lamp.intensity * in_beam * facing / d2;
    irradiance * RETROREFLECTION * back * TAPETUM
}

/// The crawler's meshes: a unit sphere (scaled into segments, head and eyes) and the limbs'
/// bones, each a capsule of its bone's length so IK never stretches it.
pub struct CrawlerMeshes {
    sphere: MeshId,
    /// Hind upper, hind lower, fore upper, fore lower.
    bones: [MeshId; 4],
}

const SKIN: [f32; 3] = [0.62, 0.58, 0.52];
const LIMB_SKIN: [f32; 3] = [0.52, 0.48, 0.43];
const DEAD_SKIN: [f32; 3] = [0.25, 0.22, 0.2];
/// The eyes' albedo (they shine by their emission): what tells an eye from the rest of a frame's instances.
pub const EYE_COLOR: [f32; 3] = [0.1; 3];

impl CrawlerMeshes {
    pub fn add_to(renderer: &mut Renderer, gpu: &Gpu) -> Self {
        let mut add = |(v, i): (Vec<_>, Vec<u32>)| renderer.add_mesh(gpu, &v, &i);
        let bone = |length: f32, radius: f32| primitives::capsule(radius, length + 2.0 * radius, 10);
        Self {
            sphere: add(primitives::uv_sphere(1.0, 14, 10)),
            bones: [
                add(bone(HIND.upper, HIND.upper_radius)),
                add(bone(HIND.lower, HIND.lower_radius)),
                add(bone(FORE.upper, FORE.upper_radius)),
                add(bone(FORE.lower, FORE.lower_radius)),
            ],
        }
    }

    #[cfg(test)]
    pub fn fake(first: u32) -> Self {
        Self { sphere: MeshId(first), bones: std::array::from_fn(|i| MeshId(first + 1 + i as u32)) }
    }

    /// The crawler's instances, posed between `prev` and `cur` (see [`pose`]).
    pub fn instances(
        &self,
        out: &mut Vec<Instance>,
        (prev, cur): (&Enemy, &Enemy),
        t: f32,
        clock: f32,
        index: usize,
        lamp: &LampLight,
    ) {
        let pose = pose(prev, cur, t, clock, index);
        let w = pose.to_world;
        let dead = cur.mind == Mind::Dead;
        let flinch = cur.flinch as f32 / 12.0;
        let (skin, limb_skin) = if dead { (DEAD_SKIN, DEAD_SKIN) } else { (SKIN, LIMB_SKIN) };
        // A hit shows as a flush of red.
        let hurt = [0.6 * flinch, 0.0, 0.0];
        let blob = |at: Vec3, rotation: Quat, size: Vec3| Mat4::from_scale_rotation_translation(size, rotation, at);
        for &(at, size) in &pose.spine {
            let transform = w * blob(at, pose.torso, size);
            out.push(Instance { mesh: self.sphere, transform, base_color: skin, emissive: hurt });
        }
        for (at, size) in [(pose.neck, NECK), (pose.head, HEAD_SIZE)] {
            let transform = w * blob(at, pose.head_rotation, size);
            out.push(Instance { mesh: self.sphere, transform, base_color: skin, emissive: hurt });
        }
        for (i, [root, joint, end]) in pose.limbs.iter().enumerate() {
            let (bone, meshes) =
                if i < 2 { (HIND, [self.bones[0], self.bones[1]]) } else { (FORE, [self.bones[2], self.bones[3]]) };
            for ((from, to), (mesh, radius)) in [(*root, *joint), (*joint, *end)]
                .into_iter()
                .zip([(meshes[0], bone.upper_radius), (meshes[1], bone.lower_radius)])
            {
                // The capsule's axis (+Y) from bone end to bone end, its caps round the joints.
                let axis = (to - from).try_normalize().unwrap_or(Vec3::Y);
                let turn = Quat::from_rotation_arc(Vec3::Y, axis);
                let transform = w * Mat4::from_rotation_translation(turn, from - axis * radius);
                out.push(Instance { mesh, transform, base_color: limb_skin, emissive: [0.0; 3] });
            }
        }
        // Their own faint glow (stronger once roused), and the lamp's light thrown back.
        let glow = match cur.mind {
            Mind::Dead => Vec3::ZERO,
            Mind::Patrol | Mind::Search => Vec3::new(0.3, 0.036, 0.0),
            _ => Vec3::new(1.5, 0.18, 0.0),
        };
        let gaze = pose.gaze();
        for eye in pose.eyes() {
            let shine = if dead { Vec3::ZERO } else { eyeshine(eye, gaze, lamp) };
            let transform = Mat4::from_scale_rotation_translation(Vec3::splat(EYE_RADIUS), Quat::IDENTITY, eye);
            out.push(Instance {
                mesh: self.sphere,
                transform,
                base_color: EYE_COLOR,
                emissive: (glow + shine).to_array(),
            });
        }
    }
}

#[cfg(test)]
mod tests;
