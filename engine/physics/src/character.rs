//! A first-person walking controller: a vertical capsule swept through the level, with
//! gravity, jumping, crouching and stepping on top.
//!
//! Each tick: crouch or stand up, set the velocity from the move (snappy on the ground, limited
//! in the air), then move by velocity × dt. On the ground that is a Quake-style step-slide: slide
//! along what is in the way; if that fell short, also try stepping up over it and keep whichever
//! went further; then follow the ground down. In the air it is a plain slide. Finally the
//! velocity that pushed into whatever stopped the motion is removed, and the feet look for
//! walkable ground.

use std::fmt;

use glam::Vec3;

use crate::level_collision::LevelCollision;
use crate::sweep::{Mover, Sweep, SKIN};

/// A surface stopped the motion when the move fell short by more than this along its normal,
/// and a step is taken only when it gets further than this beyond a plain slide, metres.
const PROGRESS_EPSILON: f32 = 1e-4;

/// The character's shape and the physics of its movement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CharacterConfig {
    /// Capsule radius, metres.
    pub radius: f32,
    /// Standing height, feet to top of the capsule, metres.
    pub height: f32,
    /// Crouching height, metres.
    pub crouch_height: f32,
    /// Steps up to this height are climbed while walking, and the feet follow the ground down
    /// drops this small instead of falling, metres.
    pub step_height: f32,
    /// Ground steeper than this (degrees from horizontal) cannot be walked up or stood on: it
    /// is a wall, and the character slides down it.
    pub max_slope_deg: f32,
    /// Downward acceleration, m/s² (positive, pulls towards -Y).
    pub gravity: f32,
    /// Vertical speed given by a jump, m/s.
    pub jump_speed: f32,
    /// Horizontal acceleration available in the air, m/s²: while airborne the horizontal
    /// velocity moves towards the wish velocity by at most `air_control × dt` per tick.
    /// 0 = no control after leaving the ground; very large = as snappy as on the ground.
    pub air_control: f32,
}

impl Default for CharacterConfig {
    fn default() -> Self {
        Self {
            radius: 0.3,
            height: 1.8,
            crouch_height: 1.2,
            step_height: 0.35,
            max_slope_deg: 46.0,
            gravity: 9.81,
            jump_speed: 4.5,
            // Turning a 4 m/s run around takes ~1.6 s, longer than a jump (~0.9 s): a jump
            // can be steered, not reversed.
            air_control: 5.0,
        }
    }
}

/// Which [`CharacterConfig`] field is unusable, and why.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CharacterConfigError {
    pub field: &'static str,
    pub reason: &'static str,
}

impl fmt::Display for CharacterConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "character config: {} {}", self.field, self.reason)
    }
}

impl std::error::Error for CharacterConfigError {}

impl CharacterConfig {
    /// Checks that the values describe a usable capsule and movement. The controller never
    /// panics on a bad config (it clamps the shape to something valid), but it will not move
    /// sensibly either; call this where the config is made.
    pub fn validate(&self) -> Result<(), CharacterConfigError> {
        let err = |field, reason| Err(CharacterConfigError { field, reason });
        let finite = [
            ("radius", self.radius),
            ("height", self.height),
            ("crouch_height", self.crouch_height),
            ("step_height", self.step_height),
            ("max_slope_deg", self.max_slope_deg),
            ("gravity", self.gravity),
            ("jump_speed", self.jump_speed),
            ("air_control", self.air_control),
        ];
        if let Some((field, _)) = finite.iter().find(|(_, v)| !v.is_finite()) {
            return err(field, "must be a finite number");
        }
        if self.radius <= 2.0 * SKIN {
            return err("radius", "must be more than 2 cm");
        }
        if self.crouch_height < 2.0 * self.radius {
            return err("crouch_height", "must be at least the capsule's diameter (2 × radius)");
        }
        if self.height < self.crouch_height {
            return err("height", "must be at least crouch_height");
        }
        if self.step_height < 0.0 || self.step_height >= self.crouch_height {
            return err("step_height", "must be in [0, crouch_height)");
        }
        if !(0.0..90.0).contains(&self.max_slope_deg) {
            return err("max_slope_deg", "must be in [0, 90)");
        }
        if self.gravity < 0.0 || self.jump_speed < 0.0 || self.air_control < 0.0 {
            return err("gravity, jump_speed and air_control", "must not be negative");
        }
        Ok(())
    }
}

/// The character's simulated state: all of it, so that copying it snapshots the character.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CharacterBody {
    /// The feet: bottom centre of the capsule, metres, Y up.
    pub position: Vec3,
    /// m/s.
    pub velocity: Vec3,
    /// Standing on walkable ground (not rising). Horizontal control is full and jumping is
    /// possible only then.
    pub grounded: bool,
    pub crouching: bool,
}

impl CharacterBody {
    /// At rest, standing, feet at `feet`; `grounded` becomes true on the first step if there is
    /// ground there.
    pub fn standing_at(feet: Vec3) -> Self {
        Self { position: feet, velocity: Vec3::ZERO, grounded: false, crouching: false }
    }

    /// Current capsule height: standing or crouching.
    pub fn height(&self, cfg: &CharacterConfig) -> f32 {
        if self.crouching {
            cfg.crouch_height
        } else {
            cfg.height
        }
    }
}

/// What the player asks of the character for one tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CharacterMove {
    /// Desired horizontal velocity, m/s; `y` is ignored, non-finite values count as zero.
    pub wish_velocity: Vec3,
    /// Jump if standing on the ground (held: jumps again on landing).
    pub jump: bool,
    /// Crouch while held; on release, stand up as soon as there is headroom.
    pub crouch: bool,
}

/// Moves a [`CharacterBody`] through a [`LevelCollision`], one fixed tick at a time.
#[derive(Clone, Debug)]
pub struct CharacterController {
    /// Read at every step (there is no other state): changes take effect on the next one.
    pub config: CharacterConfig,
}

impl CharacterController {
    pub fn new(config: CharacterConfig) -> Self {
        Self { config }
    }

    /// Advances the body by one fixed tick of `dt` seconds (a non-positive or non-finite `dt`
    /// does nothing). Deterministic: the same level, body, move and `dt` give bit-identical
    /// results.
    pub fn step(&self, level: &LevelCollision, body: &mut CharacterBody, mv: &CharacterMove, dt: f32) {
        if !(dt > 0.0 && dt.is_finite()) {
            return;
        }
        let cfg = &self.config;

        // Crouching keeps the feet where they are; standing up needs room for the full capsule.
        if mv.crouch {
            body.crouching = true;
        } else if body.crouching && Mover::new(level, cfg.radius, cfg.height, cfg.max_slope_deg).fits(body.position) {
            body.crouching = false;
        }
        let mover = Mover::new(level, cfg.radius, body.height(cfg), cfg.max_slope_deg);

        let wish = Vec3::new(mv.wish_velocity.x, 0.0, mv.wish_velocity.z);
        let wish = if wish.is_finite() { wish } else { Vec3::ZERO };
        let horizontal = Vec3::new(body.velocity.x, 0.0, body.velocity.z);
        let horizontal = if body.grounded {
            wish
        } else {
            horizontal + (wish - horizontal).clamp_length_max(cfg.air_control.max(0.0) * dt)
        };
        body.velocity.x = horizontal.x;
        body.velocity.z = horizontal.z;

        if body.grounded && mv.jump {
            body.velocity.y = cfg.jump_speed;
            body.grounded = false;
        }
        let start = body.position;
        if body.grounded {
            // The floor balances gravity: walking asks for no vertical motion.
            body.velocity.y = 0.0;
            let step_height = cfg.step_height.max(0.0);
            let desired = horizontal * dt;
            let (moved, stepped) = walk(&mover, start, desired, step_height);
            body.position = if stepped { moved.feet } else { mover.follow_ground_down(moved.feet, step_height) };
            clip_walking_velocity(&mut body.velocity, desired, moved.feet - start, &moved.hits, &mover);
            // A step may end perched on the nosing: standing, as long as the walk goes on.
            body.grounded = stepped || mover.on_ground(body.position);
        } else {
            // The exact displacement under constant gravity (not v·dt), so jump heights and
            // fall times do not depend on the tick rate.
            let desired =
                Vec3::new(horizontal.x * dt, body.velocity.y * dt - 0.5 * cfg.gravity * dt * dt, horizontal.z * dt);
            body.velocity.y -= cfg.gravity * dt;
            let moved = mover.slide(start, desired);
            body.position = moved.feet;
            clip_airborne_velocity(&mut body.velocity, desired, moved.feet - start, &moved.hits, &mover);
            body.grounded = body.velocity.y <= 0.0 && mover.on_ground(body.position);
            if body.grounded {
                body.velocity.y = 0.0;
            }
        }
    }
}

/// Step-slide: the plain slide, or, when that fell short, stepping up over the obstacle if that
/// gets further (then true). Stepping also keeps the full horizontal speed up ramps, where a
/// slide loses the part of the motion that pushed into the ramp.
fn walk(mover: &Mover, start: Vec3, desired: Vec3, step_height: f32) -> (Sweep, bool) {
    let plain = mover.slide(start, desired);
    let Some(dir) = desired.try_normalize() else { return (plain, false) };
    let progress = |sweep: &Sweep| (sweep.feet - start).dot(dir);
    let plain_progress = progress(&plain);
    if plain_progress >= desired.length() - PROGRESS_EPSILON || step_height <= 0.0 {
        return (plain, false);
    }
    match mover.step_up(start, plain.feet, desired, step_height) {
        Some(stepped) if progress(&stepped) > plain_progress + PROGRESS_EPSILON => (stepped, true),
        _ => (plain, false),
    }
}

/// On the ground only horizontal velocity matters: remove its part that pushed into a wall
/// (or a too-steep slope) the move was stopped by.
fn clip_walking_velocity(velocity: &mut Vec3, desired: Vec3, moved: Vec3, hits: &[Vec3], mover: &Mover) {
    let shortfall = desired - moved;
    for &n in hits {
        if mover.is_walkable(n) {
            continue;
        }
        let Some(n) = Vec3::new(n.x, 0.0, n.z).try_normalize() else { continue };
        if shortfall.dot(-n) > PROGRESS_EPSILON {
            *velocity -= n * velocity.dot(n).min(0.0);
        }
    }
}

/// In the air: landing on walkable ground stops the fall but keeps the horizontal speed;
/// anything else (wall, ceiling, steep slope) takes the velocity into it, leaving the slide
/// along it. Surfaces merely brushed did not cut the move short along their normal.
fn clip_airborne_velocity(velocity: &mut Vec3, desired: Vec3, moved: Vec3, hits: &[Vec3], mover: &Mover) {
    let shortfall = desired - moved;
    for &n in hits {
        if shortfall.dot(-n) <= PROGRESS_EPSILON {
            continue;
        }
        if mover.is_walkable(n) {
            velocity.y = velocity.y.max(0.0);
        } else {
            *velocity -= n * velocity.dot(n).min(0.0);
        }
    }
}
