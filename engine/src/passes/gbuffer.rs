//! Rasterises the scene from the camera into the G-buffer.

use super::core_resources::{CoreResources, HDR_FORMAT};
use crate::globals::CoreLayouts;
use crate::gpu::Gpu;
use crate::gpu_instances::INSTANCE_LAYOUT;
use crate::gpu_scene::{self, GpuScene, VERTEX_LAYOUT};
use crate::graph::{Handle, Image, PassContext, PassDecl, RenderPass, TextureDesc, Write};

pub const SHADER: &str = include_str!("../../../shaders/gbuffer.wgsl");

/// Half floats, not 8-bit sRGB: the albedo enters every radiometric result, and hardware sRGB
/// decoding differs between GPUs by up to ~0.7 % in darks.
pub const ALBEDO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
pub const POSITION_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Half floats: F0 = 0.04 would be off by 2 % in 8 bits.
pub const SPECULAR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// The colour targets in `@location` order: albedo, normal, position, emissive, specular.
const FORMATS: [wgpu::TextureFormat; 5] = [ALBEDO_FORMAT, HDR_FORMAT, POSITION_FORMAT, HDR_FORMAT, SPECULAR_FORMAT];

pub struct GBufferPass {
    pipelines: ScenePipelines,
    /// Albedo, normal, position, emissive, specular; then depth.
    colors: [Handle<Image>; 5],
    depth: Handle<Image>,
}

pub struct GBufferIo {
    colors: [Write<Image>; 5],
    depth: Write<Image>,
}

impl GBufferPass {
    pub fn new(gpu: &Gpu, layouts: &CoreLayouts, scene: &GpuScene, core: &CoreResources) -> Self {
        let device = &gpu.device;
        let module = crate::shader::module(device, "gbuffer", SHADER, &[]);
        let used = scene.variants_used();
        let g = &core.gbuffer;
        Self {
            pipelines: ScenePipelines::new(device, "gbuffer", &module, layouts, &FORMATS, used),
            colors: [g.albedo, g.normal, g.position, core.emissive, core.specular],
            depth: g.depth,
        }
    }
}

/// The pipelines rasterising a view: the level's meshes (`vs_main` and `fs_main`, or
/// `fs_masked` for alpha-tested materials; vertex layout of `scene::Vertex`, material in
/// group 1) and the frame's instances (`vs_instance`/`fs_instance`, the same vertices plus
/// [`INSTANCE_LAYOUT`], no group 1), into the same colour `targets` and reversed-Z depth
/// buffer (cleared to 0, nearer is greater).
///
/// Single-sided materials (glTF's default) have their back faces culled, in the camera's and
/// the lamp's view alike, so the lamp shines through a single-sided wall from behind as the
/// camera sees through it. Double-sided materials (OBJ's, the engine's default) and instances
/// are drawn from both sides, and each shader turns their normals towards its viewer.
pub struct ScenePipelines {
    /// One per [`gpu_scene::variant`], built for the variants the scene uses.
    scene: [Option<wgpu::RenderPipeline>; gpu_scene::VARIANTS],
    instances: wgpu::RenderPipeline,
}

impl ScenePipelines {
    pub fn new(
        device: &wgpu::Device,
        label: &str,
        module: &wgpu::ShaderModule,
        layouts: &CoreLayouts,
        targets: &[wgpu::TextureFormat],
        used: [bool; gpu_scene::VARIANTS],
    ) -> Self {
        let scene = std::array::from_fn(|v| {
            used[v].then(|| {
                let masked = gpu_scene::variant_masked(v);
                let culls = gpu_scene::variant_culls(v);
                raster_pipeline(
                    device,
                    &format!("{label}{}{}", if masked { " masked" } else { "" }, if culls { " culled" } else { "" }),
                    module,
                    ("vs_main", if masked { "fs_masked" } else { "fs_main" }, culls.then_some(wgpu::Face::Back)),
                    &[Some(&layouts.globals), Some(&layouts.material)],
                    &[Some(VERTEX_LAYOUT)],
                    targets,
                )
            })
        });
        let instances = raster_pipeline(
            device,
            &format!("{label} instances"),
            module,
            ("vs_instance", "fs_instance", None),
            &[Some(&layouts.globals)],
            &[Some(VERTEX_LAYOUT), Some(INSTANCE_LAYOUT)],
            targets,
        );
        Self { scene, instances }
    }
}

pub(super) fn raster_pipeline(
    device: &wgpu::Device,
    label: &str,
    module: &wgpu::ShaderModule,
    // Entry points, and the faces culled.
    (vertex, fragment, cull_mode): (&str, &str, Option<wgpu::Face>),
    groups: &[Option<&wgpu::BindGroupLayout>],
    buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
    targets: &[wgpu::TextureFormat],
) -> wgpu::RenderPipeline {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: groups,
        immediate_size: 0,
    });
    let targets: Vec<Option<wgpu::ColorTargetState>> = targets.iter().map(|&format| Some(format.into())).collect();
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(vertex),
            compilation_options: Default::default(),
            buffers,
        },
        // Front faces wind counter-clockwise (glTF's rule, kept by the loaders' baking).
        primitive: wgpu::PrimitiveState { cull_mode, ..Default::default() },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Greater),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fragment),
            compilation_options: Default::default(),
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Records one pass drawing every mesh, then every instance, with [`ScenePipelines`]: the
/// graph textures `colors` cleared to transparent (w = 0 marks "no geometry") and `depth`
/// cleared to 0 (reversed Z). The one place the camera and lamp views are drawn from.
pub fn draw_scene(
    ctx: &mut PassContext<'_>,
    label: &str,
    pipelines: &ScenePipelines,
    colors: &[Write<Image>],
    depth: &Write<Image>,
) {
    let colors: Vec<Option<wgpu::RenderPassColorAttachment>> = colors
        .iter()
        .map(|target| {
            Some(wgpu::RenderPassColorAttachment {
                view: ctx.view(target),
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })
        })
        .collect();
    let mut pass = ctx.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &colors,
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: ctx.view(depth),
            depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(0.0), store: wgpu::StoreOp::Store }),
            stencil_ops: None,
        }),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_bind_group(0, ctx.frame.globals, &[]);
    ctx.frame.scene.draw_all(&mut pass, &pipelines.scene);
    if !ctx.frame.instances.is_empty() {
        pass.set_pipeline(&pipelines.instances);
        ctx.frame.instances.draw_all(&mut pass);
    }
}

impl RenderPass for GBufferPass {
    type Io = GBufferIo;

    fn name(&self) -> &str {
        "gbuffer"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> GBufferIo {
        let mut formats = FORMATS.into_iter();
        GBufferIo {
            colors: self.colors.map(|h| d.create(h, TextureDesc::target(formats.next().expect("five formats")))),
            depth: d.create(self.depth, TextureDesc::target(DEPTH_FORMAT)),
        }
    }

    fn run(&mut self, io: &GBufferIo, ctx: &mut PassContext<'_>) {
        draw_scene(ctx, "gbuffer", &self.pipelines, &io.colors, &io.depth);
    }
}
