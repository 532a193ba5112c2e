//! An intensity texture across the lamp's frustum, as a level's image or IES profile gives it.
//! Below both readers, which make one, and the lamp's profile, which holds one.

/// A linear intensity texture, row-major from the top-left. PNG values are v/255 (no sRGB
/// decoding: they are intensities, not colours); EXR values are used as stored.
#[derive(Clone, Debug, PartialEq)]
pub struct DistributionImage {
    pub width: u32,
    pub height: u32,
    pub values: Vec<[f32; 3]>,
}
