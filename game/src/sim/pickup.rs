//! Things lying in the level to be picked up by walking over them.

use glam::Vec3;

use super::level_entities::{PickupKind, PickupSpawn};

/// Picked up when the player's feet come this close (horizontally, m) …
pub const GRAB_RADIUS: f32 = 0.9;
/// … and the thing is no further above or below the feet than this (one on a crate counts).
pub const GRAB_HEIGHT: f32 = 1.6;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pickup {
    pub kind: PickupKind,
    pub position: Vec3,
    pub amount: f32,
    pub taken: bool,
}

impl Pickup {
    pub fn spawn(s: &PickupSpawn) -> Self {
        Self { kind: s.kind, position: s.position, amount: s.amount, taken: false }
    }

    pub fn within_grab(&self, feet: Vec3) -> bool {
        let d = self.position - feet;
        !self.taken && d.x * d.x + d.z * d.z <= GRAB_RADIUS * GRAB_RADIUS && d.y.abs() <= GRAB_HEIGHT
    }
}
