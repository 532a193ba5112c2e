//! Typed handles to graph resources, and the tokens that prove a pass declared its use.
//!
//! A handle is made once, when a pass or plugin is built, and names one resource of the graph
//! for good: a wrong handle is a type error, not a misspelt string. A pass's `declare` turns
//! handles into tokens — [`Read`] from [`PassDecl::read`](super::PassDecl::read), [`Write`]
//! from `write` or `create` — and its `run` can reach a resource only through such a token,
//! so what a pass declares and what it uses cannot disagree.

use std::fmt;
use std::marker::PhantomData;

use super::resource::{BufferDesc, ResourceDesc, TextureDesc};

/// The kind of a texture resource: `Handle<Image>`.
#[derive(Debug)]
pub enum Image {}

/// The kind of a buffer resource: `Handle<Buffer>`.
#[derive(Debug)]
pub enum Buffer {}

/// What a kind of resource is described by when it is created.
pub trait ResourceKind: 'static {
    type Desc: Copy;
    /// "texture" or "buffer", for errors.
    const NAME: &'static str;
    fn describe(desc: Self::Desc) -> ResourceDesc;
}

impl ResourceKind for Image {
    type Desc = TextureDesc;
    const NAME: &'static str = "texture";
    fn describe(desc: TextureDesc) -> ResourceDesc {
        ResourceDesc::Texture(desc)
    }
}

impl ResourceKind for Buffer {
    type Desc = BufferDesc;
    const NAME: &'static str = "buffer";
    fn describe(desc: BufferDesc) -> ResourceDesc {
        ResourceDesc::Buffer(desc)
    }
}

/// The index of a resource in its graph's registry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ResourceId(pub(crate) u32);

/// One resource of one graph; copied freely into the passes that use it.
pub struct Handle<K> {
    pub(crate) id: ResourceId,
    kind: PhantomData<fn() -> K>,
}

impl<K> Handle<K> {
    pub(crate) fn new(id: ResourceId) -> Self {
        Self { id, kind: PhantomData }
    }
    pub fn id(&self) -> ResourceId {
        self.id
    }
}

// Written out: a derive would ask `K: Clone`, and the kinds are never values.
impl<K> Clone for Handle<K> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<K> Copy for Handle<K> {}
impl<K> PartialEq for Handle<K> {
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id
    }
}
impl<K> Eq for Handle<K> {}
impl<K> fmt::Debug for Handle<K> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Handle({})", self.id.0)
    }
}

/// A pair of resources that swap every frame the pass writing `current` runs: what it wrote
/// is `previous` in the next frame. Both are re-created (zero) on a resize and by
/// [`RenderGraph::reset_history`](super::RenderGraph::reset_history).
pub struct History<K> {
    pub(crate) current: Handle<K>,
    pub(crate) previous: Handle<K>,
}

impl<K> History<K> {
    /// This frame's: created (with its descriptor) and written by one pass.
    pub fn current(&self) -> Handle<K> {
        self.current
    }
    /// Last frame's `current`, read-only; zero in the first frame after a reset.
    pub fn previous(&self) -> Handle<K> {
        self.previous
    }
}

impl<K> std::fmt::Debug for History<K> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "History(current {:?}, previous {:?})", self.current, self.previous)
    }
}

impl<K> Clone for History<K> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<K> Copy for History<K> {}

/// Proof that the pass declared it reads the resource: only `PassDecl::read` makes one.
pub struct Read<K>(pub(crate) Handle<K>);

/// Proof that the pass declared it writes the resource (or creates it): only
/// `PassDecl::write` and `PassDecl::create` make one.
pub struct Write<K>(pub(crate) Handle<K>);

/// A declared use of a resource, read or write: what `PassContext` looks resources up by.
pub trait Access<K> {
    fn handle(&self) -> Handle<K>;
}

impl<K> Access<K> for Read<K> {
    fn handle(&self) -> Handle<K> {
        self.0
    }
}

impl<K> Access<K> for Write<K> {
    fn handle(&self) -> Handle<K> {
        self.0
    }
}
