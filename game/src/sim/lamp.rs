//! The headlamp as the simulation sees it: on or off, its battery and low-battery flicker, and
//! where it is — on the player's head, or set down / thrown and lying where it landed.

use glam::Vec3;
use physics::LevelCollision;

use super::command::{buttons, TickCommand};
use super::player::Player;
use super::rng::Rng;

/// Below this charge the lamp starts to flicker, more often the emptier it gets.
pub const LOW_BATTERY: f32 = 0.2;
/// A battery this charged counts as full: a battery pickup leaves it alone.
pub const FULL: f32 = 0.98;
/// The player can pick the lamp up when it is this close to the eye, m.
pub const REACH: f32 = 2.2;
/// Speed of a throw along the view, m/s (plus a little lift and the player's own velocity).
pub const THROW_SPEED: f32 = 8.0;
const THROW_LIFT: f32 = 1.5;
/// Set down: let go this far in front of the eye.
const SET_DOWN_AHEAD: f32 = 0.5;
/// The lamp's size for collisions, m.
const RADIUS: f32 = 0.08;
const GRAVITY: f32 = 9.81;
/// Surfaces this flat stop the lamp; steeper ones bounce it.
const FLOOR_NORMAL_Y: f32 = 0.7;
const BOUNCE: f32 = 0.3;
/// A lying lamp keeps the heading it was aimed at, pitched into this range (angle units, ±),
/// so it lights the room rather than the floor under it or the ceiling.
const REST_PITCH: (i16, i16) = (-2731, 2731);

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lamp {
    pub on: bool,
    pub attached: bool,
    /// Where the lamp is and where it points (angle units), when detached.
    pub position: Vec3,
    pub yaw: u16,
    pub pitch: i16,
    /// Flying after a throw or a set-down, m/s; zero once it lies still.
    pub velocity: Vec3,
    pub resting: bool,
    /// Charge, 0..=1.
    pub battery: f32,
    /// Brightness multiplier this tick, 1 except during a low-battery flicker.
    pub flicker: f32,
    /// Ticks left of the current flicker.
    pub flicker_ticks: u8,
}

impl Lamp {
    pub fn new() -> Self {
        Self {
            on: true,
            attached: true,
            position: Vec3::ZERO,
            yaw: 0,
            pitch: 0,
            velocity: Vec3::ZERO,
            resting: true,
            battery: 1.0,
            flicker: 1.0,
            flicker_ticks: 0,
        }
    }

    /// The light actually emitted, as a fraction of full power.
    pub fn brightness(&self) -> f32 {
        if self.on {
            self.flicker
        } else {
            0.0
        }
    }

    /// Where to draw a detached lamp between its state one tick ago (`prev`, t = 0) and now
    /// (t = 1): flying, blended; lying still, exactly where it lies.
    pub fn drawn_position(&self, prev: &Lamp, t: f32) -> Vec3 {
        if self.resting {
            self.position
        } else {
            prev.position.lerp(self.position, t)
        }
    }

    pub fn within_reach(&self, player: &Player) -> bool {
        !self.attached && self.position.distance(player.eye()) <= REACH
    }

    /// Presses, then flight, battery and flicker. Presses take effect after the player has
    /// turned this tick, so a lamp let go points exactly where the view did on that tick.
    pub fn step(
        &mut self,
        cmd: &TickCommand,
        player: &Player,
        level: &LevelCollision,
        rng: &mut Rng,
        battery_seconds: f32,
        dt: f32,
    ) {
        if cmd.held(buttons::LAMP_TOGGLE) {
            // An empty lamp stays off until a battery is found.
            self.on = !self.on && self.battery > 0.0;
        }
        if cmd.held(buttons::LAMP_DETACH) {
            if self.attached {
                self.let_go(player, Vec3::new(player.body.velocity.x, 0.0, player.body.velocity.z) * 0.5);
                self.position = self.clear_of_walls(player.eye(), player.aim() * SET_DOWN_AHEAD, level);
            } else if self.within_reach(player) {
                self.attached = true;
            }
        } else if cmd.held(buttons::LAMP_THROW) && self.attached {
            let velocity = player.body.velocity + player.aim() * THROW_SPEED + Vec3::Y * THROW_LIFT;
            self.let_go(player, velocity);
        }
        if !self.attached && !self.resting {
            self.fly(level, dt);
        }
        if self.on {
            self.battery = (self.battery - dt / battery_seconds).max(0.0);
            if self.battery == 0.0 {
                self.on = false;
            }
        }
        self.flicker(rng);
    }

    fn let_go(&mut self, player: &Player, velocity: Vec3) {
        self.attached = false;
        self.resting = false;
        self.position = player.eye();
        self.velocity = velocity;
        self.yaw = player.yaw;
        self.pitch = player.pitch.clamp(REST_PITCH.0, REST_PITCH.1);
    }

    /// `from + offset`, or short of the first wall along the way.
    fn clear_of_walls(&self, from: Vec3, offset: Vec3, level: &LevelCollision) -> Vec3 {
        let length = offset.length();
        match level.cast_ray(from, offset / length, length + RADIUS) {
            Some(hit) => from + offset / length * (hit.distance - RADIUS).max(0.0),
            None => from + offset,
        }
    }

    /// One tick of ballistic flight: lands on floors, bounces off walls.
    fn fly(&mut self, level: &LevelCollision, dt: f32) {
        self.velocity.y -= GRAVITY * dt;
        let travel = self.velocity * dt;
        let length = travel.length();
        if length <= 0.0 {
            return;
        }
        let dir = travel / length;
        match level.cast_ray(self.position, dir, length + RADIUS) {
            Some(hit) => {
                self.position = hit.point + hit.normal * RADIUS;
                if hit.normal.y >= FLOOR_NORMAL_Y {
                    self.velocity = Vec3::ZERO;
                    self.resting = true;
                } else {
                    let v = self.velocity;
                    self.velocity = (v - 2.0 * v.dot(hit.normal) * hit.normal) * BOUNCE;
                }
            }
            None => self.position += travel,
        }
    }

    /// Low battery: now and then the light drops to a random fraction for a few ticks.
    fn flicker(&mut self, rng: &mut Rng) {
        if self.flicker_ticks > 0 {
            self.flicker_ticks -= 1;
            if self.flicker_ticks == 0 {
                self.flicker = 1.0;
            }
            return;
        }
        if !self.on || self.battery >= LOW_BATTERY {
            return;
        }
        let chance = 0.02 + 0.15 * (1.0 - self.battery / LOW_BATTERY);
        if rng.next_f32() < chance {
            self.flicker_ticks = 2 + (rng.next_u64() % 9) as u8;
            self.flicker = 0.1 + 0.5 * rng.next_f32();
        }
    }
}

impl Default for Lamp {
    fn default() -> Self {
        Self::new()
    }
}
