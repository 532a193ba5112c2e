//! What a frame is rendered from (`ViewState`, CPU) and what passes see of it (`Frame`, GPU).

use scene::PunctualLight;

use crate::camera::Camera;
use crate::globals::CoreLayouts;
use crate::gpu_scene::GpuScene;
use crate::headlamp::{Headlamp, LampFrustum};

/// Everything that changes per frame: where we look from, the lamp, the lights, exposure.
#[derive(Clone, Debug)]
pub struct ViewState {
    pub camera: Camera,
    pub headlamp: Headlamp,
    pub lights: Vec<PunctualLight>,
    /// Multiplies linear radiance before tonemapping.
    pub exposure: f32,
}

/// The frame as passes see it while recording.
pub struct Frame<'a> {
    /// Size of the view in pixels.
    pub size: (u32, u32),
    pub view: &'a ViewState,
    pub lamp: LampFrustum,
    pub scene: &'a GpuScene,
    pub layouts: &'a CoreLayouts,
    /// Group 0 of every core shader: globals, lights, the lamp distribution texture, a sampler.
    pub globals: &'a wgpu::BindGroup,
}
