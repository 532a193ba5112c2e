//! Geometry-aware upsampling of the irradiance, L_i = ρ/π · E (shaders/gi/indirect.wgsl), drawn
//! by two passes: `gi_composite` adds it to the frame's HDR radiance, `gi_indirect_view` writes
//! it alone as the `indirect` view (culled unless something shows or reads that). With the GI
//! off neither reads anything upstream: the composite records nothing and the view is cleared.

use engine::graph::{Buffer, Handle, Image, PassContext, PassDecl, Read, RenderPass, TextureDesc, Write};
use engine::passes::{color_pass, procedural_pipeline, CoreResources, HDR_FORMAT};
use engine::wgpu;

use crate::bindings::{bind, layout, Resource as R, Slot as S};
use crate::resources::GiResources;
use crate::shared::GiHandle;

pub const SHADER: &str = include_str!("../../../shaders/gi/indirect.wgsl");

/// Adds the indirect radiance to the frame.
const ADDITIVE: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
};

/// The upsampling draw, into one target.
struct Upsample {
    handle: GiHandle,
    core: CoreResources,
    gi: GiResources,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

/// What the upsampling reads: the params, the irradiance, the G-buffer's albedo, normal and
/// position.
pub struct UpsampleInputs {
    params: Read<Buffer>,
    textures: [Read<Image>; 4],
}

impl Upsample {
    fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        (handle, core, gi): (GiHandle, CoreResources, GiResources),
        label: &str,
        blend: Option<wgpu::BlendState>,
    ) -> Self {
        let layout = layout(device, label, &[S::Uniform, S::Texture, S::Texture, S::Texture, S::Texture]);
        let module = crate::shader::module(device, label, SHADER);
        let targets = [Some(wgpu::ColorTargetState { format: HDR_FORMAT, blend, write_mask: wgpu::ColorWrites::ALL })];
        let pipeline = procedural_pipeline(
            device,
            label,
            &module,
            ("vs_main", "fs_main"),
            &[Some(globals), Some(&layout)],
            &targets,
            Default::default(),
        );
        Self { handle, core, gi, layout, pipeline }
    }

    /// The inputs, or None with the GI off.
    fn declare_inputs(&self, d: &mut PassDecl<'_>) -> Option<UpsampleInputs> {
        if !self.handle.settings().enabled {
            return None;
        }
        let g = &self.core.gbuffer;
        Some(UpsampleInputs {
            params: d.read(self.gi.params),
            textures: [self.gi.history.current(), g.albedo, g.normal, g.position].map(|h| d.read(h)),
        })
    }

    fn draw(
        &self,
        ctx: &mut PassContext<'_>,
        label: &str,
        inputs: &UpsampleInputs,
        target: &Write<Image>,
        clear: bool,
    ) {
        let [irradiance, albedo, normal, position] = &inputs.textures;
        let group = bind(
            &ctx.gpu.device,
            &self.layout,
            &[
                R::Buffer(ctx.buffer(&inputs.params)),
                R::View(ctx.view(irradiance)),
                R::View(ctx.view(albedo)),
                R::View(ctx.view(normal)),
                R::View(ctx.view(position)),
            ],
        );
        let load = if clear { wgpu::LoadOp::Clear(wgpu::Color::BLACK) } else { wgpu::LoadOp::Load };
        let mut pass = ctx.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: ctx.view(target),
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw(0..3, 0..1);
        drop(pass);
        ctx.count_draws(1);
    }
}

/// Adds the indirect radiance to the frame's `hdr`.
pub struct IndirectCompositePass(Upsample);

pub struct IndirectCompositeIo {
    inputs: Option<UpsampleInputs>,
    hdr: Write<Image>,
}

impl IndirectCompositePass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        shared: (GiHandle, CoreResources, GiResources),
    ) -> Self {
        Self(Upsample::new(device, globals, shared, "gi composite", Some(ADDITIVE)))
    }
}

impl RenderPass for IndirectCompositePass {
    type Io = IndirectCompositeIo;

    fn name(&self) -> &str {
        "gi_composite"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> IndirectCompositeIo {
        IndirectCompositeIo { inputs: self.0.declare_inputs(d), hdr: d.write(self.0.core.hdr) }
    }

    fn run(&mut self, io: &IndirectCompositeIo, ctx: &mut PassContext<'_>) {
        if let Some(inputs) = &io.inputs {
            self.0.draw(ctx, "gi composite", inputs, &io.hdr, false);
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
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        shared: (GiHandle, CoreResources, GiResources),
    ) -> Self {
        let target = shared.2.indirect;
        Self { upsample: Upsample::new(device, globals, shared, "gi indirect view", None), target }
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
            Some(inputs) => self.upsample.draw(ctx, "gi indirect view", inputs, &io.target, true),
            None => drop(color_pass(ctx.encoder, "gi off", ctx.view(&io.target), false)),
        }
    }
}
