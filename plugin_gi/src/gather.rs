//! The gather: each pixel of the indirect target sums the irradiance of the pyramid's lights,
//! an 8×8 tile sharing one cut through the pyramid. Three dispatches: the cuts, one invocation
//! a tile, then the few tiles whose cut filled up walked again side by side (an indirect
//! dispatch; both shaders/gi/cuts.wgsl), then the sum, one workgroup a tile
//! (shaders/gi/gather.wgsl, entered by gather_subgroup.wgsl or gather_invocation.wgsl: see
//! [`SumLanes`]). With `gi.visibility` two more before the sum: the view depth at half the
//! G-buffer's size (shaders/gi/sight_depth.wgsl), then which lights nine of each tile's
//! receivers see, marched through it (shaders/gi/sight.wgsl). The cuts buffer and the sight
//! depth are graph resources (see [`cuts_desc`], [`crate::sight_depth`]: the first bounce's
//! gather makes the depth once a frame, further bounces march the same); the retry list and
//! the sight bits are this gather's own scratch. The calls cover every tile at once, so their number never depends
//! on the resolution: the indirect target is kept small enough ([`fit_cuts_budget`]) that
//! every tile's cut fits the budget.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::graph::BufferDesc;
use engine::wgpu;

use crate::gpu_types::{GATHER_STATS_SIZE, RETRY_HEADER};
use crate::pipelines::{compute_pipeline, compute_pipeline_with};
use crate::quadtree::Quadtree;
use crate::shader::module;

pub const CUTS_SHADER: &str = include_str!("../../shaders/gi/cuts.wgsl");
pub const GATHER_SUBGROUP_SHADER: &str = include_str!("../../shaders/gi/gather_subgroup.wgsl");
pub const GATHER_INVOCATION_SHADER: &str = include_str!("../../shaders/gi/gather_invocation.wgsl");
pub const SIGHT_SHADER: &str = include_str!("../../shaders/gi/sight.wgsl");

const IRRADIANCE: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The cuts' group 1 (cuts.wgsl).
pub const CUTS: Group = Group::new(
    "gi cuts",
    &[
        B::uniform("params"),
        B::uniform("table"),
        B::storage("nodes"),
        B::texture("gbuffer_normal"),
        B::texture("gbuffer_position"),
        B::storage_rw("cuts"),
        B::storage_rw("stats"),
        B::storage_rw("centre_lights"),
        B::storage_rw("retry"),
        B::storage_rw("receiver_texels"),
    ],
);
/// The cuts' group 2: the retry dispatch's arguments, written by `main`.
pub const RETRY_ARGS: Group = Group::new("gi cuts retry arguments", &[B::storage_rw("retry_dispatch")]);
/// The sight's group 1 (sight.wgsl).
pub const SIGHT: Group = Group::new(
    "gi sight",
    &[
        B::uniform("params"),
        B::uniform("table"),
        B::texture("gbuffer_normal"),
        B::texture("gbuffer_position"),
        B::storage("cuts"),
        B::storage("receiver_texels"),
        B::storage_rw("sight"),
        B::texture("sight_depth"),
    ],
);
/// The sum's group 1 (gather.wgsl).
pub const GATHER: Group = Group::new(
    "gi gather",
    &[
        B::uniform("params"),
        B::uniform("table"),
        B::texture("gbuffer_normal"),
        B::texture("gbuffer_position"),
        B::storage_texture("irradiance_out", IRRADIANCE),
        B::storage("cuts"),
        B::texture("accumulate"),
        B::storage_texture("bounce_out", IRRADIANCE),
        B::storage("receiver_texels"),
        B::storage("sight"),
    ],
);

/// Where the gather's groups are declared.
pub const BINDINGS: &[WgslGroup] = &[
    WgslGroup::new("gi/cuts.wgsl", 1, &CUTS),
    WgslGroup::new("gi/cuts.wgsl", 2, &RETRY_ARGS),
    WgslGroup::new("gi/sight.wgsl", 1, &SIGHT),
    WgslGroup::new("gather.wgsl", 1, &GATHER),
];

/// How the sum's invocations load their lights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SumLanes {
    /// The lanes of a subgroup share the loading and unpacking of lights
    /// (gather_subgroup.wgsl): where every subgroup has 4 or 8 lanes, as on a CPU device
    /// (lavapipe), whose SIMD rows load from storage lane by lane.
    Subgroup,
    /// Each invocation loads its own (gather_invocation.wgsl): everywhere else.
    Invocation,
}

impl SumLanes {
    pub fn for_device(gpu: &engine::gpu::Gpu) -> Self {
        match gpu.subgroup_size() {
            Some(4 | 8) => SumLanes::Subgroup,
            _ => SumLanes::Invocation,
        }
    }
}

/// What one gather reads and writes.
pub struct GatherTargets<'a> {
    /// The GiParams of this bounce, the pyramid's level table and nodes.
    pub params: &'a wgpu::Buffer,
    pub levels: &'a wgpu::Buffer,
    pub nodes: &'a wgpu::Buffer,
    /// Room for every tile's cut ([`cuts_desc`]).
    pub cuts: &'a wgpu::Buffer,
    pub normal: &'a wgpu::TextureView,
    pub position: &'a wgpu::TextureView,
    /// Irradiance out (Rgba32Float storage): this bounce's plus `accumulate`'s.
    pub irradiance: &'a wgpu::TextureView,
    /// Further bounces: the total so far, added to the output (any float texture for bounce 1).
    pub accumulate: &'a wgpu::TextureView,
    /// Further bounces: this bounce's irradiance alone, for the next one (a 1×1 sink for bounce 1).
    pub bounce: &'a wgpu::TextureView,
    /// Counters and the `lights` view's draw arguments (cleared here).
    pub stats: &'a wgpu::Buffer,
    /// The cut of the tile at the centre of the view.
    pub lights: &'a wgpu::Buffer,
    /// Where each receiver is evaluated ([`receivers_desc`]): the cuts pass finds it, the sum
    /// reads it.
    pub receivers: &'a wgpu::Buffer,
    /// With visibility: the view depth to march ([`crate::sight_depth`]); `None` without.
    pub sight_depth: Option<&'a wgpu::TextureView>,
}

pub struct Gather {
    cuts_layout: wgpu::BindGroupLayout,
    cuts_pipeline: wgpu::ComputePipeline,
    /// The indirect dispatch's arguments, written by the cuts pass (its group 2).
    retry_args_layout: wgpu::BindGroupLayout,
    retry_pipeline: wgpu::ComputePipeline,
    sight_layout: wgpu::BindGroupLayout,
    sight_pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    /// The sum without visibility and with it (the `VISIBILITY` override).
    pipelines: [wgpu::ComputePipeline; 2],
    /// The retry list and the sight bits, sized for the last layout's tiles.
    scratch: Option<(CutsLayout, Scratch)>,
}

/// What the cuts' second walk and the sum need besides the cuts.
struct Scratch {
    /// The tiles whose first walk filled the cut (a count, then a slot and a ratio each).
    retry: wgpu::Buffer,
    /// The workgroups of the retry dispatch, as its indirect arguments.
    retry_args: wgpu::Buffer,
    /// One u32 a slot of the cuts: which of the tile's nine tested receivers see the light there.
    sight: wgpu::Buffer,
}

/// Receivers per tile side (`CUT_TILE` in gi_common.wgsl).
pub const TILE: u32 = 8;

/// The most lights a tile's cut holds (`CUT_MAX` in gi_common.wgsl), unless the pyramid's top
/// level has more: every one of those is in every cut.
pub const CUT_MAX: u32 = 1536;

/// Invocations (tiles) per workgroup of the cuts pass (`CUTS_GROUP` in cuts.wgsl).
pub const CUTS_GROUP: u32 = 8;

/// At most this much memory holds the cuts, so no setting can ask for an unbounded buffer: an
/// indirect target with more tiles than fit is made smaller ([`fit_cuts_budget`]). Below the
/// 128 MiB storage binding every wgpu device allows; 1,365 tiles of 1,536 lights, e.g. 320×180
/// receivers at 2560×1440 with the default scale.
const CUTS_BUDGET_BYTES: u64 = 64 << 20;

/// The cuts of an indirect target of `size` over a pyramid on a flux G-buffer of `flux_size`.
pub fn cuts_layout(size: (u32, u32), flux_size: (u32, u32)) -> CutsLayout {
    CutsLayout::new(size, &Quadtree::new(flux_size.0, flux_size.1))
}

/// The largest indirect target no larger than `size`, same shape, whose cuts over a pyramid on
/// `flux_size` fit the budget; `size` itself at every size people play.
pub fn fit_cuts_budget(size: (u32, u32), flux_size: (u32, u32)) -> (u32, u32) {
    let fits = |s: (u32, u32)| cuts_layout(s, flux_size).bytes() <= CUTS_BUDGET_BYTES;
    if fits(size) {
        return size;
    }
    // Scale both sides by the same factor, the largest that fits (bisection on rows).
    let scaled = |rows: u32| {
        let w = (u64::from(size.0) * u64::from(rows) / u64::from(size.1.max(1))).max(1) as u32;
        (w, rows)
    };
    let (mut lo, mut hi) = (1, size.1);
    while lo + 1 < hi {
        let mid = (lo + hi) / 2;
        if fits(scaled(mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    scaled(lo)
}

/// The cuts buffer.
pub fn cuts_desc(layout: &CutsLayout) -> BufferDesc {
    BufferDesc { size: layout.bytes(), usage: wgpu::BufferUsages::STORAGE }
}

/// Where each receiver of an indirect target of `size` is evaluated: a G-buffer texel, one
/// u32 a receiver (x | y << 16), row by row.
pub fn receivers_desc(size: (u32, u32)) -> BufferDesc {
    BufferDesc { size: 4 * u64::from(size.0) * u64::from(size.1), usage: wgpu::BufferUsages::STORAGE }
}

/// How the cuts of an indirect target lie in their buffer: `tiles` across and down, each
/// tile's cut `stride` vec4s (its counts, its centre, then one a light with room for the
/// classes' padding: see gi_common.wgsl).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CutsLayout {
    pub tiles: (u32, u32),
    pub stride: u32,
}

impl CutsLayout {
    /// For an indirect target of `size` over `tree`.
    pub fn new(size: (u32, u32), tree: &Quadtree) -> Self {
        let (w, h) = tree.size(crate::quadtree::TOP);
        let tiles = (size.0.div_ceil(TILE), size.1.div_ceil(TILE));
        Self { tiles, stride: 2 + 2 * CUT_MAX.max(w * h) }
    }

    /// Bytes of the cuts buffer.
    pub fn bytes(&self) -> u64 {
        u64::from(self.tiles.0) * u64::from(self.tiles.1) * u64::from(self.stride) * 16
    }
}

impl Gather {
    pub fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout, lanes: SumLanes) -> Self {
        let cuts_layout = CUTS.layout(device);
        let retry_args_layout = RETRY_ARGS.layout(device);
        let sight_layout = SIGHT.layout(device);
        let sight_module = module(device, "gi sight", SIGHT_SHADER);
        let sight_pipeline =
            compute_pipeline(device, "gi sight", &sight_module, "main", &[Some(globals), Some(&sight_layout)]);
        let layout = GATHER.layout(device);
        let cuts_module = module(device, "gi cuts", CUTS_SHADER);
        let cuts_pipeline = compute_pipeline(
            device,
            "gi cuts",
            &cuts_module,
            "main",
            &[Some(globals), Some(&cuts_layout), Some(&retry_args_layout)],
        );
        let retry_pipeline = compute_pipeline(
            device,
            "gi cuts retry",
            &cuts_module,
            "retry_full_tiles",
            &[Some(globals), Some(&cuts_layout)],
        );
        let source = match lanes {
            SumLanes::Subgroup => GATHER_SUBGROUP_SHADER,
            SumLanes::Invocation => GATHER_INVOCATION_SHADER,
        };
        let module = module(device, "gi gather", source);
        let pipelines = [false, true].map(|visibility| {
            let constants = [("VISIBILITY", f64::from(u8::from(visibility)))];
            compute_pipeline_with(device, "gi gather", &module, "main", &[Some(globals), Some(&layout)], &constants)
        });
        Self {
            cuts_layout,
            cuts_pipeline,
            retry_args_layout,
            retry_pipeline,
            sight_layout,
            sight_pipeline,
            layout,
            pipelines,
            scratch: None,
        }
    }

    /// Records the gather into `t` laid out as `layout` (as `t.cuts` was sized), with light
    /// stopped by the surfaces between where `t.sight_depth` is given; returns the number of
    /// dispatches: three, four with visibility.
    pub fn record(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        globals: &wgpu::BindGroup,
        layout: CutsLayout,
        t: &GatherTargets<'_>,
    ) -> u32 {
        if self.scratch.as_ref().is_none_or(|(l, _)| *l != layout) {
            let tiles = u64::from(layout.tiles.0 * layout.tiles.1);
            let buffers = Scratch {
                retry: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("gi cuts retry"),
                    size: RETRY_HEADER + 8 * tiles,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                retry_args: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("gi cuts retry arguments"),
                    size: std::mem::size_of::<wgpu::util::DispatchIndirectArgs>() as u64,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                sight: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("gi sight"),
                    size: layout.bytes() / 4,
                    usage: wgpu::BufferUsages::STORAGE,
                    mapped_at_creation: false,
                }),
            };
            self.scratch = Some((layout, buffers));
        }
        let (_, scratch) = self.scratch.as_ref().expect("sized above");
        encoder.clear_buffer(t.stats, 0, Some(GATHER_STATS_SIZE));
        // The cuts pass sets the arguments' y and z, and counts x up from 0.
        encoder.clear_buffer(&scratch.retry, 0, Some(RETRY_HEADER));
        encoder.clear_buffer(&scratch.retry_args, 0, None);
        let cuts_group = CUTS.bind(
            device,
            &self.cuts_layout,
            &[
                ("params", t.params.into()),
                ("table", t.levels.into()),
                ("nodes", t.nodes.into()),
                ("gbuffer_normal", t.normal.into()),
                ("gbuffer_position", t.position.into()),
                ("cuts", t.cuts.into()),
                ("stats", t.stats.into()),
                ("centre_lights", t.lights.into()),
                ("retry", (&scratch.retry).into()),
                ("receiver_texels", t.receivers.into()),
            ],
        );
        let retry_args =
            RETRY_ARGS.bind(device, &self.retry_args_layout, &[("retry_dispatch", (&scratch.retry_args).into())]);
        let group = GATHER.bind(
            device,
            &self.layout,
            &[
                ("params", t.params.into()),
                ("table", t.levels.into()),
                ("gbuffer_normal", t.normal.into()),
                ("gbuffer_position", t.position.into()),
                ("irradiance_out", t.irradiance.into()),
                ("cuts", t.cuts.into()),
                ("accumulate", t.accumulate.into()),
                ("bounce_out", t.bounce.into()),
                ("receiver_texels", t.receivers.into()),
                ("sight", (&scratch.sight).into()),
            ],
        );
        let mut pass = encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi gather"), timestamp_writes: None });
        pass.set_bind_group(0, globals, &[]);
        pass.set_pipeline(&self.cuts_pipeline);
        pass.set_bind_group(1, &cuts_group, &[]);
        pass.set_bind_group(2, &retry_args, &[]);
        pass.dispatch_workgroups((layout.tiles.0 * layout.tiles.1).div_ceil(CUTS_GROUP), 1, 1);
        pass.set_pipeline(&self.retry_pipeline);
        pass.set_bind_group(1, &cuts_group, &[]);
        pass.dispatch_workgroups_indirect(&scratch.retry_args, 0);
        if let Some(depth) = t.sight_depth {
            let sight = SIGHT.bind(
                device,
                &self.sight_layout,
                &[
                    ("params", t.params.into()),
                    ("table", t.levels.into()),
                    ("gbuffer_normal", t.normal.into()),
                    ("gbuffer_position", t.position.into()),
                    ("cuts", t.cuts.into()),
                    ("receiver_texels", t.receivers.into()),
                    ("sight", (&scratch.sight).into()),
                    ("sight_depth", depth.into()),
                ],
            );
            pass.set_pipeline(&self.sight_pipeline);
            pass.set_bind_group(1, &sight, &[]);
            pass.dispatch_workgroups(layout.tiles.0, layout.tiles.1, 1);
        }
        let visibility = t.sight_depth.is_some();
        pass.set_pipeline(&self.pipelines[usize::from(visibility)]);
        pass.set_bind_group(1, &group, &[]);
        pass.dispatch_workgroups(layout.tiles.0, layout.tiles.1, 1);
        3 + u32::from(visibility)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_tile_has_room_for_its_cut_and_the_whole_top_level() {
        let small = Quadtree::new(160, 90);
        let one = CutsLayout::new((160, 90), &small);
        assert_eq!(one, CutsLayout { tiles: (20, 12), stride: 2 + 2 * CUT_MAX });
        assert_eq!(one.bytes(), 20 * 12 * (2 + 2 * CUT_MAX as u64) * 16);
        // A top level of 60×34 lights is more than a cut holds: each tile has room for all.
        let large = Quadtree::new(3840, 2160);
        assert_eq!(CutsLayout::new((8, 8), &large).stride, 2 + 2 * 60 * 34);
    }

    #[test]
    fn play_sizes_keep_their_target_and_larger_ones_shrink_to_fit_the_budget() {
        // The defaults' targets up to 2560×1440 (their flux G-buffers halved three times).
        for (size, flux) in [((160, 90), (160, 90)), ((240, 135), (240, 135)), ((320, 180), (320, 180))] {
            assert_eq!(fit_cuts_budget(size, flux), size);
        }
        // 3840×2160 at full resolution: 480×270 tiles would need 9.6 GiB.
        let (w, h) = fit_cuts_budget((3840, 2160), (3840, 2160));
        assert!(cuts_layout((w, h), (3840, 2160)).bytes() <= CUTS_BUDGET_BYTES, "{w}x{h}");
        assert!(cuts_layout((w, h), (3840, 2160)).bytes() > CUTS_BUDGET_BYTES * 9 / 10, "{w}x{h} is far smaller");
        assert!((w as f32 / h as f32 - 16.0 / 9.0).abs() < 0.05, "{w}x{h} keeps the shape");
    }
}
