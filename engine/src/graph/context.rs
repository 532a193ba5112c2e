//! What a pass sees while it records: the GPU, the frame, the encoder, and the physical
//! resources behind the tokens its declaration made.

use super::compile::CompiledGraph;
use super::handle::{Access, Buffer, Handle, Image, ResourceId, Write};
use super::kept::KeptResources;
use super::pool::{Physical, ResourcePool};
use super::registry::{Lifetime, Registry};
use crate::frame::Frame;
use crate::gpu::Gpu;

/// A texture owned outside the graph (the swapchain image, a readback target).
pub struct ImportedTexture<'a> {
    pub handle: Handle<Image>,
    pub texture: &'a wgpu::Texture,
    pub view: &'a wgpu::TextureView,
}

/// Maps ids to the physical resources backing them for one execution.
pub(crate) struct ResourceTable<'a> {
    pub registry: &'a Registry,
    pub compiled: &'a CompiledGraph,
    pub pool: &'a ResourcePool,
    pub kept: &'a KeptResources,
    pub imports: &'a [ImportedTexture<'a>],
}

/// Where a resource lives this frame.
pub(crate) enum Backing<'a> {
    Graph(&'a Physical),
    Import(&'a ImportedTexture<'a>),
}

impl<'a> ResourceTable<'a> {
    pub fn backing(&self, id: ResourceId) -> Option<Backing<'a>> {
        match self.registry.lifetime(id) {
            Lifetime::Imported => self.imports.iter().find(|i| i.handle.id == id).map(Backing::Import),
            Lifetime::Transient => Some(Backing::Graph(self.pool.physical(self.compiled.slot(id)?))),
            Lifetime::Persistent => self.kept.physical(id, false).map(Backing::Graph),
            Lifetime::History { current, .. } => {
                self.kept.physical(self.registry.primary(id), !current).map(Backing::Graph)
            }
        }
    }

    fn get(&self, id: ResourceId) -> Backing<'a> {
        // A token exists only for a declared use, and the graph backs every declared use of a
        // scheduled pass (an import not supplied is the caller's error, named here).
        self.backing(id).unwrap_or_else(|| {
            panic!("render graph: '{}' has no backing this frame (an import not supplied?)", self.registry.label(id))
        })
    }
}

/// Draws and dispatches a pass recorded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PassCalls {
    pub draws: u32,
    pub dispatches: u32,
}

/// What a pass sees while recording.
pub struct PassContext<'a> {
    pub gpu: &'a Gpu,
    pub frame: &'a Frame<'a>,
    pub encoder: &'a mut wgpu::CommandEncoder,
    pub(crate) resources: &'a ResourceTable<'a>,
    pub(crate) calls: PassCalls,
}

// Resources borrow from the graph for the whole execution ('a), not from the context, so a
// pass can hold a view while it records into the encoder.
impl<'a> PassContext<'a> {
    pub fn texture(&self, access: &impl Access<Image>) -> &'a wgpu::Texture {
        match self.resources.get(access.handle().id) {
            Backing::Graph(p) => p.texture(),
            Backing::Import(i) => i.texture,
        }
    }

    /// The default view (all mips) of a texture.
    pub fn view(&self, access: &impl Access<Image>) -> &'a wgpu::TextureView {
        match self.resources.get(access.handle().id) {
            Backing::Graph(p) => p.view(),
            Backing::Import(i) => i.view,
        }
    }

    pub fn buffer(&self, access: &impl Access<Buffer>) -> &'a wgpu::Buffer {
        match self.resources.get(access.handle().id) {
            Backing::Graph(p) => p.buffer(),
            Backing::Import(_) => unreachable!("only textures are imported"),
        }
    }

    /// Writes `data` into a buffer at `offset` before the frame's commands run (the queue's
    /// write): the one way a pass fills a uniform it creates.
    pub fn write_buffer(&self, buffer: &Write<Buffer>, offset: u64, data: &[u8]) {
        self.gpu.queue.write_buffer(self.buffer(buffer), offset, data);
    }

    /// Frames of history behind a history pair's `previous` (read through `access`): 0 right
    /// after a reset, a resize or the first frame, when it holds zeros, and after a frame that
    /// did not write it, when it holds an older frame's.
    pub fn history_frames<K>(&self, access: &impl Access<K>) -> u32 {
        let id = access.handle().id;
        self.resources.kept.age(self.resources.registry.primary(id))
    }

    /// Counts draw calls the pass recorded (for `bench` and the overlay).
    pub fn count_draws(&mut self, n: u32) {
        self.calls.draws += n;
    }

    /// Counts compute dispatches the pass recorded.
    pub fn count_dispatches(&mut self, n: u32) {
        self.calls.dispatches += n;
    }
}
