//! Writes the selected view into the output image: tonemapped (display, PNG) or linear (EXR).

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

use super::fullscreen::{color_pass, procedural_pipeline};
use crate::bindings::{Group, ShaderBinding};
use crate::globals::CoreLayouts;
use crate::gpu::Gpu;
use crate::graph::{Handle, Image, PassContext, PassDecl, Read, RenderPass, Write};

pub const SHADER: &str = include_str!("../../../shaders/present.wgsl");

/// The view shown and how (group 1), its texture read with `textureLoad`…
pub const INPUTS: Group =
    Group::new("present inputs", &[ShaderBinding::texture("source"), ShaderBinding::uniform("params")]);
/// … or through the sampler's bilinear filter, where the format allows (`fs_upsample`).
pub const FILTERED_INPUTS: Group = Group::new(
    "present inputs, filtered",
    &[ShaderBinding::filtered_texture("source"), ShaderBinding::uniform("params")],
);

/// How a view's texture is turned into a picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputView {
    /// Linear radiance: exposure + filmic tonemap for display, as-is for EXR.
    Radiance,
    /// A colour shown as-is (albedo, debug overlays).
    Color,
    /// A unit normal, shown as n·½+½.
    Normal,
    /// The `w` channel holds a distance in metres.
    Depth,
}

/// OutputView's codes in PresentParams.mode.x (`VIEW_*` in present.wgsl).
pub const VIEW_RADIANCE: u32 = 0;
pub const VIEW_COLOR: u32 = 1;
pub const VIEW_NORMAL: u32 = 2;
pub const VIEW_DEPTH: u32 = 3;

impl OutputView {
    fn code(self) -> u32 {
        match self {
            OutputView::Radiance => VIEW_RADIANCE,
            OutputView::Color => VIEW_COLOR,
            OutputView::Normal => VIEW_NORMAL,
            OutputView::Depth => VIEW_DEPTH,
        }
    }
}

/// What the present pass shows; shared with the renderer, which changes it between frames.
#[derive(Clone, Debug, PartialEq)]
pub struct PresentSettings {
    /// Graph resource to show.
    pub source: Handle<Image>,
    pub kind: OutputView,
}

crate::gpu_struct! {
    /// `PresentParams` of shaders/present.wgsl.
    #[repr(C)]
    #[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
    pub(crate) struct PresentUniform as PresentParams {
        mode: [u32; 4],
        /// Output width, height, 1/width, 1/height.
        output: [f32; 4],
    }
}

pub struct PresentPass {
    settings: Rc<RefCell<PresentSettings>>,
    inputs: wgpu::BindGroupLayout,
    /// The same binding, filterable, for the upsampling entry point's hardware bilinear.
    filtered_inputs: wgpu::BindGroupLayout,
    globals_layout: wgpu::BindGroupLayout,
    module: wgpu::ShaderModule,
    /// By output format and whether the pipeline upsamples through the sampler.
    pipelines: HashMap<(wgpu::TextureFormat, bool), wgpu::RenderPipeline>,
    params: wgpu::Buffer,
    output: Handle<Image>,
}

pub struct PresentIo {
    source: Read<Image>,
    output: Write<Image>,
    kind: OutputView,
}

impl PresentPass {
    pub fn new(
        gpu: &Gpu,
        layouts: &CoreLayouts,
        settings: Rc<RefCell<PresentSettings>>,
        output: Handle<Image>,
    ) -> Self {
        let device = &gpu.device;
        Self {
            settings,
            inputs: INPUTS.layout(device),
            filtered_inputs: FILTERED_INPUTS.layout(device),
            globals_layout: layouts.globals.clone(),
            module: crate::shader::module(device, "present", SHADER, &[]),
            pipelines: HashMap::new(),
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("present params"),
                size: std::mem::size_of::<PresentUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            output,
        }
    }
}

impl RenderPass for PresentPass {
    type Io = PresentIo;

    fn name(&self) -> &str {
        "present"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> PresentIo {
        let settings = self.settings.borrow();
        PresentIo { source: d.read(settings.source), output: d.write(self.output), kind: settings.kind }
    }

    fn run(&mut self, io: &PresentIo, ctx: &mut PassContext<'_>) {
        let output = ctx.texture(&io.output);
        let format = output.format();
        // A float output is read back as linear values (EXR); anything else is a picture.
        let linear = format == wgpu::TextureFormat::Rgba32Float;
        // Non-sRGB 8-bit outputs (some swapchains) need the encoding done in the shader.
        let encode_srgb = !linear && !format.is_srgb();
        // A view-sized source rendered below the output's size (render scale < 1) is upsampled
        // bilinearly where blending neighbours means something (radiance, colour); normals,
        // depths and the fixed-size lamp maps stay nearest-texel.
        let source = ctx.texture(&io.source);
        let (w, h) = (output.width(), output.height());
        let upsample = (source.width(), source.height()) == ctx.frame.size
            && ctx.frame.size != (w, h)
            && matches!(io.kind, OutputView::Radiance | OutputView::Color);
        // Upsampling through the sampler's bilinear filter costs one sample a pixel instead of
        // four loads: formats that cannot be filtered (Rgba32Float) interpolate by hand.
        let filtered = upsample
            && source
                .format()
                .guaranteed_format_features(ctx.gpu.device.features())
                .flags
                .contains(wgpu::TextureFormatFeatureFlags::FILTERABLE);
        let uniform = PresentUniform {
            mode: [io.kind.code(), linear as u32, encode_srgb as u32, upsample as u32],
            output: [w as f32, h as f32, 1.0 / w as f32, 1.0 / h as f32],
        };
        ctx.gpu.queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&uniform));

        let device = &ctx.gpu.device;
        let (module, globals) = (&self.module, &self.globals_layout);
        let inputs_layout = if filtered { &self.filtered_inputs } else { &self.inputs };
        let pipeline = self.pipelines.entry((format, filtered)).or_insert_with(|| {
            let layouts = [Some(globals), Some(inputs_layout)];
            let targets = [Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })];
            let entry = if filtered { "fs_upsample" } else { "fs_main" };
            procedural_pipeline(device, "present", module, ("vs_main", entry), &layouts, &targets, Default::default())
        });
        let group = if filtered { FILTERED_INPUTS } else { INPUTS };
        let inputs = group.bind(
            device,
            inputs_layout,
            &[("source", ctx.view(&io.source).into()), ("params", (&self.params).into())],
        );
        let target = ctx.view(&io.output);
        let mut pass = color_pass(ctx.encoder, "present", target, false);
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_bind_group(1, &inputs, &[]);
        pass.draw(0..3, 0..1);
    }
}
