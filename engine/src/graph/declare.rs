//! What a pass declares each frame: the stage it runs in, and the resources it reads,
//! creates and writes, as tokens for its `run`.

use super::handle::{Handle, Read, ResourceId, ResourceKind, Write};
use super::resource::ResourceDesc;
use crate::view_state::ViewState;

/// The frame's phases, in the order they run. A pass belongs to one; every pass of an earlier
/// stage runs before every pass of a later one, so two passes of different stages are never
/// ambiguous. Within a stage, order comes from what the passes read and write, or from an
/// explicit [`PassOrder::after`](super::PassOrder::after)/[`before`](super::PassOrder::before).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Stage {
    /// The views rasterised: the camera's G-buffer, the detached lamp's own.
    GBuffer,
    /// Direct light from the G-buffer.
    Lighting,
    /// Light that arrives by way of other surfaces (a GI plugin's work).
    Indirect,
    /// The frame's radiance put together (`hdr`), and views derived from it.
    Composite,
    /// Effects over the lit frame (fog, say), after every light has been added.
    PostProcess,
    /// What is drawn over the finished frame: the weapon in hand.
    ViewModels,
    /// The chosen view (or a debug view drawn for it) written to the output.
    Present,
}

/// One declared use of a resource.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Use {
    Read(ResourceId),
    Write(ResourceId),
    Create(ResourceId, ResourceDesc),
}

impl Use {
    pub(crate) fn id(&self) -> ResourceId {
        match self {
            Use::Read(id) | Use::Write(id) | Use::Create(id, _) => *id,
        }
    }
}

/// What one pass reads, creates and writes this frame; filled in by [`RenderPass::declare`].
pub struct PassDecl<'f> {
    size: (u32, u32),
    view: &'f ViewState,
    pub(crate) uses: Vec<Use>,
}

impl<'f> PassDecl<'f> {
    pub(crate) fn new(size: (u32, u32), view: &'f ViewState) -> Self {
        Self { size, view, uses: Vec::new() }
    }

    /// The size of the view being rendered, in pixels.
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// What the frame is rendered from (declarations may depend on it: a detached lamp).
    pub fn view(&self) -> &'f ViewState {
        self.view
    }

    /// Samples or loads the resource; the pass runs after everything that creates or writes it.
    pub fn read<K>(&mut self, resource: Handle<K>) -> Read<K> {
        self.uses.push(Use::Read(resource.id));
        Read(resource)
    }

    /// Writes (or blends into) a resource another pass creates, or an imported one.
    pub fn write<K>(&mut self, resource: Handle<K>) -> Write<K> {
        self.uses.push(Use::Write(resource.id));
        Write(resource)
    }

    /// Creates the resource this frame with `desc`, and writes it: a transient's contents are
    /// undefined until then; a persistent one keeps last frame's while `desc` stays the same.
    /// One pass creates each resource.
    pub fn create<K: ResourceKind>(&mut self, resource: Handle<K>, desc: K::Desc) -> Write<K> {
        self.uses.push(Use::Create(resource.id, K::describe(desc)));
        Write(resource)
    }
}
