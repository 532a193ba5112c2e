//! The GI's irradiance at the engine's view models (a gun in hand), which are in no G-buffer
//! and so get no indirect light from the gather: one workgroup sums a level of the first
//! bounce's flux pyramid at `ViewState::view_model_probe` into the engine's ambient cube,
//! `view_model.irradiance` (shaders/gi/view_model_probe.wgsl). Nothing is recorded without
//! view models; the cube then stays as the engine cleared it.

use std::cell::RefCell;
use std::rc::Rc;

use engine::graph::{PassContext, PassDecl, RenderPass};
use engine::passes::names::VIEW_MODEL_IRRADIANCE;
use engine::wgpu;

use crate::bindings::{bind, compute_pipeline, layout, uniform_buffer, Resource as R, Slot as S};
use crate::gpu_types::{names, Probe};
use crate::passes::{module, VIEW_MODEL_PROBE_SHADER};
use crate::pyramid::FluxPyramid;
use crate::quadtree::LEVELS;
use crate::shared::GiHandle;

/// The finest pyramid level with at most this many nodes is summed: fine enough that nodes
/// stay small against their distance to the probe, cheap enough for one workgroup.
const MAX_NODES: u32 = 4096;

pub struct ViewModelProbePass {
    handle: GiHandle,
    pyramid: Rc<RefCell<FluxPyramid>>,
    /// `Probe` of the shader: the point, the level.
    probe: wgpu::Buffer,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

impl ViewModelProbePass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        pyramid: Rc<RefCell<FluxPyramid>>,
    ) -> Self {
        let layout = layout(
            device,
            "gi view model probe",
            &[S::Uniform, S::Uniform, S::Storage { read_only: true }, S::Storage { read_only: false }],
        );
        let module = module(device, "gi view model probe", VIEW_MODEL_PROBE_SHADER);
        let pipeline =
            compute_pipeline(device, "gi view model probe", &module, "main", &[Some(globals), Some(&layout)]);
        let probe = uniform_buffer(device, "gi view model probe", 32);
        Self { handle, pyramid, probe, layout, pipeline }
    }
}

impl RenderPass for ViewModelProbePass {
    fn name(&self) -> &str {
        "gi_view_model"
    }

    fn declare(&self, d: &mut PassDecl) {
        // FLUX orders this after the pyramid, which it reads through the shared node buffer.
        if self.handle.settings().enabled {
            d.read(names::FLUX).write(VIEW_MODEL_IRRADIANCE);
        }
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let Some(point) = ctx.frame.view.view_model_probe() else {
            return;
        };
        let pyramid = self.pyramid.borrow();
        let buffers = pyramid.buffers();
        let level = (0..LEVELS)
            .find(|&l| {
                let (w, h) = buffers.tree.size(l);
                w * h <= MAX_NODES
            })
            .unwrap_or(LEVELS - 1);
        let probe = Probe { position: [point.x, point.y, point.z, 0.0], level: [level, 0, 0, 0] };
        ctx.gpu.queue.write_buffer(&self.probe, 0, bytemuck::bytes_of(&probe));
        let group = bind(
            &ctx.gpu.device,
            &self.layout,
            &[
                R::Buffer(&self.probe),
                R::Buffer(&buffers.levels),
                R::Buffer(&buffers.nodes),
                R::Buffer(ctx.buffer(VIEW_MODEL_IRRADIANCE)),
            ],
        );
        let mut pass = ctx.encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("gi view model probe"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.dispatch_workgroups(1, 1, 1);
        self.handle.0.borrow_mut().stats.dispatches += 1;
    }
}
