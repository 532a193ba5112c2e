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
}

impl Player {
    pub fn spawn(feet: Vec3, yaw: u16, pitch: i16, config: &CharacterConfig) -> Self {
        let body = CharacterBody::standing_at(feet);
        Self { body, yaw, pitch, eye_height: body.height(config) - EYE_BELOW_TOP, health: MAX_HEALTH, hurt_ticks: 0 }
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
