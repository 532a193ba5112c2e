//! A bounce's sum (shaders/gi/gather.wgsl): each receiver of the indirect target sums the
//! irradiance of its tile's cut, one workgroup a tile; with visibility each light weighed by
//! which receivers see it (the sight pass). The first bounce's is the irradiance; a further
//! bounce's is added to the bounces' before, and kept alone for the next one to reflect.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::graph::{Buffer, Image, PassContext, PassDecl, Read, TextureDesc, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use super::params::fixed;
use crate::cuts_layout::CutsLayout;
use crate::frame::GiFrame;
use crate::pipelines::compute_pipeline_with;
use crate::resources::GiResources;
use crate::schedule::{bounce_pass_name, GiPass};
use crate::shader::module;

pub const SUBGROUP_SHADER: &str = include_str!("../../../shaders/gi/gather_subgroup.wgsl");
pub const INVOCATION_SHADER: &str = include_str!("../../../shaders/gi/gather_invocation.wgsl");

/// The irradiance format: f32 storage, summed by the gather itself (no blending).
pub const IRRADIANCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The sum's group 1 (gather.wgsl).
pub const GATHER: Group = Group::new(
    "gi gather",
    &[
        B::uniform("params"),
        B::uniform("table"),
        B::texture("gbuffer_normal"),
        B::texture("gbuffer_position"),
        B::storage_texture("irradiance_out", IRRADIANCE_FORMAT),
        B::storage("cuts"),
        B::storage("receiver_texels"),
        B::storage("sight"),
    ],
);
/// A further bounce's group 2 (`main_bounce`).
pub const BOUNCE: Group =
    Group::new("gi gather bounce", &[B::texture("accumulate"), B::storage_texture("bounce_out", IRRADIANCE_FORMAT)]);

/// Where the sum's groups are declared.
pub const BINDINGS: &[WgslGroup] = &[
    WgslGroup::new("gather.wgsl", 1, &GATHER),
    WgslGroup::new("gather.wgsl", 2, &BOUNCE).for_entry_points(&["main_bounce"]),
];

/// An irradiance-sized storage texture (a bounce's irradiance, or the blend's).
pub(crate) fn irradiance_texture(size: (u32, u32)) -> TextureDesc {
    let usage = wgpu::TextureUsages::STORAGE_BINDING
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::COPY_DST;
    TextureDesc { usage, size: fixed(size), ..TextureDesc::target(IRRADIANCE_FORMAT) }
}

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

/// Sums bounce `bounce`'s cuts (1: the headlamp's).
pub struct GatherPass {
    name: String,
    bounce: u32,
    core: CoreResources,
    gi: GiResources,
    layout: wgpu::BindGroupLayout,
    /// A further bounce's group 2.
    bounce_layout: Option<wgpu::BindGroupLayout>,
    /// Without visibility and with it (the shader's `VISIBILITY`).
    pipelines: [wgpu::ComputePipeline; 2],
}

pub struct GatherIo {
    params: Read<Buffer>,
    levels: Read<Buffer>,
    normal: Read<Image>,
    position: Read<Image>,
    cuts: Read<Buffer>,
    receivers: Read<Buffer>,
    irradiance: Write<Image>,
    /// A further bounce's: the bounces' before, and its own alone.
    bounce: Option<(Read<Image>, Write<Image>)>,
    layout: CutsLayout,
    visibility: bool,
}

impl GatherPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        bounce: u32,
        lanes: SumLanes,
        core: CoreResources,
        gi: GiResources,
    ) -> Self {
        let layout = GATHER.layout(device);
        let bounce_layout = (bounce > 1).then(|| BOUNCE.layout(device));
        let source = match lanes {
            SumLanes::Subgroup => SUBGROUP_SHADER,
            SumLanes::Invocation => INVOCATION_SHADER,
        };
        let module = module(device, "gi gather", source);
        let entry = if bounce > 1 { "main_bounce" } else { "main" };
        let layouts = [Some(globals), Some(&layout), bounce_layout.as_ref()];
        let pipelines = [false, true].map(|visibility| {
            let constants = [("VISIBILITY", f64::from(u8::from(visibility)))];
            compute_pipeline_with(device, "gi gather", &module, entry, &layouts, &constants)
        });
        let name = bounce_pass_name("gather", bounce);
        Self { name, bounce, core, gi, layout, bounce_layout, pipelines }
    }
}

impl GiPass for GatherPass {
    type Io = GatherIo;

    fn name(&self) -> &str {
        &self.name
    }

    fn declare(&self, d: &mut PassDecl<'_>, frame: &GiFrame) -> GatherIo {
        let k = self.bounce;
        let own = self.gi.bounce(k);
        let size = frame.indirect;
        GatherIo {
            params: d.read(own.params),
            levels: d.read(self.gi.levels),
            normal: d.read(self.core.gbuffer.normal),
            position: d.read(self.core.gbuffer.position),
            cuts: d.read(own.cuts),
            receivers: d.read(own.receivers),
            irradiance: d.create(own.irradiance, irradiance_texture(size)),
            bounce: (k > 1)
                .then(|| (d.read(self.gi.bounce(k - 1).irradiance), d.create(own.alone, irradiance_texture(size)))),
            layout: frame.of_bounce(self.bounce).1,
            visibility: frame.visibility(),
        }
    }

    fn run(&mut self, io: &GatherIo, _: &GiFrame, ctx: &mut PassContext<'_>) {
        let device = &ctx.gpu.device;
        let group = GATHER.bind(
            device,
            &self.layout,
            &[
                ("params", ctx.buffer(&io.params).into()),
                ("table", ctx.buffer(&io.levels).into()),
                ("gbuffer_normal", ctx.view(&io.normal).into()),
                ("gbuffer_position", ctx.view(&io.position).into()),
                ("irradiance_out", ctx.view(&io.irradiance).into()),
                ("cuts", ctx.buffer(&io.cuts).into()),
                ("receiver_texels", ctx.buffer(&io.receivers).into()),
                // The sight bits lie after the cuts (crate::cuts_layout).
                ("sight", ctx.buffer(&io.cuts).into()),
            ],
        );
        let bounce = match (&io.bounce, &self.bounce_layout) {
            (Some((before, alone)), Some(layout)) => Some(BOUNCE.bind(
                device,
                layout,
                &[("accumulate", ctx.view(before).into()), ("bounce_out", ctx.view(alone).into())],
            )),
            _ => None,
        };
        let mut pass = ctx
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi gather"), timestamp_writes: None });
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_pipeline(&self.pipelines[usize::from(io.visibility)]);
        pass.set_bind_group(1, &group, &[]);
        if let Some(bounce) = &bounce {
            pass.set_bind_group(2, bounce, &[]);
        }
        pass.dispatch_workgroups(io.layout.tiles.0, io.layout.tiles.1, 1);
        drop(pass);
        ctx.count_dispatches(1);
    }
}
