//! What passes see of a frame while recording: its size, its view, and the GPU objects it is
//! drawn with.

use crate::globals::CoreLayouts;
use crate::gpu_instances::GpuInstances;
use crate::gpu_scene::GpuScene;
use crate::headlamp::LampFrustum;
pub use crate::view_state::{Instance, MeshId, ViewState};

/// The frame as passes see it while recording.
pub struct Frame<'a> {
    /// Size of the view in pixels: the render size, i.e. the output's times the render scale.
    /// View-sized graph textures have this size; the present pass scales to the output.
    pub size: (u32, u32),
    pub view: &'a ViewState,
    pub lamp: LampFrustum,
    pub scene: &'a GpuScene,
    /// This frame's instances, already uploaded.
    pub instances: &'a GpuInstances,
    pub layouts: &'a CoreLayouts,
    /// Group 0 of every core shader: globals, lights, the lamp distribution texture, a sampler.
    pub globals: &'a wgpu::BindGroup,
}
