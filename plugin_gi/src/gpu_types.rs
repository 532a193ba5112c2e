//! CPU mirrors of the structs in shaders/gi/gi_common.wgsl, and the names of the graph
//! resources the GI passes exchange.

use bytemuck::{Pod, Zeroable};

pub mod names {
    /// Reflected flux Φ per lamp-view texel, W (Rgba32Float).
    pub const FLUX: &str = "gi.flux";
    /// Φ / (P · Ω_texel) = ρ·T(ω): the flux view (Rgba16Float).
    pub const FLUX_VIEW: &str = "gi.flux_view";
    /// The reflection lights (instance buffer) and their indirect draw arguments.
    pub const LIGHTS: &str = "gi.lights";
    pub const DRAW_ARGS: &str = "gi.draw_args";
    /// Indirect irradiance E at the indirect resolution (W/m²; Rgba32Float where the device
    /// blends f32, else Rgba16Float).
    pub const IRRADIANCE: &str = "gi.irradiance";
    /// Indirect radiance L_i = ρ/π · E at full resolution (Rgba16Float).
    pub const INDIRECT: &str = "gi.indirect";
    /// The frame with the reflection lights drawn as dots (Rgba8UnormSrgb).
    pub const LIGHTS_VIEW: &str = "gi.lights_view";
    /// Brute-force indirect radiance (Rgba32Float).
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
    pub cutoff: f32,
    pub d_min: f32,
    /// 0: flux from the lamp; 1: flux from the previous bounce's irradiance.
    pub source: u32,
}

/// A reflection light as the GPU builds it: a Lambertian emitter I_r(ω) = Φ/π · max(0, n·ω).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct ReflectionLight {
    pub position: [f32; 3],
    pub radius: f32,
    pub normal: [f32; 3],
    pub level: u32,
    pub flux: [f32; 3],
    pub pad: f32,
}

/// Size in bytes of one quadtree node (see `Node` in gi_common.wgsl).
pub const NODE_SIZE: u64 = 48;
/// Indirect draw arguments: vertex count, instance count, first vertex, first instance.
pub const DRAW_ARGS_SIZE: u64 = 16;
/// Each slot emits at most 4² lights (two levels of refinement).
pub const LIGHTS_PER_SLOT: u32 = 16;
