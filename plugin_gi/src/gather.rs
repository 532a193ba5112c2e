//! The gather: each pixel of the indirect target sums the irradiance of the pyramid's lights,
//! an 8×8 tile sharing one cut through the pyramid. Three dispatches: the cuts, one invocation
//! a tile, then the few tiles whose cut filled up walked again side by side (an indirect
//! dispatch; both shaders/gi/cuts.wgsl), then the sum, one workgroup a tile
//! (shaders/gi/gather.wgsl). The cuts buffer is a graph resource (see [`cuts_desc`]); the
//! bands' small buffers are this gather's own scratch.

use engine::graph::BufferDesc;
use engine::wgpu;
use engine::wgpu::util::DeviceExt;

use crate::bindings::{bind, compute_pipeline, layout, Resource as R, Slot as S};
use crate::gpu_types::{Band, GATHER_STATS_SIZE, RETRY_HEADER};
use crate::quadtree::Quadtree;
use crate::shader::module;

pub const CUTS_SHADER: &str = include_str!("../../shaders/gi/cuts.wgsl");
pub const GATHER_SHADER: &str = include_str!("../../shaders/gi/gather.wgsl");

/// What one gather reads and writes.
pub struct GatherTargets<'a> {
    /// The GiParams of this bounce, the pyramid's level table and nodes.
    pub params: &'a wgpu::Buffer,
    pub levels: &'a wgpu::Buffer,
    pub nodes: &'a wgpu::Buffer,
    /// Room for one band's cuts ([`cuts_desc`]).
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
}

pub struct Gather {
    cuts_layout: wgpu::BindGroupLayout,
    cuts_pipeline: wgpu::ComputePipeline,
    /// The indirect dispatch's arguments, written by the cuts pass (its group 2).
    retry_args_layout: wgpu::BindGroupLayout,
    retry_pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    /// Per band of the last indirect target and pyramid (see [`Bands`]), its first row (a
    /// uniform) and its full tiles.
    bands: Option<(Bands, Vec<BandBuffers>)>,
}

/// What one band's dispatches share besides the cuts.
struct BandBuffers {
    /// The band's first row and its number of rows.
    first: wgpu::Buffer,
    /// The tiles whose first walk filled the cut (a count, then a slot and a ratio each).
    retry: wgpu::Buffer,
    /// The workgroups of the retry dispatch, as its indirect arguments.
    retry_args: wgpu::Buffer,
}

/// Receivers per tile side (`CUT_TILE` in gi_common.wgsl).
pub const TILE: u32 = 8;

/// The most lights a tile's cut holds (`CUT_MAX` in gi_common.wgsl), unless the pyramid's top
/// level has more: every one of those is in every cut.
pub const CUT_MAX: u32 = 1536;

/// Invocations (tiles) per workgroup of the cuts pass.
const CUTS_GROUP: u32 = 8;

/// At most this much memory holds the cuts: a larger target is gathered a band of tile rows
/// at a time (two dispatches a band), so no setting can ask for an unbounded buffer. Below
/// the 128 MiB storage binding every wgpu device allows.
const CUTS_BUDGET_BYTES: u64 = 32 << 20;

/// The bands an indirect target of `size` is gathered in, over a pyramid on a flux G-buffer
/// of `flux_size`.
pub fn bands(size: (u32, u32), flux_size: (u32, u32)) -> Bands {
    Bands::new(size, &Quadtree::new(flux_size.0, flux_size.1), CUTS_BUDGET_BYTES)
}

/// The cuts buffer of one band.
pub fn cuts_desc(bands: &Bands) -> BufferDesc {
    BufferDesc { size: bands.bytes(), usage: wgpu::BufferUsages::STORAGE }
}

/// How the tiles of an indirect target are gathered: `rows` tile rows at a time, `count`
/// times, each tile's cut `stride` vec4s (its counts, its centre, then one a light with room
/// for the classes' padding: see gi_common.wgsl).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bands {
    pub tiles: (u32, u32),
    pub stride: u32,
    pub rows: u32,
    pub count: u32,
}

impl Bands {
    /// For an indirect target of `size` over `tree`, with at most `budget` bytes of cuts.
    pub fn new(size: (u32, u32), tree: &Quadtree, budget: u64) -> Self {
        let (w, h) = tree.size(crate::quadtree::TOP);
        let tiles = (size.0.div_ceil(TILE), size.1.div_ceil(TILE));
        let stride = 2 + 2 * CUT_MAX.max(w * h);
        let row_bytes = tiles.0 as u64 * stride as u64 * 16;
        let rows = (budget / row_bytes).clamp(1, tiles.1.max(1) as u64) as u32;
        Self { tiles, stride, rows, count: tiles.1.div_ceil(rows) }
    }

    /// Bytes of the cuts buffer: one band's tiles.
    pub fn bytes(&self) -> u64 {
        self.tiles.0 as u64 * self.rows as u64 * self.stride as u64 * 16
    }
}

impl Gather {
    pub fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout) -> Self {
        let storage = |read_only| S::Storage { read_only };
        let cuts_layout = layout(
            device,
            "gi cuts",
            &[
                S::Uniform,
                S::Uniform,
                storage(true),
                S::Texture,
                S::Texture,
                storage(false),
                storage(false),
                storage(false),
                S::Uniform,
                storage(false),
            ],
        );
        let retry_args_layout = layout(device, "gi cuts retry arguments", &[storage(false)]);
        let layout = layout(
            device,
            "gi gather",
            &[
                S::Uniform,
                S::Uniform,
                S::Texture,
                S::Texture,
                S::StorageTexture(wgpu::TextureFormat::Rgba32Float),
                storage(true),
                S::Texture,
                S::StorageTexture(wgpu::TextureFormat::Rgba32Float),
                S::Uniform,
            ],
        );
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
        let module = module(device, "gi gather", GATHER_SHADER);
        let pipeline = compute_pipeline(device, "gi gather", &module, "main", &[Some(globals), Some(&layout)]);
        Self { cuts_layout, cuts_pipeline, retry_args_layout, retry_pipeline, layout, pipeline, bands: None }
    }

    /// Records the gather in `bands` (from [`bands`], as `t.cuts` was sized); returns the
    /// number of dispatches.
    pub fn record(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        globals: &wgpu::BindGroup,
        bands: Bands,
        t: &GatherTargets<'_>,
    ) -> u32 {
        if self.bands.as_ref().is_none_or(|(b, _)| *b != bands) {
            let tiles_per_band = u64::from(bands.tiles.0 * bands.rows);
            let per_band = (0..bands.count)
                .map(|i| BandBuffers {
                    first: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some("gi band"),
                        contents: bytemuck::bytes_of(&Band {
                            first_row: i * bands.rows,
                            rows: bands.rows,
                            pad: [0; 2],
                        }),
                        usage: wgpu::BufferUsages::UNIFORM,
                    }),
                    retry: device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("gi cuts retry"),
                        size: RETRY_HEADER + 8 * tiles_per_band,
                        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    }),
                    retry_args: device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("gi cuts retry arguments"),
                        size: std::mem::size_of::<wgpu::util::DispatchIndirectArgs>() as u64,
                        usage: wgpu::BufferUsages::STORAGE
                            | wgpu::BufferUsages::INDIRECT
                            | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    }),
                })
                .collect();
            self.bands = Some((bands, per_band));
        }
        let (_, per_band) = self.bands.as_ref().expect("sized above");
        let cuts = t.cuts;
        encoder.clear_buffer(t.stats, 0, Some(GATHER_STATS_SIZE));
        for band in per_band {
            // The cuts pass sets the arguments' y and z, and counts x up from 0.
            encoder.clear_buffer(&band.retry, 0, Some(RETRY_HEADER));
            encoder.clear_buffer(&band.retry_args, 0, None);
        }
        let mut pass = encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi gather"), timestamp_writes: None });
        pass.set_bind_group(0, globals, &[]);
        for band in per_band {
            let first = &band.first;
            let cuts_group = bind(
                device,
                &self.cuts_layout,
                &[
                    R::Buffer(t.params),
                    R::Buffer(t.levels),
                    R::Buffer(t.nodes),
                    R::View(t.normal),
                    R::View(t.position),
                    R::Buffer(cuts),
                    R::Buffer(t.stats),
                    R::Buffer(t.lights),
                    R::Buffer(first),
                    R::Buffer(&band.retry),
                ],
            );
            let retry_args = bind(device, &self.retry_args_layout, &[R::Buffer(&band.retry_args)]);
            let group = bind(
                device,
                &self.layout,
                &[
                    R::Buffer(t.params),
                    R::Buffer(t.levels),
                    R::View(t.normal),
                    R::View(t.position),
                    R::View(t.irradiance),
                    R::Buffer(cuts),
                    R::View(t.accumulate),
                    R::View(t.bounce),
                    R::Buffer(first),
                ],
            );
            pass.set_pipeline(&self.cuts_pipeline);
            pass.set_bind_group(1, &cuts_group, &[]);
            pass.set_bind_group(2, &retry_args, &[]);
            pass.dispatch_workgroups((bands.tiles.0 * bands.rows).div_ceil(CUTS_GROUP), 1, 1);
            pass.set_pipeline(&self.retry_pipeline);
            pass.set_bind_group(1, &cuts_group, &[]);
            pass.dispatch_workgroups_indirect(&band.retry_args, 0);
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(1, &group, &[]);
            pass.dispatch_workgroups(bands.tiles.0, bands.rows, 1);
        }
        3 * bands.count
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shaders_share_the_cut_layout() {
        let common = crate::shader::INCLUDES[0].1;
        assert!(common.contains(&format!("const CUT_TILE: u32 = {TILE}u;")), "gi_common.wgsl's CUT_TILE is {TILE}");
        assert!(common.contains(&format!("const CUT_MAX: u32 = {CUT_MAX}u;")), "gi_common.wgsl's CUT_MAX is {CUT_MAX}");
    }

    #[test]
    fn every_tile_has_room_for_its_cut_and_the_whole_top_level() {
        let small = Quadtree::new(160, 90);
        let one = Bands::new((160, 90), &small, CUTS_BUDGET_BYTES);
        assert_eq!(one, Bands { tiles: (20, 12), stride: 2 + 2 * CUT_MAX, rows: 12, count: 1 });
        assert_eq!(one.bytes(), 20 * 12 * (2 + 2 * CUT_MAX as u64) * 16);
        // A top level of 60×34 lights is more than a cut holds: each tile has room for all.
        let large = Quadtree::new(3840, 2160);
        assert_eq!(Bands::new((8, 8), &large, CUTS_BUDGET_BYTES).stride, 2 + 2 * 60 * 34);
    }

    #[test]
    fn a_large_target_is_gathered_in_bands_within_the_budget() {
        // 3840×2160 at full resolution: 480×270 tiles, 4,082 vec4s each.
        let tree = Quadtree::new(3840, 2160);
        let bands = Bands::new((3840, 2160), &tree, CUTS_BUDGET_BYTES);
        assert!(bands.bytes() <= CUTS_BUDGET_BYTES, "{bands:?}");
        assert!(bands.rows * bands.count >= 270 && (bands.count - 1) * bands.rows < 270, "{bands:?}");
        // Even a budget too small for one row gathers a row at a time.
        let tiny = Bands::new((3840, 2160), &tree, 1);
        assert_eq!((tiny.rows, tiny.count), (1, 270));
    }
}
