//! The first bounce's gather: the irradiance of every indirect-target pixel from the pyramid.

use std::cell::RefCell;
use std::rc::Rc;

use engine::graph::{BufferDesc, PassContext, PassDecl, RenderPass, TextureDesc};
use engine::passes::names::{GBUFFER_NORMAL, GBUFFER_POSITION};
use engine::wgpu;

use super::flux::indirect_size;
use crate::gather::{Gather, GatherTargets};
use crate::gpu_types::{names, CENTRE_LIGHTS, GATHER_STATS_SIZE};
use crate::pyramid::FluxPyramid;
use crate::shared::{GiHandle, GpuShared};

pub struct GatherPass {
    handle: GiHandle,
    pyramid: Rc<RefCell<FluxPyramid>>,
    gather: Gather,
    /// Stand in for the bounce-only bindings (one read, one written).
    sinks: [wgpu::TextureView; 2],
}

/// The irradiance format: f32 storage, summed by the gather itself (no blending).
pub const IRRADIANCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// A 1×1 Rgba32Float texture for bindings a pass does not use.
pub(crate) fn sink(device: &wgpu::Device) -> wgpu::TextureView {
    device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some("gi sink"),
            size: wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: IRRADIANCE_FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        })
        .create_view(&Default::default())
}

impl GatherPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gpu: Rc<GpuShared>,
        pyramid: Rc<RefCell<FluxPyramid>>,
    ) -> Self {
        Self {
            gather: Gather::new(device, globals, gpu.params.clone()),
            handle,
            pyramid,
            sinks: [sink(device), sink(device)],
        }
    }
}

impl RenderPass for GatherPass {
    fn name(&self) -> &str {
        "gi_gather"
    }

    fn declare(&self, d: &mut PassDecl) {
        let size = self.handle.settings().indirect_size();
        let usage = wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST;
        let target = TextureDesc { usage, size, ..TextureDesc::target(IRRADIANCE_FORMAT) };
        let buffer = |size, usage| BufferDesc {
            size,
            usage: usage | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        };
        // FLUX orders this after the pyramid, which it reads through the shared node buffer.
        d.read(names::FLUX)
            .read(GBUFFER_NORMAL)
            .read(GBUFFER_POSITION)
            .create_texture(names::IRRADIANCE, target)
            .create_buffer(names::STATS, buffer(GATHER_STATS_SIZE, wgpu::BufferUsages::INDIRECT))
            .create_buffer(names::LIGHTS, buffer(CENTRE_LIGHTS * 48, wgpu::BufferUsages::empty()));
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let settings = self.handle.settings();
        let pyramid = self.pyramid.borrow();
        let targets = GatherTargets {
            normal: ctx.view(GBUFFER_NORMAL),
            position: ctx.view(GBUFFER_POSITION),
            irradiance: ctx.view(names::IRRADIANCE),
            accumulate: &self.sinks[0],
            bounce: &self.sinks[1],
            stats: ctx.buffer(names::STATS),
            lights: ctx.buffer(names::LIGHTS),
        };
        let size = indirect_size(&settings, ctx);
        let dispatches =
            self.gather.record(&ctx.gpu.device, ctx.encoder, ctx.frame.globals, pyramid.buffers(), size, &targets);
        self.handle.0.borrow_mut().stats.dispatches += dispatches;
    }
}
