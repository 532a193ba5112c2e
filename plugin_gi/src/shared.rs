//! State shared by the GI passes and the game: settings in, figures out.

use std::cell::RefCell;
use std::rc::Rc;

use engine::wgpu;

use crate::gpu_types::GiParams;
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

/// The game's handle on the plugin: change settings live, read the last frame's figures.
#[derive(Clone, Default)]
pub struct GiHandle(pub(crate) Rc<RefCell<Shared>>);

#[derive(Default)]
pub(crate) struct Shared {
    pub settings: GiSettings,
    pub stats: GiStats,
    /// See [`GiHandle::set_reference_stride`]; 0 stands for 1.
    pub reference_stride: u32,
}

impl GiHandle {
    pub fn settings(&self) -> GiSettings {
        self.0.borrow().settings.clone()
    }
    pub fn set_settings(&self, settings: GiSettings) {
        self.0.borrow_mut().settings = settings;
    }
    pub fn stats(&self) -> GiStats {
        self.0.borrow().stats
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

/// GPU objects every GI pass binds: the per-frame parameters.
pub(crate) struct GpuShared {
    pub params: wgpu::Buffer,
}

impl GpuShared {
    pub fn write_params(&self, queue: &wgpu::Queue, params: &GiParams) {
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(params));
    }
}
