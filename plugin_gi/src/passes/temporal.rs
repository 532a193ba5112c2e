//! Temporal accumulation of the irradiance (shaders/gi/temporal.wgsl): this frame's gather
//! blended with last frame's result, reprojected to the receiver's world point, rejected where
//! the point was hidden and pulled into this frame's range where the lighting changed. Its
//! output, a graph history pair, is what the composite upsamples.

use std::cell::Cell;

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::glam::{Mat4, Vec3};
use engine::graph::{Buffer, History, Image, PassContext, PassDecl, Read, RenderPass, Write};
use engine::headlamp::LampFrustum;
use engine::passes::CoreResources;
use engine::view_state::ViewState;
use engine::wgpu;

use super::gather::{irradiance_texture, IRRADIANCE_FORMAT};
use crate::gpu_types::TemporalParams;
use crate::grids::Grids;
use crate::pipelines::{compute_pipeline, uniform_buffer, TEXEL_GROUP};
use crate::resources::GiResources;
use crate::shared::GiHandle;

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

pub struct TemporalPass {
    handle: GiHandle,
    core: CoreResources,
    params: engine::graph::Handle<Buffer>,
    irradiance: engine::graph::Handle<Image>,
    receivers: engine::graph::Handle<Buffer>,
    history: History<Image>,
    uniform: wgpu::Buffer,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    /// The view-projection, the lamp, what it emitted and where the receivers lay in the frame
    /// whose result `history` holds.
    previous: Option<(Mat4, LampFrustum, Emission, [f32; 2])>,
    /// Set by a frame with the GI off (which runs nothing here): the history is stale then.
    skipped: Cell<bool>,
}

pub struct TemporalIo {
    params: Read<Buffer>,
    current: Read<Image>,
    previous: Read<Image>,
    position: Read<Image>,
    blended: Write<Image>,
    receivers: Read<Buffer>,
    size: (u32, u32),
}

impl TemporalPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        handle: GiHandle,
        core: CoreResources,
        gi: GiResources,
    ) -> Self {
        let layout = TEMPORAL.layout(device);
        let module = crate::shader::module(device, "gi temporal", SHADER);
        let pipeline = compute_pipeline(device, "gi temporal", &module, "main", &[Some(globals), Some(&layout)]);
        let uniform = uniform_buffer(device, "gi temporal params", std::mem::size_of::<TemporalParams>() as u64);
        Self {
            handle,
            core,
            params: gi.params,
            irradiance: gi.irradiance,
            receivers: gi.receivers,
            history: gi.history,
            uniform,
            layout,
            pipeline,
            previous: None,
            skipped: Cell::new(false),
        }
    }
}

impl RenderPass for TemporalPass {
    type Io = Option<TemporalIo>;

    fn name(&self) -> &str {
        "gi_temporal"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> Option<TemporalIo> {
        let frame = self.handle.frame(d.size(), d.view().headlamp.attached);
        if !frame.enabled() {
            self.skipped.set(true);
            return None;
        }
        let size = frame.indirect;
        Some(TemporalIo {
            params: d.read(self.params),
            current: d.read(self.irradiance),
            previous: d.read(self.history.previous()),
            position: d.read(self.core.gbuffer.position),
            blended: d.create(self.history.current(), irradiance_texture(size)),
            receivers: d.read(self.receivers),
            size,
        })
    }

    fn run(&mut self, io: &Option<TemporalIo>, ctx: &mut PassContext<'_>) {
        let Some(io) = io else {
            return;
        };
        // The history is not carried through frames without the GI.
        if self.skipped.replace(false) {
            self.previous = None;
        }
        let (w, h) = ctx.frame.size;
        let view_proj = ctx.frame.view.camera.view_projection(w as f32 / h.max(1) as f32);
        let (lamp, emission) = (ctx.frame.lamp, Emission::of(ctx.frame.view));
        let previous = self.previous.filter(|p| ctx.history_frames(&io.previous) > 0 && p.2 == emission);
        let steadiness = previous.map_or(0.0, |(_, before, ..)| lamp_steadiness(&before, &lamp));
        // (The receivers' grid alone: where this frame's samples lie, for the next frame.)
        let offset = Grids::of(&ctx.frame.view.camera, ctx.frame.size, io.size, 1).receiver_offset;
        let history = self.handle.frame(ctx.frame.size, ctx.frame.view.headlamp.attached).settings.history * steadiness;
        let value = TemporalParams {
            previous_view_proj: previous.map_or(view_proj, |(m, ..)| m).to_cols_array_2d(),
            blend: [1.0 - history, if history > 0.0 { 1.0 } else { 0.0 }, HISTORY_SLACK, 0.0],
            previous_offset: previous.map_or([offset[0], offset[1], 0.0, 0.0], |p| [p.3[0], p.3[1], 0.0, 0.0]),
        };
        ctx.gpu.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&value));
        self.previous = Some((view_proj, lamp, emission, offset));
        let group = TEMPORAL.bind(
            &ctx.gpu.device,
            &self.layout,
            &[
                ("params", ctx.buffer(&io.params).into()),
                ("temporal", (&self.uniform).into()),
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
        pass.dispatch_workgroups(io.size.0.div_ceil(TEXEL_GROUP), io.size.1.div_ceil(TEXEL_GROUP), 1);
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
