//! Further bounces (settings.bounces ≥ 2, attached lamp): each feeds the previous bounce's
//! irradiance back as flux, Φ = ρ·E·A_texel, builds a new pyramid with the same machinery and
//! gathers it, adding its irradiance to the total.

use engine::graph::{PassContext, PassDecl, RenderPass};
use engine::passes::names::{GBUFFER_ALBEDO, GBUFFER_NORMAL, GBUFFER_POSITION};
use engine::wgpu;

use super::flux::{flux_size, indirect_size, params};
use super::gather::IRRADIANCE_FORMAT;
use crate::bindings::uniform_buffer;
use crate::gather::{Gather, GatherTargets};
use crate::gpu_types::{names, GiParams, CENTRE_LIGHTS, GATHER_STATS_SIZE};
use crate::pyramid::{FluxPyramid, PyramidInputs};
use crate::shared::GiHandle;

/// Working storage, sized to the view.
struct Scratch {
    key: ((u32, u32), (u32, u32)),
    flux: wgpu::TextureView,
    flux_view: wgpu::TextureView,
    /// The previous bounce's irradiance and the one being gathered (swapped each bounce).
    bounce: [wgpu::Texture; 2],
    /// The total so far, which the gather adds to.
    total: wgpu::Texture,
    stats: wgpu::Buffer,
    lights: wgpu::Buffer,
}

pub struct BouncePass {
    handle: GiHandle,
    /// This pass's GiParams (source = previous bounce).
    params: wgpu::Buffer,
    pyramid: FluxPyramid,
    gather: Gather,
    scratch: Option<Scratch>,
}

impl BouncePass {
    pub(crate) fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout, handle: GiHandle) -> Self {
        let params = uniform_buffer(device, "gi bounce params", std::mem::size_of::<GiParams>() as u64);
        Self {
            pyramid: FluxPyramid::new(device, globals, params.clone()),
            gather: Gather::new(device, globals, params.clone()),
            params,
            handle,
            scratch: None,
        }
    }

    fn ensure_scratch(&mut self, device: &wgpu::Device, size: (u32, u32), low: (u32, u32)) {
        let key = (size, low);
        if self.scratch.as_ref().is_some_and(|s| s.key == key) {
            return;
        }
        let texture = |label, (width, height): (u32, u32), format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let storage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let copied = storage | wgpu::TextureUsages::COPY_DST;
        let view = |t: wgpu::Texture| t.create_view(&Default::default());
        let buffer = |label, size| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        self.scratch = Some(Scratch {
            key,
            flux: view(texture("gi bounce flux", size, wgpu::TextureFormat::Rgba32Float, storage)),
            // The flux view is only shown for the first bounce: a 1×1 sink.
            flux_view: view(texture("gi bounce flux view", (1, 1), wgpu::TextureFormat::Rgba16Float, storage)),
            bounce: [0, 1].map(|_| texture("gi bounce irradiance", low, IRRADIANCE_FORMAT, copied)),
            total: texture("gi bounce total", low, IRRADIANCE_FORMAT, copied),
            stats: buffer("gi bounce stats", GATHER_STATS_SIZE),
            lights: buffer("gi bounce lights", CENTRE_LIGHTS * 48),
        });
    }
}

impl RenderPass for BouncePass {
    fn name(&self) -> &str {
        "gi_bounces"
    }

    fn declare(&self, d: &mut PassDecl) {
        let s = self.handle.settings();
        // Bounces reuse the camera G-buffer as the lamp view: attached lamp only.
        if s.enabled && s.bounces >= 2 && d.context().lamp_attached {
            d.read(GBUFFER_ALBEDO).read(GBUFFER_NORMAL).read(GBUFFER_POSITION).write(names::IRRADIANCE);
        }
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let (device, queue) = (&ctx.gpu.device, &ctx.gpu.queue);
        let settings = self.handle.settings();
        let size = flux_size(&settings, ctx);
        let low = indirect_size(&settings, ctx);
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params(&settings, ctx, 1)));
        self.pyramid.prepare(device, queue, size);
        self.ensure_scratch(device, size, low);
        let scratch = self.scratch.as_ref().expect("sized above");
        let extent = wgpu::Extent3d { width: low.0, height: low.1, depth_or_array_layers: 1 };
        let total = ctx.texture(names::IRRADIANCE);
        // Bounce 1's irradiance is the first source.
        ctx.encoder.copy_texture_to_texture(total.as_image_copy(), scratch.bounce[0].as_image_copy(), extent);
        let mut dispatches = 0;
        for bounce in 2..=settings.bounces {
            let (src, dst) = if bounce % 2 == 0 { (0, 1) } else { (1, 0) };
            let src_view = scratch.bounce[src].create_view(&Default::default());
            let dst_view = scratch.bounce[dst].create_view(&Default::default());
            let inputs = PyramidInputs {
                albedo: ctx.view(GBUFFER_ALBEDO),
                normal: ctx.view(GBUFFER_NORMAL),
                position: ctx.view(GBUFFER_POSITION),
                previous: &src_view,
                flux: &scratch.flux,
                flux_view: &scratch.flux_view,
            };
            dispatches += self.pyramid.record(device, ctx.encoder, ctx.frame.globals, &inputs);
            ctx.encoder.copy_texture_to_texture(total.as_image_copy(), scratch.total.as_image_copy(), extent);
            let total_view = scratch.total.create_view(&Default::default());
            let targets = GatherTargets {
                normal: ctx.view(GBUFFER_NORMAL),
                position: ctx.view(GBUFFER_POSITION),
                irradiance: ctx.view(names::IRRADIANCE),
                accumulate: &total_view,
                bounce: &dst_view,
                stats: &scratch.stats,
                lights: &scratch.lights,
            };
            let buffers = self.pyramid.buffers();
            dispatches += self.gather.record(device, ctx.encoder, ctx.frame.globals, buffers, low, &targets);
        }
        self.handle.0.borrow_mut().stats.dispatches += dispatches;
    }
}
