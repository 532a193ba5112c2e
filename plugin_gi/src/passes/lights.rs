//! The first bounce's reflection lights, built from the headlamp's flux.

use std::rc::Rc;

use engine::graph::{BufferDesc, PassContext, PassDecl, RenderPass, SizeRule, TextureDesc};
use engine::passes::names::{
    GBUFFER_ALBEDO, GBUFFER_NORMAL, GBUFFER_POSITION, LAMP_ALBEDO, LAMP_NORMAL, LAMP_POSITION,
};
use engine::passes::LAMP_MAP_SIZE;
use engine::wgpu;

use crate::gpu_types::{names, GiParams, DRAW_ARGS_SIZE};
use crate::light_builder::{light_capacity, BuildTargets, LightBuilder, TableKey};
use crate::settings::GiSettings;
use crate::shared::{GiHandle, GiStats, GpuShared};

pub struct LightsPass {
    handle: GiHandle,
    gpu: Rc<GpuShared>,
    builder: LightBuilder,
}

impl LightsPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        gpu: Rc<GpuShared>,
    ) -> Self {
        Self { builder: LightBuilder::new(device, globals, gpu.params.clone()), handle, gpu }
    }
}

/// Where the lamp's view comes from: the camera G-buffer while the lamp is attached (the
/// article's first-person case), the lamp's own G-buffer (reflective shadow map) when detached.
pub(crate) struct LampView {
    pub albedo: &'static str,
    pub normal: &'static str,
    pub position: &'static str,
    pub size: SizeRule,
}

pub(crate) fn lamp_view(attached: bool) -> LampView {
    if attached {
        LampView {
            albedo: GBUFFER_ALBEDO,
            normal: GBUFFER_NORMAL,
            position: GBUFFER_POSITION,
            size: SizeRule::ViewScaled(1.0),
        }
    } else {
        LampView {
            albedo: LAMP_ALBEDO,
            normal: LAMP_NORMAL,
            position: LAMP_POSITION,
            size: SizeRule::Fixed(LAMP_MAP_SIZE, LAMP_MAP_SIZE),
        }
    }
}

/// The frame's GI parameters; `source` 0 builds from the lamp.
pub(crate) fn params(settings: &GiSettings, ctx: &PassContext<'_>, source: u32) -> GiParams {
    let size = flux_size(ctx);
    let lamp = ctx.frame.lamp;
    let tan_y = (lamp.fov_y * 0.5).tan();
    let indirect = SizeRule::ViewScaled(settings.resolution_scale).resolve(ctx.frame.size);
    GiParams {
        flux_size: [size.0, size.1],
        indirect_size: [indirect.0, indirect.1],
        lamp_tan: [tan_y * lamp.aspect, tan_y],
        lamp_power: ctx.frame.view.headlamp.profile.power,
        cos_merge: settings.merge_normal_deg.to_radians().cos(),
        merge_distance: settings.merge_distance,
        cutoff: settings.cutoff,
        d_min: settings.d_min,
        source,
    }
}

/// Size of the flux G-buffer: the lamp view's.
pub(crate) fn flux_size(ctx: &PassContext<'_>) -> (u32, u32) {
    lamp_view(ctx.frame.view.headlamp.attached).size.resolve(ctx.frame.size)
}

pub(crate) fn table_key(settings: &GiSettings, ctx: &PassContext<'_>) -> TableKey {
    TableKey {
        size: flux_size(ctx),
        budget: settings.light_budget,
        distribution: ctx.frame.view.headlamp.profile.distribution.clone(),
        fov_y: ctx.frame.lamp.fov_y,
        aspect: ctx.frame.lamp.aspect,
    }
}

impl RenderPass for LightsPass {
    fn name(&self) -> &str {
        "gi_lights"
    }

    fn declare(&self, d: &mut PassDecl) {
        let budget = self.handle.settings().light_budget;
        let storage =
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC;
        let lamp = lamp_view(d.context().lamp_attached);
        let texture = |format| TextureDesc { format, size: lamp.size, usage: storage, mip_levels: 1 };
        let buffer = |size, usage| BufferDesc {
            size,
            usage: usage | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        };
        d.read(lamp.albedo)
            .read(lamp.normal)
            .read(lamp.position)
            .create_texture(names::FLUX, texture(wgpu::TextureFormat::Rgba32Float))
            .create_texture(names::FLUX_VIEW, texture(wgpu::TextureFormat::Rgba16Float))
            .create_buffer(names::LIGHTS, buffer(light_capacity(budget) as u64 * 48, wgpu::BufferUsages::empty()))
            .create_buffer(names::DRAW_ARGS, buffer(DRAW_ARGS_SIZE, wgpu::BufferUsages::INDIRECT));
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let (device, queue) = (&ctx.gpu.device, &ctx.gpu.queue);
        let settings = self.handle.settings();
        self.gpu.write_params(queue, &params(&settings, ctx, 0));
        self.builder.prepare(device, queue, table_key(&settings, ctx));
        let lamp = lamp_view(ctx.frame.view.headlamp.attached);
        let targets = BuildTargets {
            albedo: ctx.view(lamp.albedo),
            normal: ctx.view(lamp.normal),
            position: ctx.view(lamp.position),
            // Not read when building from the lamp.
            previous: ctx.view(lamp.albedo),
            flux: ctx.view(names::FLUX),
            flux_view: ctx.view(names::FLUX_VIEW),
            lights: ctx.buffer(names::LIGHTS),
            args: ctx.buffer(names::DRAW_ARGS),
        };
        let dispatches = self.builder.record(device, ctx.encoder, ctx.frame.globals, &targets);
        // The first GI pass of the frame: later passes add their calls.
        self.handle.0.borrow_mut().stats = GiStats {
            slots: self.builder.slot_count(),
            light_capacity: light_capacity(settings.light_budget),
            dispatches,
            draws: 0,
        };
    }
}
