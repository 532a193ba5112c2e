//! The GI's parameters for the shaders, from the frame's description (crate::frame), and the
//! passes that write each GiParams uniform, its one writer each: the first bounce's, and the
//! one further bounces share; where the lamp's view comes from.

use engine::glam::Vec3;
use engine::graph::{Buffer, BufferDesc, Handle, PassContext, PassDecl, SizeRule, Write};
use engine::passes::GBuffer;
use engine::wgpu;

use crate::frame::GiFrame;
use crate::gpu_types::GiParams;
use crate::grids::Grids;
use crate::schedule::GiPass;

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

/// The frame's GI parameters for bounce `bounce` (from 1).
pub(crate) fn params(frame: &GiFrame, ctx: &PassContext<'_>, bounce: u32) -> GiParams {
    let (settings, indirect) = (&frame.settings, frame.indirect);
    let (senders, _) = frame.of_bounce(bounce);
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
        interleave: settings.interleave,
        flux_block: block,
        receiver_offset: grids.receiver_offset,
        sender_offset: grids.sender_offset,
        article_interleave: settings.article_interleave,
        volume_reach: settings.volume_reach,
        receiver_steps: grids.receiver_steps[0] | grids.receiver_steps[1] << 16,
        sender_steps: grids.sender_steps[0] | grids.sender_steps[1] << 16,
        pad: [0; 3],
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

/// Writes a GiParams uniform: the first bounce's (which the flux, the cuts, the sum, the
/// composite and the reference read), or the one every further bounce reads.
pub struct GiParamsPass {
    name: &'static str,
    /// 1, or 2 for every further bounce (their parameters are the same).
    bounce: u32,
    params: Handle<Buffer>,
}

impl GiParamsPass {
    pub(crate) fn first(params: Handle<Buffer>) -> Self {
        Self { name: "gi_params", bounce: 1, params }
    }

    pub(crate) fn further(params: Handle<Buffer>) -> Self {
        Self { name: "gi_bounce_params", bounce: 2, params }
    }
}

impl GiPass for GiParamsPass {
    type Io = Write<Buffer>;

    fn name(&self) -> &str {
        self.name
    }

    fn declare(&self, d: &mut PassDecl<'_>, _: &GiFrame) -> Write<Buffer> {
        d.create(self.params, params_desc())
    }

    fn run(&mut self, params: &Write<Buffer>, frame: &GiFrame, ctx: &mut PassContext<'_>) {
        let value = self::params(frame, ctx, self.bounce);
        ctx.write_buffer(params, 0, bytemuck::bytes_of(&value));
    }
}
