//! Keyboard, mouse and gamepad state gathered from window and pad events, read once per frame
//! by the app.

use glam::Vec2;

use crate::gamepad::PadState;
pub use winit::event::MouseButton;
pub use winit::keyboard::KeyCode;

#[derive(Default, Debug, Clone)]
pub struct Input {
    held: Vec<KeyCode>,
    pressed: Vec<KeyCode>,
    mouse_held: Vec<MouseButton>,
    mouse_pressed: Vec<MouseButton>,
    /// Raw mouse motion since the last frame (only while the cursor is captured).
    pub mouse_delta: Vec2,
    /// The cursor is grabbed and hidden: mouse motion steers the view.
    pub captured: bool,
    /// The gamepads (all connected pads together).
    pub pad: PadState,
}

impl Input {
    pub fn held(&self, k: KeyCode) -> bool {
        self.held.contains(&k)
    }
    /// Went down since the last frame (key repeat excluded).
    pub fn pressed(&self, k: KeyCode) -> bool {
        self.pressed.contains(&k)
    }
    pub fn mouse_held(&self, b: MouseButton) -> bool {
        self.mouse_held.contains(&b)
    }
    pub fn mouse_pressed(&self, b: MouseButton) -> bool {
        self.mouse_pressed.contains(&b)
    }
    /// Every key that went down since the last frame, in order (e.g. "press a key to rebind").
    pub fn pressed_keys(&self) -> &[KeyCode] {
        &self.pressed
    }
    /// Every mouse button that went down since the last frame, in order.
    pub fn pressed_buttons(&self) -> &[MouseButton] {
        &self.mouse_pressed
    }

    /// A key went down or up. The window runner calls these from window events; tests drive
    /// an `Input` the same way.
    pub fn key_event(&mut self, k: KeyCode, down: bool, repeat: bool) {
        if down {
            if !repeat {
                self.pressed.push(k);
            }
            if !self.held.contains(&k) {
                self.held.push(k);
            }
        } else {
            self.held.retain(|&x| x != k);
        }
    }

    pub fn mouse_button(&mut self, b: MouseButton, down: bool) {
        if down {
            self.mouse_pressed.push(b);
            if !self.mouse_held.contains(&b) {
                self.mouse_held.push(b);
            }
        } else {
            self.mouse_held.retain(|&x| x != b);
        }
    }

    /// Forgets held keys (focus lost: key-up events will not arrive).
    pub(crate) fn release_all(&mut self) {
        self.held.clear();
        self.mouse_held.clear();
    }

    /// Clears per-frame edges and motion after the app has seen them.
    pub fn end_frame(&mut self) {
        self.pressed.clear();
        self.mouse_pressed.clear();
        self.mouse_delta = Vec2::ZERO;
        self.pad.end_frame();
    }
}
