//! The headlamp as the simulation sees it: on or off, on the player's head or put down.

use glam::Vec3;

use super::command::{buttons, TickCommand};
use super::player::Player;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lamp {
    pub on: bool,
    pub attached: bool,
    /// Where the lamp was put down and where it points (angle units), when detached.
    pub position: Vec3,
    pub yaw: u16,
    pub pitch: i16,
}

impl Lamp {
    pub fn new() -> Self {
        Self { on: true, attached: true, position: Vec3::ZERO, yaw: 0, pitch: 0 }
    }

    /// Lamp presses take effect after the player has turned this tick, so a detached lamp
    /// points exactly where the view did on that tick.
    pub fn apply(&mut self, cmd: &TickCommand, player: &Player) {
        if cmd.held(buttons::LAMP_TOGGLE) {
            self.on = !self.on;
        }
        if cmd.held(buttons::LAMP_DETACH) {
            if self.attached {
                self.attached = false;
                self.position = player.eye();
                self.yaw = player.yaw;
                self.pitch = player.pitch;
            } else {
                self.attached = true;
            }
        }
    }
}

impl Default for Lamp {
    fn default() -> Self {
        Self::new()
    }
}
