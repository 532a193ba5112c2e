//! A plugin that adds one pass to the render graph: exponential fog by view depth, blended
//! over the frame's radiance after the light (stage PostProcess), before the view models.
//! docs/architecture.md, "Writing a pass and a plugin", walks through it.

use engine::bindings::{Group, ShaderBinding};
use engine::graph::{Handle, Image, PassContext, PassDecl, Read, RenderPass, Stage, Write};
use engine::passes::{color_pass, fullscreen_pipeline, HDR_FORMAT};
use engine::plugin::{Plugin, PluginContext};
use engine::wgpu::{self, util::DeviceExt};

pub const SHADER: &str = include_str!("depth_fog.wgsl");

/// The fog and the G-buffer's positions (group 1 of depth_fog.wgsl), named as the WGSL names them.
pub const INPUTS: Group =
    Group::new("depth fog", &[ShaderBinding::uniform("fog"), ShaderBinding::texture("gbuffer_position")]);

/// The fog: its radiance (W·sr⁻¹·m⁻², linear RGB) and density (per metre).
#[derive(Clone, Copy, Debug)]
pub struct DepthFogPlugin {
    pub radiance: [f32; 3],
    pub density: f32,
}

impl Plugin for DepthFogPlugin {
    fn name(&self) -> &str {
        "depth_fog"
    }

    fn build(&mut self, ctx: &mut PluginContext<'_>) {
        let pass = DepthFogPass::new(ctx, *self);
        ctx.add_pass(Stage::PostProcess, pass);
    }
}

struct DepthFogPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    /// The fog's radiance and density: set once, read every frame.
    fog: wgpu::Buffer,
    position: Handle<Image>,
    hdr: Handle<Image>,
}

/// What the pass declared: it reads the G-buffer's positions and blends into `hdr`.
struct DepthFogIo {
    position: Read<Image>,
    hdr: Write<Image>,
}

impl DepthFogPass {
    fn new(ctx: &PluginContext<'_>, fog: DepthFogPlugin) -> Self {
        let device = &ctx.gpu.device;
        let layout = INPUTS.layout(device);
        let module = engine::shader::module(device, "depth fog", SHADER, &[]);
        // Over the frame: colour = src + dst·(1 − src.a).
        let blend = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent::OVER,
        };
        let groups = [Some(&ctx.layouts.globals), Some(&layout)];
        let pipeline = fullscreen_pipeline(device, "depth fog", &module, &groups, HDR_FORMAT, Some(blend));
        let [r, g, b] = fog.radiance;
        let fog = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("depth fog"),
            contents: bytemuck::cast_slice(&[r, g, b, fog.density]),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let core = ctx.core();
        Self { pipeline, layout, fog, position: core.gbuffer.position, hdr: core.hdr }
    }
}

impl RenderPass for DepthFogPass {
    type Io = DepthFogIo;

    fn name(&self) -> &str {
        "depth_fog"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> DepthFogIo {
        DepthFogIo { position: d.read(self.position), hdr: d.write(self.hdr) }
    }

    fn run(&mut self, io: &DepthFogIo, ctx: &mut PassContext<'_>) {
        let inputs = INPUTS.bind(
            &ctx.gpu.device,
            &self.layout,
            &[("fog", (&self.fog).into()), ("gbuffer_position", ctx.view(&io.position).into())],
        );
        let mut pass = color_pass(ctx.encoder, "depth fog", ctx.view(&io.hdr), true);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &inputs, &[]);
        pass.draw(0..3, 0..1);
        drop(pass);
        ctx.count_draws(1);
    }
}
