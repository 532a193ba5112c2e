//! Gamepads: the state of every connected pad, built from [`PadEvent`]s. The window loop
//! turns gilrs' events into them ([`Gamepads`]); tests feed a fake device's events straight
//! to [`PadState::apply`], so everything above the driver is plain data.
//!
//! Buttons follow the standard layout by position (South is Xbox A / PlayStation Cross), as
//! gilrs reports them. Several pads may be connected: a button is held if any pad holds it,
//! and each stick reads from the pad that deflects it most.

use glam::Vec2;

/// A pad button, by position on the standard layout. Triggers are buttons with a travel:
/// they count as held past [`TRIGGER_PRESS`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PadButton {
    /// Bottom face button (Xbox A, PlayStation Cross).
    South,
    /// Right face button (B, Circle).
    East,
    /// Left face button (X, Square).
    West,
    /// Top face button (Y, Triangle).
    North,
    LeftBumper,
    RightBumper,
    LeftTrigger,
    RightTrigger,
    Select,
    Start,
    /// Clicking the left stick.
    LeftStick,
    /// Clicking the right stick.
    RightStick,
    DPadUp,
    DPadDown,
    DPadLeft,
    DPadRight,
}

impl PadButton {
    pub const ALL: [PadButton; 16] = [
        PadButton::South,
        PadButton::East,
        PadButton::West,
        PadButton::North,
        PadButton::LeftBumper,
        PadButton::RightBumper,
        PadButton::LeftTrigger,
        PadButton::RightTrigger,
        PadButton::Select,
        PadButton::Start,
        PadButton::LeftStick,
        PadButton::RightStick,
        PadButton::DPadUp,
        PadButton::DPadDown,
        PadButton::DPadLeft,
        PadButton::DPadRight,
    ];

    /// Has an analogue travel (and a threshold).
    pub fn is_trigger(self) -> bool {
        matches!(self, PadButton::LeftTrigger | PadButton::RightTrigger)
    }
}

/// One stick axis, −1 to 1; Y is up-positive (pushing the stick away from you).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PadAxis {
    LeftX,
    LeftY,
    RightX,
    RightY,
}

/// Which connected pad an event came from (gilrs' id).
pub type PadId = usize;

/// What a pad reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PadEvent {
    Connected(PadId),
    /// Everything the pad held is let go: its events stop here.
    Disconnected(PadId),
    /// A button's value, 0 (up) to 1 (fully down; a trigger anywhere between).
    Button(PadId, PadButton, f32),
    Axis(PadId, PadAxis, f32),
}

/// A trigger goes down past this much of its travel...
pub const TRIGGER_PRESS: f32 = 0.5;
/// ...and up again below this: the gap keeps a trigger resting near the threshold from
/// chattering between pressed and released.
pub const TRIGGER_RELEASE: f32 = 0.35;

#[derive(Clone, Debug, Default)]
struct OnePad {
    id: PadId,
    held: Vec<PadButton>,
    left: Vec2,
    right: Vec2,
}

/// Every connected pad's buttons and sticks, and the presses since the last frame.
#[derive(Clone, Debug, Default)]
pub struct PadState {
    pads: Vec<OnePad>,
    pressed: Vec<PadButton>,
}

impl PadState {
    /// Applies one event. Events of a pad not seen connected connect it (a pad plugged in
    /// before the game started reports no `Connected`).
    pub fn apply(&mut self, event: PadEvent) {
        match event {
            PadEvent::Connected(id) => {
                self.pad(id);
            }
            PadEvent::Disconnected(id) => self.pads.retain(|p| p.id != id),
            PadEvent::Button(id, button, value) => {
                let pad = self.pad(id);
                let was = pad.held.contains(&button);
                let down = if !button.is_trigger() {
                    value > 0.5
                } else if was {
                    value >= TRIGGER_RELEASE
                } else {
                    value >= TRIGGER_PRESS
                };
                if down && !was {
                    pad.held.push(button);
                    self.pressed.push(button);
                } else if !down && was {
                    pad.held.retain(|&b| b != button);
                }
            }
            PadEvent::Axis(id, axis, value) => {
                let pad = self.pad(id);
                let value = if value.is_finite() { value.clamp(-1.0, 1.0) } else { 0.0 };
                match axis {
                    PadAxis::LeftX => pad.left.x = value,
                    PadAxis::LeftY => pad.left.y = value,
                    PadAxis::RightX => pad.right.x = value,
                    PadAxis::RightY => pad.right.y = value,
                }
            }
        }
    }

    fn pad(&mut self, id: PadId) -> &mut OnePad {
        match self.pads.iter().position(|p| p.id == id) {
            Some(i) => &mut self.pads[i],
            None => {
                self.pads.push(OnePad { id, ..OnePad::default() });
                self.pads.last_mut().expect("just pushed")
            }
        }
    }

    /// How many pads are connected.
    pub fn connected(&self) -> usize {
        self.pads.len()
    }

    /// Any pad holds it down.
    pub fn held(&self, button: PadButton) -> bool {
        self.pads.iter().any(|p| p.held.contains(&button))
    }

    /// Went down since the last frame.
    pub fn pressed(&self, button: PadButton) -> bool {
        self.pressed.contains(&button)
    }

    /// Every button that went down since the last frame, in order (e.g. "press a button to
    /// rebind").
    pub fn pressed_buttons(&self) -> &[PadButton] {
        &self.pressed
    }

    /// The left stick, raw (no dead zone): x right, y forward.
    pub fn left_stick(&self) -> Vec2 {
        strongest(self.pads.iter().map(|p| p.left))
    }

    /// The right stick, raw (no dead zone).
    pub fn right_stick(&self) -> Vec2 {
        strongest(self.pads.iter().map(|p| p.right))
    }

    /// Clears the presses after the app has seen them.
    pub fn end_frame(&mut self) {
        self.pressed.clear();
    }
}

fn strongest(sticks: impl Iterator<Item = Vec2>) -> Vec2 {
    sticks.fold(Vec2::ZERO, |best, s| if s.length_squared() > best.length_squared() { s } else { best })
}

/// The egui key a pad button stands for while a menu has the screen: the d-pad moves the
/// keyboard focus (down/up as Tab/Shift+Tab, left/right as the arrows a focused slider
/// follows), South presses the focused widget (Enter), East and Start go back (Escape).
pub fn menu_key(button: PadButton) -> Option<(egui::Key, egui::Modifiers)> {
    let plain = egui::Modifiers::NONE;
    Some(match button {
        PadButton::DPadDown => (egui::Key::Tab, plain),
        PadButton::DPadUp => (egui::Key::Tab, egui::Modifiers::SHIFT),
        PadButton::DPadLeft => (egui::Key::ArrowLeft, plain),
        PadButton::DPadRight => (egui::Key::ArrowRight, plain),
        PadButton::South => (egui::Key::Enter, plain),
        PadButton::East | PadButton::Start => (egui::Key::Escape, plain),
        _ => return None,
    })
}

/// The pads' driver: gilrs, polled by the window loop. Without one (no udev in a container,
/// no permission, an unsupported platform) the game goes on with keyboard and mouse, after one
/// log line.
pub(crate) struct Gamepads {
    gilrs: Option<gilrs::Gilrs>,
}

impl Gamepads {
    pub fn start() -> Self {
        let gilrs = match gilrs::Gilrs::new() {
            Ok(g) => {
                for (id, pad) in g.gamepads() {
                    log::info!("gamepad {}: {}", usize::from(id), pad.name());
                }
                Some(g)
            }
            Err(e) => {
                log::warn!("gamepads unavailable ({e}); playing with keyboard and mouse");
                None
            }
        };
        Self { gilrs }
    }

    /// Every event since the last poll, in order.
    pub fn poll(&mut self) -> Vec<PadEvent> {
        let Some(gilrs) = &mut self.gilrs else { return Vec::new() };
        let mut events = Vec::new();
        while let Some(ev) = gilrs.next_event() {
            let id = usize::from(ev.id);
            if matches!(ev.event, gilrs::EventType::Connected) {
                log::info!("gamepad {id} connected: {}", gilrs.gamepad(ev.id).name());
            }
            if matches!(ev.event, gilrs::EventType::Disconnected) {
                log::info!("gamepad {id} disconnected");
            }
            events.extend(from_gilrs(id, &ev.event));
        }
        events
    }
}

/// One gilrs event as ours. Triggers come from their value (`ButtonChanged`), as gilrs' own
/// pressed/released use its threshold, not ours; other buttons from pressed/released.
fn from_gilrs(id: PadId, event: &gilrs::EventType) -> Option<PadEvent> {
    use gilrs::EventType as E;
    Some(match *event {
        E::Connected => PadEvent::Connected(id),
        E::Disconnected => PadEvent::Disconnected(id),
        E::ButtonChanged(b, value, _) => {
            let button = button_of(b).filter(|b| b.is_trigger())?;
            PadEvent::Button(id, button, value)
        }
        E::ButtonPressed(b, _) => PadEvent::Button(id, button_of(b).filter(|b| !b.is_trigger())?, 1.0),
        E::ButtonReleased(b, _) => PadEvent::Button(id, button_of(b).filter(|b| !b.is_trigger())?, 0.0),
        E::AxisChanged(a, value, _) => PadEvent::Axis(id, axis_of(a)?, value),
        _ => return None,
    })
}

/// gilrs calls the bumpers `LeftTrigger`/`RightTrigger` and the triggers `…Trigger2`.
fn button_of(b: gilrs::Button) -> Option<PadButton> {
    use gilrs::Button as G;
    Some(match b {
        G::South => PadButton::South,
        G::East => PadButton::East,
        G::West => PadButton::West,
        G::North => PadButton::North,
        G::LeftTrigger => PadButton::LeftBumper,
        G::RightTrigger => PadButton::RightBumper,
        G::LeftTrigger2 => PadButton::LeftTrigger,
        G::RightTrigger2 => PadButton::RightTrigger,
        G::Select => PadButton::Select,
        G::Start => PadButton::Start,
        G::LeftThumb => PadButton::LeftStick,
        G::RightThumb => PadButton::RightStick,
        G::DPadUp => PadButton::DPadUp,
        G::DPadDown => PadButton::DPadDown,
        G::DPadLeft => PadButton::DPadLeft,
        G::DPadRight => PadButton::DPadRight,
        // C, Z, Mode (the guide button: the system's) and unknown ones.
        _ => return None,
    })
}

fn axis_of(a: gilrs::Axis) -> Option<PadAxis> {
    use gilrs::Axis as G;
    Some(match a {
        G::LeftStickX => PadAxis::LeftX,
        G::LeftStickY => PadAxis::LeftY,
        G::RightStickX => PadAxis::RightX,
        G::RightStickY => PadAxis::RightY,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buttons_are_held_and_pressed_once() {
        let mut pad = PadState::default();
        pad.apply(PadEvent::Button(0, PadButton::South, 1.0));
        assert!(pad.held(PadButton::South) && pad.pressed(PadButton::South));
        assert_eq!(pad.connected(), 1, "a pad that speaks is connected");
        pad.end_frame();
        assert!(pad.held(PadButton::South) && !pad.pressed(PadButton::South));
        pad.apply(PadEvent::Button(0, PadButton::South, 1.0));
        assert!(!pad.pressed(PadButton::South), "a repeat of a held button is no new press");
        pad.apply(PadEvent::Button(0, PadButton::South, 0.0));
        assert!(!pad.held(PadButton::South));
    }

    #[test]
    fn triggers_press_past_a_threshold_and_release_below_a_lower_one() {
        let mut pad = PadState::default();
        let rt = PadButton::RightTrigger;
        pad.apply(PadEvent::Button(0, rt, TRIGGER_PRESS - 0.05));
        assert!(!pad.held(rt) && !pad.pressed(rt), "a light touch does not fire");
        pad.apply(PadEvent::Button(0, rt, TRIGGER_PRESS));
        assert!(pad.held(rt) && pad.pressed(rt));
        pad.end_frame();
        // Between the two thresholds it stays down: no chatter.
        pad.apply(PadEvent::Button(0, rt, (TRIGGER_PRESS + TRIGGER_RELEASE) / 2.0));
        assert!(pad.held(rt) && !pad.pressed(rt));
        pad.apply(PadEvent::Button(0, rt, TRIGGER_RELEASE - 0.01));
        assert!(!pad.held(rt));
        pad.apply(PadEvent::Button(0, rt, (TRIGGER_PRESS + TRIGGER_RELEASE) / 2.0));
        assert!(!pad.held(rt), "coming back up to between them does not press it");
    }

    #[test]
    fn a_disconnect_lets_go_of_everything_that_pad_held() {
        let mut pad = PadState::default();
        pad.apply(PadEvent::Connected(3));
        pad.apply(PadEvent::Connected(4));
        pad.apply(PadEvent::Button(3, PadButton::RightTrigger, 1.0));
        pad.apply(PadEvent::Axis(3, PadAxis::LeftY, 1.0));
        pad.apply(PadEvent::Axis(4, PadAxis::LeftX, 0.3));
        pad.apply(PadEvent::Button(4, PadButton::East, 1.0));
        assert_eq!(pad.left_stick(), Vec2::new(0.0, 1.0), "the stick pushed furthest wins");
        pad.apply(PadEvent::Disconnected(3));
        assert!(!pad.held(PadButton::RightTrigger));
        assert_eq!(pad.left_stick(), Vec2::new(0.3, 0.0), "the other pad's stick remains");
        assert!(pad.held(PadButton::East), "the other pad's buttons remain");
        assert_eq!(pad.connected(), 1);
        pad.apply(PadEvent::Disconnected(4));
        assert_eq!((pad.left_stick(), pad.right_stick(), pad.connected()), (Vec2::ZERO, Vec2::ZERO, 0));
    }

    #[test]
    fn axes_are_clamped_and_a_nan_reads_as_centred() {
        let mut pad = PadState::default();
        pad.apply(PadEvent::Axis(0, PadAxis::RightX, 1.7));
        pad.apply(PadEvent::Axis(0, PadAxis::RightY, f32::NAN));
        assert_eq!(pad.right_stick(), Vec2::new(1.0, 0.0));
    }

    #[test]
    fn gilrs_names_map_by_position_and_bumpers_are_not_triggers() {
        assert_eq!(button_of(gilrs::Button::LeftTrigger), Some(PadButton::LeftBumper));
        assert_eq!(button_of(gilrs::Button::RightTrigger2), Some(PadButton::RightTrigger));
        assert_eq!(button_of(gilrs::Button::Mode), None, "the guide button belongs to the system");
        assert_eq!(axis_of(gilrs::Axis::RightStickY), Some(PadAxis::RightY));
        assert_eq!(axis_of(gilrs::Axis::LeftZ), None);
        // Every button of ours comes from one of gilrs'.
        let all = [
            gilrs::Button::South,
            gilrs::Button::East,
            gilrs::Button::West,
            gilrs::Button::North,
            gilrs::Button::LeftTrigger,
            gilrs::Button::RightTrigger,
            gilrs::Button::LeftTrigger2,
            gilrs::Button::RightTrigger2,
            gilrs::Button::Select,
            gilrs::Button::Start,
            gilrs::Button::LeftThumb,
            gilrs::Button::RightThumb,
            gilrs::Button::DPadUp,
            gilrs::Button::DPadDown,
            gilrs::Button::DPadLeft,
            gilrs::Button::DPadRight,
        ];
        let mut ours: Vec<PadButton> = all.into_iter().filter_map(button_of).collect();
        ours.sort();
        assert_eq!(ours, PadButton::ALL.to_vec());
    }

    #[test]
    fn menus_get_focus_moves_press_and_back() {
        assert_eq!(menu_key(PadButton::DPadDown), Some((egui::Key::Tab, egui::Modifiers::NONE)));
        assert_eq!(menu_key(PadButton::DPadUp), Some((egui::Key::Tab, egui::Modifiers::SHIFT)));
        assert_eq!(menu_key(PadButton::South).map(|k| k.0), Some(egui::Key::Enter));
        assert_eq!(menu_key(PadButton::East).map(|k| k.0), Some(egui::Key::Escape));
        assert_eq!(menu_key(PadButton::Start).map(|k| k.0), Some(egui::Key::Escape));
        assert_eq!(menu_key(PadButton::RightTrigger), None);
    }
}
