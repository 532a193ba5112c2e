//! The article's pipeline (`gi.method = article`), on the same pyramid as the cuts: the
//! distribution table ([`crate::distribution_table`], made on the CPU when the resolution, the
//! budget or the lamp changes) chooses the pyramid's slots; a compute pass turns them into the
//! instance stream of the light volumes and its draw arguments (shaders/gi/article_stream.wgsl);
//! one indirect draw shades every light's volume additively into the receivers
//! (article_volumes.wgsl), interleaved over N×N sub-images, which are split before and joined
//! after (article_sub_images.wgsl). Three dispatches and one draw, whatever the number of lights.

use std::rc::Rc;

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::headlamp::distribution_texels;
use engine::scene::IntensityDistribution;
use engine::wgpu;
use engine::wgpu::util::DeviceExt;

use crate::distribution_table::{lamp_importance, DistributionTable};
use crate::gpu_types::VOLUME_LIGHT_SIZE;
use crate::pipelines::{compute_pipeline, TEXEL_GROUP};
use crate::quadtree::Quadtree;
use crate::shader::module;
use crate::world_grid::{WorldGrid, WORLD};

/// What stops a light volume's light (the volumes' pipelines, in this order).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Sight {
    None,
    /// The surfaces the camera sees.
    Screen,
    /// Those, and the level's walls where the screen cannot tell.
    World,
}

pub const STREAM_SHADER: &str = include_str!("../../../../shaders/gi/article_stream.wgsl");
pub const VOLUMES_SHADER: &str = include_str!("../../../../shaders/gi/article_volumes.wgsl");
pub const SUB_IMAGES_SHADER: &str = include_str!("../../../../shaders/gi/article_sub_images.wgsl");

/// The coarse tier has this share of the budget (its lights cover every receiver of their
/// sub-image, the fine ones only their volumes).
const COARSE_SHARE: u32 = 4;
/// A slot is drawn as at most this many lights (an incoherent one refined two levels, a block
/// spanning a fold as its two sides; `LIGHTS_PER_SLOT` in article_stream.wgsl).
pub const LIGHTS_PER_SLOT: u32 = 32;
/// The receivers' positions and normals in their sub-images (article_sub_images.wgsl).
const RECEIVERS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;

/// The light stream's group 1 (article_stream.wgsl).
pub const STREAM: Group = Group::new(
    "gi light stream",
    &[
        B::uniform("table"),
        B::storage("nodes"),
        B::storage("entries"),
        B::storage_rw("stream"),
        B::storage_rw("args"),
        B::storage_rw("stats"),
        B::storage_rw("shown"),
        B::uniform("params"),
    ],
);
/// The sub-images' group 1, for both entry points (article_sub_images.wgsl).
pub const SUB_IMAGES: Group = Group::new(
    "gi sub-images",
    &[
        B::uniform("params"),
        B::texture("gbuffer_normal"),
        B::texture("gbuffer_position"),
        B::storage_rw("receiver_texels"),
    ],
);
/// `split`'s group 2: the receivers laid out as sub-images.
pub const SPLIT: Group = Group::new("gi sub-images split", &[B::storage_texture("receivers_out", RECEIVERS_FORMAT)]);
/// `join`'s group 3: the shaded sub-images back into the indirect target.
pub const JOIN: Group = Group::new(
    "gi sub-images join",
    &[
        B::uint_texture("receivers_in"),
        B::texture("shaded"),
        B::storage_texture("irradiance_out", wgpu::TextureFormat::Rgba32Float),
    ],
);
/// The light volumes' group 1 (article_volumes.wgsl).
pub const VOLUMES: Group =
    Group::new("gi light volumes", &[B::uniform("params"), B::storage("stream"), B::uint_texture("receivers")]);
/// `fs_sight`'s group 2: the view depth its march reads.
pub const VOLUMES_SIGHT: Group = Group::new("gi light volumes sight", &[B::texture("sight_depth")]);

/// Where the article's groups are declared.
pub const BINDINGS: &[WgslGroup] = &[
    WgslGroup::new("gi/article_stream.wgsl", 1, &STREAM),
    WgslGroup::new("gi/article_sub_images.wgsl", 1, &SUB_IMAGES),
    WgslGroup::new("gi/article_sub_images.wgsl", 2, &SPLIT),
    WgslGroup::new("gi/article_sub_images.wgsl", 3, &JOIN),
    WgslGroup::new("gi/article_volumes.wgsl", 1, &VOLUMES),
    WgslGroup::new("gi/article_volumes.wgsl", 2, &VOLUMES_SIGHT).for_entry_points(&["fs_sight", "fs_world"]),
    WgslGroup::new("gi/article_volumes.wgsl", 3, &WORLD).for_entry_points(&["fs_world"]),
];

/// What the table is made for: when any of it changes, it is made again.
#[derive(Clone, Copy, Debug)]
pub struct TableKey<'a> {
    pub frame: TableFrame,
    /// The lamp's distribution over its frustum (borrowed: the table keeps a copy).
    pub distribution: &'a IntensityDistribution,
}

/// The key's sizes and frustum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableFrame {
    /// The pyramid's base (the flux G-buffer), the lamp view, and a base texel's side in
    /// lamp-view texels.
    pub base: (u32, u32),
    pub view: (u32, u32),
    pub block: u32,
    /// The pyramid's finest level built (GiParams::min_level): no slot is finer.
    pub floor: u32,
    pub budget: u32,
    /// The lamp frustum's vertical field of view and aspect.
    pub fov_y: f32,
    pub aspect: f32,
}

impl TableKey<'_> {
    pub fn table(&self) -> DistributionTable {
        let f = &self.frame;
        let (tw, th, texels) = distribution_texels(self.distribution, f.fov_y, f.aspect);
        let tan = ((f.fov_y * 0.5).tan() * f.aspect, (f.fov_y * 0.5).tan());
        let importance = lamp_importance(f.base, f.view, f.block, tan, (tw, th, &texels));
        let coarse = (f.budget / COARSE_SHARE).max(16);
        let tree = Quadtree::new(f.base.0, f.base.1);
        DistributionTable::build(&tree, &importance, f.floor, f.budget, coarse)
    }
}

/// What one frame's light volumes read and write.
pub struct VolumeTargets<'a> {
    pub params: &'a wgpu::Buffer,
    pub levels: &'a wgpu::Buffer,
    pub nodes: &'a wgpu::Buffer,
    pub normal: &'a wgpu::TextureView,
    pub position: &'a wgpu::TextureView,
    /// Where each receiver is evaluated (crate::cuts_layout::receivers_desc), written here.
    pub receivers: &'a wgpu::Buffer,
    /// The irradiance out (Rgba32Float storage, the gather's format).
    pub irradiance: &'a wgpu::TextureView,
    /// With visibility: the view depth to march (`gi_sight_depth`'s); None without.
    pub sight_depth: Option<&'a wgpu::TextureView>,
    /// With visibility: march what the screen cannot tell through the level's voxels too.
    pub world_sight: bool,
    /// The gather's counters and the `lights` view's lights (the fine tier's).
    pub stats: &'a wgpu::Buffer,
    pub lights: &'a wgpu::Buffer,
    /// The indirect target's receivers, and N of the N×N sub-images they are split into.
    pub indirect: (u32, u32),
    pub interleave: u32,
}

pub struct LightVolumes {
    stream_layout: wgpu::BindGroupLayout,
    stream_pipeline: wgpu::ComputePipeline,
    common_layout: wgpu::BindGroupLayout,
    split_layout: wgpu::BindGroupLayout,
    join_layout: wgpu::BindGroupLayout,
    split_pipeline: wgpu::ComputePipeline,
    join_pipeline: wgpu::ComputePipeline,
    volumes_layout: wgpu::BindGroupLayout,
    sight_layout: wgpu::BindGroupLayout,
    world: Rc<WorldGrid>,
    /// Without visibility (`fs_main`), through the screen (`fs_sight`), and through the level's
    /// voxels too (`fs_world`), as [`Sight`] counts.
    volumes_pipelines: [wgpu::RenderPipeline; 3],
    /// Rgba32Float where the device blends it, else Rgba16Float.
    shaded_format: wgpu::TextureFormat,
    /// The table in its GPU form, and what it was made for.
    table: Option<(TableFrame, IntensityDistribution, wgpu::Buffer)>,
    scratch: Option<(ScratchKey, Scratch)>,
}

#[derive(Clone, Copy, PartialEq, Eq)]
struct ScratchKey {
    entries: u64,
    target: (u32, u32),
}

/// The instance stream, its draw arguments and the sub-images.
struct Scratch {
    stream: wgpu::Buffer,
    args: wgpu::Buffer,
    receivers: wgpu::TextureView,
    shaded: wgpu::TextureView,
}

impl LightVolumes {
    pub fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        float32_blendable: bool,
        world: Rc<WorldGrid>,
    ) -> Self {
        let stream_layout = STREAM.layout(device);
        let stream_module = module(device, "gi light stream", STREAM_SHADER);
        let stream_pipeline =
            compute_pipeline(device, "gi light stream", &stream_module, "main", &[Some(globals), Some(&stream_layout)]);
        let common_layout = SUB_IMAGES.layout(device);
        let split_layout = SPLIT.layout(device);
        let join_layout = JOIN.layout(device);
        let sub_module = module(device, "gi sub-images", SUB_IMAGES_SHADER);
        let split_pipeline = compute_pipeline(
            device,
            "gi sub-images split",
            &sub_module,
            "split",
            &[Some(globals), Some(&common_layout), Some(&split_layout)],
        );
        let join_pipeline = compute_pipeline(
            device,
            "gi sub-images join",
            &sub_module,
            "join",
            &[Some(globals), Some(&common_layout), None, Some(&join_layout)],
        );
        let volumes_layout = VOLUMES.layout(device);
        let sight_layout = VOLUMES_SIGHT.layout(device);
        let shaded_format =
            if float32_blendable { wgpu::TextureFormat::Rgba32Float } else { wgpu::TextureFormat::Rgba16Float };
        let add = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        let targets = [Some(wgpu::ColorTargetState {
            format: shaded_format,
            blend: Some(wgpu::BlendState { color: add, alpha: add }),
            write_mask: wgpu::ColorWrites::ALL,
        })];
        let volumes_module = module(device, "gi light volumes", VOLUMES_SHADER);
        let volumes_pipelines = [Sight::None, Sight::Screen, Sight::World].map(|sight| {
            let (fragment, layouts) = match sight {
                Sight::None => ("fs_main", &[Some(globals), Some(&volumes_layout)][..]),
                Sight::Screen => ("fs_sight", &[Some(globals), Some(&volumes_layout), Some(&sight_layout)][..]),
                Sight::World => {
                    ("fs_world", &[Some(globals), Some(&volumes_layout), Some(&sight_layout), Some(&world.layout)][..])
                }
            };
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("gi light volumes"),
                bind_group_layouts: layouts,
                immediate_size: 0,
            });
            let options = wgpu::PipelineCompilationOptions::default();
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("gi light volumes"),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &volumes_module,
                    entry_point: Some("vs_main"),
                    compilation_options: options.clone(),
                    buffers: &[],
                },
                // Back faces only: each receiver inside a volume is shaded once, the camera
                // inside it or not.
                primitive: wgpu::PrimitiveState { cull_mode: Some(wgpu::Face::Front), ..Default::default() },
                depth_stencil: None,
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &volumes_module,
                    entry_point: Some(fragment),
                    compilation_options: options,
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        });
        Self {
            stream_layout,
            stream_pipeline,
            common_layout,
            split_layout,
            join_layout,
            split_pipeline,
            join_pipeline,
            volumes_layout,
            sight_layout,
            world,
            volumes_pipelines,
            shaded_format,
            table: None,
            scratch: None,
        }
    }

    /// The table for `key`, made again only when the key changed; its entries' buffer.
    fn table(&mut self, device: &wgpu::Device, key: &TableKey) -> &wgpu::Buffer {
        let same =
            |(f, d, _): &(TableFrame, IntensityDistribution, wgpu::Buffer)| *f == key.frame && d == key.distribution;
        if !self.table.as_ref().is_some_and(same) {
            log::info!("gi: distribution table of {} slots over {:?}", key.frame.budget, key.frame.base);
            let entries = key.table().entries();
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("gi distribution table"),
                contents: bytemuck::cast_slice(&entries),
                usage: wgpu::BufferUsages::STORAGE,
            });
            self.table = Some((key.frame, key.distribution.clone(), buffer));
        }
        &self.table.as_ref().expect("made above").2
    }

    /// Records the light volumes of the pyramid in `t` for the table of `key`; returns
    /// (dispatches, draws): (3, 1).
    pub fn record(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        globals: &wgpu::BindGroup,
        key: &TableKey,
        t: &VolumeTargets<'_>,
    ) -> (u32, u32) {
        let entries = self.table(device, key).size() / 16;
        // N sub-images each way, each ⌈size / N⌉ + 1 (article_sub_image_layout.wgsl).
        let (indirect, n) = (t.indirect, t.interleave.max(1));
        let target = ((indirect.0.div_ceil(n) + 1) * n, (indirect.1.div_ceil(n) + 1) * n);
        let scratch_key = ScratchKey { entries, target };
        if self.scratch.as_ref().is_none_or(|(k, _)| *k != scratch_key) {
            let texture = |label, format, usage| {
                device
                    .create_texture(&wgpu::TextureDescriptor {
                        label: Some(label),
                        size: wgpu::Extent3d { width: target.0, height: target.1, depth_or_array_layers: 1 },
                        mip_level_count: 1,
                        sample_count: 1,
                        dimension: wgpu::TextureDimension::D2,
                        format,
                        usage: usage | wgpu::TextureUsages::TEXTURE_BINDING,
                        view_formats: &[],
                    })
                    .create_view(&Default::default())
            };
            let scratch = Scratch {
                stream: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("gi light stream"),
                    size: entries * u64::from(LIGHTS_PER_SLOT) * VOLUME_LIGHT_SIZE,
                    usage: wgpu::BufferUsages::STORAGE,
                    mapped_at_creation: false,
                }),
                args: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("gi light volumes' draw arguments"),
                    size: std::mem::size_of::<wgpu::util::DrawIndirectArgs>() as u64,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT,
                    mapped_at_creation: false,
                }),
                receivers: texture("gi sub-image receivers", RECEIVERS_FORMAT, wgpu::TextureUsages::STORAGE_BINDING),
                shaded: texture("gi light volumes", self.shaded_format, wgpu::TextureUsages::RENDER_ATTACHMENT),
            };
            self.scratch = Some((scratch_key, scratch));
        }
        let (_, s) = self.scratch.as_ref().expect("sized above");
        let (_, _, table) = self.table.as_ref().expect("made above");
        let common = SUB_IMAGES.bind(
            device,
            &self.common_layout,
            &[
                ("params", t.params.into()),
                ("gbuffer_normal", t.normal.into()),
                ("gbuffer_position", t.position.into()),
                ("receiver_texels", t.receivers.into()),
            ],
        );
        let split = SPLIT.bind(device, &self.split_layout, &[("receivers_out", (&s.receivers).into())]);
        let stream = STREAM.bind(
            device,
            &self.stream_layout,
            &[
                ("table", t.levels.into()),
                ("nodes", t.nodes.into()),
                ("entries", table.into()),
                ("stream", (&s.stream).into()),
                ("args", (&s.args).into()),
                ("stats", t.stats.into()),
                ("shown", t.lights.into()),
                ("params", t.params.into()),
            ],
        );
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("gi light stream"),
            timestamp_writes: None,
        });
        pass.set_bind_group(0, globals, &[]);
        pass.set_pipeline(&self.split_pipeline);
        pass.set_bind_group(1, &common, &[]);
        pass.set_bind_group(2, &split, &[]);
        pass.dispatch_workgroups(indirect.0.div_ceil(TEXEL_GROUP), indirect.1.div_ceil(TEXEL_GROUP), 1);
        pass.set_pipeline(&self.stream_pipeline);
        pass.set_bind_group(1, &stream, &[]);
        pass.dispatch_workgroups(1, 1, 1);
        drop(pass);

        let volumes = VOLUMES.bind(
            device,
            &self.volumes_layout,
            &[("params", t.params.into()), ("stream", (&s.stream).into()), ("receivers", (&s.receivers).into())],
        );
        let sight =
            t.sight_depth.map(|depth| VOLUMES_SIGHT.bind(device, &self.sight_layout, &[("sight_depth", depth.into())]));
        let mut pass = engine::passes::color_pass(encoder, "gi light volumes", &s.shaded, false);
        let kind = match (&sight, t.world_sight) {
            (None, _) => Sight::None,
            (Some(_), false) => Sight::Screen,
            (Some(_), true) => Sight::World,
        };
        pass.set_pipeline(&self.volumes_pipelines[kind as usize]);
        pass.set_bind_group(0, globals, &[]);
        pass.set_bind_group(1, &volumes, &[]);
        if let Some(sight) = &sight {
            pass.set_bind_group(2, sight, &[]);
        }
        if kind == Sight::World {
            pass.set_bind_group(3, &self.world.group, &[]);
        }
        pass.draw_indirect(&s.args, 0);
        drop(pass);

        let join = JOIN.bind(
            device,
            &self.join_layout,
            &[
                ("receivers_in", (&s.receivers).into()),
                ("shaded", (&s.shaded).into()),
                ("irradiance_out", t.irradiance.into()),
            ],
        );
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("gi sub-images join"),
            timestamp_writes: None,
        });
        pass.set_bind_group(0, globals, &[]);
        pass.set_pipeline(&self.join_pipeline);
        pass.set_bind_group(1, &common, &[]);
        pass.set_bind_group(3, &join, &[]);
        pass.dispatch_workgroups(indirect.0.div_ceil(TEXEL_GROUP), indirect.1.div_ceil(TEXEL_GROUP), 1);
        (3, 1)
    }
}
