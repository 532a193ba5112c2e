//! A viewpoint and its projection. Perspective projections use reversed, infinite depth
//! (near → 1, infinity → 0) for even precision across large levels.

use glam::{Mat4, Quat, Vec3};

/// The vertical field of view a camera has unless a level or the player says otherwise.
pub const DEFAULT_FOV_Y: f32 = 60.0 * std::f32::consts::PI / 180.0;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraProjection {
    /// Vertical field of view in radians.
    Perspective { fov_y: f32 },
    /// Half-height of the view volume in metres.
    Orthographic { half_height: f32 },
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    /// Looks down its local -Z with +Y up, as glTF cameras.
    pub rotation: Quat,
    pub projection: CameraProjection,
    pub near: f32,
}

impl Camera {
    pub const DEFAULT_NEAR: f32 = 0.05;

    pub fn perspective(position: Vec3, rotation: Quat, fov_y: f32) -> Self {
        Self { position, rotation, projection: CameraProjection::Perspective { fov_y }, near: Self::DEFAULT_NEAR }
    }

    /// Looks from `eye` at `target` with +Y up (any up when looking straight up or down).
    pub fn look_at(eye: Vec3, target: Vec3, fov_y: f32) -> Self {
        let forward = (target - eye).try_normalize().unwrap_or(Vec3::NEG_Z);
        Self::perspective(eye, rotation_looking(forward), fov_y)
    }

    /// Yaw about +Y (0 looks down -Z, positive turns left) then pitch (positive looks up).
    pub fn from_yaw_pitch(position: Vec3, yaw: f32, pitch: f32, fov_y: f32) -> Self {
        Self::perspective(position, yaw_pitch_rotation(yaw, pitch), fov_y)
    }

    pub fn forward(&self) -> Vec3 {
        self.rotation * Vec3::NEG_Z
    }

    pub fn fov_y(&self) -> Option<f32> {
        match self.projection {
            CameraProjection::Perspective { fov_y } => Some(fov_y),
            CameraProjection::Orthographic { .. } => None,
        }
    }

    pub fn view_matrix(&self) -> Mat4 {
        Mat4::from_rotation_translation(self.rotation, self.position).inverse()
    }

    pub fn projection_matrix(&self, aspect: f32) -> Mat4 {
        match self.projection {
            CameraProjection::Perspective { fov_y } => {
                glam::camera::rh::proj::directx::perspective_infinite_reverse(fov_y, aspect, self.near)
            }
            CameraProjection::Orthographic { half_height } => {
                let hw = half_height * aspect;
                // Far and near swapped: reversed depth like the perspective case.
                glam::camera::rh::proj::directx::orthographic(-hw, hw, -half_height, half_height, 1000.0, self.near)
            }
        }
    }

    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        self.projection_matrix(aspect) * self.view_matrix()
    }
}

pub fn yaw_pitch_rotation(yaw: f32, pitch: f32) -> Quat {
    Quat::from_rotation_y(yaw) * Quat::from_rotation_x(pitch)
}

/// The rotation whose -Z is `forward`, keeping +Y up where possible.
pub fn rotation_looking(forward: Vec3) -> Quat {
    let f = forward.normalize();
    let up = if f.y.abs() > 0.999 { Vec3::Z } else { Vec3::Y };
    let right = f.cross(up).normalize();
    let up = right.cross(f);
    Quat::from_mat3(&glam::Mat3::from_cols(right, up, -f))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_at_points_forward() {
        let c = Camera::look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::new(1.0, 2.0, 0.0), 1.0);
        assert!((c.forward() - Vec3::NEG_Z).length() < 1e-5);
        let c = Camera::look_at(Vec3::ZERO, Vec3::new(1.0, 0.0, 0.0), 1.0);
        assert!((c.forward() - Vec3::X).length() < 1e-5);
        // A point in front projects to the centre with depth in (0, 1].
        let p = c.view_projection(1.5).project_point3(Vec3::new(4.0, 0.0, 0.0));
        assert!(p.x.abs() < 1e-5 && p.y.abs() < 1e-5 && p.z > 0.0 && p.z <= 1.0);
    }

    #[test]
    fn yaw_turns_left() {
        let c = Camera::from_yaw_pitch(Vec3::ZERO, std::f32::consts::FRAC_PI_2, 0.0, 1.0);
        assert!((c.forward() - Vec3::NEG_X).length() < 1e-5);
    }
}
