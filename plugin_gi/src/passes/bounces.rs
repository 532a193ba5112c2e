//! Further bounces (settings.bounces ≥ 2, attached lamp): each feeds the previous bounce's
//! irradiance back as flux, Φ = ρ·E·A_texel, builds a new generation of reflection lights with
//! the same machinery, shades them, and adds their irradiance to the total.

use engine::graph::{PassContext, PassDecl, RenderPass, SizeRule};
use engine::passes::names::{GBUFFER_ALBEDO, GBUFFER_NORMAL, GBUFFER_POSITION};
use engine::passes::{bind_textures, color_pass, fullscreen_pipeline, textures_layout};
use engine::wgpu;

use super::lights::{params, table_key};
use super::shade::{VolumeShader, ADDITIVE};
use crate::bindings::uniform_buffer;
use crate::gpu_types::{names, GiParams, DRAW_ARGS_SIZE};
use crate::light_builder::{light_capacity, BuildTargets, LightBuilder};
use crate::shared::GiHandle;

pub const ADD_SHADER: &str = include_str!("../../../shaders/gi/add.wgsl");

/// Working storage, sized to the view and the budget.
struct Scratch {
    key: ((u32, u32), (u32, u32), u32),
    flux: wgpu::TextureView,
    flux_view: wgpu::TextureView,
    /// The previous bounce's irradiance and the one being shaded (swapped each bounce).
    irradiance: [wgpu::Texture; 2],
    lights: wgpu::Buffer,
    args: wgpu::Buffer,
}

pub struct BouncePass {
    handle: GiHandle,
    /// This pass's GiParams (source = previous bounce).
    params: wgpu::Buffer,
    builder: LightBuilder,
    shader: VolumeShader,
    add_layout: wgpu::BindGroupLayout,
    add: wgpu::RenderPipeline,
    scratch: Option<Scratch>,
}

impl BouncePass {
    pub(crate) fn new(gpu_ctx: &engine::gpu::Gpu, globals: &wgpu::BindGroupLayout, handle: GiHandle) -> Self {
        let device = &gpu_ctx.device;
        let params = uniform_buffer(device, "gi bounce params", std::mem::size_of::<GiParams>() as u64);
        let shader = VolumeShader::new(gpu_ctx, globals);
        let add_layout = textures_layout(device, "gi add bounce", 1, false);
        let module = engine::shader::module(device, "gi add bounce", ADD_SHADER, &[]);
        let add = fullscreen_pipeline(
            device,
            "gi add bounce",
            &module,
            &[Some(globals), Some(&add_layout)],
            shader.format,
            Some(ADDITIVE),
        );
        Self {
            builder: LightBuilder::new(device, globals, params.clone()),
            params,
            shader,
            add_layout,
            add,
            handle,
            scratch: None,
        }
    }

    fn ensure_scratch(&mut self, device: &wgpu::Device, size: (u32, u32), low: (u32, u32), budget: u32) {
        let key = (size, low, budget);
        if self.scratch.as_ref().is_some_and(|s| s.key == key) {
            return;
        }
        let texture = |label, (width, height): (u32, u32), format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let storage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let target = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_DST;
        let view = |t: wgpu::Texture| t.create_view(&Default::default());
        let buffer = |label, size, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: usage | wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        };
        self.scratch = Some(Scratch {
            key,
            flux: view(texture("gi bounce flux", size, wgpu::TextureFormat::Rgba32Float, storage)),
            // The flux view is only shown for the first bounce: a 1×1 sink.
            flux_view: view(texture("gi bounce flux view", (1, 1), wgpu::TextureFormat::Rgba16Float, storage)),
            irradiance: [0, 1].map(|_| texture("gi bounce irradiance", low, self.shader.format, target)),
            lights: buffer("gi bounce lights", light_capacity(budget) as u64 * 48, wgpu::BufferUsages::empty()),
            args: buffer("gi bounce draw args", DRAW_ARGS_SIZE, wgpu::BufferUsages::INDIRECT),
        });
    }
}

impl RenderPass for BouncePass {
    fn name(&self) -> &str {
        "gi_bounces"
    }

    fn declare(&self, d: &mut PassDecl) {
        let s = self.handle.settings();
        // Bounces reuse the camera G-buffer as the lamp view: attached lamp only.
        if s.enabled && s.bounces >= 2 && d.context().lamp_attached {
            d.read(GBUFFER_ALBEDO).read(GBUFFER_NORMAL).read(GBUFFER_POSITION).write(names::IRRADIANCE);
        }
    }

    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let (device, queue) = (&ctx.gpu.device, &ctx.gpu.queue);
        let settings = self.handle.settings();
        let size = ctx.frame.size;
        let low = SizeRule::ViewScaled(settings.resolution_scale).resolve(size);
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params(&settings, ctx, 1)));
        self.builder.prepare(device, queue, table_key(&settings, ctx));
        self.ensure_scratch(device, size, low, settings.light_budget);
        let scratch = self.scratch.as_ref().expect("sized above");
        let total = ctx.texture(names::IRRADIANCE);
        // Bounce 1's irradiance becomes the first source.
        ctx.encoder.copy_texture_to_texture(
            total.as_image_copy(),
            scratch.irradiance[0].as_image_copy(),
            wgpu::Extent3d { width: low.0, height: low.1, depth_or_array_layers: 1 },
        );
        let mut dispatches = 0;
        for bounce in 2..=settings.bounces {
            let (src, dst) = if bounce % 2 == 0 { (0, 1) } else { (1, 0) };
            let src_view = scratch.irradiance[src].create_view(&Default::default());
            let dst_view = scratch.irradiance[dst].create_view(&Default::default());
            let targets = BuildTargets {
                albedo: ctx.view(GBUFFER_ALBEDO),
                normal: ctx.view(GBUFFER_NORMAL),
                position: ctx.view(GBUFFER_POSITION),
                previous: &src_view,
                flux: &scratch.flux,
                flux_view: &scratch.flux_view,
                lights: &scratch.lights,
                args: &scratch.args,
            };
            dispatches += self.builder.record(device, ctx.encoder, ctx.frame.globals, &targets);
            let gbuffer = (ctx.view(GBUFFER_NORMAL), ctx.view(GBUFFER_POSITION));
            self.shader.record(
                device,
                ctx.encoder,
                ctx.frame.globals,
                &self.params,
                &scratch.lights,
                &scratch.args,
                gbuffer,
                &dst_view,
            );
            let group = bind_textures(device, &self.add_layout, &[&dst_view], None);
            let mut pass = color_pass(ctx.encoder, "gi add bounce", ctx.view(names::IRRADIANCE), true);
            pass.set_pipeline(&self.add);
            pass.set_bind_group(0, ctx.frame.globals, &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.draw(0..3, 0..1);
        }
        let mut shared = self.handle.0.borrow_mut();
        shared.stats.dispatches += dispatches;
        shared.stats.draws += 2 * (settings.bounces - 1);
    }
}
