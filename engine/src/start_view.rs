//! The first view of a level: where the camera starts, the headlamp, lights and exposure.
//! A bare scene file gets sensible defaults so any glTF/OBJ can be rendered as-is.

use glam::Vec3;
use scene::{Level, Projection, Scene};

use crate::camera::{Camera, CameraProjection};
use crate::headlamp::Headlamp;
use crate::view_state::ViewState;

pub use crate::camera::DEFAULT_FOV_Y;

/// Overrides from the command line.
#[derive(Clone, Copy, Debug, Default)]
pub struct ViewOverrides {
    /// Eye and target points.
    pub look: Option<(Vec3, Vec3)>,
    /// Vertical field of view (radians) of both the camera and the lamp.
    pub fov_y: Option<f32>,
}

/// Chooses the camera: overrides, then the level's spawn, then the file's first camera, then
/// a view framing the whole scene.
pub fn initial_camera(level: &Level, overrides: &ViewOverrides) -> Camera {
    let mut camera = if let Some((eye, target)) = overrides.look {
        Camera::look_at(eye, target, DEFAULT_FOV_Y)
    } else if let Some(spawn) = &level.spawn {
        Camera::from_yaw_pitch(spawn.eye(), spawn.yaw, spawn.pitch, DEFAULT_FOV_Y)
    } else if let Some(cam) = level.scene.cameras.first() {
        let projection = match cam.projection {
            Projection::Perspective { yfov, .. } => CameraProjection::Perspective { fov_y: yfov },
            Projection::Orthographic { ymag, .. } => CameraProjection::Orthographic { half_height: ymag },
        };
        let near = match cam.projection {
            Projection::Perspective { znear, .. } | Projection::Orthographic { znear, .. } => znear,
        };
        Camera { position: cam.position, rotation: cam.rotation, projection, near: near.max(1e-4) }
    } else {
        framing_camera(&level.scene, DEFAULT_FOV_Y)
    };
    if let Some(fov_y) = overrides.fov_y {
        camera.projection = CameraProjection::Perspective { fov_y };
    }
    camera
}

/// Looks at the scene's bounding sphere from the front, slightly above, so all of it is in view.
pub fn framing_camera(scene: &Scene, fov_y: f32) -> Camera {
    let bounds = scene.bounds();
    if bounds.is_empty() {
        return Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, fov_y);
    }
    let centre = bounds.center();
    let radius = (bounds.size().length() * 0.5).max(1e-3);
    // A little margin, and high enough above that top faces are not seen edge-on.
    let distance = 1.2 * radius / (fov_y * 0.5).sin();
    let dir = Vec3::new(0.45, 0.55, 1.0).normalize();
    Camera::look_at(centre + dir * distance, centre, fov_y)
}

/// The complete first view of `level`.
pub fn initial_view(level: &Level, overrides: &ViewOverrides) -> ViewState {
    let camera = initial_camera(level, overrides);
    let mut profile = level.headlamp.clone();
    if let Some(fov_y) = overrides.fov_y {
        profile.fov_y = fov_y;
    }
    let power = profile.power;
    let headlamp = Headlamp::new(profile);
    let exposure = level.exposure.unwrap_or_else(|| auto_exposure(&level.scene, &camera, power));
    ViewState {
        camera,
        headlamp,
        lights: level.scene.lights.clone(),
        exposure,
        instances: vec![],
        camera_flash: [0.0; 3],
        view_models: vec![],
    }
}

/// An exposure under which a white surface facing the lamp at the distance of the scene's
/// centre comes out near mid-grey: its radiance is ρ·P/(π d²), so scale by π d²/P.
pub fn auto_exposure(scene: &Scene, camera: &Camera, power: f32) -> f32 {
    let bounds = scene.bounds();
    let d = if bounds.is_empty() { 1.0 } else { (bounds.center() - camera.position).length().max(0.5) };
    std::f32::consts::PI * d * d / power.max(1e-6)
}
