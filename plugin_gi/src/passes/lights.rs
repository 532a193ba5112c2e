//! Flux G-buffer → reduction → reflection lights: the compute half of the GI, one graph pass of
//! a fixed number of dispatches (1 + one per mip level + 2) whatever the light count.

use std::rc::Rc;

use engine::graph::{BufferDesc, PassContext, PassDecl, RenderPass, SizeRule, TextureDesc};
use engine::passes::names::{GBUFFER_ALBEDO, GBUFFER_NORMAL, GBUFFER_POSITION};
use engine::scene::IntensityDistribution;
use engine::wgpu;

use crate::bindings::{bind, compute_pipeline, layout, uniform_buffer, Resource as R, Slot as S};
use crate::distribution_table::{self, Slot};
use crate::gpu_types::{names, GiParams, DRAW_ARGS_SIZE, LIGHTS_PER_SLOT, NODE_SIZE};
use crate::quadtree::Quadtree;
use crate::shared::{GiHandle, GiStats, GpuShared};

pub const FLUX_SHADER: &str = include_str!("../../../shaders/gi/flux.wgsl");
pub const REDUCE_SHADER: &str = include_str!("../../../shaders/gi/reduce.wgsl");
pub const BUILD_SHADER: &str = include_str!("../../../shaders/gi/build_lights.wgsl");

/// The light buffer holds every slot's worst case; slots never exceed max(budget, 4096)
/// (the coarsest level of a 4K view has fewer nodes).
pub fn light_capacity(budget: u32) -> u32 {
    budget.max(4096) * LIGHTS_PER_SLOT
}

#[derive(Clone, PartialEq)]
struct TableKey {
    size: (u32, u32),
    budget: u32,
    distribution: IntensityDistribution,
    fov_y: f32,
    aspect: f32,
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

pub struct LightsPass {
    handle: GiHandle,
    gpu: Rc<GpuShared>,
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

impl LightsPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gpu: Rc<GpuShared>,
    ) -> Self {
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
            ],
        );
        let reduce_layout = layout(device, "gi reduce", &[S::Uniform, S::Uniform, S::Storage { read_only: false }]);
        let build_layout = layout(
            device,
            "gi build lights",
            &[
                S::Uniform,
                S::Uniform,
                S::Storage { read_only: true },
                S::Storage { read_only: true },
                S::Storage { read_only: false },
                S::Storage { read_only: false },
                S::Storage { read_only: false },
            ],
        );
        let flux_module = super::module(device, "gi flux", FLUX_SHADER);
        let reduce_module = super::module(device, "gi reduce", REDUCE_SHADER);
        let build_module = super::module(device, "gi build lights", BUILD_SHADER);
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
            flux_layout,
            reduce_layout,
            build_layout,
            handle,
            gpu,
            sized: None,
            table: None,
        }
    }

    fn ensure_sized(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, size: (u32, u32)) {
        if self.sized.as_ref().is_some_and(|s| s.size == size) {
            return;
        }
        let tree = Quadtree::new(size.0, size.1);
        let nodes = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("gi nodes"),
            size: tree.node_count() as u64 * NODE_SIZE,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
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
                bind(
                    device,
                    &self.reduce_layout,
                    &[R::Buffer(&self.gpu.params), R::Buffer(&uniform), R::Buffer(&nodes)],
                )
            })
            .collect();
        self.sized = Some(Sized { size, tree, nodes, cutoff, levels, reduce_groups });
    }

    /// Rebuilds the distribution table when the resolution, budget or lamp profile changed.
    fn ensure_table(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, key: TableKey) {
        if self.table.as_ref().is_some_and(|(k, _, _)| *k == key) {
            return;
        }
        let tree = &self.sized.as_ref().expect("sized first").tree;
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
        log::debug!("gi: distribution table of {} slots for {:?}", slots.len(), key.size);
        self.table = Some((key, buffer, slots.len() as u32));
    }
}

impl RenderPass for LightsPass {
    fn name(&self) -> &str {
        "gi_lights"
    }

    fn declare(&self, d: &mut PassDecl) {
        let budget = self.handle.settings().light_budget;
        let storage =
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC;
        let texture = |format| TextureDesc { format, size: SizeRule::ViewScaled(1.0), usage: storage, mip_levels: 1 };
        let buffer = |size, usage| BufferDesc {
            size,
            usage: usage | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        };
        d.read(GBUFFER_ALBEDO)
            .read(GBUFFER_NORMAL)
            .read(GBUFFER_POSITION)
            .create_texture(names::FLUX, texture(wgpu::TextureFormat::Rgba32Float))
            .create_texture(names::FLUX_VIEW, texture(wgpu::TextureFormat::Rgba16Float))
            .create_buffer(names::LIGHTS, buffer(light_capacity(budget) as u64 * 48, wgpu::BufferUsages::empty()))
            .create_buffer(names::DRAW_ARGS, buffer(DRAW_ARGS_SIZE, wgpu::BufferUsages::INDIRECT));
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let (device, queue) = (&ctx.gpu.device, &ctx.gpu.queue);
        let settings = self.handle.settings();
        let size = ctx.frame.size;
        let lamp = ctx.frame.lamp;
        let tan_y = (lamp.fov_y * 0.5).tan();
        let indirect = SizeRule::ViewScaled(settings.resolution_scale).resolve(size);
        self.gpu.write_params(
            queue,
            &GiParams {
                flux_size: [size.0, size.1],
                indirect_size: [indirect.0, indirect.1],
                lamp_tan: [tan_y * lamp.aspect, tan_y],
                lamp_power: ctx.frame.view.headlamp.profile.power,
                cos_merge: settings.merge_normal_deg.to_radians().cos(),
                merge_distance: settings.merge_distance,
                cutoff: settings.cutoff,
                d_min: settings.d_min,
                pad: 0.0,
            },
        );
        self.ensure_sized(device, queue, size);
        let key = TableKey {
            size,
            budget: settings.light_budget,
            distribution: ctx.frame.view.headlamp.profile.distribution.clone(),
            fov_y: lamp.fov_y,
            aspect: lamp.aspect,
        };
        self.ensure_table(device, queue, key);
        let sized = self.sized.as_ref().expect("sized above");
        let (_, slots, slot_count) = self.table.as_ref().expect("table above");

        let flux_group = bind(
            device,
            &self.flux_layout,
            &[
                R::View(ctx.view(GBUFFER_ALBEDO)),
                R::View(ctx.view(GBUFFER_NORMAL)),
                R::View(ctx.view(GBUFFER_POSITION)),
                R::Buffer(&self.gpu.params),
                R::Buffer(&sized.nodes),
                R::View(ctx.view(names::FLUX)),
                R::View(ctx.view(names::FLUX_VIEW)),
            ],
        );
        let build_group = bind(
            device,
            &self.build_layout,
            &[
                R::Buffer(&self.gpu.params),
                R::Buffer(&sized.levels),
                R::Buffer(&sized.nodes),
                R::Buffer(slots),
                R::Buffer(ctx.buffer(names::LIGHTS)),
                R::Buffer(ctx.buffer(names::DRAW_ARGS)),
                R::Buffer(&sized.cutoff),
            ],
        );

        let mut pass = ctx
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi lights"), timestamp_writes: None });
        pass.set_bind_group(0, ctx.frame.globals, &[]);
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
        drop(pass);

        let mut shared = self.handle.0.borrow_mut();
        shared.stats = GiStats {
            slots: *slot_count,
            light_capacity: light_capacity(settings.light_budget),
            dispatches: 3 + sized.reduce_groups.len() as u32,
            draws: shared.stats.draws,
        };
    }
}
