//! The player's headlamp: a point emitter whose radiant intensity is I(ω) = P · T(uv(ω)), T being
//! the intensity distribution texture laid over the lamp frustum.

use glam::{Mat4, Quat, Vec3};
use scene::{HeadlampProfile, IntensityDistribution};

use crate::camera::{rotation_looking, Camera, CameraProjection};

/// Width and height of the detached lamp's view (every `lamp.*` texture), in texels.
pub const LAMP_MAP_SIZE: u32 = 1024;

#[derive(Clone, Debug, PartialEq)]
pub struct Headlamp {
    pub on: bool,
    /// Attached: the lamp sits at the camera and its frustum is the camera's (the article's
    /// first-person case). Detached: `position`/`rotation` and the profile's own FOV.
    pub attached: bool,
    pub position: Vec3,
    pub rotation: Quat,
    pub profile: HeadlampProfile,
}

/// Where the lamp is and how directions map onto its distribution texture this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LampFrustum {
    pub position: Vec3,
    pub rotation: Quat,
    pub fov_y: f32,
    pub aspect: f32,
    pub view_proj: Mat4,
}

impl Headlamp {
    pub fn new(profile: HeadlampProfile) -> Self {
        Self { on: true, attached: true, position: Vec3::ZERO, rotation: Quat::IDENTITY, profile }
    }

    /// Radiant intensity scale P·colour (W/sr) before the distribution texture.
    pub fn intensity(&self) -> Vec3 {
        Vec3::from(self.profile.color) * self.profile.power
    }

    /// Puts the lamp down where the camera is, pointing where it looks.
    pub fn detach_at(&mut self, camera: &Camera) {
        self.attached = false;
        self.position = camera.position;
        self.rotation = camera.rotation;
    }

    /// Puts the lamp down at `eye`, pointing at `target` (+Y up where possible).
    pub fn detach_looking_at(&mut self, eye: Vec3, target: Vec3) {
        self.attached = false;
        self.position = eye;
        self.rotation = rotation_looking((target - eye).try_normalize().unwrap_or(Vec3::NEG_Z));
    }

    pub fn frustum(&self, camera: &Camera, view_aspect: f32) -> LampFrustum {
        let (position, rotation, fov_y, aspect) = match (self.attached, camera.projection) {
            (true, CameraProjection::Perspective { fov_y }) => (camera.position, camera.rotation, fov_y, view_aspect),
            (true, CameraProjection::Orthographic { .. }) => {
                (camera.position, camera.rotation, self.profile.fov_y, view_aspect)
            }
            (false, _) => (self.position, self.rotation, self.profile.fov_y, 1.0),
        };
        let lamp_camera = Camera::perspective(position, rotation, fov_y);
        LampFrustum { position, rotation, fov_y, aspect, view_proj: lamp_camera.view_projection(aspect) }
    }
}

/// The distribution texture T for a frustum: width, height and linear RGBA texels, top row first.
pub fn distribution_texels(dist: &IntensityDistribution, fov_y: f32, aspect: f32) -> (u32, u32, Vec<[f32; 4]>) {
    match dist {
        // Every direction inside the frustum gets T = 1.
        IntensityDistribution::Uniform => (1, 1, vec![[1.0; 4]]),
        IntensityDistribution::Spot { inner, outer } => {
            const SIZE: u32 = 256;
            let (tan_y, tan_x) = ((fov_y * 0.5).tan(), (fov_y * 0.5).tan() * aspect);
            let mut texels = Vec::with_capacity((SIZE * SIZE) as usize);
            for y in 0..SIZE {
                for x in 0..SIZE {
                    let ndc_x = (x as f32 + 0.5) / SIZE as f32 * 2.0 - 1.0;
                    let ndc_y = 1.0 - (y as f32 + 0.5) / SIZE as f32 * 2.0;
                    let dir = Vec3::new(ndc_x * tan_x, ndc_y * tan_y, -1.0).normalize();
                    let angle = (-dir.z).clamp(-1.0, 1.0).acos();
                    let t = ((outer - angle) / (outer - inner).max(1e-6)).clamp(0.0, 1.0);
                    let v = t * t * (3.0 - 2.0 * t);
                    texels.push([v, v, v, 1.0]);
                }
            }
            (SIZE, SIZE, texels)
        }
        IntensityDistribution::Image(img) => {
            let texels = img.values.iter().map(|c| [c[0], c[1], c[2], 1.0]).collect();
            (img.width, img.height, texels)
        }
        // As fine across as down: a wide frustum gets a wider texture.
        IntensityDistribution::Photometric(ies) => {
            let height = scene::ies_texture_size(fov_y);
            let width = ((height as f32 * aspect).round() as u32).clamp(3, 2 * height) | 1;
            let img = ies.distribution(fov_y, aspect, width, height);
            (width, height, img.values.iter().map(|c| [c[0], c[1], c[2], 1.0]).collect())
        }
    }
}
