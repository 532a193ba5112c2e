//! The GI's irradiance at the engine's view models (a gun in hand), which are in no G-buffer
//! and so get no indirect light from the gather: one workgroup sums a level of the first
//! bounce's flux pyramid at `ViewState::view_model_probe` into the engine's ambient cube,
//! `view_model.irradiance` (shaders/gi/view_model_irradiance.wgsl). Nothing is recorded without
//! view models; the cube then stays as the engine cleared it.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::graph::{Buffer, Handle, PassContext, PassDecl, Read, RenderPass, Write};
use engine::wgpu;

use crate::gpu_types::Probe;
use crate::pipelines::{compute_pipeline, uniform_buffer};
use crate::quadtree::{Quadtree, LEVELS};
use crate::resources::GiResources;
use crate::shared::GiHandle;

pub const SHADER: &str = include_str!("../../../shaders/gi/view_model_irradiance.wgsl");

/// The probe's group 1 (view_model_irradiance.wgsl): where it is, the pyramid, the cube out.
pub const PROBE: Group = Group::new(
    "gi view model irradiance",
    &[B::uniform("probe"), B::uniform("levels"), B::storage("nodes"), B::storage_rw("ambient_cube")],
);

/// Where its group is declared.
pub const BINDINGS: &[WgslGroup] = &[WgslGroup::new("gi/view_model_irradiance.wgsl", 1, &PROBE)];

/// The finest pyramid level with at most this many nodes is summed: fine enough that nodes
/// stay small against their distance to the probe, cheap enough for one workgroup.
const MAX_NODES: u32 = 4096;

pub struct ViewModelIrradiancePass {
    handle: GiHandle,
    gi: GiResources,
    irradiance: Handle<Buffer>,
    /// The probe's point and level: this pass's own uniform, written once a frame.
    probe: wgpu::Buffer,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

pub struct ViewModelIrradianceIo {
    levels: Read<Buffer>,
    nodes: Read<Buffer>,
    irradiance: Write<Buffer>,
    flux_size: (u32, u32),
}

impl ViewModelIrradiancePass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gi: GiResources,
        irradiance: Handle<Buffer>,
    ) -> Self {
        let layout = PROBE.layout(device);
        let module = crate::shader::module(device, "gi view model irradiance", SHADER);
        let pipeline =
            compute_pipeline(device, "gi view model irradiance", &module, "main", &[Some(globals), Some(&layout)]);
        let probe = uniform_buffer(device, "gi view model probe", std::mem::size_of::<Probe>() as u64);
        Self { handle, gi, irradiance, probe, layout, pipeline }
    }
}

impl RenderPass for ViewModelIrradiancePass {
    type Io = Option<ViewModelIrradianceIo>;

    fn name(&self) -> &str {
        "gi_view_model"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> Option<ViewModelIrradianceIo> {
        let frame = self.handle.frame(d.size(), d.view().headlamp.attached);
        frame.enabled().then(|| ViewModelIrradianceIo {
            levels: d.read(self.gi.levels),
            nodes: d.read(self.gi.nodes),
            irradiance: d.write(self.irradiance),
            flux_size: frame.lamp.flux,
        })
    }

    fn run(&mut self, io: &Option<ViewModelIrradianceIo>, ctx: &mut PassContext<'_>) {
        let (Some(io), Some(point)) = (io, ctx.frame.view.view_model_probe()) else {
            return;
        };
        let tree = Quadtree::new(io.flux_size.0, io.flux_size.1);
        let level = (0..LEVELS)
            .find(|&l| {
                let (w, h) = tree.size(l);
                w * h <= MAX_NODES
            })
            .unwrap_or(LEVELS - 1);
        let probe = Probe { position: [point.x, point.y, point.z, 0.0], level: [level, 0, 0, 0] };
        ctx.gpu.queue.write_buffer(&self.probe, 0, bytemuck::bytes_of(&probe));
        let group = PROBE.bind(
            &ctx.gpu.device,
            &self.layout,
            &[
                ("probe", (&self.probe).into()),
                ("levels", ctx.buffer(&io.levels).into()),
                ("nodes", ctx.buffer(&io.nodes).into()),
                ("ambient_cube", ctx.buffer(&io.irradiance).into()),
            ],
        );
        let mut pass = ctx.encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("gi view model irradiance"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.dispatch_workgroups(1, 1, 1);
        drop(pass);
        ctx.count_dispatches(1);
    }
}
