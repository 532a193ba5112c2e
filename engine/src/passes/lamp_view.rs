//! The lamp's own G-buffer — a reflective shadow map — rendered from the detached headlamp.
//!
//! While the lamp is **detached** this pass rasterises the scene from the lamp frustum
//! (`Headlamp::frustum`: its own pose, `profile.fov_y`, aspect 1) into `lamp.*`, fixed at
//! [`LAMP_MAP_SIZE`]². The direct light pass uses `lamp.depth` as the headlamp's shadow map and
//! the GI plugin takes its reflection lights from `lamp.*`.
//!
//! While the lamp is **attached** the camera G-buffer *is* the lamp view (same position, same
//! frustum, same formats and meanings), so this pass records nothing at all: no render pass,
//! no draw, no clear. Its declarations do not depend on the mode — the textures stay declared
//! (and allocated, ~32 MiB) in both modes — so toggling the lamp never recompiles the graph
//! and consumers bind the same names every frame. Their contents are meaningful only while
//! detached; attached consumers read `gbuffer.*` instead (see [`super::names`]).

use super::core_resources::{GBuffer, HDR_FORMAT};
use crate::globals::CoreLayouts;
use crate::gpu::Gpu;
use crate::gpu_scene::GpuScene;
use crate::graph::{Image, PassContext, PassDecl, RenderPass, TextureDesc, Write};
use crate::headlamp::LAMP_MAP_SIZE;

pub const SHADER: &str = include_str!("../../../shaders/lamp_view.wgsl");

/// Half floats like the camera G-buffer's albedo: hardware sRGB decoding differs between GPUs.
pub const LAMP_ALBEDO_FORMAT: wgpu::TextureFormat = super::gbuffer::ALBEDO_FORMAT;
pub const LAMP_NORMAL_FORMAT: wgpu::TextureFormat = HDR_FORMAT;
pub const LAMP_POSITION_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// The camera's depth format: both views are drawn by the same scene pipeline.
pub const LAMP_DEPTH_FORMAT: wgpu::TextureFormat = super::gbuffer::DEPTH_FORMAT;

/// The descriptor of a `lamp.*` texture: fixed size, sampled by later passes, and copyable so
/// tools and tests can read it back.
/// The sampler passes read `lamp.depth` through as the detached headlamp's shadow map: a bilinear
/// comparison that lights a receiver where its depth is at least the stored one (reversed Z).
pub(super) fn lamp_shadow_sampler(device: &wgpu::Device, label: &str) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some(label),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        compare: Some(wgpu::CompareFunction::GreaterEqual),
        ..Default::default()
    })
}

fn lamp_texture(format: wgpu::TextureFormat) -> TextureDesc {
    TextureDesc::target(format).fixed(LAMP_MAP_SIZE, LAMP_MAP_SIZE).usage(wgpu::TextureUsages::COPY_SRC)
}

pub struct LampViewPass {
    pipelines: super::gbuffer::ScenePipelines,
    lamp: GBuffer,
}

pub struct LampViewIo {
    colors: [Write<Image>; 3],
    depth: Write<Image>,
}

impl LampViewPass {
    pub fn new(gpu: &Gpu, layouts: &CoreLayouts, scene: &GpuScene, lamp: GBuffer) -> Self {
        let device = &gpu.device;
        let module = crate::shader::module(device, "lamp view", SHADER, &[]);
        // Same rasterisation as the camera's G-buffer, instances included: the same alpha
        // cut-outs (so shadows and the GI's reflected flux see the holes), the same culling of
        // single-sided materials' back faces (double-sided ones block the lamp from either
        // side); reversed Z. No rasteriser depth bias: the shadow test applies its own, in metres.
        let targets = [LAMP_ALBEDO_FORMAT, LAMP_NORMAL_FORMAT, LAMP_POSITION_FORMAT];
        let used = scene.variants_used();
        let pipelines = super::gbuffer::ScenePipelines::new(device, "lamp view", &module, layouts, &targets, used);
        Self { pipelines, lamp }
    }
}

impl RenderPass for LampViewPass {
    type Io = LampViewIo;

    fn name(&self) -> &str {
        "lamp_view"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> LampViewIo {
        let l = &self.lamp;
        LampViewIo {
            colors: [
                d.create(l.albedo, lamp_texture(LAMP_ALBEDO_FORMAT)),
                d.create(l.normal, lamp_texture(LAMP_NORMAL_FORMAT)),
                d.create(l.position, lamp_texture(LAMP_POSITION_FORMAT)),
            ],
            depth: d.create(l.depth, lamp_texture(LAMP_DEPTH_FORMAT)),
        }
    }

    fn run(&mut self, io: &LampViewIo, ctx: &mut PassContext<'_>) {
        if ctx.frame.view.headlamp.attached {
            return;
        }
        super::gbuffer::draw_scene(ctx, "lamp view", &self.pipelines, &io.colors, &io.depth);
    }
}
