//! The GI's parameters for the shaders, from the frame's description (crate::frame), and the
//! pass that writes the first bounce's GiParams uniform, its one writer; where the lamp's view
//! comes from.

use engine::glam::Vec3;
use engine::graph::{Buffer, BufferDesc, Handle, PassContext, PassDecl, RenderPass, SizeRule, Write};
use engine::passes::GBuffer;
use engine::wgpu;

use crate::frame::GiFrame;
use crate::gpu_types::GiParams;
use crate::grids::Grids;
use crate::pyramid::FluxSource;
use crate::shared::GiHandle;

/// Where the lamp's view comes from: the camera G-buffer while the lamp is attached (the
/// article's first-person case), the lamp's own G-buffer (reflective shadow map) when detached.
pub(crate) fn lamp_view(camera: &GBuffer, lamp: &GBuffer, attached: bool) -> GBuffer {
    if attached {
        *camera
    } else {
        *lamp
    }
}

/// A fixed-size rule for a size derived above.
pub(crate) fn fixed((w, h): (u32, u32)) -> SizeRule {
    SizeRule::Fixed(w, h)
}

/// The frame's GI parameters, for a pyramid built from `source`.
pub(crate) fn params(frame: &GiFrame, ctx: &PassContext<'_>, source: FluxSource) -> GiParams {
    let (settings, indirect) = (&frame.settings, frame.indirect);
    let senders = match source {
        FluxSource::Lamp => frame.lamp,
        FluxSource::Bounce => frame.bounce,
    };
    let flux = senders.flux;
    let lamp = ctx.frame.lamp;
    let tan_y = (lamp.fov_y * 0.5).tan();
    let block = senders.block();
    let grids = Grids::of(&ctx.frame.view.camera, frame.size, indirect, block);
    GiParams {
        flux_size: [flux.0, flux.1],
        indirect_size: indirect.into(),
        lamp_tan: [tan_y * lamp.aspect, tan_y],
        lamp_power: ctx.frame.view.headlamp.profile.power,
        cos_merge: settings.merge_normal_deg.to_radians().cos(),
        merge_distance: settings.merge_distance,
        split_ratio: settings.split_ratio,
        min_level: senders.finest_level,
        source: source.code(),
        interleave: settings.interleave,
        flux_block: block,
        receiver_offset: grids.receiver_offset,
        sender_offset: grids.sender_offset,
        article_interleave: settings.article_interleave,
        volume_reach: settings.volume_reach,
        receiver_steps: grids.receiver_steps[0] | grids.receiver_steps[1] << 16,
        sender_steps: grids.sender_steps[0] | grids.sender_steps[1] << 16,
        pad: [0; 2],
        view_origin: lamp.position.extend(1.0).to_array(),
        view_forward: (lamp.rotation * Vec3::NEG_Z).extend(0.0).to_array(),
        view_right: (lamp.rotation * Vec3::X * tan_y * lamp.aspect).extend(0.0).to_array(),
        view_up: (lamp.rotation * Vec3::Y * tan_y).extend(0.0).to_array(),
    }
}

/// A GiParams uniform.
pub(crate) fn params_desc() -> BufferDesc {
    BufferDesc {
        size: std::mem::size_of::<GiParams>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    }
}

/// Writes the first bounce's GiParams, which the flux, gather, composite and reference read.
pub struct GiParamsPass {
    pub(crate) handle: GiHandle,
    pub(crate) params: Handle<Buffer>,
}

impl RenderPass for GiParamsPass {
    type Io = Write<Buffer>;

    fn name(&self) -> &str {
        "gi_params"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> Write<Buffer> {
        d.create(self.params, params_desc())
    }

    fn run(&mut self, params: &Write<Buffer>, ctx: &mut PassContext<'_>) {
        let frame = self.handle.frame(ctx.frame.size, ctx.frame.view.headlamp.attached);
        let value = self::params(&frame, ctx, FluxSource::Lamp);
        ctx.write_buffer(params, 0, bytemuck::bytes_of(&value));
    }
}
