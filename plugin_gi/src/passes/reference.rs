//! The exact one bounce: every flux texel a sender, as the small patch it is, with no merging,
//! no cutoff and no clamp (the `reference` view). Culled by the graph unless something shows or reads it.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::graph::{Buffer, BufferDesc, Image, PassContext, PassDecl, Read, SizeRule, TextureDesc, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use super::params::lamp_view;
use crate::frame::GiFrame;
use crate::gpu_types::SenderRange;
use crate::pipelines::{compute_pipeline, uniform_buffer};
use crate::resources::GiResources;
use crate::schedule::GiPass;
use crate::shared::GiHandle;

pub const SHADER: &str = include_str!("../../../shaders/gi/reference.wgsl");

/// The reference's group 1 (reference.wgsl): the senders (the lamp's view), the receivers (the
/// camera's G-buffer), the output, a dispatch's range of senders and the running sums.
pub const REFERENCE: Group = Group::new(
    "gi reference",
    &[
        B::uniform("params"),
        B::texture("light_albedo"),
        B::texture("light_position"),
        B::texture("light_normal"),
        B::texture("gbuffer_albedo"),
        B::texture("gbuffer_normal"),
        B::texture("gbuffer_position"),
        B::storage_texture("reference_out", wgpu::TextureFormat::Rgba32Float),
        B::uniform("range"),
        B::storage_rw("sums"),
    ],
);

/// Where its group is declared.
pub const BINDINGS: &[WgslGroup] = &[WgslGroup::new("gi/reference.wgsl", 1, &REFERENCE)];

/// Senders per dispatch: with the 64-sender tiles, 16,640 loop iterations, well inside the
/// 65,535 that llvmpipe allows a loop nest.
const SENDERS_PER_DISPATCH: u32 = 16384;

/// Receivers per workgroup (reference.wgsl's workgroup size, one receiver an invocation).
pub(crate) const GROUP: u32 = 64;

pub struct ReferencePass {
    handle: GiHandle,
    core: CoreResources,
    gi: GiResources,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    /// One uniform per sender range, each dispatch's own, made as the lamp view grows.
    ranges: Vec<wgpu::Buffer>,
}

impl ReferencePass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        core: CoreResources,
        gi: GiResources,
    ) -> Self {
        let layout = REFERENCE.layout(device);
        let module = crate::shader::module(device, "gi reference", SHADER);
        let pipeline = compute_pipeline(device, "gi reference", &module, "main", &[Some(globals), Some(&layout)]);
        Self { handle, core, gi, layout, pipeline, ranges: Vec::new() }
    }
}

pub struct ReferenceIo {
    params: Read<Buffer>,
    /// The lamp view's albedo, position and normal (the senders), then the camera's (the
    /// receivers).
    textures: [Read<Image>; 6],
    target: Write<Image>,
    /// Each receiver's irradiance summed over the sender ranges so far (a vec4 each).
    sums: Write<Buffer>,
    /// The lamp view's size: one sender a texel.
    senders: (u32, u32),
}

impl GiPass for ReferencePass {
    type Io = ReferenceIo;

    fn name(&self) -> &str {
        "gi_reference"
    }

    fn declare(&self, d: &mut PassDecl<'_>, frame: &GiFrame) -> ReferenceIo {
        let usage =
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC;
        let desc = TextureDesc {
            format: wgpu::TextureFormat::Rgba32Float,
            size: SizeRule::ViewScaled(1.0),
            usage,
            mip_levels: 1,
        };
        let (g, lamp) = (&self.core.gbuffer, lamp_view(&self.core.gbuffer, &self.core.lamp, frame.attached));
        let (w, h) = frame.size;
        let sums = BufferDesc { size: (u64::from(w) * u64::from(h)).max(1) * 16, usage: wgpu::BufferUsages::STORAGE };
        ReferenceIo {
            params: d.read(self.gi.params()),
            textures: [lamp.albedo, lamp.position, lamp.normal, g.albedo, g.normal, g.position].map(|h| d.read(h)),
            target: d.create(self.gi.reference, desc),
            sums: d.create(self.gi.reference_sums, sums),
            senders: frame.lamp.view,
        }
    }

    fn run(&mut self, io: &ReferenceIo, _: &GiFrame, ctx: &mut PassContext<'_>) {
        let device = &ctx.gpu.device;
        let (w, h) = ctx.frame.size;
        // (A view smaller than the stride is evaluated at its first pixel.)
        let stride = self.handle.reference_stride().min(w.min(h)).max(1);
        let receivers = (w / stride) * (h / stride);
        let senders = io.senders.0 * io.senders.1;
        let chunks = senders.div_ceil(SENDERS_PER_DISPATCH).max(1);
        while self.ranges.len() < chunks as usize {
            self.ranges.push(uniform_buffer(device, "gi reference range", std::mem::size_of::<SenderRange>() as u64));
        }
        let sums = ctx.buffer(&io.sums);
        let [lamp_albedo, lamp_position, lamp_normal, albedo, normal, position] = &io.textures;
        for chunk in 0..chunks {
            let range = SenderRange {
                first: chunk * SENDERS_PER_DISPATCH,
                count: SENDERS_PER_DISPATCH,
                last: u32::from(chunk + 1 == chunks),
                stride,
            };
            let uniform = &self.ranges[chunk as usize];
            ctx.gpu.queue.write_buffer(uniform, 0, bytemuck::bytes_of(&range));
            let group = REFERENCE.bind(
                device,
                &self.layout,
                &[
                    ("params", ctx.buffer(&io.params).into()),
                    ("light_albedo", ctx.view(lamp_albedo).into()),
                    ("light_position", ctx.view(lamp_position).into()),
                    ("light_normal", ctx.view(lamp_normal).into()),
                    ("gbuffer_albedo", ctx.view(albedo).into()),
                    ("gbuffer_normal", ctx.view(normal).into()),
                    ("gbuffer_position", ctx.view(position).into()),
                    ("reference_out", ctx.view(&io.target).into()),
                    ("range", uniform.into()),
                    ("sums", sums.into()),
                ],
            );
            let mut pass = ctx.encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("gi reference"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, ctx.frame.globals, &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.dispatch_workgroups(receivers.div_ceil(GROUP), 1, 1);
        }
    }
}
