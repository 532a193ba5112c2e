//! The GI's irradiance at the engine's view models (a gun in hand), which are in no G-buffer
//! and so get no indirect light from the gather: one workgroup sums a level of the first
//! bounce's flux pyramid at `ViewState::view_model_probe` into the engine's ambient cube,
//! `view_model.irradiance` (shaders/gi/view_model_irradiance.wgsl). Nothing is recorded without
//! view models; the cube then stays as the engine cleared it.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::graph::{Buffer, BufferDesc, Handle, PassContext, PassDecl, Read, Write};
use engine::wgpu;

use crate::frame::GiFrame;
use crate::gpu_types::Probe;
use crate::pipelines::compute_pipeline;
use crate::quadtree::{Quadtree, LEVELS};
use crate::resources::GiResources;
use crate::schedule::GiPass;

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
    gi: GiResources,
    irradiance: Handle<Buffer>,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

pub struct ViewModelIrradianceIo {
    /// The probe's point and level: a uniform this pass writes.
    probe: Write<Buffer>,
    levels: Read<Buffer>,
    nodes: Read<Buffer>,
    irradiance: Write<Buffer>,
    flux_size: (u32, u32),
}

impl ViewModelIrradiancePass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        gi: GiResources,
        irradiance: Handle<Buffer>,
    ) -> Self {
        let layout = PROBE.layout(device);
        let module = crate::shader::module(device, "gi view model irradiance", SHADER);
        let pipeline =
            compute_pipeline(device, "gi view model irradiance", &module, "main", &[Some(globals), Some(&layout)]);
        Self { gi, irradiance, layout, pipeline }
    }
}

impl GiPass for ViewModelIrradiancePass {
    type Io = ViewModelIrradianceIo;

    fn name(&self) -> &str {
        "gi_view_model"
    }

    fn declare(&self, d: &mut PassDecl<'_>, frame: &GiFrame) -> ViewModelIrradianceIo {
        let usage = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
        ViewModelIrradianceIo {
            probe: d.create(self.gi.probe, BufferDesc { size: std::mem::size_of::<Probe>() as u64, usage }),
            levels: d.read(self.gi.levels),
            nodes: d.read(self.gi.first().nodes),
            irradiance: d.write(self.irradiance),
            flux_size: frame.lamp.flux,
        }
    }

    fn run(&mut self, io: &ViewModelIrradianceIo, _: &GiFrame, ctx: &mut PassContext<'_>) {
        let Some(point) = ctx.frame.view.view_model_probe() else {
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
        ctx.write_buffer(&io.probe, 0, bytemuck::bytes_of(&probe));
        let group = PROBE.bind(
            &ctx.gpu.device,
            &self.layout,
            &[
                ("probe", ctx.buffer(&io.probe).into()),
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
