//! Temporal accumulation of the irradiance (shaders/gi/temporal.wgsl): this frame's gather
//! blended with last frame's result, reprojected to the receiver's world point, rejected where
//! the point was hidden and pulled into this frame's range where the lighting changed. Its
//! output, a graph history pair, is what the composite upsamples.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::glam::{Mat4, Vec3};
use engine::graph::{Buffer, BufferDesc, Image, PassContext, PassDecl, Read, Write};
use engine::headlamp::LampFrustum;
use engine::passes::CoreResources;
use engine::view_state::ViewState;
use engine::wgpu;

use super::gather::{irradiance_texture, IRRADIANCE_FORMAT};
use crate::frame::GiFrame;
use crate::gpu_types::TemporalParams;
use crate::grids::Grids;
use crate::pipelines::{compute_pipeline, TEXEL_GROUP};
use crate::resources::GiResources;
use crate::schedule::GiPass;

pub const SHADER: &str = include_str!("../../../shaders/gi/temporal.wgsl");

/// The blend's group 1 (temporal.wgsl).
pub const TEMPORAL: Group = Group::new(
    "gi temporal",
    &[
        B::uniform("params"),
        B::uniform("temporal"),
        B::texture("current"),
        B::texture("history"),
        B::texture("gbuffer_position"),
        B::storage_texture("blended", IRRADIANCE_FORMAT),
        B::storage("receiver_texels"),
    ],
);

/// Where its group is declared.
pub const BINDINGS: &[WgslGroup] = &[WgslGroup::new("gi/temporal.wgsl", 1, &TEMPORAL)];

/// How far history may lie outside the range of this frame's 3×3 neighbourhood on its surface,
/// relative, before it is pulled in: wide enough for the gather's own frame-to-frame wobble,
/// narrow enough that a change of lighting shows within a few frames.
pub const HISTORY_SLACK: f32 = 0.1;

/// A lamp that turns or moves this much from one frame to the next lights the scene so
/// differently that its history is worth nothing; less, and the history counts in proportion:
/// a slow pan (0.5° a frame) keeps 95 % of `gi.history`, a jump to another view none.
const LAMP_TURN_CUT_DEG: f32 = 10.0;
const LAMP_MOVE_CUT_M: f32 = 0.5;

/// What the light sources emit: any change (the lamp switched, its power, the camera's flash)
/// relights the whole view at once, so the history is dropped.
#[derive(Clone, Copy, PartialEq)]
struct Emission {
    lamp: Option<Vec3>,
    flash: [f32; 3],
}

impl Emission {
    fn of(view: &ViewState) -> Self {
        Self { lamp: view.headlamp.on.then(|| view.headlamp.intensity()), flash: view.camera_flash }
    }
}

/// How much of the history weight a frame keeps after the lamp went from `before` to `now`.
fn lamp_steadiness(before: &LampFrustum, now: &LampFrustum) -> f32 {
    let turn = before.rotation.angle_between(now.rotation).to_degrees();
    let moved = before.position.distance(now.position);
    (1.0 - (turn / LAMP_TURN_CUT_DEG).max(moved / LAMP_MOVE_CUT_M)).max(0.0)
}

/// The frame whose result the history holds, as the blend needs it.
#[derive(Clone, Copy)]
struct Previous {
    view_proj: Mat4,
    lamp: LampFrustum,
    emission: Emission,
    /// Where its receivers lay (`GiParams::receiver_offset`).
    receiver_offset: [f32; 2],
}

pub struct TemporalPass {
    core: CoreResources,
    gi: GiResources,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    /// The last frame blended; the graph says whether the history still holds it.
    previous: Option<Previous>,
}

pub struct TemporalIo {
    params: Read<Buffer>,
    temporal: Write<Buffer>,
    current: Read<Image>,
    previous: Read<Image>,
    position: Read<Image>,
    blended: Write<Image>,
    receivers: Read<Buffer>,
}

/// The blend's own parameters, a uniform it writes each frame.
fn temporal_desc() -> BufferDesc {
    BufferDesc {
        size: std::mem::size_of::<TemporalParams>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    }
}

impl TemporalPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        core: CoreResources,
        gi: GiResources,
    ) -> Self {
        let layout = TEMPORAL.layout(device);
        let module = crate::shader::module(device, "gi temporal", SHADER);
        let pipeline = compute_pipeline(device, "gi temporal", &module, "main", &[Some(globals), Some(&layout)]);
        Self { core, gi, layout, pipeline, previous: None }
    }
}

impl GiPass for TemporalPass {
    type Io = TemporalIo;

    fn name(&self) -> &str {
        "gi_temporal"
    }

    fn declare(&self, d: &mut PassDecl<'_>, frame: &GiFrame) -> TemporalIo {
        // The total of every bounce computed.
        let last = self.gi.bounce(frame.bounces());
        TemporalIo {
            params: d.read(self.gi.params()),
            temporal: d.create(self.gi.temporal, temporal_desc()),
            current: d.read(last.irradiance),
            previous: d.read(self.gi.history.previous()),
            position: d.read(self.core.gbuffer.position),
            blended: d.create(self.gi.history.current(), irradiance_texture(frame.indirect)),
            receivers: d.read(self.gi.first().receivers),
        }
    }

    fn run(&mut self, io: &TemporalIo, frame: &GiFrame, ctx: &mut PassContext<'_>) {
        let (w, h) = ctx.frame.size;
        let view_proj = ctx.frame.view.camera.view_projection(w as f32 / h.max(1) as f32);
        let (lamp, emission) = (ctx.frame.lamp, Emission::of(ctx.frame.view));
        // (A frame without the GI leaves the history holding an older frame: none then.)
        let previous = self.previous.filter(|p| ctx.history_frames(&io.previous) > 0 && p.emission == emission);
        let steadiness = previous.map_or(0.0, |p| lamp_steadiness(&p.lamp, &lamp));
        // (The receivers' grid alone: where this frame's samples lie, for the next frame.)
        let receiver_offset = Grids::of(&ctx.frame.view.camera, ctx.frame.size, frame.indirect, 1).receiver_offset;
        let history = frame.settings.history * steadiness;
        let value = TemporalParams {
            previous_view_proj: previous.map_or(view_proj, |p| p.view_proj).to_cols_array_2d(),
            previous_offset: previous.map_or(receiver_offset, |p| p.receiver_offset),
            current_weight: 1.0 - history,
            slack: HISTORY_SLACK,
            has_history: u32::from(history > 0.0),
            pad: [0; 3],
        };
        ctx.write_buffer(&io.temporal, 0, bytemuck::bytes_of(&value));
        self.previous = Some(Previous { view_proj, lamp, emission, receiver_offset });
        let group = TEMPORAL.bind(
            &ctx.gpu.device,
            &self.layout,
            &[
                ("params", ctx.buffer(&io.params).into()),
                ("temporal", ctx.buffer(&io.temporal).into()),
                ("current", ctx.view(&io.current).into()),
                ("history", ctx.view(&io.previous).into()),
                ("gbuffer_position", ctx.view(&io.position).into()),
                ("blended", ctx.view(&io.blended).into()),
                ("receiver_texels", ctx.buffer(&io.receivers).into()),
            ],
        );
        let mut pass = ctx
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi temporal"), timestamp_writes: None });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &group, &[]);
        let size = frame.indirect;
        pass.dispatch_workgroups(size.0.div_ceil(TEXEL_GROUP), size.1.div_ceil(TEXEL_GROUP), 1);
        drop(pass);
        ctx.count_dispatches(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::glam::Quat;

    fn lamp(position: Vec3, yaw_deg: f32) -> LampFrustum {
        let rotation = Quat::from_rotation_y(yaw_deg.to_radians());
        LampFrustum { position, rotation, fov_y: 1.0, aspect: 1.0, view_proj: Mat4::IDENTITY }
    }

    #[test]
    fn a_steady_lamp_keeps_its_history_and_a_jump_loses_it() {
        let here = lamp(Vec3::ZERO, 0.0);
        assert_eq!(lamp_steadiness(&here, &here), 1.0);
        assert!((lamp_steadiness(&here, &lamp(Vec3::ZERO, 0.5)) - 0.95).abs() < 1e-3);
        assert!((lamp_steadiness(&here, &lamp(Vec3::new(0.0, 0.0, 0.02), 0.0)) - 0.96).abs() < 1e-3);
        assert_eq!(lamp_steadiness(&here, &lamp(Vec3::ZERO, 45.0)), 0.0);
        assert_eq!(lamp_steadiness(&here, &lamp(Vec3::new(2.0, 0.0, 0.0), 0.0)), 0.0);
    }
}
