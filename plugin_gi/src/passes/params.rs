//! What the GI's passes derive from the frame and the settings (where the lamp's view comes
//! from, the sizes of the flux G-buffer and the indirect target), and the pass that writes the
//! first bounce's GiParams uniform, its one writer.

use engine::glam::Vec3;
use engine::graph::{Buffer, BufferDesc, Handle, PassContext, PassDecl, RenderPass, SizeRule, Write};
use engine::passes::{GBuffer, LAMP_MAP_SIZE};
use engine::wgpu;

use crate::gpu_types::GiParams;
use crate::grids::{Grids, SENDER_PAD};
use crate::pyramid::FluxSource;
use crate::settings::GiSettings;
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

/// The size of the lamp's view for a frame of `size` pixels.
pub(crate) fn lamp_view_size(size: (u32, u32), attached: bool) -> (u32, u32) {
    if attached {
        size
    } else {
        (LAMP_MAP_SIZE, LAMP_MAP_SIZE)
    }
}

/// Halvings of the lamp view the pyramid's base is subsampled by: attached, down to the
/// indirect target's resolution (finer senders than the receivers would only be merged back
/// up to that footprint by the gather), at most three; detached, none.
const MAX_HALVINGS: u32 = 3;

/// How many times the flux G-buffer halves the lamp view: as many times as the view, halved
/// (rounding up), stays at least as tall as the indirect target.
pub(crate) fn halvings(settings: &GiSettings, size: (u32, u32), attached: bool) -> u32 {
    if !attached {
        return 0;
    }
    let target = settings.indirect_size().resolve(size).1;
    let mut k = 0;
    while k < MAX_HALVINGS && size.1.max(1).div_ceil(1 << (k + 1)) >= target {
        k += 1;
    }
    k
}

/// Whether the flux G-buffer's texels are blocks of lamp-view texels (its nodes then have
/// halves: see Quadtree::halves).
pub(crate) fn flux_blocks(settings: &GiSettings, size: (u32, u32), attached: bool) -> bool {
    halvings(settings, size, attached) > 0
}

/// Size of the flux G-buffer (the pyramid's base): the lamp view's blocks, and where they are
/// blocks of several texels, SENDER_PAD more each way, as their grid moves with the picture
/// (crate::grids).
pub(crate) fn flux_size(settings: &GiSettings, size: (u32, u32), attached: bool) -> (u32, u32) {
    let (w, h) = flux_view_size(settings, size, attached);
    let pad = if halvings(settings, size, attached) > 0 { SENDER_PAD } else { 0 };
    (w + pad, h + pad)
}

/// Size of the `flux` view: the blocks that cover the lamp view, ⌈view / k⌉ each way.
pub(crate) fn flux_view_size(settings: &GiSettings, size: (u32, u32), attached: bool) -> (u32, u32) {
    let (w, h) = lamp_view_size(size, attached);
    let k = halvings(settings, size, attached);
    (w.max(1).div_ceil(1 << k), h.max(1).div_ceil(1 << k))
}

/// Size of the irradiance target: the settings' rule, made smaller only where its cuts would
/// outgrow their budget (far above play sizes), so the gather is always three calls.
pub(crate) fn indirect_size(settings: &GiSettings, size: (u32, u32)) -> (u32, u32) {
    // A cut has room for the pyramid's whole top level, which only the attached lamp's flux
    // G-buffer can make larger than CUT_MAX (a detached lamp's has 16×16 nodes).
    crate::gather::fit_cuts_budget(settings.indirect_size().resolve(size), flux_size(settings, size, true))
}

/// The pyramid's finest level that is built and used: the receivers' footprint, in levels
/// above the (already subsampled) base.
pub(crate) fn finest_level(settings: &GiSettings, size: (u32, u32), attached: bool) -> u32 {
    let indirect = indirect_size(settings, size);
    crate::settings::min_level(size.1, indirect.1).saturating_sub(halvings(settings, size, attached))
}

/// A fixed-size rule for a size derived above.
pub(crate) fn fixed((w, h): (u32, u32)) -> SizeRule {
    SizeRule::Fixed(w, h)
}

/// The frame's GI parameters, for a pyramid built from `source`.
pub(crate) fn params(settings: &GiSettings, ctx: &PassContext<'_>, source: FluxSource) -> GiParams {
    let (size, attached) = (ctx.frame.size, ctx.frame.view.headlamp.attached);
    let flux = flux_size(settings, size, attached);
    let indirect = indirect_size(settings, size);
    let lamp = ctx.frame.lamp;
    let tan_y = (lamp.fov_y * 0.5).tan();
    let block = 1 << halvings(settings, size, attached);
    let grids = Grids::of(&ctx.frame.view.camera, size, indirect, block);
    GiParams {
        flux_size: [flux.0, flux.1],
        indirect_size: indirect.into(),
        lamp_tan: [tan_y * lamp.aspect, tan_y],
        lamp_power: ctx.frame.view.headlamp.profile.power,
        cos_merge: settings.merge_normal_deg.to_radians().cos(),
        merge_distance: settings.merge_distance,
        split_ratio: settings.split_ratio,
        min_level: finest_level(settings, size, attached),
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
        let value = self::params(&self.handle.settings(), ctx, FluxSource::Lamp);
        ctx.write_buffer(params, 0, bytemuck::bytes_of(&value));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halving_toward_the_indirect_target_stops_before_it_gets_shorter() {
        let mut s = GiSettings { resolution_scale: 0.25, min_rows: 90, ..GiSettings::default() };
        // Blocks of lamp-view texels: their grid moves with the picture, SENDER_PAD more of them.
        let rule = |s: &GiSettings, view| {
            let (w, h) = flux_size(s, view, true);
            if halvings(s, view, true) > 0 {
                (w - SENDER_PAD, h - SENDER_PAD)
            } else {
                (w, h)
            }
        };
        // 360 rows → 180 → 90: two halvings reach the 90-row target exactly.
        assert_eq!(rule(&s, (640, 360)), (160, 90));
        assert_eq!(flux_size(&s, (640, 360), true), (160 + SENDER_PAD, 90 + SENDER_PAD));
        // 720 rows: a quarter is 180 rows, so two halvings; a third would give 90 < 180.
        assert_eq!(rule(&s, (1280, 720)), (320, 180));
        // 240 rows: the target is 90; 120 ≥ 90 but 60 < 90.
        assert_eq!(rule(&s, (320, 240)), (160, 120));
        // No halving: the lamp view's own texels, no padding.
        assert_eq!(rule(&s, (160, 120)), (160, 120));
        assert_eq!(flux_size(&s, (160, 120), true), (160, 120));
        assert_eq!(rule(&s, (1281, 721)), (321, 181));
        // Never more than three halvings.
        s.resolution_scale = 0.0625;
        s.min_rows = 16;
        assert_eq!(rule(&s, (1024, 1024)), (128, 128));
        // Detached: the lamp's own map, whole.
        assert_eq!(flux_size(&s, (640, 360), false), (LAMP_MAP_SIZE, LAMP_MAP_SIZE));
    }
}
