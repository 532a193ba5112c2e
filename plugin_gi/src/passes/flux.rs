//! The first bounce's flux pyramid, built from the headlamp's light on the lamp view.

use std::cell::RefCell;
use std::rc::Rc;

use engine::glam::Vec3;
use engine::graph::{PassContext, PassDecl, RenderPass, SizeRule, TextureDesc};
use engine::passes::names::{
    GBUFFER_ALBEDO, GBUFFER_NORMAL, GBUFFER_POSITION, LAMP_ALBEDO, LAMP_NORMAL, LAMP_POSITION,
};
use engine::passes::LAMP_MAP_SIZE;
use engine::wgpu;

use crate::gpu_types::{names, GiParams};
use crate::pyramid::{FluxPyramid, PyramidInputs};
use crate::settings::GiSettings;
use crate::shared::{GiHandle, GiStats, GpuShared};

pub struct FluxPass {
    handle: GiHandle,
    gpu: Rc<GpuShared>,
    pyramid: Rc<RefCell<FluxPyramid>>,
}

impl FluxPass {
    pub(crate) fn new(handle: GiHandle, gpu: Rc<GpuShared>, pyramid: Rc<RefCell<FluxPyramid>>) -> Self {
        Self { handle, gpu, pyramid }
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

/// Halvings of the lamp view the pyramid's base is subsampled by: attached, down to the
/// indirect target's resolution (finer senders than the receivers would only be merged back
/// up to that footprint by the gather), at most three; detached, none.
const MAX_HALVINGS: u32 = 3;

/// The size of the pyramid's base, the flux G-buffer: the lamp view halved `halvings` times.
pub(crate) fn flux_rule(settings: &GiSettings, attached: bool) -> SizeRule {
    if attached {
        SizeRule::ViewHalvedToward(settings.resolution_scale, settings.min_rows, MAX_HALVINGS)
    } else {
        lamp_view(false).size
    }
}

/// How many times the flux G-buffer halves the lamp view this frame.
fn halvings(settings: &GiSettings, ctx: &PassContext<'_>) -> u32 {
    if !ctx.frame.view.headlamp.attached {
        return 0;
    }
    SizeRule::halvings_toward(ctx.frame.size, settings.resolution_scale, settings.min_rows, MAX_HALVINGS)
}

/// The frame's GI parameters; `source` 0 builds from the lamp.
pub(crate) fn params(settings: &GiSettings, ctx: &PassContext<'_>, source: u32) -> GiParams {
    let size = flux_size(settings, ctx);
    let lamp = ctx.frame.lamp;
    let tan_y = (lamp.fov_y * 0.5).tan();
    GiParams {
        flux_size: [size.0, size.1],
        indirect_size: indirect_size(settings, ctx).into(),
        lamp_tan: [tan_y * lamp.aspect, tan_y],
        lamp_power: ctx.frame.view.headlamp.profile.power,
        cos_merge: settings.merge_normal_deg.to_radians().cos(),
        merge_distance: settings.merge_distance,
        split_ratio: settings.split_ratio,
        // The receivers' footprint, in levels above the (already subsampled) base.
        min_level: crate::settings::min_level(ctx.frame.size.1, indirect_size(settings, ctx).1)
            .saturating_sub(halvings(settings, ctx)),
        source,
        interleave: settings.interleave,
        pad: [0; 3],
        view_origin: lamp.position.extend(1.0).to_array(),
        view_forward: (lamp.rotation * Vec3::NEG_Z).extend(0.0).to_array(),
        view_right: (lamp.rotation * Vec3::X * tan_y * lamp.aspect).extend(0.0).to_array(),
        view_up: (lamp.rotation * Vec3::Y * tan_y).extend(0.0).to_array(),
    }
}

/// Size of the flux G-buffer (the pyramid's base).
pub(crate) fn flux_size(settings: &GiSettings, ctx: &PassContext<'_>) -> (u32, u32) {
    flux_rule(settings, ctx.frame.view.headlamp.attached).resolve(ctx.frame.size)
}

/// Size of the irradiance target.
pub(crate) fn indirect_size(settings: &GiSettings, ctx: &PassContext<'_>) -> (u32, u32) {
    settings.indirect_size().resolve(ctx.frame.size)
}

impl RenderPass for FluxPass {
    fn name(&self) -> &str {
        "gi_flux"
    }

    fn declare(&self, d: &mut PassDecl) {
        let storage =
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC;
        let attached = d.context().lamp_attached;
        let lamp = lamp_view(attached);
        let size = flux_rule(&self.handle.settings(), attached);
        let texture = |format| TextureDesc { format, size, usage: storage, mip_levels: 1 };
        d.read(lamp.albedo)
            .read(lamp.normal)
            .read(lamp.position)
            .create_texture(names::FLUX, texture(wgpu::TextureFormat::Rgba32Float))
            .create_texture(names::FLUX_VIEW, texture(wgpu::TextureFormat::Rgba16Float));
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let (device, queue) = (&ctx.gpu.device, &ctx.gpu.queue);
        let settings = self.handle.settings();
        self.gpu.write_params(queue, &params(&settings, ctx, 0));
        let mut pyramid = self.pyramid.borrow_mut();
        pyramid.prepare(device, queue, flux_size(&settings, ctx));
        let lamp = lamp_view(ctx.frame.view.headlamp.attached);
        let inputs = PyramidInputs {
            albedo: ctx.view(lamp.albedo),
            normal: ctx.view(lamp.normal),
            position: ctx.view(lamp.position),
            // Not read when building from the lamp.
            previous: ctx.view(lamp.albedo),
            flux: ctx.view(names::FLUX),
            flux_view: ctx.view(names::FLUX_VIEW),
        };
        let dispatches = pyramid.record(device, ctx.encoder, ctx.frame.globals, &inputs);
        // The first GI pass of the frame: later passes add their calls.
        self.handle.0.borrow_mut().stats = GiStats { dispatches, draws: 0 };
    }
}
