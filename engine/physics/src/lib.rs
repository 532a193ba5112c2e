//! Collision against a level's triangles, and a deterministic first-person walking controller.
//!
//! [`LevelCollision`] turns a [`scene::Scene`] (or a bare triangle list) into one static rapier
//! triangle mesh that can be ray-cast and swept against. [`CharacterController`] moves a
//! [`CharacterBody`] (a vertical capsule, feet at `position`) through it one fixed tick at a
//! time: walls stop it, gravity pulls it down, it jumps, crouches, climbs ramps and small steps.
//!
//! Everything here is meant to run inside a replayed fixed-tick simulation, so it is
//! deterministic: the same level and the same inputs give bit-identical results. There are no
//! threads, clocks or hash-map iteration on the way, and rapier is built with
//! `enhanced-determinism`. The crate knows no game rules: the game decides how fast the player
//! wants to go ([`CharacterMove::wish_velocity`]) and when they jump or crouch.
//!
//! Units are SI (metres, seconds), +Y is up, as in [`scene`].

mod character;
mod error;
mod level_collision;
mod sweep;

pub use character::{CharacterBody, CharacterConfig, CharacterConfigError, CharacterController, CharacterMove};
pub use error::CollisionError;
pub use level_collision::{LevelCollision, RayHit};
