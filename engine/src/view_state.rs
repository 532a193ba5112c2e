//! What a frame is rendered from: where we look from, the lamp, the lights, what is placed.

use scene::PunctualLight;

use crate::camera::Camera;
use crate::headlamp::Headlamp;

/// Everything that changes per frame: where we look from, the lamp, the lights, exposure.
#[derive(Clone, Debug)]
pub struct ViewState {
    pub camera: Camera,
    pub headlamp: Headlamp,
    pub lights: Vec<PunctualLight>,
    /// Multiplies linear radiance before tonemapping.
    pub exposure: f32,
    /// Meshes placed this frame (enemies, pickups, marks), drawn into the camera's G-buffer
    /// and the lamp's view like the level itself.
    pub instances: Vec<Instance>,
    /// Radiant intensity (W/sr, RGB) of an isotropic point emitter at the camera position (a
    /// muzzle flash); zero is off. It lights what the camera sees directly, with no shadow
    /// test (nothing the eye sees is hidden from a light at the eye). While the headlamp is
    /// attached it also feeds the GI, the camera G-buffer being the reflective shadow map;
    /// while the lamp is detached the reflective shadow map is the lamp's view, which cannot
    /// hold the flash's light, so the flash then lights directly only.
    pub camera_flash: [f32; 3],
    /// Meshes held in front of the camera (a weapon in hand), placed in the world like
    /// `instances`. They are drawn after the frame's lighting and the plugins, over the scene
    /// with a depth buffer of their own, so they never go into a wall; they are lit by the
    /// headlamp (shadowed by `lamp.depth` while it is detached), the camera flash, the punctual
    /// lights and the indirect irradiance a plugin writes into `view_model.irradiance` at
    /// [`ViewState::view_model_probe`]. They are in neither the G-buffer nor the lamp's view:
    /// they cast no shadows and reflect no light into the scene, so a gun at the eye cannot
    /// flood the reflective shadow map that the GI reads.
    pub view_models: Vec<Instance>,
}

impl Default for ViewState {
    /// At the origin looking down −Z with the default field of view, the lamp attached and
    /// on, nothing else: what a render graph is checked against before a level is shown.
    fn default() -> Self {
        let camera = Camera::perspective(glam::Vec3::ZERO, glam::Quat::IDENTITY, crate::camera::DEFAULT_FOV_Y);
        Self {
            camera,
            headlamp: Headlamp::new(Default::default()),
            lights: Vec::new(),
            exposure: 1.0,
            instances: Vec::new(),
            camera_flash: [0.0; 3],
            view_models: Vec::new(),
        }
    }
}

impl ViewState {
    /// Where the view models take their indirect light from: the mean of their origins; None
    /// when there are none.
    pub fn view_model_probe(&self) -> Option<glam::Vec3> {
        if self.view_models.is_empty() {
            return None;
        }
        let sum: glam::Vec3 = self.view_models.iter().map(|i| i.transform.w_axis.truncate()).sum();
        Some(sum / self.view_models.len() as f32)
    }
}

/// A mesh added with `Renderer::add_mesh`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MeshId(pub u32);

/// One placement of a mesh for one frame. Instances naming a mesh the renderer does not know
/// are not drawn.
#[derive(Clone, Copy, Debug)]
pub struct Instance {
    pub mesh: MeshId,
    /// Model to world (affine).
    pub transform: glam::Mat4,
    /// Linear diffuse albedo ρ.
    pub base_color: [f32; 3],
    /// Emitted radiance (W·sr⁻¹·m⁻²), as a material's `emissive`.
    pub emissive: [f32; 3],
}
