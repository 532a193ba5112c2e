//! CPU mirrors of the structs in shaders/gi/gi_common.wgsl, and the names of the graph
//! resources the GI passes exchange.

use bytemuck::{Pod, Zeroable};

pub mod names {
    /// Reflected flux Φ per lamp-view texel, W (Rgba32Float).
    pub const FLUX: &str = "gi.flux";
    /// Φ / (P · Ω_texel) = ρ·T(ω): the flux view (Rgba16Float).
    pub const FLUX_VIEW: &str = "gi.flux_view";
    /// The reflection lights of the tile at the centre of the view (its cut through the
    /// pyramid), for the `lights` view and tests.
    pub const LIGHTS: &str = "gi.lights";
    /// The gather's counters; they begin with the `lights` view's indirect draw arguments.
    pub const STATS: &str = "gi.stats";
    /// Indirect irradiance E at the indirect resolution (W/m², Rgba32Float).
    pub const IRRADIANCE: &str = "gi.irradiance";
    /// Indirect radiance L_i = ρ/π · E at full resolution (Rgba16Float).
    pub const INDIRECT: &str = "gi.indirect";
    /// The frame with the reflection lights drawn as dots (Rgba8UnormSrgb).
    pub const LIGHTS_VIEW: &str = "gi.lights_view";
    /// The exact one bounce (Rgba32Float).
    pub const REFERENCE: &str = "gi.reference";
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GiParams {
    pub flux_size: [u32; 2],
    pub indirect_size: [u32; 2],
    pub lamp_tan: [f32; 2],
    pub lamp_power: f32,
    pub cos_merge: f32,
    pub merge_distance: f32,
    pub split_ratio: f32,
    /// Lights are not split below this pyramid level.
    pub min_level: u32,
    /// 0: flux from the lamp; 1: flux from the previous bounce's irradiance.
    pub source: u32,
    /// 2: the gather's receivers share the cut in a 2×2 pattern; 1: each evaluates all of it.
    pub interleave: u32,
    pub pad: [u32; 3],
    /// The frame the lamp view (the flux G-buffer's source) was rendered from: its origin, its
    /// forward axis, and its right and up axes scaled by `lamp_tan` (w unused), so a texel's
    /// corner rays follow from its index: the reference's footprints in its near field.
    pub view_origin: [f32; 4],
    pub view_forward: [f32; 4],
    pub view_right: [f32; 4],
    pub view_up: [f32; 4],
}

/// A reflection light as the gather used it: a Lambertian patch of area `area`,
/// I_r(ω) = Φ/π · max(0, n·ω).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct ReflectionLight {
    pub position: [f32; 3],
    pub area: f32,
    pub normal: [f32; 3],
    /// The pyramid level it came from (0 = one texel).
    pub level: u32,
    pub flux: [f32; 3],
    /// 1 when it faces away from every receiver of its tile (left unevaluated), else 0.
    pub faces_away: f32,
}

/// Size in bytes of one pyramid node (see `Node` in gi_common.wgsl).
pub const NODE_SIZE: u64 = 48;
/// The gather's counters (see `Stats` in cuts.wgsl, which fills them).
pub const GATHER_STATS_SIZE: u64 = 32;
/// Capacity of the centre tile's light list.
pub const CENTRE_LIGHTS: u64 = 8192;
