//! The flux pyramid: the lamp view's reflected flux per texel, merged up a quadtree into
//! reflection lights of every size. Two dispatches whatever the resolution (levels 0–3, then
//! 4–6, each reduced in workgroup memory). Used once per bounce.

use engine::wgpu;

use crate::bindings::{bind, compute_pipeline, layout, uniform_buffer, Resource as R, Slot as S};
use crate::gpu_types::{Levels, NODE_SIZE};
use crate::passes::{module, PYRAMID_SHADER};
use crate::quadtree::Quadtree;

/// The resources one build reads and writes.
pub struct PyramidInputs<'a> {
    pub albedo: &'a wgpu::TextureView,
    pub normal: &'a wgpu::TextureView,
    pub position: &'a wgpu::TextureView,
    /// Previous bounce's irradiance (any float texture when building from the lamp).
    pub previous: &'a wgpu::TextureView,
    pub flux: &'a wgpu::TextureView,
    pub flux_view: &'a wgpu::TextureView,
}

/// Everything that depends on the lamp view's size.
pub struct PyramidBuffers {
    pub size: (u32, u32),
    pub tree: Quadtree,
    pub nodes: wgpu::Buffer,
    /// The level table (offset, width, height per level), a uniform.
    pub levels: wgpu::Buffer,
}

pub struct FluxPyramid {
    /// The GiParams this pyramid's passes read (its `source` says lamp or bounce).
    params: wgpu::Buffer,
    layout: wgpu::BindGroupLayout,
    flux: wgpu::ComputePipeline,
    reduce: wgpu::ComputePipeline,
    buffers: Option<PyramidBuffers>,
}

impl FluxPyramid {
    pub fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout, params: wgpu::Buffer) -> Self {
        let layout = layout(
            device,
            "gi pyramid",
            &[
                S::Texture,
                S::Texture,
                S::Texture,
                S::Uniform,
                S::Uniform,
                S::Storage { read_only: false },
                S::StorageTexture(wgpu::TextureFormat::Rgba32Float),
                S::StorageTexture(wgpu::TextureFormat::Rgba16Float),
                S::Texture,
            ],
        );
        let module = module(device, "gi pyramid", PYRAMID_SHADER);
        let layouts = [Some(globals), Some(&layout)];
        Self {
            flux: compute_pipeline(device, "gi flux", &module, "flux", &layouts),
            reduce: compute_pipeline(device, "gi reduce", &module, "reduce", &layouts),
            params,
            layout,
            buffers: None,
        }
    }

    /// Sizes the node buffer for a lamp view of `size`.
    pub fn prepare(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, size: (u32, u32)) {
        if self.buffers.as_ref().is_some_and(|b| b.size == size) {
            return;
        }
        let tree = Quadtree::new(size.0, size.1);
        let nodes = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("gi nodes"),
            size: tree.node_count() as u64 * NODE_SIZE,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let levels = uniform_buffer(device, "gi levels", std::mem::size_of::<Levels>() as u64);
        queue.write_buffer(&levels, 0, bytemuck::bytes_of(&Levels { levels: tree.table() }));
        self.buffers = Some(PyramidBuffers { size, tree, nodes, levels });
    }

    pub fn buffers(&self) -> &PyramidBuffers {
        self.buffers.as_ref().expect("prepare() before use")
    }

    /// Records the flux and the reduction; returns the number of dispatches.
    pub fn record(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        globals: &wgpu::BindGroup,
        t: &PyramidInputs<'_>,
    ) -> u32 {
        let b = self.buffers();
        let group = bind(
            device,
            &self.layout,
            &[
                R::View(t.albedo),
                R::View(t.normal),
                R::View(t.position),
                R::Buffer(&self.params),
                R::Buffer(&b.levels),
                R::Buffer(&b.nodes),
                R::View(t.flux),
                R::View(t.flux_view),
                R::View(t.previous),
            ],
        );
        let mut pass = encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi pyramid"), timestamp_writes: None });
        pass.set_bind_group(0, globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.set_pipeline(&self.flux);
        pass.dispatch_workgroups(b.size.0.div_ceil(8), b.size.1.div_ceil(8), 1);
        // Each workgroup of the second dispatch reduces 8×8 nodes of level 3.
        let (w3, h3) = b.tree.size(3);
        pass.set_pipeline(&self.reduce);
        pass.dispatch_workgroups(w3.div_ceil(8), h3.div_ceil(8), 1);
        2
    }
}
