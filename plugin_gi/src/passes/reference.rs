//! The exact one bounce: every flux texel a sender, as the small patch it is, with no merging,
//! no cutoff and no clamp (the `reference` view). Culled by the graph unless something shows or reads it.

use std::rc::Rc;

use engine::graph::{PassContext, PassDecl, RenderPass, SizeRule, TextureDesc};
use engine::passes::names::{GBUFFER_ALBEDO, GBUFFER_NORMAL, GBUFFER_POSITION};
use engine::wgpu;

use super::flux::lamp_view;
use crate::bindings::{bind, compute_pipeline, layout, uniform_buffer, Resource as R, Slot as S};
use crate::gpu_types::{names, SenderRange};
use crate::shared::{GiHandle, GpuShared};

pub const SHADER: &str = include_str!("../../../shaders/gi/reference.wgsl");

/// Senders per dispatch: with the 64-sender tiles, 16,640 loop iterations, well inside the
/// 65,535 that llvmpipe allows a loop nest.
const SENDERS_PER_DISPATCH: u32 = 16384;

pub struct ReferencePass {
    handle: GiHandle,
    gpu: Rc<GpuShared>,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    /// One uniform per sender range, and the running sums, kept while the sizes hold.
    ranges: Vec<wgpu::Buffer>,
    sums: Option<((u32, u32), wgpu::Buffer)>,
}

impl ReferencePass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gpu: Rc<GpuShared>,
    ) -> Self {
        let mut slots = vec![S::Uniform];
        slots.extend([S::Texture; 6]);
        slots.push(S::StorageTexture(wgpu::TextureFormat::Rgba32Float));
        slots.extend([S::Uniform, S::Storage { read_only: false }]);
        let layout = layout(device, "gi reference", &slots);
        let module = super::module(device, "gi reference", SHADER);
        let pipeline = compute_pipeline(device, "gi reference", &module, "main", &[Some(globals), Some(&layout)]);
        Self { handle, gpu, layout, pipeline, ranges: Vec::new(), sums: None }
    }
}

impl RenderPass for ReferencePass {
    fn name(&self) -> &str {
        "gi_reference"
    }

    fn declare(&self, d: &mut PassDecl) {
        let usage =
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC;
        let desc = TextureDesc {
            format: wgpu::TextureFormat::Rgba32Float,
            size: SizeRule::ViewScaled(1.0),
            usage,
            mip_levels: 1,
        };
        let lamp = lamp_view(d.context().lamp_attached);
        d.read(lamp.albedo).read(lamp.normal).read(lamp.position);
        d.read(GBUFFER_ALBEDO).read(GBUFFER_NORMAL).read(GBUFFER_POSITION).create_texture(names::REFERENCE, desc);
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let device = &ctx.gpu.device;
        // Shown alone, the reference runs without the flux pass, which otherwise writes these.
        self.gpu.write_params(&ctx.gpu.queue, &super::flux::params(&self.handle.settings(), ctx, 0));
        let lamp = lamp_view(ctx.frame.view.headlamp.attached);
        let (w, h) = ctx.frame.size;
        // (A view smaller than the stride is evaluated at its first pixel.)
        let stride = self.handle.reference_stride().min(w.min(h)).max(1);
        let receivers = (w / stride) * (h / stride);
        let (fw, fh) = lamp.size.resolve(ctx.frame.size);
        let senders = fw * fh;
        let chunks = senders.div_ceil(SENDERS_PER_DISPATCH).max(1);
        while self.ranges.len() < chunks as usize {
            self.ranges.push(uniform_buffer(device, "gi reference range", 16));
        }
        if self.sums.as_ref().is_none_or(|(size, _)| *size != (w, h)) {
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("gi reference sums"),
                size: (w as u64 * h as u64).max(1) * 16,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            });
            self.sums = Some(((w, h), buffer));
        }
        let sums = &self.sums.as_ref().expect("made above").1;
        for chunk in 0..chunks {
            let range = SenderRange {
                first: chunk * SENDERS_PER_DISPATCH,
                count: SENDERS_PER_DISPATCH,
                last: u32::from(chunk + 1 == chunks),
                stride,
            };
            let uniform = &self.ranges[chunk as usize];
            ctx.gpu.queue.write_buffer(uniform, 0, bytemuck::bytes_of(&range));
            let group = bind(
                device,
                &self.layout,
                &[
                    R::Buffer(&self.gpu.params),
                    R::View(ctx.view(lamp.albedo)),
                    R::View(ctx.view(lamp.position)),
                    R::View(ctx.view(lamp.normal)),
                    R::View(ctx.view(GBUFFER_ALBEDO)),
                    R::View(ctx.view(GBUFFER_NORMAL)),
                    R::View(ctx.view(GBUFFER_POSITION)),
                    R::View(ctx.view(names::REFERENCE)),
                    R::Buffer(uniform),
                    R::Buffer(sums),
                ],
            );
            let mut pass = ctx.encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("gi reference"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, ctx.frame.globals, &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.dispatch_workgroups(receivers.div_ceil(64), 1, 1);
        }
    }
}
