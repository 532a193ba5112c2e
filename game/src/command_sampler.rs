//! Live input → tick commands. Mouse motion and key presses arrive per frame; ticks run at
//! their own rate. The sampler gathers both between ticks and quantises them into each
//! [`TickCommand`] exactly as the simulation will consume it, so a recording of these commands
//! is the game that was played. Which key does what comes from the player's [`KeyBindings`];
//! a gamepad adds to them ([`GamepadSettings`]): the left stick walks at any speed up to full,
//! the right stick turns the view at a rate, and pad buttons act as keys do.

use engine::input::Input;
use game_ui::{Action, GamepadSettings, KeyBindings};

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
    pub pad: GamepadSettings,
    /// Mouse and stick turn and look not yet put into a command, angle units (fractional).
    pending: (f32, f32),
    /// Presses since the last command: each reaches exactly one tick.
    presses: u8,
    /// The pad's sprint button was clicked: sprinting goes on until the left stick is let go
    /// (holding a stick pressed in while steering with it is hard on the thumb).
    pad_sprint: bool,
}

impl CommandSampler {
    pub fn new(sensitivity: f32, invert_y: bool, bindings: KeyBindings) -> Self {
        let pad = GamepadSettings::default();
        Self { sensitivity, invert_y, bindings, pad, pending: (0.0, 0.0), presses: 0, pad_sprint: false }
    }

    /// Once per frame of `dt` seconds: collects mouse motion (only while the mouse steers the
    /// view), the right stick's turning over the frame, and presses.
    pub fn gather(&mut self, input: &Input, dt: f32) {
        let look = if self.invert_y { -1.0 } else { 1.0 };
        if input.captured {
            self.pending.0 -= angle_units(input.mouse_delta.x * self.sensitivity);
            self.pending.1 -= look * angle_units(input.mouse_delta.y * self.sensitivity);
        }
        // A rate times the frame's time: the same turn at any frame rate. The deflection is
        // squared so small movements aim finely and a full push still turns at full speed.
        let stick = self.pad.stick(input.pad.right_stick());
        let rate = stick * stick.length() * self.pad.radians_per_second();
        self.pending.0 -= angle_units(rate.x * dt);
        self.pending.1 += look * angle_units(rate.y * dt);
        for (action, button) in PRESSES {
            if self.bindings.pressed(action, input) || self.pad.bindings.pressed(action, &input.pad) {
                self.presses |= button;
            }
        }
        if self.pad.bindings.pressed(Action::Sprint, &input.pad) {
            self.pad_sprint = !self.pad_sprint;
        }
    }

    /// Forgets gathered motion and presses (the game was paused: they belong to the menu).
    pub fn clear(&mut self) {
        self.pending = (0.0, 0.0);
        self.presses = 0;
        self.pad_sprint = false;
    }

    /// The next tick's command: held keys now, plus everything gathered since the last one.
    /// Whole angle units go into the command; the fraction waits for the next.
    pub fn next_command(&mut self, input: &Input) -> TickCommand {
        let walk = self.pad.stick(input.pad.left_stick());
        if walk == engine::glam::Vec2::ZERO {
            self.pad_sprint = false;
        }
        let held = |a: Action| {
            self.bindings.held(a, input)
                || self.pad.bindings.held(a, &input.pad)
                || (a == Action::Sprint && self.pad_sprint)
        };
        // Keys give full speed; the stick any fraction of it (the command's ×127 steps).
        let axis = |plus: Action, minus: Action, stick: f32| {
            let keys = 127 * held(plus) as i32 - 127 * held(minus) as i32;
            (keys + (stick * 127.0).round() as i32).clamp(-127, 127) as i8
        };
        let quantise = |v: &mut f32| {
            let whole = v.round().clamp(i16::MIN as f32, i16::MAX as f32);
            *v -= whole;
            whole as i16
        };
        let buttons = HELD.iter().filter(|(a, _)| held(*a)).fold(0, |b, (_, bit)| b | bit);
        TickCommand {
            forward: axis(Action::MoveForward, Action::MoveBack, walk.y),
            strafe: axis(Action::StrafeRight, Action::StrafeLeft, walk.x),
            turn: quantise(&mut self.pending.0),
            look: quantise(&mut self.pending.1),
            buttons: buttons | std::mem::take(&mut self.presses),
        }
    }

    /// Mouse and stick motion gathered but not yet in a command (angle units): the view adds it so that
    /// looking around responds this frame, not on the next tick.
    pub fn pending_look(&self) -> (f32, f32) {
        self.pending
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::gamepad::{PadAxis, PadButton, PadEvent};
    use engine::input::{KeyCode, MouseButton};

    const FRAME: f32 = 1.0 / 60.0;

    /// A fake pad's events, as the window loop applies them.
    fn pad(input: &mut Input, events: &[PadEvent]) {
        for &e in events {
            input.pad.apply(e);
        }
    }

    #[test]
    fn bindings_decide_what_keys_do() {
        let mut bindings = KeyBindings::default();
        let mut s = CommandSampler::new(MOUSE_SENSITIVITY, false, bindings.clone());
        let mut input = Input::default();
        input.key_event(KeyCode::KeyW, true, false);
        input.mouse_button(MouseButton::Left, true);
        s.gather(&input, 1.0 / 60.0);
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
        s.gather(&input, 1.0 / 60.0);
        let first = s.next_command(&input);
        assert_eq!(first.buttons, buttons::LAMP_DETACH);
        assert!(first.look > 0, "inverted: moving the mouse down looks up");
        assert_eq!(s.next_command(&input).buttons, 0);
    }

    #[test]
    fn the_left_stick_walks_at_its_deflection_past_the_dead_zone() {
        let mut s = CommandSampler::new(MOUSE_SENSITIVITY, false, KeyBindings::default());
        let mut input = Input::default();
        pad(&mut input, &[PadEvent::Axis(0, PadAxis::LeftY, 0.1), PadEvent::Axis(0, PadAxis::LeftX, -0.05)]);
        s.gather(&input, FRAME);
        let c = s.next_command(&input);
        assert_eq!((c.forward, c.strafe), (0, 0), "inside the dead zone a resting stick does not creep");
        // Past it: rescaled from its edge, so half way between edge and rim is half speed.
        let half = s.pad.dead_zone + (1.0 - s.pad.dead_zone) / 2.0;
        pad(&mut input, &[PadEvent::Axis(0, PadAxis::LeftY, half), PadEvent::Axis(0, PadAxis::LeftX, 0.0)]);
        let c = s.next_command(&input);
        assert_eq!((c.forward, c.strafe), (64, 0));
        pad(&mut input, &[PadEvent::Axis(0, PadAxis::LeftY, -1.0), PadEvent::Axis(0, PadAxis::LeftX, 1.0)]);
        let c = s.next_command(&input);
        assert!(c.forward < -80 && c.strafe > 80 && c.forward == -c.strafe, "a full diagonal: {c:?}");
        // Keys and stick add up to no more than full speed.
        input.key_event(KeyCode::KeyS, true, false);
        assert_eq!(s.next_command(&input).forward, -127);
    }

    #[test]
    fn the_right_stick_turns_at_a_rate_whatever_the_frame_rate() {
        let turn_over_a_second = |fps: u32, invert_y: bool| {
            let mut s = CommandSampler::new(MOUSE_SENSITIVITY, invert_y, KeyBindings::default());
            let mut input = Input::default();
            pad(&mut input, &[PadEvent::Axis(0, PadAxis::RightX, 1.0), PadEvent::Axis(0, PadAxis::RightY, 0.5)]);
            let (mut turn, mut look) = (0i32, 0i32);
            for _ in 0..fps {
                s.gather(&input, 1.0 / fps as f32);
                let c = s.next_command(&input);
                turn += c.turn as i32;
                look += c.look as i32;
            }
            (turn, look)
        };
        let (turn, look) = turn_over_a_second(60, false);
        // Pushed to the rim at sensitivity 1: half a turn a second, shared between turning (to
        // the right: negative) and looking in the direction of the push, (1, 0.5) normalised.
        let half_turn = -(angle_units(GamepadSettings::BASE_RADIANS_PER_SECOND)).round() as i32;
        let expected = (half_turn as f32 / 1.25f32.sqrt()).round() as i32;
        assert!((turn - expected).abs() <= 2, "{turn} vs {expected}");
        assert!(look > 0, "pushing the stick away looks up");
        let (turn_20, look_20) = turn_over_a_second(20, false);
        assert!((turn_20 - turn).abs() <= 2 && (look_20 - look).abs() <= 2, "20 fps: {turn_20}, {look_20}");
        assert_eq!(turn_over_a_second(60, true), (turn, -look), "invert Y flips the stick's look too");
        // Half a push turns a quarter as fast: fine aim near the centre.
        let mut s = CommandSampler::new(MOUSE_SENSITIVITY, false, KeyBindings::default());
        s.pad.dead_zone = 0.0;
        let mut input = Input::default();
        pad(&mut input, &[PadEvent::Axis(0, PadAxis::RightX, 0.5)]);
        s.gather(&input, 1.0);
        assert!((s.pending_look().0 - half_turn as f32 / 4.0).abs() < 1.0, "{:?}", s.pending_look());
    }

    #[test]
    fn pad_buttons_act_through_their_bindings_and_can_be_rebound() {
        let mut s = CommandSampler::new(MOUSE_SENSITIVITY, false, KeyBindings::default());
        let mut input = Input::default();
        pad(&mut input, &[PadEvent::Button(0, PadButton::RightTrigger, 0.3)]);
        s.gather(&input, FRAME);
        assert_eq!(s.next_command(&input).buttons, 0, "a trigger short of its threshold does not fire");
        pad(
            &mut input,
            &[PadEvent::Button(0, PadButton::RightTrigger, 0.8), PadEvent::Button(0, PadButton::North, 1.0)],
        );
        s.gather(&input, FRAME);
        assert_eq!(s.next_command(&input).buttons, buttons::FIRE | buttons::LAMP_TOGGLE);
        input.end_frame();
        s.gather(&input, FRAME);
        assert_eq!(s.next_command(&input).buttons, buttons::FIRE, "fire is held; the lamp press was one tick");
        // Rebinding: the lamp to the d-pad; North does nothing any more.
        s.pad.bindings.set(Action::LampToggle, PadButton::DPadRight).unwrap();
        pad(&mut input, &[PadEvent::Button(0, PadButton::North, 0.0), PadEvent::Button(0, PadButton::North, 1.0)]);
        pad(&mut input, &[PadEvent::Button(0, PadButton::South, 1.0), PadEvent::Button(0, PadButton::East, 1.0)]);
        s.gather(&input, FRAME);
        assert_eq!(s.next_command(&input).buttons, buttons::FIRE | buttons::JUMP | buttons::CROUCH);
        pad(&mut input, &[PadEvent::Button(0, PadButton::DPadRight, 1.0)]);
        s.gather(&input, FRAME);
        assert!(s.next_command(&input).held(buttons::LAMP_TOGGLE));
    }

    #[test]
    fn a_stick_click_sprints_until_the_stick_is_let_go() {
        let mut s = CommandSampler::new(MOUSE_SENSITIVITY, false, KeyBindings::default());
        let mut input = Input::default();
        pad(&mut input, &[PadEvent::Axis(0, PadAxis::LeftY, 1.0), PadEvent::Button(0, PadButton::LeftStick, 1.0)]);
        s.gather(&input, FRAME);
        assert!(s.next_command(&input).held(buttons::SPRINT));
        input.end_frame();
        pad(&mut input, &[PadEvent::Button(0, PadButton::LeftStick, 0.0)]);
        s.gather(&input, FRAME);
        assert!(s.next_command(&input).held(buttons::SPRINT), "still sprinting after the click");
        pad(&mut input, &[PadEvent::Axis(0, PadAxis::LeftY, 0.0)]);
        assert!(!s.next_command(&input).held(buttons::SPRINT), "stopping ends it");
        pad(&mut input, &[PadEvent::Axis(0, PadAxis::LeftY, 1.0)]);
        assert!(!s.next_command(&input).held(buttons::SPRINT), "and walking again walks");
    }

    #[test]
    fn a_disconnected_pad_lets_go_of_everything() {
        let mut s = CommandSampler::new(MOUSE_SENSITIVITY, false, KeyBindings::default());
        let mut input = Input::default();
        pad(
            &mut input,
            &[
                PadEvent::Connected(1),
                PadEvent::Axis(1, PadAxis::LeftY, 1.0),
                PadEvent::Axis(1, PadAxis::RightX, 1.0),
                PadEvent::Button(1, PadButton::RightTrigger, 1.0),
                PadEvent::Button(1, PadButton::East, 1.0),
            ],
        );
        s.gather(&input, FRAME);
        let c = s.next_command(&input);
        assert!(c.forward == 127 && c.turn < 0 && c.held(buttons::FIRE) && c.held(buttons::CROUCH), "{c:?}");
        input.end_frame();
        pad(&mut input, &[PadEvent::Disconnected(1)]);
        s.gather(&input, FRAME);
        let c = s.next_command(&input);
        assert_eq!(c, TickCommand::default(), "nothing stays held, walking or turning");
    }
}
