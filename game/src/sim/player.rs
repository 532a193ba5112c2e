//! The player in the tick: heading and pitch in whole angle units, a walking body, and the
//! rules that turn a command into a wish to move.

use glam::Vec3;
use physics::{CharacterBody, CharacterConfig, CharacterMove};

use super::command::{buttons, radians, TickCommand};

/// Walking speeds, m/s.
pub const WALK_SPEED: f32 = 4.0;
pub const SPRINT_SPEED: f32 = 6.5;
pub const CROUCH_SPEED: f32 = 2.0;
/// The eye sits this far below the top of the body.
pub const EYE_BELOW_TOP: f32 = 0.2;
/// How fast the eye follows the body's height when crouching or standing, m/s: the view
/// lowers over a few ticks instead of jumping.
pub const EYE_SPEED: f32 = 4.0;
/// Pitch stops just short of straight up/down (89°), where yaw would lose its meaning.
pub const MAX_PITCH: i32 = 16_201;
pub const MAX_HEALTH: f32 = 100.0;
/// Ticks the HUD shows a hit for.
pub const HURT_TICKS: u8 = 30;
/// Walking from standing, the first footfall comes after this far, m.
pub const FIRST_STEP: f32 = 0.5;
/// A landing this fast (falling, m/s) is heard; slower ones (a step down) are not.
pub const LANDING_HEARD: f32 = 2.0;

/// How the player is moving on foot, for the sound of their steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gait {
    Walk,
    Sprint,
    Crouch,
}

impl Gait {
    /// Distance between footfalls, m: longer strides at a faster pace (walking 2.2 steps a
    /// second, sprinting 2.8, crouching 1.8).
    pub fn stride(self) -> f32 {
        match self {
            Gait::Walk => 1.8,
            Gait::Sprint => 2.3,
            Gait::Crouch => 1.1,
        }
    }
}

/// What the player's feet did in a tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Footfall {
    Step(Gait),
    Jumped,
    /// Came down from a fall or a jump at this speed, m/s.
    Landed(f32),
}

/// The unit direction of a heading and pitch in angle units.
pub fn aim(yaw: u16, pitch: i16) -> Vec3 {
    // libm, not std: the same bits on every platform and libc.
    let (yaw, pitch) = (radians(yaw as f32), radians(pitch as f32));
    let (sy, cy, sp, cp) = (libm::sinf(yaw), libm::cosf(yaw), libm::sinf(pitch), libm::cosf(pitch));
    Vec3::new(-sy * cp, sp, -cy * cp)
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Player {
    pub body: CharacterBody,
    /// Angle units, wrapping: 0 looks down −Z, increasing turns left.
    pub yaw: u16,
    /// Angle units, ±[`MAX_PITCH`]; positive looks up.
    pub pitch: i16,
    /// Eye height above the feet, m.
    pub eye_height: f32,
    pub health: f32,
    /// Ticks since the last hit still shown (counts down to 0).
    pub hurt_ticks: u8,
    /// Metres left to walk until the next footfall.
    pub to_next_step: f32,
}

impl Player {
    pub fn spawn(feet: Vec3, yaw: u16, pitch: i16, config: &CharacterConfig) -> Self {
        let body = CharacterBody::standing_at(feet);
        Self {
            body,
            yaw,
            pitch,
            eye_height: body.height(config) - EYE_BELOW_TOP,
            health: MAX_HEALTH,
            hurt_ticks: 0,
            to_next_step: FIRST_STEP,
        }
    }

    pub fn eye(&self) -> Vec3 {
        self.body.position + Vec3::Y * self.eye_height
    }

    pub fn alive(&self) -> bool {
        self.health > 0.0
    }

    /// The unit direction the view looks along.
    pub fn aim(&self) -> Vec3 {
        aim(self.yaw, self.pitch)
    }

    pub fn hurt(&mut self, damage: f32) {
        self.health = (self.health - damage).max(0.0);
        self.hurt_ticks = HURT_TICKS;
    }

    /// Turns by the command and says how the body wants to move this tick.
    pub fn steer(&mut self, cmd: &TickCommand) -> CharacterMove {
        self.yaw = self.yaw.wrapping_add(cmd.turn as u16);
        self.pitch = (self.pitch as i32 + cmd.look as i32).clamp(-MAX_PITCH, MAX_PITCH) as i16;
        let crouch = cmd.held(buttons::CROUCH);
        let speed = if crouch || self.body.crouching {
            CROUCH_SPEED
        } else if cmd.held(buttons::SPRINT) {
            SPRINT_SPEED
        } else {
            WALK_SPEED
        };
        // libm, not std: the same bits on every platform and libc.
        let yaw = radians(self.yaw as f32);
        let (sin, cos) = (libm::sinf(yaw), libm::cosf(yaw));
        let forward = Vec3::new(-sin, 0.0, -cos);
        let right = Vec3::new(cos, 0.0, -sin);
        let mut wish = forward * (cmd.forward as f32 / 127.0) + right * (cmd.strafe as f32 / 127.0);
        // Diagonals are no faster than straight lines.
        let len2 = wish.length_squared();
        if len2 > 1.0 {
            wish /= libm::sqrtf(len2);
        }
        CharacterMove { wish_velocity: wish * speed, jump: cmd.held(buttons::JUMP), crouch }
    }

    /// After the body moved from `before` this tick: a footfall when the ground walked since the
    /// last one reaches a stride, a jump leaving the ground, or a landing.
    pub fn footfall(&mut self, before: &CharacterBody, dt: f32) -> Option<Footfall> {
        let now = &self.body;
        if before.grounded && !now.grounded {
            return (now.velocity.y > 0.0).then_some(Footfall::Jumped);
        }
        if !now.grounded {
            return None;
        }
        if !before.grounded {
            // The landing is the footfall; the next step comes a stride later.
            self.to_next_step = Gait::Walk.stride();
            let speed = -before.velocity.y;
            return (speed >= LANDING_HEARD).then_some(Footfall::Landed(speed));
        }
        let (dx, dz) = (now.position.x - before.position.x, now.position.z - before.position.z);
        let moved = libm::sqrtf(dx * dx + dz * dz);
        if moved < 0.2 * dt {
            self.to_next_step = FIRST_STEP;
            return None;
        }
        let gait = if now.crouching {
            Gait::Crouch
        } else if moved > 0.5 * (WALK_SPEED + SPRINT_SPEED) * dt {
            Gait::Sprint
        } else {
            Gait::Walk
        };
        self.to_next_step -= moved;
        if self.to_next_step > 0.0 {
            return None;
        }
        self.to_next_step = (self.to_next_step + gait.stride()).max(0.0);
        Some(Footfall::Step(gait))
    }

    /// Moves the eye toward the body's current height.
    pub fn settle_eye(&mut self, config: &CharacterConfig, dt: f32) {
        let target = self.body.height(config) - EYE_BELOW_TOP;
        let step = EYE_SPEED * dt;
        self.eye_height = if self.eye_height < target {
            (self.eye_height + step).min(target)
        } else {
            (self.eye_height - step).max(target)
        };
    }
}
