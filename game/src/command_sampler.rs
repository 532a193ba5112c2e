//! Live input → tick commands. Mouse motion and key presses arrive per frame; ticks run at
//! their own rate. The sampler gathers both between ticks and quantises them into each
//! [`TickCommand`] exactly as the simulation will consume it, so a recording of these commands
//! is the game that was played. Which key does what comes from the player's [`KeyBindings`].

use engine::input::Input;
use game_ui::{Action, KeyBindings};

use crate::sim::command::{angle_units, buttons, TickCommand};

/// Radians of view rotation per pixel of mouse motion, at sensitivity 1.
pub const MOUSE_SENSITIVITY: f32 = game_ui::Config::BASE_RADIANS_PER_PIXEL;

/// Actions that act once per press, and the button each sets on one tick.
const PRESSES: [(Action, u8); 5] = [
    (Action::LampToggle, buttons::LAMP_TOGGLE),
    (Action::LampDetach, buttons::LAMP_DETACH),
    (Action::LampThrow, buttons::LAMP_THROW),
    (Action::Reload, buttons::RELOAD),
    // A click shorter than a tick still fires once.
    (Action::Fire, buttons::FIRE),
];

/// Actions that act while held.
const HELD: [(Action, u8); 4] = [
    (Action::Jump, buttons::JUMP),
    (Action::Crouch, buttons::CROUCH),
    (Action::Sprint, buttons::SPRINT),
    (Action::Fire, buttons::FIRE),
];

#[derive(Clone, Debug)]
pub struct CommandSampler {
    /// Radians per pixel.
    pub sensitivity: f32,
    /// Moving the mouse forward looks down.
    pub invert_y: bool,
    pub bindings: KeyBindings,
    /// Mouse turn and look not yet put into a command, angle units (fractional).
    pending: (f32, f32),
    /// Presses since the last command: each reaches exactly one tick.
    presses: u8,
}

impl CommandSampler {
    pub fn new(sensitivity: f32, invert_y: bool, bindings: KeyBindings) -> Self {
        Self { sensitivity, invert_y, bindings, pending: (0.0, 0.0), presses: 0 }
    }

    /// Once per frame: collects mouse motion (only while the mouse steers the view) and presses.
    pub fn gather(&mut self, input: &Input) {
        if input.captured {
            let look = if self.invert_y { -1.0 } else { 1.0 };
            self.pending.0 -= angle_units(input.mouse_delta.x * self.sensitivity);
            self.pending.1 -= look * angle_units(input.mouse_delta.y * self.sensitivity);
        }
        for (action, button) in PRESSES {
            if self.bindings.pressed(action, input) {
                self.presses |= button;
            }
        }
    }

    /// Forgets gathered motion and presses (the game was paused: they belong to the menu).
    pub fn clear(&mut self) {
        self.pending = (0.0, 0.0);
        self.presses = 0;
    }

    /// The next tick's command: held keys now, plus everything gathered since the last one.
    /// Whole angle units go into the command; the fraction waits for the next.
    pub fn next_command(&mut self, input: &Input) -> TickCommand {
        let held = |a: Action| self.bindings.held(a, input);
        let axis = |plus: Action, minus: Action| 127 * held(plus) as i8 - 127 * held(minus) as i8;
        let quantise = |v: &mut f32| {
            let whole = v.round().clamp(i16::MIN as f32, i16::MAX as f32);
            *v -= whole;
            whole as i16
        };
        let buttons = HELD.iter().filter(|(a, _)| held(*a)).fold(0, |b, (_, bit)| b | bit);
        TickCommand {
            forward: axis(Action::MoveForward, Action::MoveBack),
            strafe: axis(Action::StrafeRight, Action::StrafeLeft),
            turn: quantise(&mut self.pending.0),
            look: quantise(&mut self.pending.1),
            buttons: buttons | std::mem::take(&mut self.presses),
        }
    }

    /// Mouse motion gathered but not yet in a command (angle units): the view adds it so that
    /// looking around responds this frame, not on the next tick.
    pub fn pending_look(&self) -> (f32, f32) {
        self.pending
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::input::{KeyCode, MouseButton};

    #[test]
    fn bindings_decide_what_keys_do() {
        let mut bindings = KeyBindings::default();
        let mut s = CommandSampler::new(MOUSE_SENSITIVITY, false, bindings.clone());
        let mut input = Input::default();
        input.key_event(KeyCode::KeyW, true, false);
        input.mouse_button(MouseButton::Left, true);
        s.gather(&input);
        let c = s.next_command(&input);
        assert_eq!((c.forward, c.buttons), (127, buttons::FIRE));
        // Rebind forward to the up arrow: W no longer walks.
        bindings.set(Action::MoveForward, 0, game_ui::Binding::Key(KeyCode::ArrowUp));
        bindings.clear(Action::MoveForward, 1);
        let mut s = CommandSampler::new(MOUSE_SENSITIVITY, false, bindings);
        assert_eq!(s.next_command(&input).forward, 0);
    }

    #[test]
    fn presses_reach_one_tick_and_invert_y_flips_look() {
        let mut s = CommandSampler::new(MOUSE_SENSITIVITY, true, KeyBindings::default());
        let mut input = Input::default();
        input.captured = true;
        input.key_event(KeyCode::KeyG, true, false);
        input.mouse_delta = engine::glam::Vec2::new(0.0, 100.0);
        s.gather(&input);
        let first = s.next_command(&input);
        assert_eq!(first.buttons, buttons::LAMP_DETACH);
        assert!(first.look > 0, "inverted: moving the mouse down looks up");
        assert_eq!(s.next_command(&input).buttons, 0);
    }
}
