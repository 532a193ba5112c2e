//! Geometry-aware upsampling of the irradiance, L_i = ρ/π · E (shaders/gi/indirect.wgsl), drawn
//! by two passes: `gi_composite`, in place of the engine's `composite`, makes the frame's HDR
//! radiance, direct + emissive + indirect, in one draw; `gi_indirect_view` writes the indirect
//! radiance alone as the `indirect` view (culled unless something shows or reads that). With
//! the GI off neither reads anything of the GI: the composite draws the engine's composite and
//! the view is cleared.

use engine::bindings::{Group, Resource, ShaderBinding as B, WgslGroup};
use engine::globals::CoreLayouts;
use engine::gpu::Gpu;
use engine::graph::{Buffer, Handle, Image, PassContext, PassDecl, Read, RenderPass, TextureDesc, Write};
use engine::passes::{color_pass, procedural_pipeline, CompositePass, CoreResources, HDR_FORMAT};
use engine::wgpu;

use crate::resources::GiResources;
use crate::shared::GiHandle;

pub const SHADER: &str = include_str!("../../../shaders/gi/indirect.wgsl");

/// The frame's upsampling, `fs_frame` (group 1 of indirect.wgsl): the irradiance and the
/// G-buffer, and the direct and emitted light the indirect light is added to.
pub const FRAME: Group = Group::new(
    "gi composite",
    &[
        B::uniform("params"),
        B::texture("irradiance"),
        B::texture("gbuffer_albedo"),
        B::texture("gbuffer_normal"),
        B::texture("gbuffer_position"),
        B::texture("direct_radiance"),
        B::texture("gbuffer_emissive"),
    ],
);
/// The indirect light alone, `fs_indirect`: the same group less the frame's light.
pub const INDIRECT_ONLY: Group = Group::new("gi indirect view", FRAME.bindings.split_at(5).0);

/// Where the upsampling's groups are declared.
pub const BINDINGS: &[WgslGroup] = &[
    WgslGroup::new("gi/indirect.wgsl", 1, &FRAME).for_entry_points(&["vs_main", "fs_frame"]),
    WgslGroup::new("gi/indirect.wgsl", 1, &INDIRECT_ONLY).for_entry_points(&["vs_main", "fs_indirect"]),
];

/// What an upsampling draw writes: the frame's radiance with the indirect light in it, or the
/// indirect light alone.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Output {
    Frame,
    IndirectOnly,
}

impl Output {
    fn group(self) -> Group {
        match self {
            Output::Frame => FRAME,
            Output::IndirectOnly => INDIRECT_ONLY,
        }
    }
}

/// What the upsampling passes are made with: the settings, the engine's resources and the
/// GI's.
pub(crate) struct Gi {
    pub handle: GiHandle,
    pub core: CoreResources,
    pub resources: GiResources,
}

/// The upsampling draw, into one target.
struct Upsample {
    handle: GiHandle,
    core: CoreResources,
    gi: GiResources,
    output: Output,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

/// What the upsampling reads: the params, the irradiance, the G-buffer's albedo, normal and
/// position, and for the frame its direct and emissive radiance.
pub struct UpsampleInputs {
    params: Read<Buffer>,
    textures: [Read<Image>; 4],
    frame: Option<[Read<Image>; 2]>,
}

impl Upsample {
    fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout, gi: Gi, label: &str, output: Output) -> Self {
        let layout = output.group().layout(device);
        let fragment = match output {
            Output::Frame => "fs_frame",
            Output::IndirectOnly => "fs_indirect",
        };
        let module = crate::shader::module(device, label, SHADER);
        let targets =
            [Some(wgpu::ColorTargetState { format: HDR_FORMAT, blend: None, write_mask: wgpu::ColorWrites::ALL })];
        let pipeline = procedural_pipeline(
            device,
            label,
            &module,
            ("vs_main", fragment),
            &[Some(globals), Some(&layout)],
            &targets,
            Default::default(),
        );
        let Gi { handle, core, resources: gi } = gi;
        Self { handle, core, gi, output, layout, pipeline }
    }

    /// The inputs, or None with the GI off.
    fn declare_inputs(&self, d: &mut PassDecl<'_>) -> Option<UpsampleInputs> {
        if !self.handle.frame(d.size(), d.view().headlamp.attached).enabled() {
            return None;
        }
        let g = &self.core.gbuffer;
        Some(UpsampleInputs {
            params: d.read(self.gi.params()),
            textures: [self.gi.history.current(), g.albedo, g.normal, g.position].map(|h| d.read(h)),
            frame: (self.output == Output::Frame).then(|| [self.core.direct, self.core.emissive].map(|h| d.read(h))),
        })
    }

    fn draw(&self, ctx: &mut PassContext<'_>, label: &str, inputs: &UpsampleInputs, target: &Write<Image>) {
        let [irradiance, albedo, normal, position] = &inputs.textures;
        let mut resources: Vec<(&str, Resource<'_>)> = vec![
            ("params", ctx.buffer(&inputs.params).into()),
            ("irradiance", ctx.view(irradiance).into()),
            ("gbuffer_albedo", ctx.view(albedo).into()),
            ("gbuffer_normal", ctx.view(normal).into()),
            ("gbuffer_position", ctx.view(position).into()),
        ];
        if let Some([direct, emissive]) = &inputs.frame {
            resources.extend([
                ("direct_radiance", ctx.view(direct).into()),
                ("gbuffer_emissive", ctx.view(emissive).into()),
            ]);
        }
        let group = self.output.group().bind(&ctx.gpu.device, &self.layout, &resources);
        let mut pass = color_pass(ctx.encoder, label, ctx.view(target), false);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw(0..3, 0..1);
        drop(pass);
        ctx.count_draws(1);
    }
}

/// Makes the frame's `hdr`, direct + emissive + indirect, in place of the engine's composite
/// (one full-screen draw instead of the composite's and another adding to it), or with the GI
/// off draws the engine's composite.
pub struct IndirectCompositePass {
    upsample: Upsample,
    gi_off: CompositePass,
}

pub enum IndirectCompositeIo {
    On { inputs: UpsampleInputs, hdr: Write<Image> },
    Off(<CompositePass as RenderPass>::Io),
}

impl IndirectCompositePass {
    pub(crate) fn new(gpu: &Gpu, layouts: &CoreLayouts, gi: Gi) -> Self {
        let gi_off = CompositePass::new(gpu, layouts, &gi.core);
        Self { upsample: Upsample::new(&gpu.device, &layouts.globals, gi, "gi composite", Output::Frame), gi_off }
    }
}

impl RenderPass for IndirectCompositePass {
    type Io = IndirectCompositeIo;

    fn name(&self) -> &str {
        "gi_composite"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> IndirectCompositeIo {
        match self.upsample.declare_inputs(d) {
            Some(inputs) => IndirectCompositeIo::On {
                inputs,
                hdr: d.create(self.upsample.core.hdr, TextureDesc::target(HDR_FORMAT)),
            },
            None => IndirectCompositeIo::Off(self.gi_off.declare(d)),
        }
    }

    fn run(&mut self, io: &IndirectCompositeIo, ctx: &mut PassContext<'_>) {
        match io {
            IndirectCompositeIo::On { inputs, hdr } => self.upsample.draw(ctx, "gi composite", inputs, hdr),
            IndirectCompositeIo::Off(io) => self.gi_off.run(io, ctx),
        }
    }
}

/// The indirect radiance alone, as the `indirect` view.
pub struct IndirectViewPass {
    upsample: Upsample,
    target: Handle<Image>,
}

pub struct IndirectViewIo {
    inputs: Option<UpsampleInputs>,
    target: Write<Image>,
}

impl IndirectViewPass {
    pub(crate) fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout, gi: Gi) -> Self {
        let target = gi.resources.indirect;
        Self { upsample: Upsample::new(device, globals, gi, "gi indirect view", Output::IndirectOnly), target }
    }
}

impl RenderPass for IndirectViewPass {
    type Io = IndirectViewIo;

    fn name(&self) -> &str {
        "gi_indirect_view"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> IndirectViewIo {
        IndirectViewIo {
            inputs: self.upsample.declare_inputs(d),
            target: d.create(self.target, TextureDesc::target(HDR_FORMAT)),
        }
    }

    fn run(&mut self, io: &IndirectViewIo, ctx: &mut PassContext<'_>) {
        match &io.inputs {
            Some(inputs) => self.upsample.draw(ctx, "gi indirect view", inputs, &io.target),
            None => drop(color_pass(ctx.encoder, "gi off", ctx.view(&io.target), false)),
        }
    }
}
