//! Key bindings: which keys and mouse buttons drive which player action.
//!
//! Keys are physical (winit's `KeyCode`, named after the US layout position), so WASD stays
//! under the left hand on AZERTY or Dvorak keyboards. Each binding has a stable text name for
//! the config file (`KeyW`, `Space`, `ShiftLeft`, `MouseLeft`: winit's own variant names) and a
//! short label for the screen (`W`, `Space`, `Left Shift`, `Left mouse`).

use std::borrow::Cow;
use std::fmt;
use std::str::FromStr;

use engine::egui;
use engine::input::{Input, KeyCode, MouseButton};

/// What the player can do with a key or button.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Action {
    MoveForward,
    MoveBack,
    StrafeLeft,
    StrafeRight,
    Jump,
    Crouch,
    Sprint,
    Fire,
    Reload,
    LampToggle,
    /// Set the lamp down, or pick it up again.
    LampDetach,
    /// Throw the lamp where you look.
    LampThrow,
}

impl Action {
    /// Every action, in the order the settings screen lists them.
    pub const ALL: [Action; 12] = [
        Action::MoveForward,
        Action::MoveBack,
        Action::StrafeLeft,
        Action::StrafeRight,
        Action::Jump,
        Action::Crouch,
        Action::Sprint,
        Action::Fire,
        Action::Reload,
        Action::LampToggle,
        Action::LampDetach,
        Action::LampThrow,
    ];

    /// The key in the config file's `[bindings]` table.
    pub fn name(self) -> &'static str {
        match self {
            Action::MoveForward => "MoveForward",
            Action::MoveBack => "MoveBack",
            Action::StrafeLeft => "StrafeLeft",
            Action::StrafeRight => "StrafeRight",
            Action::Jump => "Jump",
            Action::Crouch => "Crouch",
            Action::Sprint => "Sprint",
            Action::Fire => "Fire",
            Action::Reload => "Reload",
            Action::LampToggle => "LampToggle",
            Action::LampDetach => "LampDetach",
            Action::LampThrow => "LampThrow",
        }
    }

    /// What the settings screen calls it.
    pub fn label(self) -> &'static str {
        match self {
            Action::MoveForward => "Move forward",
            Action::MoveBack => "Move back",
            Action::StrafeLeft => "Strafe left",
            Action::StrafeRight => "Strafe right",
            Action::Jump => "Jump",
            Action::Crouch => "Crouch",
            Action::Sprint => "Sprint",
            Action::Fire => "Fire",
            Action::Reload => "Reload",
            Action::LampToggle => "Lamp on / off",
            Action::LampDetach => "Set down / pick up lamp",
            Action::LampThrow => "Throw lamp",
        }
    }

    /// The action whose config name is `name`.
    pub fn from_name(name: &str) -> Option<Action> {
        Action::ALL.into_iter().find(|a| a.name() == name)
    }

    fn index(self) -> usize {
        self as usize
    }
}

/// A key or a mouse button.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Binding {
    Key(KeyCode),
    Mouse(MouseButton),
}

/// One bindable key: its config name, its label and the key egui reports for it (egui sees
/// some presses the game's `Input` does not, e.g. Tab, which egui always consumes).
struct KeyInfo {
    code: KeyCode,
    name: &'static str,
    label: &'static str,
    egui: Option<egui::Key>,
}

/// `key_table![KeyA "A" A, ...]`: the config name is the `KeyCode` variant's own name, so the
/// two cannot drift apart; the optional last ident is the `egui::Key`.
macro_rules! key_table {
    ($($code:ident $label:literal $($egui:ident)?),* $(,)?) => {
        &[$(KeyInfo {
            code: KeyCode::$code,
            name: stringify!($code),
            label: $label,
            egui: key_table!(@egui $($egui)?),
        }),*]
    };
    (@egui) => { None };
    (@egui $egui:ident) => { Some(egui::Key::$egui) };
}

/// Every key that can be bound. Escape is missing on purpose: it pauses and cancels.
const KEYS: &[KeyInfo] = key_table![
    KeyA "A" A, KeyB "B" B, KeyC "C" C, KeyD "D" D, KeyE "E" E, KeyF "F" F, KeyG "G" G,
    KeyH "H" H, KeyI "I" I, KeyJ "J" J, KeyK "K" K, KeyL "L" L, KeyM "M" M, KeyN "N" N,
    KeyO "O" O, KeyP "P" P, KeyQ "Q" Q, KeyR "R" R, KeyS "S" S, KeyT "T" T, KeyU "U" U,
    KeyV "V" V, KeyW "W" W, KeyX "X" X, KeyY "Y" Y, KeyZ "Z" Z,
    Digit0 "0" Num0, Digit1 "1" Num1, Digit2 "2" Num2, Digit3 "3" Num3, Digit4 "4" Num4,
    Digit5 "5" Num5, Digit6 "6" Num6, Digit7 "7" Num7, Digit8 "8" Num8, Digit9 "9" Num9,
    F1 "F1" F1, F2 "F2" F2, F3 "F3" F3, F4 "F4" F4, F5 "F5" F5, F6 "F6" F6,
    F7 "F7" F7, F8 "F8" F8, F9 "F9" F9, F10 "F10" F10, F11 "F11" F11, F12 "F12" F12,
    ArrowUp "Up" ArrowUp, ArrowDown "Down" ArrowDown, ArrowLeft "Left" ArrowLeft,
    ArrowRight "Right" ArrowRight,
    Space "Space" Space, Tab "Tab" Tab, Enter "Enter" Enter, Backspace "Backspace" Backspace,
    ShiftLeft "Left Shift", ShiftRight "Right Shift", ControlLeft "Left Ctrl",
    ControlRight "Right Ctrl", AltLeft "Left Alt", AltRight "Right Alt", CapsLock "Caps Lock",
    Backquote "`" Backtick, Minus "-" Minus, Equal "=" Equals, BracketLeft "[" OpenBracket,
    BracketRight "]" CloseBracket, Backslash "\\" Backslash, IntlBackslash "< >",
    Semicolon ";" Semicolon, Quote "'" Quote, Comma "," Comma, Period "." Period,
    Slash "/" Slash,
    Insert "Insert" Insert, Delete "Delete" Delete, Home "Home" Home, End "End" End,
    PageUp "Page Up" PageUp, PageDown "Page Down" PageDown,
    // egui reports the keypad's digits as the main row's: only `Input` tells them apart.
    Numpad0 "Num 0", Numpad1 "Num 1", Numpad2 "Num 2", Numpad3 "Num 3", Numpad4 "Num 4",
    Numpad5 "Num 5", Numpad6 "Num 6", Numpad7 "Num 7", Numpad8 "Num 8", Numpad9 "Num 9",
    NumpadAdd "Num +", NumpadSubtract "Num -", NumpadMultiply "Num *", NumpadDivide "Num /",
    NumpadDecimal "Num .", NumpadEnter "Num Enter",
];

/// Mouse buttons with names; any other is `Mouse<N>` (winit's `Other(N)`).
const BUTTONS: &[(MouseButton, &str, &str)] = &[
    (MouseButton::Left, "MouseLeft", "Left mouse"),
    (MouseButton::Right, "MouseRight", "Right mouse"),
    (MouseButton::Middle, "MouseMiddle", "Middle mouse"),
    (MouseButton::Back, "MouseBack", "Mouse back"),
    (MouseButton::Forward, "MouseForward", "Mouse forward"),
];

impl Binding {
    /// Every key the config file and the rebinding screen accept.
    pub fn supported_keys() -> impl Iterator<Item = KeyCode> {
        KEYS.iter().map(|k| k.code)
    }

    /// Whether the config file can name it (so a rebinding can be saved).
    pub fn is_supported(self) -> bool {
        match self {
            Binding::Key(code) => key_info(code).is_some(),
            Binding::Mouse(_) => true,
        }
    }

    /// The stable name written to the config file.
    pub fn name(self) -> Cow<'static, str> {
        match self {
            Binding::Key(code) => match key_info(code) {
                Some(k) => Cow::Borrowed(k.name),
                // Not in the table: winit's name, which `FromStr` refuses, so it is never saved
                // silently (the rebinding screen only offers supported keys).
                None => Cow::Owned(format!("{code:?}")),
            },
            Binding::Mouse(MouseButton::Other(n)) => Cow::Owned(format!("Mouse{n}")),
            Binding::Mouse(b) => Cow::Borrowed(BUTTONS.iter().find(|(x, ..)| *x == b).map_or("Mouse?", |e| e.1)),
        }
    }

    /// Short text for the screen.
    pub fn label(self) -> Cow<'static, str> {
        match self {
            Binding::Key(code) => match key_info(code) {
                Some(k) => Cow::Borrowed(k.label),
                None => Cow::Owned(format!("{code:?}")),
            },
            Binding::Mouse(MouseButton::Other(n)) => Cow::Owned(format!("Mouse {n}")),
            Binding::Mouse(b) => Cow::Borrowed(BUTTONS.iter().find(|(x, ..)| *x == b).map_or("Mouse ?", |e| e.2)),
        }
    }

    /// The key egui calls `key` (a physical key, when egui-winit knows it).
    pub fn from_egui_key(key: egui::Key) -> Option<Binding> {
        KEYS.iter().find(|k| k.egui == Some(key)).map(|k| Binding::Key(k.code))
    }

    /// The mouse button egui calls `button`.
    pub fn from_egui_button(button: egui::PointerButton) -> Binding {
        Binding::Mouse(match button {
            egui::PointerButton::Primary => MouseButton::Left,
            egui::PointerButton::Secondary => MouseButton::Right,
            egui::PointerButton::Middle => MouseButton::Middle,
            egui::PointerButton::Extra1 => MouseButton::Back,
            egui::PointerButton::Extra2 => MouseButton::Forward,
        })
    }

    /// Held down now.
    pub fn held(self, input: &Input) -> bool {
        match self {
            Binding::Key(k) => input.held(k),
            Binding::Mouse(b) => input.mouse_held(b),
        }
    }

    /// Went down since the last frame.
    pub fn pressed(self, input: &Input) -> bool {
        match self {
            Binding::Key(k) => input.pressed(k),
            Binding::Mouse(b) => input.mouse_pressed(b),
        }
    }
}

fn key_info(code: KeyCode) -> Option<&'static KeyInfo> {
    KEYS.iter().find(|k| k.code == code)
}

impl fmt::Display for Binding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

/// A name that is no key or button [`Binding`] knows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownBinding(pub String);

impl fmt::Display for UnknownBinding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown key or button name '{}' (names are like KeyW, Digit1, F1, Space, ShiftLeft, ControlLeft, \
             ArrowUp, MouseLeft, MouseRight, MouseMiddle)",
            self.0
        )
    }
}

impl std::error::Error for UnknownBinding {}

impl FromStr for Binding {
    type Err = UnknownBinding;

    fn from_str(name: &str) -> Result<Self, Self::Err> {
        if let Some(k) = KEYS.iter().find(|k| k.name == name) {
            return Ok(Binding::Key(k.code));
        }
        if let Some((b, ..)) = BUTTONS.iter().find(|(_, n, _)| *n == name) {
            return Ok(Binding::Mouse(*b));
        }
        // `Mouse<N>` for winit's `Other(N)`, written the one way `name` writes it.
        if let Some(n) = name.strip_prefix("Mouse").and_then(|n| n.parse::<u16>().ok()) {
            if format!("Mouse{n}") == name {
                return Ok(Binding::Mouse(MouseButton::Other(n)));
            }
        }
        Err(UnknownBinding(name.to_owned()))
    }
}

/// Bindings per action.
pub const SLOTS: usize = 2;

/// Each action's bindings: up to [`SLOTS`] each, and no key or button in two actions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KeyBindings {
    slots: [[Option<Binding>; SLOTS]; Action::ALL.len()],
}

impl Default for KeyBindings {
    /// W/S/A/D, Space, C or Left Ctrl, Left Shift, left mouse, R, F, G, Q: the keys of most
    /// first-person games, and the lamp's on the left hand's reach.
    fn default() -> Self {
        let key = |k| Some(Binding::Key(k));
        let mut slots = [[None; SLOTS]; Action::ALL.len()];
        for (action, bound) in [
            (Action::MoveForward, [key(KeyCode::KeyW), None]),
            (Action::MoveBack, [key(KeyCode::KeyS), None]),
            (Action::StrafeLeft, [key(KeyCode::KeyA), None]),
            (Action::StrafeRight, [key(KeyCode::KeyD), None]),
            (Action::Jump, [key(KeyCode::Space), None]),
            (Action::Crouch, [key(KeyCode::KeyC), key(KeyCode::ControlLeft)]),
            (Action::Sprint, [key(KeyCode::ShiftLeft), None]),
            (Action::Fire, [Some(Binding::Mouse(MouseButton::Left)), None]),
            (Action::Reload, [key(KeyCode::KeyR), None]),
            (Action::LampToggle, [key(KeyCode::KeyF), None]),
            (Action::LampDetach, [key(KeyCode::KeyG), None]),
            (Action::LampThrow, [key(KeyCode::KeyQ), None]),
        ] {
            slots[action.index()] = bound;
        }
        Self { slots }
    }
}

impl KeyBindings {
    /// No action bound to anything.
    pub fn unbound() -> Self {
        Self { slots: [[None; SLOTS]; Action::ALL.len()] }
    }

    /// The action's slots (`None`: empty).
    pub fn get(&self, action: Action) -> [Option<Binding>; SLOTS] {
        self.slots[action.index()]
    }

    /// The action's bindings, empty slots skipped.
    pub fn bindings(&self, action: Action) -> impl Iterator<Item = Binding> + '_ {
        self.slots[action.index()].iter().flatten().copied()
    }

    /// The action `binding` drives, if any.
    pub fn action_of(&self, binding: Binding) -> Option<Action> {
        Action::ALL.into_iter().find(|a| self.bindings(*a).any(|b| b == binding))
    }

    /// Binds `binding` to `action` in `slot` (0 or 1; panics otherwise). A key or button does
    /// one thing only: if another action had it, it is removed there, and that action is
    /// returned so the screen can say so. Within one action it moves to the new slot.
    pub fn set(&mut self, action: Action, slot: usize, binding: Binding) -> Option<Action> {
        assert!(slot < SLOTS, "slot {slot} of {SLOTS}");
        let taken_from = self.action_of(binding).filter(|&a| a != action);
        for slots in &mut self.slots {
            for s in slots.iter_mut().filter(|s| **s == Some(binding)) {
                *s = None;
            }
        }
        self.slots[action.index()][slot] = Some(binding);
        taken_from
    }

    /// Empties one slot (0 or 1; panics otherwise).
    pub fn clear(&mut self, action: Action, slot: usize) {
        self.slots[action.index()][slot] = None;
    }

    /// Replaces all of an action's bindings (`bound` in slot order; at most [`SLOTS`]), leaving
    /// other actions alone: the caller keeps the one-action-per-key rule (the config loader does).
    pub(crate) fn replace(&mut self, action: Action, bound: &[Binding]) {
        let mut slots = [None; SLOTS];
        for (slot, b) in slots.iter_mut().zip(bound) {
            *slot = Some(*b);
        }
        self.slots[action.index()] = slots;
    }

    pub fn reset_defaults(&mut self) {
        *self = Self::default();
    }

    /// Any of the action's keys or buttons is held.
    pub fn held(&self, action: Action, input: &Input) -> bool {
        self.bindings(action).any(|b| b.held(input))
    }

    /// Any of the action's keys or buttons went down since the last frame.
    pub fn pressed(&self, action: Action, input: &Input) -> bool {
        self.bindings(action).any(|b| b.pressed(input))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_supported_key_round_trips_through_its_name() {
        let mut names = std::collections::HashSet::new();
        for code in Binding::supported_keys() {
            let b = Binding::Key(code);
            let name = b.name();
            assert_eq!(name, format!("{code:?}"), "config names are winit's variant names");
            assert_eq!(name.parse::<Binding>(), Ok(b), "{name}");
            assert!(names.insert(name.clone()), "{name} twice in the table");
            assert!(!b.label().is_empty());
        }
        // The brief's families are all there.
        for name in ["KeyA", "KeyZ", "Digit0", "Digit9", "F1", "F12", "ArrowUp", "ArrowLeft", "Space", "Tab"] {
            assert!(names.contains(name), "{name} is bindable");
        }
        for name in ["Enter", "Backspace", "ShiftLeft", "ShiftRight", "ControlLeft", "AltRight", "Comma", "Slash"] {
            assert!(names.contains(name), "{name} is bindable");
        }
        assert!(!Binding::Key(KeyCode::Escape).is_supported(), "Escape pauses and cancels; it is not bindable");
    }

    #[test]
    fn mouse_buttons_round_trip_and_unknown_names_are_named() {
        for b in [
            MouseButton::Left,
            MouseButton::Right,
            MouseButton::Middle,
            MouseButton::Back,
            MouseButton::Forward,
            MouseButton::Other(7),
        ] {
            let binding = Binding::Mouse(b);
            assert_eq!(binding.name().parse::<Binding>(), Ok(binding), "{}", binding.name());
        }
        assert_eq!(Binding::Mouse(MouseButton::Left).name(), "MouseLeft");
        assert_eq!(Binding::Mouse(MouseButton::Right).name(), "MouseRight");
        for bad in ["Spacebar", "keyw", "", "Mouse", "Mouse+7", "Mouse07", "Escape"] {
            let err = bad.parse::<Binding>().unwrap_err();
            assert!(err.to_string().contains(&format!("'{bad}'")), "{err}");
        }
    }

    #[test]
    fn defaults_bind_every_action_and_no_key_twice() {
        let b = KeyBindings::default();
        let mut seen = Vec::new();
        for action in Action::ALL {
            assert!(b.bindings(action).next().is_some(), "{action:?} has a default");
            assert_eq!(Action::from_name(action.name()), Some(action));
            for binding in b.bindings(action) {
                assert!(binding.is_supported());
                assert!(!seen.contains(&binding), "{binding} bound twice");
                seen.push(binding);
            }
        }
        assert_eq!(
            b.get(Action::Crouch),
            [Some(Binding::Key(KeyCode::KeyC)), Some(Binding::Key(KeyCode::ControlLeft))]
        );
        assert_eq!(b.get(Action::Fire)[0], Some(Binding::Mouse(MouseButton::Left)));
    }

    #[test]
    fn binding_a_key_used_elsewhere_moves_it() {
        let mut b = KeyBindings::default();
        let w = Binding::Key(KeyCode::KeyW);
        assert_eq!(b.set(Action::Jump, 1, w), Some(Action::MoveForward));
        assert_eq!(b.get(Action::Jump), [Some(Binding::Key(KeyCode::Space)), Some(w)]);
        assert_eq!(b.get(Action::MoveForward), [None, None]);
        assert_eq!(b.action_of(w), Some(Action::Jump));
        // Within one action it just changes slot, and nobody else is named.
        assert_eq!(b.set(Action::Jump, 0, w), None);
        assert_eq!(b.get(Action::Jump), [Some(w), None]);
        b.clear(Action::Jump, 0);
        assert_eq!(b.get(Action::Jump), [None, None]);
        b.reset_defaults();
        assert_eq!(b, KeyBindings::default());
    }

    #[test]
    fn held_and_pressed_follow_any_binding() {
        let b = KeyBindings::default();
        let mut input = Input::default();
        input.key_event(KeyCode::ControlLeft, true, false);
        input.mouse_button(MouseButton::Left, true);
        assert!(b.held(Action::Crouch, &input) && b.pressed(Action::Crouch, &input));
        assert!(b.held(Action::Fire, &input) && b.pressed(Action::Fire, &input));
        assert!(!b.held(Action::Jump, &input));
        input.end_frame();
        assert!(b.held(Action::Crouch, &input) && !b.pressed(Action::Crouch, &input), "held, no new press");
        input.key_event(KeyCode::ControlLeft, false, false);
        assert!(!b.held(Action::Crouch, &input));
    }
}
