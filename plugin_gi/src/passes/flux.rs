//! The first bounce's flux pyramid, built from the headlamp's light on the lamp view.

use engine::graph::{Buffer, Image, PassContext, PassDecl, Read, RenderPass, TextureDesc, Write};
use engine::passes::CoreResources;
use engine::wgpu;

use super::params::{fixed, lamp_view};
use crate::gpu_types::Levels;
use crate::pyramid::{levels_desc, nodes_desc, FluxSource, PyramidBindings, PyramidPipelines};
use crate::quadtree::Quadtree;
use crate::resources::GiResources;

pub struct FluxPass {
    core: CoreResources,
    gi: GiResources,
    pyramid: PyramidPipelines,
    settings: crate::shared::GiHandle,
}

pub struct FluxIo {
    params: Read<Buffer>,
    /// The lamp view's albedo, normal and position.
    lamp: [Read<Image>; 3],
    flux: Write<Image>,
    flux_view: Write<Image>,
    levels: Write<Buffer>,
    nodes: Write<Buffer>,
    size: (u32, u32),
    /// Whether the base is of lamp-view texel blocks (which have halves: see Quadtree).
    blocks: bool,
}

impl FluxPass {
    pub(crate) fn new(
        device: &wgpu::Device,
        globals: &wgpu::BindGroupLayout,
        settings: crate::shared::GiHandle,
        core: CoreResources,
        gi: GiResources,
    ) -> Self {
        Self { core, gi, pyramid: PyramidPipelines::new(device, globals, FluxSource::Lamp), settings }
    }
}

/// A storage texture of the flux G-buffer's size.
pub(crate) fn flux_texture(format: wgpu::TextureFormat, size: (u32, u32)) -> TextureDesc {
    let usage =
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC;
    TextureDesc { format, size: fixed(size), usage, mip_levels: 1 }
}

impl RenderPass for FluxPass {
    type Io = FluxIo;

    fn name(&self) -> &str {
        "gi_flux"
    }

    fn declare(&self, d: &mut PassDecl<'_>) -> FluxIo {
        let attached = d.view().headlamp.attached;
        let lamp = lamp_view(&self.core.gbuffer, &self.core.lamp, attached);
        let senders = self.settings.frame(d.size(), attached).lamp;
        let (size, blocks) = (senders.flux, senders.blocks());
        FluxIo {
            params: d.read(self.gi.params),
            lamp: [lamp.albedo, lamp.normal, lamp.position].map(|h| d.read(h)),
            flux: d.create(self.gi.flux, flux_texture(wgpu::TextureFormat::Rgba32Float, size)),
            flux_view: d.create(self.gi.flux_view, flux_texture(wgpu::TextureFormat::Rgba16Float, senders.flux_view)),
            levels: d.create(self.gi.levels, levels_desc()),
            nodes: d.create(self.gi.nodes, nodes_desc(size, blocks)),
            size,
            blocks,
        }
    }

    fn run(&mut self, io: &FluxIo, ctx: &mut PassContext<'_>) {
        let levels = Levels { levels: Quadtree::of_blocks(io.size.0, io.size.1, io.blocks).table() };
        ctx.write_buffer(&io.levels, 0, bytemuck::bytes_of(&levels));
        let [albedo, normal, position] = &io.lamp;
        let bindings = PyramidBindings {
            params: ctx.buffer(&io.params),
            levels: ctx.buffer(&io.levels),
            nodes: ctx.buffer(&io.nodes),
            albedo: ctx.view(albedo),
            normal: ctx.view(normal),
            position: ctx.view(position),
            // Not read when building from the lamp.
            previous: ctx.view(albedo),
            flux: ctx.view(&io.flux),
            flux_view: ctx.view(&io.flux_view),
            blocks: io.blocks,
        };
        let dispatches = self.pyramid.record(&ctx.gpu.device, ctx.encoder, ctx.frame.globals, io.size, &bindings);
        ctx.count_dispatches(dispatches);
    }
}
