//! The view models (`ViewState::view_models`, a weapon in hand): drawn last onto the frame's
//! radiance, after the plugins, with a depth buffer of their own cleared first, so they are
//! never hidden by a wall the camera is pressed against. They are in no G-buffer and not in the
//! lamp's view, so the GI never sees them as reflectors (a gun 0.4 m from the attached
//! headlamp would otherwise be the brightest thing in its reflective shadow map).
//!
//! Their indirect light comes through one engine resource, `view_model.irradiance`: an ambient
//! cube at `ViewState::view_model_probe`, which [`ViewModelIrradianceClearPass`] creates zeroed
//! (stage Lighting) and a GI plugin may `write` (in a later stage). The engine so knows no
//! plugin, and without one the view models are lit directly only.

use super::core_resources::{CoreResources, HDR_FORMAT};
use super::gbuffer::{raster_pipeline, DEPTH_FORMAT};
use crate::bindings::{Group, ShaderBinding};
use crate::globals::CoreLayouts;
use crate::gpu::Gpu;
use crate::gpu_instances::INSTANCE_LAYOUT;
use crate::gpu_scene::VERTEX_LAYOUT;
use crate::graph::{Buffer, BufferDesc, Handle, Image, PassContext, PassDecl, Read, RenderPass, TextureDesc, Write};

pub const SHADER: &str = include_str!("../../../shaders/view_model.wgsl");

/// The ambient cube and the detached lamp's shadow map (group 2).
pub const INPUTS: Group = Group::new(
    "view model inputs",
    &[
        ShaderBinding::storage("ambient_cube"),
        ShaderBinding::depth_texture("lamp_depth"),
        ShaderBinding::comparison_sampler("lamp_shadow"),
    ],
);

/// Bytes of `view_model.irradiance`: six `vec4<f32>`.
pub const VIEW_MODEL_IRRADIANCE_SIZE: u64 = 6 * 16;

/// Creates `view_model.irradiance` and clears it to zero.
pub struct ViewModelIrradianceClearPass(pub Handle<Buffer>);

impl RenderPass for ViewModelIrradianceClearPass {
    type Io = Write<Buffer>;

    fn name(&self) -> &str {
        "view_model_irradiance_clear"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> Write<Buffer> {
        let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC;
        d.create(self.0, BufferDesc { size: VIEW_MODEL_IRRADIANCE_SIZE, usage })
    }

    fn run(&mut self, irradiance: &Write<Buffer>, ctx: &mut PassContext<'_>) {
        ctx.encoder.clear_buffer(ctx.buffer(irradiance), 0, None);
    }
}

pub struct ViewModelPass {
    pipeline: wgpu::RenderPipeline,
    inputs: wgpu::BindGroupLayout,
    /// As the direct light pass's: bilinear GreaterEqual comparison of `lamp.depth`.
    shadow_sampler: wgpu::Sampler,
    core: CoreResources,
}

pub struct ViewModelIo {
    irradiance: Read<Buffer>,
    lamp_depth: Read<Image>,
    hdr: Write<Image>,
    depth: Write<Image>,
}

impl ViewModelPass {
    pub fn new(gpu: &Gpu, layouts: &CoreLayouts, core: &CoreResources) -> Self {
        let device = &gpu.device;
        let module = crate::shader::module(device, "view model", SHADER, &[]);
        let inputs = INPUTS.layout(device);
        // Group 1 (scene_surface.wgsl's material) is not used by this pipeline.
        let pipeline = raster_pipeline(
            device,
            "view model",
            &module,
            ("vs_main", "fs_main", None),
            &[Some(&layouts.globals), None, Some(&inputs)],
            &[Some(VERTEX_LAYOUT), Some(INSTANCE_LAYOUT)],
            &[HDR_FORMAT],
        );
        let shadow_sampler = super::lamp_view::lamp_shadow_sampler(device, "view model lamp shadow");
        Self { pipeline, inputs, shadow_sampler, core: *core }
    }
}

impl RenderPass for ViewModelPass {
    type Io = ViewModelIo;

    fn name(&self) -> &str {
        "view_model"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> ViewModelIo {
        // The same declarations every frame, view models or none, so the graph never changes.
        let c = &self.core;
        ViewModelIo {
            irradiance: d.read(c.view_model_irradiance),
            lamp_depth: d.read(c.lamp.depth),
            hdr: d.write(c.hdr),
            depth: d.create(c.view_model_depth, TextureDesc::target(DEPTH_FORMAT)),
        }
    }

    fn run(&mut self, io: &ViewModelIo, ctx: &mut PassContext<'_>) {
        if ctx.frame.instances.view_models_empty() {
            return;
        }
        let inputs = INPUTS.bind(
            &ctx.gpu.device,
            &self.inputs,
            &[
                ("ambient_cube", ctx.buffer(&io.irradiance).into()),
                ("lamp_depth", ctx.view(&io.lamp_depth).into()),
                ("lamp_shadow", (&self.shadow_sampler).into()),
            ],
        );
        let mut pass = ctx.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("view model"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: ctx.view(&io.hdr),
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: ctx.view(&io.depth),
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(0.0), store: wgpu::StoreOp::Discard }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(2, &inputs, &[]);
        ctx.frame.instances.draw_view_models(&mut pass);
    }
}
