//! CPU twins of the structs in shaders/gi/*.wgsl (see `engine::gpu_layout`; the layout test
//! compares them), and the names of the graph resources the GI passes exchange.

use bytemuck::{Pod, Zeroable};
use engine::gpu_layout::{GpuLayout, Layout};

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
    /// The irradiance blended over frames (a history pair: this frame's and last).
    pub const IRRADIANCE_HISTORY: &str = "gi.irradiance_history";
    /// Indirect radiance L_i = ρ/π · E at full resolution (Rgba16Float).
    pub const INDIRECT: &str = "gi.indirect";
    /// The frame with the reflection lights drawn as dots (Rgba8UnormSrgb).
    pub const LIGHTS_VIEW: &str = "gi.lights_view";
    /// The exact one bounce (Rgba32Float).
    pub const REFERENCE: &str = "gi.reference";
}

engine::gpu_struct! {
    /// The per-frame parameters every GI pass reads (gi_common.wgsl).
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
        /// 2: the gather's receivers share the cut in a 2×2 pattern; 1: each evaluates all of it.
        pub interleave: u32,
        /// The side in lamp-view texels of one flux G-buffer texel (a power of two).
        pub flux_block: u32,
        /// The article method's interleaved sampling: its lights dealt over N×N sub-images.
        pub article_interleave: u32,
        /// Where the receivers' and the flux G-buffer's grids lie this frame (see `grids`).
        pub receiver_offset: [f32; 2],
        pub sender_offset: [f32; 2],
        /// The article method's fine light volumes, in sizes of their coarse lights.
        pub volume_reach: f32,
        /// The whole cells the receivers' grid has stepped back, mod RECEIVER_PERIOD each way
        /// (x | y << 16; see `grids`): the gather's 2×2 interleave follows their parity, the
        /// article's sub-images them.
        pub receiver_steps: u32,
        /// The periods the senders' grid has stepped back, plus SENDER_STEPS_OFFSET, each way
        /// (x | y << 16).
        pub sender_steps: u32,
        pub pad: [u32; 3],
        /// The frame the lamp view (the flux G-buffer's source) was rendered from: its origin,
        /// its forward axis, and its right and up axes scaled by `lamp_tan` (w unused), so a
        /// texel's corner rays follow from its index: the reference's footprints in its near
        /// field.
        pub view_origin: [f32; 4],
        pub view_forward: [f32; 4],
        pub view_right: [f32; 4],
        pub view_up: [f32; 4],
    }
}

engine::gpu_struct! {
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
}

engine::gpu_struct! {
    /// The gather's counters, `Stats` in cuts.wgsl (which fills them; atomics there): first the
    /// `lights` view's indirect draw arguments (the centre tile's cut), then the totals. With
    /// `gi.method = article` article_stream.wgsl fills them: the dots are the fine tier's lights,
    /// `lights` the volumes drawn, `tiles` the distribution table's slots, `full` 0.
    #[repr(C)]
    #[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
    pub struct GatherStats as Stats {
        pub vertex_count: u32,
        /// Reflection lights in the centre tile's cut.
        pub instance_count: u32,
        pub first_vertex: u32,
        pub first_instance: u32,
        /// Σ cut sizes over the tiles.
        pub lights: u32,
        /// Tiles with receivers.
        pub tiles: u32,
        /// Tiles whose cut filled up.
        pub full: u32,
        pub pad: u32,
    }
}

engine::gpu_struct! {
    /// Per pyramid level: offset into the node buffer, width, height (gi_common.wgsl).
    #[repr(C)]
    #[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
    pub struct Levels {
        pub levels: [[u32; 4]; 8],
    }
}

engine::gpu_struct! {
    /// One dispatch of the reference's senders (reference.wgsl).
    #[repr(C)]
    #[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
    pub struct SenderRange {
        pub first: u32,
        pub count: u32,
        /// 1 on the final range.
        pub last: u32,
        pub stride: u32,
    }
}

engine::gpu_struct! {
    /// The view-model probe (view_model_probe.wgsl): xyz the point (m), and the pyramid level
    /// summed in `level.x`.
    #[repr(C)]
    #[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
    pub struct Probe {
        pub position: [f32; 4],
        pub level: [u32; 4],
    }
}

engine::gpu_struct! {
    /// The temporal pass's parameters (temporal.wgsl).
    #[repr(C)]
    #[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
    pub struct TemporalParams {
        /// Last frame's view-projection, column-major.
        pub previous_view_proj: [[f32; 4]; 4],
        /// Last frame's `GiParams::receiver_offset`.
        pub previous_offset: [f32; 2],
        /// The weight of this frame's irradiance (1: none of the history's).
        pub current_weight: f32,
        /// How far history may lie outside this frame's neighbourhood, relative.
        pub slack: f32,
        /// 1 when the history holds last frame's irradiance.
        pub has_history: u32,
        pub pad: [u32; 3],
    }
}

engine::gpu_struct! {
    /// A level's occupancy grid, as the world sight test reads it (world_sight.wgsl).
    #[repr(C)]
    #[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
    pub struct WorldGrid {
        /// The grid's lowest corner and a voxel's side, metres.
        pub origin: [f32; 3],
        pub voxel: f32,
        /// Its size in blocks of occupancy::BLOCK³ voxels.
        pub blocks: [u32; 3],
        pub pad: u32,
    }
}

/// The twins of the structs in the GI's shaders (shaders/gi/*.wgsl).
pub fn twins() -> Vec<Layout> {
    vec![
        GiParams::layout(),
        ReflectionLight::layout(),
        GatherStats::layout(),
        Levels::layout(),
        SenderRange::layout(),
        Probe::layout(),
        TemporalParams::layout(),
        WorldGrid::layout(),
    ]
}

/// The structs in the GI's shaders that have no Rust twin, and why. The sizes the CPU needs of
/// some of them are constants below, which the layout test checks.
pub const GPU_ONLY: &[(&str, &str)] = &[
    ("VolumeLight", "the article's instance stream, written and read by the GPU only (VOLUME_LIGHT_SIZE sizes it)"),
    ("DrawArgs", "written by the GPU, read as wgpu's DrawIndirectArgs"),
    ("Place", "a function's value, never in a buffer"),
    ("Receiver", "a function's value, never in a buffer"),
    ("SubPixel", "a function's value, never in a buffer"),
    ("VolumeOut", "stage IO between vertex and fragment shaders"),
    ("Node", "the pyramid's nodes are written and read by the GPU only (NODE_SIZE sizes them)"),
    ("RetryList", "written and read by the GPU only (the CPU clears RETRY_HEADER)"),
    ("DispatchArgs", "written by the GPU, read as wgpu's DispatchIndirectArgs"),
    ("Sender", "workgroup memory"),
    ("CutLight", "a function's value, never in a buffer"),
    ("TileBounds", "a function's value, never in a buffer"),
    ("Walk", "a function's value, never in a buffer"),
    ("Halves", "a function's value, never in a buffer"),
    ("Sums", "a function's value, never in a buffer"),
    ("SamplePlace", "a function's value, never in a buffer"),
    ("SurfacePoint", "a function's value, never in a buffer"),
    ("PlacedReceiver", "a function's value, never in a buffer"),
    ("Sequence", "a function's value, never in a buffer"),
    ("Lanes", "a function's value, never in a buffer"),
    ("Gathered", "a function's value, never in a buffer"),
    ("Shaded", "a function's value, never in a buffer"),
    ("ScreenSight", "a function's value, never in a buffer"),
    ("DotOut", "stage IO between vertex and fragment shaders"),
];

/// Size in bytes of one light of the article's instance stream (`VolumeLight` in
/// gi_common.wgsl).
pub const VOLUME_LIGHT_SIZE: u64 = 80;

/// Size in bytes of one pyramid node (`Node` in gi_common.wgsl).
pub const NODE_SIZE: u64 = 48;
/// The gather's counters (`Stats` in cuts.wgsl).
pub const GATHER_STATS_SIZE: u64 = std::mem::size_of::<GatherStats>() as u64;
/// Bytes of the retry list's header, before its `tiles` (`RetryList` in cuts.wgsl).
pub const RETRY_HEADER: u64 = 16;
/// Capacity of the centre tile's light list.
pub const CENTRE_LIGHTS: u64 = 8192;
