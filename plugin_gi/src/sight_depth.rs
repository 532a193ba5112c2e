//! The view depth the visibility march reads (shaders/gi/sight_depth.wgsl): the G-buffer's,
//! at half its size each way, R32Float, so the march's scattered loads are small ones. Made
//! once a frame by the first bounce's gather (cuts) or the light volumes (article), as the
//! graph image `gi.sight_depth`.

use engine::bindings::{Group, ShaderBinding as B, WgslGroup};
use engine::graph::{Handle, Image, PassContext, PassDecl, Read, TextureDesc, Write};
use engine::wgpu;

use crate::pipelines::{compute_pipeline, TEXEL_GROUP};
use crate::shader::module;

pub const SHADER: &str = include_str!("../../shaders/gi/sight_depth.wgsl");

/// The sight depth's group 1 (sight_depth.wgsl).
pub const SIGHT_DEPTH: Group = Group::new(
    "gi sight depth",
    &[B::texture("gbuffer_position"), B::storage_texture("depth", wgpu::TextureFormat::R32Float)],
);

/// Where its group is declared.
pub const BINDINGS: &[WgslGroup] = &[WgslGroup::new("gi/sight_depth.wgsl", 1, &SIGHT_DEPTH)];

/// The sight depth for a G-buffer of `gbuffer` texels: half its size each way, rounded up.
fn sight_depth_desc(gbuffer: (u32, u32)) -> TextureDesc {
    let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
    TextureDesc { usage, ..TextureDesc::target(wgpu::TextureFormat::R32Float) }
        .fixed(gbuffer.0.div_ceil(2), gbuffer.1.div_ceil(2))
}

/// Declares the sight depth `image`, made by the declaring pass, where `visibility`.
pub fn declare(d: &mut PassDecl<'_>, image: Handle<Image>, visibility: bool) -> Option<Write<Image>> {
    visibility.then(|| d.create(image, sight_depth_desc(d.size())))
}

pub struct SightDepth {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

impl SightDepth {
    pub fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout) -> Self {
        let layout = SIGHT_DEPTH.layout(device);
        let module = module(device, "gi sight depth", SHADER);
        let pipeline = compute_pipeline(device, "gi sight depth", &module, "main", &[Some(globals), Some(&layout)]);
        Self { layout, pipeline }
    }

    /// Records the sight depth (`depth`, as [`declare`]d) from the G-buffer's `position`;
    /// returns the number of dispatches, one.
    pub fn record(&self, ctx: &mut PassContext<'_>, position: &Read<Image>, depth: &Write<Image>) -> u32 {
        let size = ctx.texture(depth).size();
        let group = SIGHT_DEPTH.bind(
            &ctx.gpu.device,
            &self.layout,
            &[("gbuffer_position", ctx.view(position).into()), ("depth", ctx.view(depth).into())],
        );
        let mut pass = ctx
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("gi sight depth"), timestamp_writes: None });
        pass.set_bind_group(0, ctx.frame.globals, &[]);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(1, &group, &[]);
        pass.dispatch_workgroups(size.width.div_ceil(TEXEL_GROUP), size.height.div_ceil(TEXEL_GROUP), 1);
        1
    }
}
