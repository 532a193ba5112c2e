//! Live input → tick commands. Mouse motion and key presses arrive per frame; ticks run at
//! their own rate. The sampler gathers both between ticks and quantises them into each
//! [`TickCommand`] exactly as the simulation will consume it, so a recording of these commands
//! is the game that was played.

use engine::input::{Input, KeyCode};

use crate::sim::command::{angle_units, buttons, TickCommand};

/// Radians of view rotation per pixel of mouse motion.
pub const MOUSE_SENSITIVITY: f32 = 0.0025;

#[derive(Clone, Debug)]
pub struct CommandSampler {
    /// Radians per pixel.
    pub sensitivity: f32,
    /// Mouse turn and look not yet put into a command, angle units (fractional).
    pending: (f32, f32),
    /// Presses since the last command: each reaches exactly one tick.
    presses: u8,
}

impl CommandSampler {
    pub fn new(sensitivity: f32) -> Self {
        Self { sensitivity, pending: (0.0, 0.0), presses: 0 }
    }

    /// Once per frame: collects mouse motion (only while the mouse steers the view) and presses.
    pub fn gather(&mut self, input: &Input) {
        if input.captured {
            self.pending.0 -= angle_units(input.mouse_delta.x * self.sensitivity);
            self.pending.1 -= angle_units(input.mouse_delta.y * self.sensitivity);
        }
        for (key, button) in [(KeyCode::KeyF, buttons::LAMP_TOGGLE), (KeyCode::KeyG, buttons::LAMP_DETACH)] {
            if input.pressed(key) {
                self.presses |= button;
            }
        }
    }

    /// The next tick's command: held keys now, plus everything gathered since the last one.
    /// Whole angle units go into the command; the fraction waits for the next.
    pub fn next_command(&mut self, input: &Input) -> TickCommand {
        let axis = |plus: KeyCode, minus: KeyCode| 127 * input.held(plus) as i8 - 127 * input.held(minus) as i8;
        let quantise = |v: &mut f32| {
            let whole = v.round().clamp(i16::MIN as f32, i16::MAX as f32);
            *v -= whole;
            whole as i16
        };
        let mut held = 0;
        for (key, button) in [
            (KeyCode::Space, buttons::JUMP),
            (KeyCode::KeyC, buttons::CROUCH),
            (KeyCode::ControlLeft, buttons::CROUCH),
            (KeyCode::ShiftLeft, buttons::SPRINT),
        ] {
            if input.held(key) {
                held |= button;
            }
        }
        TickCommand {
            forward: axis(KeyCode::KeyW, KeyCode::KeyS),
            strafe: axis(KeyCode::KeyD, KeyCode::KeyA),
            turn: quantise(&mut self.pending.0),
            look: quantise(&mut self.pending.1),
            buttons: held | std::mem::take(&mut self.presses),
        }
    }

    /// Mouse motion gathered but not yet in a command (angle units): the view adds it so that
    /// looking around responds this frame, not on the next tick.
    pub fn pending_look(&self) -> (f32, f32) {
        self.pending
    }
}
