//! Flux G-buffer → reduction → reflection lights: the compute half of the GI, a fixed number of
//! dispatches (1 + one per mip level + 2) whatever the light count. Used once per bounce.

use engine::scene::IntensityDistribution;
use engine::wgpu;

use crate::bindings::{bind, compute_pipeline, layout, uniform_buffer, Resource as R, Slot as S};
use crate::distribution_table::{self, Slot};
use crate::gpu_types::{LIGHTS_PER_SLOT, NODE_SIZE};
use crate::passes::{module, BUILD_SHADER, FLUX_SHADER, REDUCE_SHADER};
use crate::quadtree::Quadtree;

/// The light buffer holds every slot's worst case; slots never exceed max(budget, 4096)
/// (the coarsest level of a 4K view has fewer nodes).
pub fn light_capacity(budget: u32) -> u32 {
    budget.max(4096) * LIGHTS_PER_SLOT
}

/// What the distribution table depends on.
#[derive(Clone, PartialEq)]
pub struct TableKey {
    pub size: (u32, u32),
    pub budget: u32,
    pub distribution: IntensityDistribution,
    pub fov_y: f32,
    pub aspect: f32,
}

/// The resources one build reads and writes.
pub struct BuildTargets<'a> {
    pub albedo: &'a wgpu::TextureView,
    pub normal: &'a wgpu::TextureView,
    pub position: &'a wgpu::TextureView,
    /// Previous bounce's irradiance (any texture when building from the lamp).
    pub previous: &'a wgpu::TextureView,
    pub flux: &'a wgpu::TextureView,
    pub flux_view: &'a wgpu::TextureView,
    pub lights: &'a wgpu::Buffer,
    pub args: &'a wgpu::Buffer,
}

/// Everything that depends on the flux G-buffer's size.
struct Sized {
    size: (u32, u32),
    tree: Quadtree,
    nodes: wgpu::Buffer,
    /// The frame's absolute volume cutoff, computed on the GPU.
    cutoff: wgpu::Buffer,
    levels: wgpu::Buffer,
    reduce_groups: Vec<wgpu::BindGroup>,
}

pub struct LightBuilder {
    /// The GiParams this builder's passes read (its `source` says lamp or bounce).
    params: wgpu::Buffer,
    flux_layout: wgpu::BindGroupLayout,
    reduce_layout: wgpu::BindGroupLayout,
    build_layout: wgpu::BindGroupLayout,
    flux: wgpu::ComputePipeline,
    reduce: wgpu::ComputePipeline,
    reset: wgpu::ComputePipeline,
    build: wgpu::ComputePipeline,
    sized: Option<Sized>,
    table: Option<(TableKey, wgpu::Buffer, u32)>,
}

impl LightBuilder {
    pub fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout, params: wgpu::Buffer) -> Self {
        let flux_layout = layout(
            device,
            "gi flux",
            &[
                S::Texture,
                S::Texture,
                S::Texture,
                S::Uniform,
                S::Storage { read_only: false },
                S::StorageTexture(wgpu::TextureFormat::Rgba32Float),
                S::StorageTexture(wgpu::TextureFormat::Rgba16Float),
                S::Texture,
            ],
        );
        let reduce_layout = layout(device, "gi reduce", &[S::Uniform, S::Uniform, S::Storage { read_only: false }]);
        let mut build_slots =
            vec![S::Uniform, S::Uniform, S::Storage { read_only: true }, S::Storage { read_only: true }];
        build_slots.extend([S::Storage { read_only: false }; 3]);
        let build_layout = layout(device, "gi build lights", &build_slots);
        let flux_module = module(device, "gi flux", FLUX_SHADER);
        let reduce_module = module(device, "gi reduce", REDUCE_SHADER);
        let build_module = module(device, "gi build lights", BUILD_SHADER);
        Self {
            flux: compute_pipeline(device, "gi flux", &flux_module, "main", &[Some(globals), Some(&flux_layout)]),
            reduce: compute_pipeline(
                device,
                "gi reduce",
                &reduce_module,
                "main",
                &[Some(globals), Some(&reduce_layout)],
            ),
            reset: compute_pipeline(device, "gi reset", &build_module, "reset", &[Some(globals), Some(&build_layout)]),
            build: compute_pipeline(device, "gi build", &build_module, "main", &[Some(globals), Some(&build_layout)]),
            params,
            flux_layout,
            reduce_layout,
            build_layout,
            sized: None,
            table: None,
        }
    }

    /// Sizes the quadtree and (re)builds the distribution table when what it depends on changed.
    pub fn prepare(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, key: TableKey) {
        if self.sized.as_ref().is_none_or(|s| s.size != key.size) {
            self.sized = Some(self.sized_state(device, queue, key.size));
        }
        if self.table.as_ref().is_some_and(|(k, _, _)| *k == key) {
            return;
        }
        let tree = &self.sized.as_ref().expect("sized above").tree;
        let (tw, th, t) = engine::headlamp::distribution_texels(&key.distribution, key.fov_y, key.aspect);
        let tan = ((key.fov_y * 0.5).tan() * key.aspect, (key.fov_y * 0.5).tan());
        let importance = distribution_table::lamp_importance(key.size.0, key.size.1, tan, &t, tw, th);
        let slots: Vec<Slot> = distribution_table::build(tree, &importance, key.budget);
        let packed: Vec<[u32; 2]> = slots.iter().map(Slot::packed).collect();
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("gi distribution table"),
            size: (packed.len().max(1) * 8) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(&buffer, 0, bytemuck::cast_slice(&packed));
        self.table = Some((key, buffer, slots.len() as u32));
    }

    fn sized_state(&self, device: &wgpu::Device, queue: &wgpu::Queue, size: (u32, u32)) -> Sized {
        let tree = Quadtree::new(size.0, size.1);
        let nodes = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("gi nodes"),
            size: tree.node_count() as u64 * NODE_SIZE,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let cutoff = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("gi volume cutoff"),
            size: 16,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let mut table = [[0u32; 4]; 16];
        for (i, &(offset, w, h)) in tree.levels.iter().enumerate() {
            table[i] = [offset, w, h, 0];
        }
        let levels = uniform_buffer(device, "gi levels", 256);
        queue.write_buffer(&levels, 0, bytemuck::cast_slice(&table));
        let reduce_groups = (1..tree.levels.len())
            .map(|l| {
                let (src, dst) = (tree.levels[l - 1], tree.levels[l]);
                let level = [src.0, dst.0, src.1, src.2, dst.1, dst.2, 0, 0];
                let uniform = uniform_buffer(device, "gi level", 32);
                queue.write_buffer(&uniform, 0, bytemuck::cast_slice(&level));
                bind(device, &self.reduce_layout, &[R::Buffer(&self.params), R::Buffer(&uniform), R::Buffer(&nodes)])
            })
            .collect();
        Sized { size, tree, nodes, cutoff, levels, reduce_groups }
    }

    /// Entries of the current distribution table.
    pub fn slot_count(&self) -> u32 {
        self.table.as_ref().map_or(0, |(_, _, n)| *n)
    }

    /// Records flux, reduction and light building; returns the number of dispatches.
    pub fn record(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        globals: &wgpu::BindGroup,
        t: &BuildTargets<'_>,
    ) -> u32 {
        let sized = self.sized.as_ref().expect("prepare() before record()");
        let (_, slots, slot_count) = self.table.as_ref().expect("prepare() before record()");
        let flux_group = bind(
            device,
            &self.flux_layout,
            &[
                R::View(t.albedo),
                R::View(t.normal),
                R::View(t.position),
                R::Buffer(&self.params),
                R::Buffer(&sized.nodes),
                R::View(t.flux),
                R::View(t.flux_view),
                R::View(t.previous),
            ],
        );
        let build_group = bind(
            device,
            &self.build_layout,
            &[
                R::Buffer(&self.params),
                R::Buffer(&sized.levels),
                R::Buffer(&sized.nodes),
                R::Buffer(slots),
                R::Buffer(t.lights),
                R::Buffer(t.args),
                R::Buffer(&sized.cutoff),
            ],
        );
        let size = sized.size;
        let mut pass = encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi lights"), timestamp_writes: None });
        pass.set_bind_group(0, globals, &[]);
        pass.set_pipeline(&self.flux);
        pass.set_bind_group(1, &flux_group, &[]);
        pass.dispatch_workgroups(size.0.div_ceil(8), size.1.div_ceil(8), 1);
        pass.set_pipeline(&self.reduce);
        for (l, group) in sized.reduce_groups.iter().enumerate() {
            let (w, h) = sized.tree.size(l as u32 + 1);
            pass.set_bind_group(1, group, &[]);
            pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
        }
        pass.set_bind_group(1, &build_group, &[]);
        pass.set_pipeline(&self.reset);
        pass.dispatch_workgroups(1, 1, 1);
        pass.set_pipeline(&self.build);
        pass.dispatch_workgroups(slot_count.div_ceil(64).max(1), 1, 1);
        3 + sized.reduce_groups.len() as u32
    }
}
