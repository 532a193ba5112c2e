//! A sender: a patch of a level triangle, and the light the lamp puts on it. Shared by the
//! world that cuts and lights patches and the transport that sums them.

use engine::glam::Vec3;

/// One patch: a sub-triangle of a level triangle. Where it lies depends on the scene and the
/// patch size only.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Patch {
    /// Corners in the winding of their triangle.
    pub corners: [Vec3; 3],
    /// The centroid.
    pub centre: Vec3,
    /// The triangle's geometric unit normal, (b − a) × (c − a): its front.
    pub normal: Vec3,
    pub area: f32,
    /// Which triangle of [`World`](crate::World) it was cut from (meshes in order, then indices in order).
    pub triangle: u32,
}

/// A patch the lamp lights: the side it is lit on and the flux it reflects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LitPatch {
    pub patch: Patch,
    /// Unit normal of the lit side (the patch's normal, turned towards the lamp on a double-sided
    /// material).
    pub normal: Vec3,
    /// Reflected flux Φ = ρ · I · max(0, n·l) · A / d² (W).
    pub flux: Vec3,
}
