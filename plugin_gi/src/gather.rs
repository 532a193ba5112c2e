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
        let module = module(device, "gi gather", GATHER_SHADER);
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
