//! The gather: each pixel of the indirect target sums the irradiance of the pyramid's lights,
//! an 8×8 tile sharing one cut through the pyramid (shaders/gi/gather.wgsl). One dispatch.

use engine::wgpu;

use crate::bindings::{bind, compute_pipeline, layout, Resource as R, Slot as S};
use crate::gpu_types::GATHER_STATS_SIZE;
use crate::passes::{module, GATHER_SHADER};
use crate::pyramid::PyramidBuffers;

/// What one gather reads and writes.
pub struct GatherTargets<'a> {
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
    params: wgpu::Buffer,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

/// Receivers per tile side.
pub const TILE: u32 = 8;

/// The most lights a tile's cut holds, and what the gather's workgroup memory holds besides
/// the cut and its two fronts (4 bytes per light each): the light batch, the receivers,
/// their partial sums and a few counters.
const CUT_MAX: u32 = 1536;
const WORKGROUP_FIXED_BYTES: u32 = 6400;

/// The gather's source with its cut as large as the device's workgroup memory allows, up to
/// [`CUT_MAX`] (a larger cut splits lights as finely as `split_ratio` asks in more tiles).
pub fn sized_to(source: &str, limits: wgpu::Limits) -> String {
    let cut = cut_capacity(limits.max_compute_workgroup_storage_size);
    source.replace(&format!("const CUT_MAX: u32 = {CUT_MAX}u;"), &format!("const CUT_MAX: u32 = {cut}u;"))
}

/// Lights per cut for `bytes` of workgroup memory: a multiple of 64, from 256 to [`CUT_MAX`].
pub fn cut_capacity(bytes: u32) -> u32 {
    (bytes.saturating_sub(WORKGROUP_FIXED_BYTES) / 12 / 64 * 64).clamp(256, CUT_MAX)
}

impl Gather {
    pub fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout, params: wgpu::Buffer) -> Self {
        let storage = |read_only| S::Storage { read_only };
        let layout = layout(
            device,
            "gi gather",
            &[
                S::Uniform,
                S::Uniform,
                storage(true),
                S::Texture,
                S::Texture,
                S::StorageTexture(wgpu::TextureFormat::Rgba32Float),
                storage(false),
                storage(false),
                S::Texture,
                S::StorageTexture(wgpu::TextureFormat::Rgba32Float),
            ],
        );
        let module = module(device, "gi gather", &sized_to(GATHER_SHADER, device.limits()));
        let pipeline = compute_pipeline(device, "gi gather", &module, "main", &[Some(globals), Some(&layout)]);
        Self { params, layout, pipeline }
    }

    /// Records the gather into an indirect target of `size`; returns the number of dispatches.
    pub fn record(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        globals: &wgpu::BindGroup,
        pyramid: &PyramidBuffers,
        size: (u32, u32),
        t: &GatherTargets<'_>,
    ) -> u32 {
        let group = bind(
            device,
            &self.layout,
            &[
                R::Buffer(&self.params),
                R::Buffer(&pyramid.levels),
                R::Buffer(&pyramid.nodes),
                R::View(t.normal),
                R::View(t.position),
                R::View(t.irradiance),
                R::Buffer(t.stats),
                R::Buffer(t.lights),
                R::View(t.accumulate),
                R::View(t.bounce),
            ],
        );
        encoder.clear_buffer(t.stats, 0, Some(GATHER_STATS_SIZE));
        let mut pass = encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi gather"), timestamp_writes: None });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.dispatch_workgroups(size.0.div_ceil(TILE), size.1.div_ceil(TILE), 1);
        1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cut_fits_the_workgroup_memory() {
        assert_eq!(cut_capacity(16384), 832);
        assert_eq!(cut_capacity(32768), CUT_MAX);
        assert_eq!(cut_capacity(0), 256);
        let shader = crate::passes::GATHER_SHADER;
        assert!(shader.contains(&format!("const CUT_MAX: u32 = {CUT_MAX}u;")), "gather.wgsl's CUT_MAX is {CUT_MAX}");
        let small = sized_to(shader, wgpu::Limits { max_compute_workgroup_storage_size: 16384, ..Default::default() });
        assert!(small.contains("const CUT_MAX: u32 = 832u;"));
    }
}
