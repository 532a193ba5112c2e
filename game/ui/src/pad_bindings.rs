//! Gamepad settings: which pad button does which action, how fast the right stick turns the
//! view, and the sticks' dead zone. The left stick always walks and the right one always
//! looks; buttons are rebound in Settings → Gamepad. Start is not bindable: it pauses, and
//! cancels a rebinding, as Escape does for keys.

use std::fmt;
use std::ops::RangeInclusive;

use engine::gamepad::{PadButton, PadState};
use engine::glam::Vec2;

use crate::bindings::Action;

/// The config file's name for a button (the [`PadButton`] variant's own name).
pub fn button_name(button: PadButton) -> &'static str {
    match button {
        PadButton::South => "South",
        PadButton::East => "East",
        PadButton::West => "West",
        PadButton::North => "North",
        PadButton::LeftBumper => "LeftBumper",
        PadButton::RightBumper => "RightBumper",
        PadButton::LeftTrigger => "LeftTrigger",
        PadButton::RightTrigger => "RightTrigger",
        PadButton::Select => "Select",
        PadButton::Start => "Start",
        PadButton::LeftStick => "LeftStick",
        PadButton::RightStick => "RightStick",
        PadButton::DPadUp => "DPadUp",
        PadButton::DPadDown => "DPadDown",
        PadButton::DPadLeft => "DPadLeft",
        PadButton::DPadRight => "DPadRight",
    }
}

/// What the screen calls a button: Xbox letters with the position, which names the same
/// button on a PlayStation or Switch pad.
pub fn button_label(button: PadButton) -> &'static str {
    match button {
        PadButton::South => "A (bottom)",
        PadButton::East => "B (right)",
        PadButton::West => "X (left)",
        PadButton::North => "Y (top)",
        PadButton::LeftBumper => "LB",
        PadButton::RightBumper => "RB",
        PadButton::LeftTrigger => "LT",
        PadButton::RightTrigger => "RT",
        PadButton::Select => "Select / Back",
        PadButton::Start => "Start",
        PadButton::LeftStick => "Left stick click",
        PadButton::RightStick => "Right stick click",
        PadButton::DPadUp => "D-pad up",
        PadButton::DPadDown => "D-pad down",
        PadButton::DPadLeft => "D-pad left",
        PadButton::DPadRight => "D-pad right",
    }
}

/// Start pauses and cancels: it does nothing else.
pub fn is_bindable(button: PadButton) -> bool {
    button != PadButton::Start
}

/// A name that is no bindable pad button.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownPadButton(pub String);

impl fmt::Display for UnknownPadButton {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = PadButton::ALL.into_iter().filter(|b| is_bindable(*b)).map(button_name).collect();
        write!(f, "unknown gamepad button '{}' (the buttons are {})", self.0, names.join(", "))
    }
}

/// Parses a bindable button's config name.
pub fn parse_button(name: &str) -> Result<PadButton, UnknownPadButton> {
    PadButton::ALL
        .into_iter()
        .find(|b| is_bindable(*b) && button_name(*b) == name)
        .ok_or_else(|| UnknownPadButton(name.to_owned()))
}

/// One pad button per action at most, and no button in two actions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PadBindings {
    buttons: [Option<PadButton>; Action::ALL.len()],
}

impl Default for PadBindings {
    /// The common shooter layout: RT fires, A jumps, B crouches, X reloads, clicking the left
    /// stick sprints, Y switches the lamp, the bumpers set it down and throw it. Walking is the
    /// left stick's, so the move actions have no button.
    fn default() -> Self {
        let mut b = Self::unbound();
        for (action, button) in [
            (Action::Jump, PadButton::South),
            (Action::Crouch, PadButton::East),
            (Action::Sprint, PadButton::LeftStick),
            (Action::Fire, PadButton::RightTrigger),
            (Action::Reload, PadButton::West),
            (Action::LampToggle, PadButton::North),
            (Action::LampDetach, PadButton::LeftBumper),
            (Action::LampThrow, PadButton::RightBumper),
        ] {
            b.buttons[action as usize] = Some(button);
        }
        b
    }
}

impl PadBindings {
    pub fn unbound() -> Self {
        Self { buttons: [None; Action::ALL.len()] }
    }

    pub fn get(&self, action: Action) -> Option<PadButton> {
        self.buttons[action as usize]
    }

    /// The action `button` drives, if any.
    pub fn action_of(&self, button: PadButton) -> Option<Action> {
        Action::ALL.into_iter().find(|a| self.get(*a) == Some(button))
    }

    /// Binds `button` to `action`. A button does one thing: if another action had it, that
    /// action loses it and is returned so the screen can say so. Start is refused (returns
    /// `Err`): it pauses.
    pub fn set(&mut self, action: Action, button: PadButton) -> Result<Option<Action>, UnknownPadButton> {
        if !is_bindable(button) {
            return Err(UnknownPadButton(button_name(button).to_owned()));
        }
        let taken_from = self.action_of(button).filter(|&a| a != action);
        if let Some(other) = taken_from {
            self.buttons[other as usize] = None;
        }
        self.buttons[action as usize] = Some(button);
        Ok(taken_from)
    }

    pub fn clear(&mut self, action: Action) {
        self.buttons[action as usize] = None;
    }

    /// Sets an action's button without the one-action rule: the config loader keeps it.
    pub(crate) fn replace(&mut self, action: Action, button: Option<PadButton>) {
        self.buttons[action as usize] = button;
    }

    pub fn reset_defaults(&mut self) {
        *self = Self::default();
    }

    pub fn held(&self, action: Action, pad: &PadState) -> bool {
        self.get(action).is_some_and(|b| pad.held(b))
    }

    pub fn pressed(&self, action: Action, pad: &PadState) -> bool {
        self.get(action).is_some_and(|b| pad.pressed(b))
    }
}

/// Everything about the gamepad the player sets.
#[derive(Clone, Debug, PartialEq)]
pub struct GamepadSettings {
    /// Right-stick turn speed as a multiplier of [`GamepadSettings::BASE_RADIANS_PER_SECOND`].
    pub look_sensitivity: f32,
    /// Stick deflection ignored around the centre (worn sticks rest off it), 0 to 1 of the
    /// travel, in [`GamepadSettings::DEAD_ZONE_RANGE`].
    pub dead_zone: f32,
    pub bindings: PadBindings,
}

impl Default for GamepadSettings {
    fn default() -> Self {
        Self { look_sensitivity: 1.0, dead_zone: 0.15, bindings: PadBindings::default() }
    }
}

impl GamepadSettings {
    /// The right stick held fully over turns the view this fast at sensitivity 1: half a turn
    /// in a second, about what console shooters use.
    pub const BASE_RADIANS_PER_SECOND: f32 = std::f32::consts::PI;
    pub const SENSITIVITY_RANGE: RangeInclusive<f32> = 0.1..=5.0;
    pub const DEAD_ZONE_RANGE: RangeInclusive<f32> = 0.0..=0.5;

    /// Right-stick turn speed at full deflection, radians per second.
    pub fn radians_per_second(&self) -> f32 {
        self.look_sensitivity * Self::BASE_RADIANS_PER_SECOND
    }

    /// A stick's reading with the dead zone taken out: zero inside it, then rising from zero at
    /// its edge to 1 at full travel (so no speed is lost and none jumps in), direction kept.
    /// Radial, so a diagonal is not cut to an axis.
    pub fn stick(&self, raw: Vec2) -> Vec2 {
        let len = raw.length();
        if len <= self.dead_zone || !len.is_finite() {
            return Vec2::ZERO;
        }
        let scaled = ((len - self.dead_zone) / (1.0 - self.dead_zone)).min(1.0);
        raw / len * scaled
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::gamepad::PadEvent;

    #[test]
    fn every_bindable_button_round_trips_through_its_name() {
        for b in PadButton::ALL.into_iter().filter(|b| is_bindable(*b)) {
            assert_eq!(parse_button(button_name(b)), Ok(b));
            assert_eq!(button_name(b), format!("{b:?}"), "config names are the variant names");
            assert!(!button_label(b).is_empty());
        }
        let err = parse_button("Start").unwrap_err().to_string();
        assert!(err.contains("'Start'") && err.contains("RightTrigger"), "{err}");
        assert!(parse_button("south").is_err());
    }

    #[test]
    fn defaults_bind_every_action_but_walking_and_no_button_twice() {
        let b = PadBindings::default();
        let mut seen = Vec::new();
        for action in Action::ALL {
            let walking =
                matches!(action, Action::MoveForward | Action::MoveBack | Action::StrafeLeft | Action::StrafeRight);
            assert_eq!(b.get(action).is_some(), !walking, "{action:?}");
            if let Some(button) = b.get(action) {
                assert!(is_bindable(button) && !seen.contains(&button), "{button:?}");
                seen.push(button);
            }
        }
        assert_eq!(b.get(Action::Fire), Some(PadButton::RightTrigger));
    }

    #[test]
    fn rebinding_moves_a_button_and_start_is_refused() {
        let mut b = PadBindings::default();
        assert_eq!(b.set(Action::Fire, PadButton::South), Ok(Some(Action::Jump)));
        assert_eq!((b.get(Action::Fire), b.get(Action::Jump)), (Some(PadButton::South), None));
        assert_eq!(b.set(Action::Fire, PadButton::South), Ok(None), "already its own");
        assert!(b.set(Action::Jump, PadButton::Start).is_err());
        assert_eq!(b.get(Action::Jump), None);
        b.clear(Action::Fire);
        assert_eq!(b.action_of(PadButton::South), None);
        b.reset_defaults();
        assert_eq!(b, PadBindings::default());
    }

    #[test]
    fn bindings_read_a_fake_pad() {
        let b = PadBindings::default();
        let mut pad = PadState::default();
        pad.apply(PadEvent::Button(0, PadButton::RightTrigger, 0.9));
        assert!(b.held(Action::Fire, &pad) && b.pressed(Action::Fire, &pad));
        assert!(!b.held(Action::Jump, &pad) && !b.held(Action::MoveForward, &pad));
    }

    #[test]
    fn the_dead_zone_is_radial_and_rescaled() {
        let s = GamepadSettings { dead_zone: 0.2, ..GamepadSettings::default() };
        assert_eq!(s.stick(Vec2::new(0.1, 0.15)), Vec2::ZERO, "inside: nothing");
        assert_eq!(s.stick(Vec2::new(0.0, 0.2)), Vec2::ZERO, "its edge: still nothing");
        let half = s.stick(Vec2::new(0.6, 0.0));
        assert!((half.x - 0.5).abs() < 1e-6 && half.y == 0.0, "{half}");
        let full = s.stick(Vec2::new(0.0, -1.0));
        assert!((full.y + 1.0).abs() < 1e-6);
        // A diagonal keeps its direction.
        let d = s.stick(Vec2::new(0.5, 0.5));
        assert!((d.x - d.y).abs() < 1e-6 && d.x > 0.0);
        // Beyond the circle (square gates read up to √2 on diagonals): at most 1.
        assert!(s.stick(Vec2::new(1.0, 1.0)).length() <= 1.0 + 1e-6);
    }
}
