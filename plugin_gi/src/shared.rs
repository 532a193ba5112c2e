//! What the game shares with the GI passes: the settings in (read by the passes), and the
//! figures of the last frame out (from the render graph's own count of each pass's calls).

use std::cell::RefCell;
use std::rc::Rc;

use engine::renderer::Renderer;

use crate::frame::GiFrame;
use crate::settings::GiSettings;

/// Per-frame figures of the GI. Draws and dispatches depend on the number of bounces, never on
/// the light count, the resolution or the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GiStats {
    /// Compute dispatches the GI issued last frame.
    pub dispatches: u32,
    /// Draw calls the GI issued last frame.
    pub draws: u32,
}

impl GiStats {
    /// The calls of the GI's passes (their names begin with `gi_`) in the renderer's last frame.
    pub fn of(renderer: &Renderer) -> Self {
        let gi = renderer.graph().last_calls().filter(|(name, _)| name.starts_with("gi_"));
        gi.fold(Self::default(), |s, (_, c)| Self { dispatches: s.dispatches + c.dispatches, draws: s.draws + c.draws })
    }
}

/// The game's handle on the plugin: change settings live.
#[derive(Clone, Default)]
pub struct GiHandle(Rc<RefCell<Shared>>);

#[derive(Default)]
struct Shared {
    settings: GiSettings,
    /// The last frame description made, for the settings as they were then.
    frame: Option<GiFrame>,
    /// See [`GiHandle::set_reference_stride`]; 0 stands for 1.
    reference_stride: u32,
}

impl GiHandle {
    pub fn settings(&self) -> GiSettings {
        self.0.borrow().settings.clone()
    }
    pub fn set_settings(&self, settings: GiSettings) {
        self.0.borrow_mut().settings = settings;
    }

    /// The frame as the GI's passes see it, for a frame of `size` with the lamp `attached`:
    /// made once for each frame size, lamp and settings, and read by every pass.
    pub(crate) fn frame(&self, size: (u32, u32), attached: bool) -> GiFrame {
        let mut shared = self.0.borrow_mut();
        let Shared { settings, frame, .. } = &mut *shared;
        match frame {
            Some(f) if f.size == size && f.attached == attached && f.settings == *settings => f.clone(),
            _ => frame.insert(GiFrame::of(settings, size, attached)).clone(),
        }
    }

    /// For tools that check the `reference` view against finer senders: it then evaluates only
    /// the centre pixel of each `stride`×`stride` block of the view (whose size should be a
    /// multiple of it) and writes the rest of the block black. Rendered at k times a size with
    /// stride k (k odd), those pixels look along the rays of that size's pixels, so they are
    /// its receivers lit by k² as many senders, at k² its cost rather than k⁴. 1 (the
    /// default) evaluates every pixel.
    pub fn set_reference_stride(&self, stride: u32) {
        self.0.borrow_mut().reference_stride = stride.max(1);
    }

    pub fn reference_stride(&self) -> u32 {
        self.0.borrow().reference_stride.max(1)
    }
}
