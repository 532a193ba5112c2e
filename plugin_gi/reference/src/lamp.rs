//! The headlamp as the reference sees it: a point emitter of radiant intensity
//! I(x) = P·colour·T(uv(x)) towards a world point x, exactly as the shaders'
//! `lamp_intensity_towards` (shaders/common.wgsl) takes it from the frame's globals.

use engine::camera::Camera;
use engine::glam::{Mat4, Vec3};
use engine::headlamp::{distribution_texels, Headlamp};

/// Where the lamp is, how directions map onto its distribution texture, and the texture.
#[derive(Clone, Debug)]
pub struct Lamp {
    pub position: Vec3,
    /// World → the lamp frustum's clip space.
    pub view_proj: Mat4,
    /// P·colour (W/sr); zero while the lamp is off.
    pub intensity: Vec3,
    width: u32,
    height: u32,
    /// Linear RGB texels, top row first.
    texels: Vec<[f32; 3]>,
}

impl Lamp {
    /// The frame's lamp: its frustum from [`Headlamp::frustum`] (attached: the camera's with the
    /// view's aspect; detached: the profile's field of view, aspect 1), its distribution texture
    /// from [`distribution_texels`] for that frustum.
    pub fn new(headlamp: &Headlamp, camera: &Camera, view_aspect: f32) -> Self {
        let frustum = headlamp.frustum(camera, view_aspect);
        let (width, height, texels) =
            distribution_texels(&headlamp.profile.distribution, frustum.fov_y, frustum.aspect);
        let intensity = if headlamp.on { headlamp.intensity() } else { Vec3::ZERO };
        Self::with_texels(frustum.position, frustum.view_proj, intensity, width, height, &texels)
    }

    /// A lamp at `position` whose frustum is `view_proj`, T a `width`×`height` RGBA texture (top
    /// row first; alpha unused) and `intensity` = P·colour.
    pub fn with_texels(
        position: Vec3,
        view_proj: Mat4,
        intensity: Vec3,
        width: u32,
        height: u32,
        texels: &[[f32; 4]],
    ) -> Self {
        assert!(width > 0 && height > 0, "a distribution texture has texels");
        assert_eq!(texels.len(), (width * height) as usize, "{width}x{height} texels");
        let texels = texels.iter().map(|t| [t[0], t[1], t[2]]).collect();
        Self { position, view_proj, intensity, width, height, texels }
    }

    /// Whether the lamp gives any light at all.
    pub fn is_on(&self) -> bool {
        self.intensity.max_element() > 0.0
    }

    /// Whether `x` is inside the lamp's frustum (where [`Lamp::intensity_towards`] can be
    /// non-zero).
    pub fn in_frustum(&self, x: Vec3) -> bool {
        let clip = self.view_proj * x.extend(1.0);
        clip.w > 0.0 && clip.x.abs() <= clip.w && clip.y.abs() <= clip.w
    }

    /// Radiant intensity towards world point `x` (W/sr): zero behind the lamp or outside its
    /// frustum, else P·colour·T(uv) with T sampled bilinearly, edges clamped (the shaders'
    /// `linear_clamp` sampler: texel centres at +0.5).
    pub fn intensity_towards(&self, x: Vec3) -> Vec3 {
        let clip = self.view_proj * x.extend(1.0);
        if clip.w <= 0.0 {
            return Vec3::ZERO;
        }
        let (ndc_x, ndc_y) = (clip.x / clip.w, clip.y / clip.w);
        if ndc_x.abs() > 1.0 || ndc_y.abs() > 1.0 {
            return Vec3::ZERO;
        }
        let uv = [ndc_x * 0.5 + 0.5, 0.5 - ndc_y * 0.5];
        self.intensity * self.distribution(uv)
    }

    /// T at `uv`, bilinear with clamp-to-edge.
    pub fn distribution(&self, uv: [f32; 2]) -> Vec3 {
        let (w, h) = (self.width as i64, self.height as i64);
        let x = uv[0] * self.width as f32 - 0.5;
        let y = uv[1] * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let texel = |i: i64, j: i64| Vec3::from(self.texels[(j.clamp(0, h - 1) * w + i.clamp(0, w - 1)) as usize]);
        let (i, j) = (x0 as i64, y0 as i64);
        let top = texel(i, j).lerp(texel(i + 1, j), fx);
        let bottom = texel(i, j + 1).lerp(texel(i + 1, j + 1), fx);
        top.lerp(bottom, fy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::camera::Camera;
    use engine::glam::Quat;
    use engine::scene::{HeadlampProfile, IntensityDistribution};

    fn lamp(distribution: IntensityDistribution) -> Lamp {
        let profile = HeadlampProfile { power: 10.0, fov_y: 1.0, color: [1.0, 0.5, 0.25], distribution };
        let camera = Camera::perspective(Vec3::ZERO, Quat::IDENTITY, 1.0);
        Lamp::new(&engine::headlamp::Headlamp::new(profile), &camera, 1.5)
    }

    #[test]
    fn a_uniform_lamp_is_its_power_inside_the_frustum_and_dark_outside() {
        let l = lamp(IntensityDistribution::Uniform);
        assert_eq!(l.intensity_towards(Vec3::new(0.0, 0.0, -2.0)), Vec3::new(10.0, 5.0, 2.5));
        // The frustum is tan(0.5)·1.5 wide at unit distance: 0.819.
        assert_eq!(l.intensity_towards(Vec3::new(0.8, 0.0, -1.0)), Vec3::new(10.0, 5.0, 2.5));
        assert_eq!(l.intensity_towards(Vec3::new(0.84, 0.0, -1.0)), Vec3::ZERO);
        assert_eq!(l.intensity_towards(Vec3::new(0.0, 0.0, 1.0)), Vec3::ZERO, "behind the lamp");
    }

    #[test]
    fn a_spot_is_bright_on_its_axis_and_fades_off_it_and_off_is_dark() {
        let l = lamp(IntensityDistribution::Spot { inner: 0.1, outer: 0.3 });
        assert!((l.intensity_towards(Vec3::new(0.0, 0.0, -1.0)) - Vec3::new(10.0, 5.0, 2.5)).length() < 1e-4);
        assert_eq!(l.intensity_towards(Vec3::new(0.0, 0.45, -1.0)), Vec3::ZERO, "beyond the outer cone");
        let mid = l.intensity_towards(Vec3::new(0.0, 0.2f32.tan(), -1.0)).x;
        assert!(mid > 2.0 && mid < 8.0, "half way between the cones: {mid}");
        let mut off = engine::headlamp::Headlamp::new(HeadlampProfile::default());
        off.on = false;
        let camera = Camera::perspective(Vec3::ZERO, Quat::IDENTITY, 1.0);
        assert_eq!(Lamp::new(&off, &camera, 1.0).intensity_towards(Vec3::new(0.0, 0.0, -1.0)), Vec3::ZERO);
    }

    #[test]
    fn the_distribution_is_bilinear_with_clamped_edges() {
        let texels = [[0.0; 4], [1.0; 4], [2.0; 4], [3.0; 4]];
        let l = Lamp::with_texels(Vec3::ZERO, Mat4::IDENTITY, Vec3::ONE, 2, 2, &texels);
        assert_eq!(l.distribution([0.25, 0.25]), Vec3::ZERO, "a texel centre");
        assert_eq!(l.distribution([0.5, 0.25]), Vec3::splat(0.5), "between two");
        assert_eq!(l.distribution([0.5, 0.5]), Vec3::splat(1.5), "between four");
        assert_eq!(l.distribution([0.0, 1.0]), Vec3::splat(2.0), "clamped at a corner");
    }
}
