//! The player's lamp as a level sets it: `level.toml`'s `[headlamp]`.

use crate::distribution_image::DistributionImage;
use crate::ies::IesProfile;

/// The player's lamp: radiant intensity I(ω) = power · color · T(uv(ω)) over its frustum.
#[derive(Clone, Debug, PartialEq)]
pub struct HeadlampProfile {
    /// W/sr.
    pub power: f32,
    /// Vertical field of view of the lamp frustum, radians.
    pub fov_y: f32,
    /// Linear RGB tint.
    pub color: [f32; 3],
    pub distribution: IntensityDistribution,
}

impl Default for HeadlampProfile {
    fn default() -> Self {
        Self { power: 1.0, fov_y: 60f32.to_radians(), color: [1.0; 3], distribution: IntensityDistribution::Uniform }
    }
}

/// T in I(ω) = P·T(uv(ω)): the relative intensity across the lamp frustum.
#[derive(Clone, Debug, PartialEq)]
pub enum IntensityDistribution {
    /// T = 1 everywhere in the frustum.
    Uniform,
    /// T = 1 within `inner` of the axis, 0 beyond `outer` (half-angles, radians), smooth between.
    Spot { inner: f32, outer: f32 },
    /// T sampled from a texture spanning the frustum.
    Image(DistributionImage),
    /// T from a photometric candela table (an IES file), candela / its largest value in each
    /// direction: baked for whatever frustum the lamp has (the camera's while worn, `fov_deg`
    /// square when put down), so the angles stay right at any field of view and aspect.
    Photometric(IesProfile),
}
