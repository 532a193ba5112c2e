//! A small render graph in the spirit of kajiya-rg, Bevy and rend3.
//!
//! - Resources are typed handles ([`Handle<Image>`], [`Handle<Buffer>`]) made once when passes
//!   are built; their labels name them in errors, debug views and menus.
//! - Each pass belongs to a [`Stage`]; every frame it declares what it reads, creates and
//!   writes, and gets back tokens ([`Read`], [`Write`]) that are its only way to the resources
//!   in `run`.
//! - The graph orders passes by stage, then by their declarations and explicit
//!   [`PassOrder::after`]/[`PassOrder::before`]; it culls passes whose results reach no import,
//!   and it refuses, naming the passes, a graph whose order is unclear: two writers of one
//!   resource that nothing orders, a uniform written by two passes, a cycle.
//! - Transient resources are pooled by descriptor and share memory when their lifetimes do not
//!   overlap. Persistent resources and [`History`] pairs live across frames, owned by the graph,
//!   until a resize or [`RenderGraph::reset_history`].

mod compile;
mod context;
mod declare;
mod handle;
mod kept;
mod pass;
mod pool;
mod registry;
mod resource;

pub use compile::{CompiledGraph, GraphError};
pub use context::{ImportedTexture, PassCalls, PassContext};
pub use declare::{PassDecl, Stage};
pub use handle::{Access, Buffer, Handle, History, Image, Read, ResourceId, ResourceKind, Write};
pub use pass::{PassOrder, RenderPass};
pub use pool::{PoolStats, ResourcePool};
pub use resource::{BufferDesc, ResourceDesc, SizeRule, TextureDesc};

use compile::PassInfo;
use context::{Backing, ResourceTable};
use declare::Use;
use kept::KeptResources;
use pass::{Declared, Node};
use registry::{Lifetime, Registry};

use crate::frame::Frame;
use crate::gpu::Gpu;
use crate::gpu_timer::GpuTimer;
use crate::view_state::ViewState;

struct Registered {
    stage: Stage,
    node: Box<dyn Node>,
}

/// The resources, the passes, the compiled schedule, and the memory behind it all.
#[derive(Default)]
pub struct RenderGraph {
    registry: Registry,
    passes: Vec<Registered>,
    /// Explicit orders, (before, after) by pass name.
    explicit: Vec<(String, String)>,
    /// Passes asked to be replaced that the graph did not have (an error at compile).
    unknown_replaced: Vec<String>,
    compiled: Option<CompiledGraph>,
    /// The declarations `compiled` was built from.
    declared: Vec<Vec<Use>>,
    pool: ResourcePool,
    kept: KeptResources,
    allocated_for: Option<(u32, u32)>,
    /// Whether to time passes; the timer is made on the first timed frame.
    timing: bool,
    timer: Option<GpuTimer>,
    /// Each scheduled pass of the last frame (its index in `passes`) and what it recorded.
    calls: Vec<(usize, PassCalls)>,
}

impl RenderGraph {
    pub fn new() -> Self {
        Self::default()
    }

    /// A texture that lives within a frame (from the pass creating it to its last reader).
    pub fn image(&mut self, label: &str) -> Handle<Image> {
        Handle::new(self.add(label, Lifetime::Transient))
    }

    /// A buffer that lives within a frame.
    pub fn buffer(&mut self, label: &str) -> Handle<Buffer> {
        Handle::new(self.add(label, Lifetime::Transient))
    }

    /// A texture kept across frames (re-created, zero, on a resize and on a history reset).
    pub fn persistent_image(&mut self, label: &str) -> Handle<Image> {
        Handle::new(self.add(label, Lifetime::Persistent))
    }

    /// A buffer kept across frames (re-created, zero, when its size changes and on a reset).
    pub fn persistent_buffer(&mut self, label: &str) -> Handle<Buffer> {
        Handle::new(self.add(label, Lifetime::Persistent))
    }

    /// A texture with last frame's contents beside this frame's (labels `label` and
    /// `label.previous`).
    pub fn history_image(&mut self, label: &str) -> History<Image> {
        let (current, previous) = self.registry.add_pair(label);
        self.compiled = None;
        History { current: Handle::new(current), previous: Handle::new(previous) }
    }

    /// A buffer with last frame's contents beside this frame's.
    pub fn history_buffer(&mut self, label: &str) -> History<Buffer> {
        let (current, previous) = self.registry.add_pair(label);
        self.compiled = None;
        History { current: Handle::new(current), previous: Handle::new(previous) }
    }

    /// A texture supplied at execution (see [`ImportedTexture`]). Passes writing an import are
    /// the graph's roots: everything they depend on is kept, the rest is culled.
    pub fn import_image(&mut self, label: &str) -> Handle<Image> {
        Handle::new(self.add(label, Lifetime::Imported))
    }

    fn add(&mut self, label: &str, lifetime: Lifetime) -> ResourceId {
        self.compiled = None;
        self.registry.add(label, lifetime)
    }

    /// The label a resource was made with.
    pub fn label(&self, id: ResourceId) -> &str {
        self.registry.label(id)
    }

    /// The texture labelled `label`, for tools and tests that read results back by name
    /// (passes hold handles).
    pub fn find_image(&self, label: &str) -> Option<Handle<Image>> {
        self.registry.find(label).map(Handle::new)
    }

    /// The buffer labelled `label` (see [`RenderGraph::find_image`]).
    pub fn find_buffer(&self, label: &str) -> Option<Handle<Buffer>> {
        self.registry.find(label).map(Handle::new)
    }

    /// Adds a pass to `stage`; the returned [`PassOrder`] can order it against passes of the
    /// same stage by name.
    pub fn add_pass<P: RenderPass>(&mut self, stage: Stage, pass: P) -> PassOrder<'_> {
        let name = pass.name().to_owned();
        self.passes.push(Registered { stage, node: Box::new(Declared { pass, io: None }) });
        self.compiled = None;
        PassOrder { name, edges: &mut self.explicit }
    }

    /// Puts `pass` in the place of the pass named `name`: in its stage, and in the explicit
    /// orders that name it. For a plugin that does a pass's work together with its own in one
    /// pass (the GI makes the frame's radiance, direct + emissive + indirect, in one draw in
    /// place of `composite`). A name no pass has is an error when the graph is compiled.
    pub fn replace_pass<P: RenderPass>(&mut self, name: &str, pass: P) -> PassOrder<'_> {
        let new_name = pass.name().to_owned();
        match self.passes.iter_mut().find(|p| p.node.name() == name) {
            Some(old) => {
                old.node = Box::new(Declared { pass, io: None });
                for (before, after) in &mut self.explicit {
                    for end in [before, after] {
                        if end == name {
                            end.clone_from(&new_name);
                        }
                    }
                }
            }
            None => self.unknown_replaced.push(name.to_owned()),
        }
        self.compiled = None;
        PassOrder { name: new_name, edges: &mut self.explicit }
    }

    /// Forgets every history and persistent resource: the next frame starts from zeros, as
    /// after a cut (a level loaded, a restart, a teleport, the lamp set down or picked up).
    pub fn reset_history(&mut self) {
        self.kept.reset();
    }

    pub fn pass_names(&self) -> Vec<String> {
        self.passes.iter().map(|p| p.node.name().to_owned()).collect()
    }

    /// Declares every pass for a frame of `size` rendered from `view`, then orders, culls and
    /// checks the graph; errors name the passes and resources at fault. Re-schedules only when
    /// some declaration changed since the last call.
    pub fn compile(&mut self, size: (u32, u32), view: &ViewState) -> Result<&CompiledGraph, GraphError> {
        if let Some(name) = self.unknown_replaced.first() {
            return Err(GraphError::UnknownPass(name.clone()));
        }
        let decls: Vec<Vec<Use>> = self
            .passes
            .iter_mut()
            .map(|p| {
                let mut d = PassDecl::new(size, view);
                p.node.declare(&mut d);
                d.uses
            })
            .collect();
        if self.compiled.is_none() || decls != self.declared {
            self.compiled = None;
            let infos: Vec<PassInfo<'_>> = self
                .passes
                .iter()
                .zip(&decls)
                .map(|(p, uses)| PassInfo { name: p.node.name(), stage: p.stage, uses })
                .collect();
            let compiled = CompiledGraph::compile(&infos, &self.explicit, &self.registry)?;
            self.compiled = Some(compiled);
            self.declared = decls;
            self.allocated_for = None;
        }
        Ok(self.compiled.as_ref().expect("just compiled"))
    }

    /// Backs every resource the scheduled passes use for a view of `size`: transients from the
    /// pool, kept resources made where missing or of another size.
    pub fn allocate(&mut self, gpu: &Gpu, size: (u32, u32), view: &ViewState) -> Result<(), GraphError> {
        self.compile(size, view)?;
        let compiled = self.compiled.as_mut().expect("compiled above");
        if self.allocated_for != Some(size) {
            compiled.assign_slots(&mut self.pool, &gpu.device, size, &self.registry);
            self.allocated_for = Some(size);
        }
        let registry = &self.registry;
        let wanted = compiled.kept.iter().map(|(&id, &desc)| {
            let pair = matches!(registry.lifetime(id), Lifetime::History { .. });
            (id, desc, pair, registry.label(id))
        });
        self.kept.prepare(&gpu.device, wanted, size);
        Ok(())
    }

    /// Times every scheduled pass on the GPU from the next frame on (when the device can write
    /// timestamps inside encoders), or stops and forgets the timings.
    pub fn set_timing(&mut self, on: bool) {
        self.timing = on;
        if !on {
            self.timer = None;
        }
    }

    pub fn timing(&self) -> bool {
        self.timing
    }

    /// The GPU time of each pass of the last timed frame, in execution order, in milliseconds;
    /// None when timing is off or unsupported, or before the first timed frame. Blocks until
    /// that frame has finished on the GPU.
    pub fn last_pass_times(&self, gpu: &Gpu) -> Option<Vec<(String, f64)>> {
        self.timer.as_ref()?.read(gpu)
    }

    /// Each pass of the last frame, in execution order, and the draws and dispatches it
    /// recorded.
    pub fn last_calls(&self) -> impl Iterator<Item = (&str, PassCalls)> {
        self.calls.iter().map(|&(i, calls)| (self.passes[i].node.name(), calls))
    }

    pub fn pool_stats(&self) -> PoolStats {
        let pool = self.pool.stats();
        PoolStats { live: pool.live + self.kept.live(), allocations: pool.allocations + self.kept.allocations() }
    }

    /// The schedule of the last compile (see [`CompiledGraph::order_names`]).
    pub fn compiled(&self) -> Option<&CompiledGraph> {
        self.compiled.as_ref()
    }

    /// The id of the pooled resource backing a transient (for tests and debugging).
    pub fn physical_slot<K>(&self, resource: Handle<K>) -> Option<usize> {
        self.compiled.as_ref()?.slot(resource.id)
    }

    fn backing(&self, id: ResourceId) -> Option<&pool::Physical> {
        let compiled = self.compiled.as_ref()?;
        let table =
            ResourceTable { registry: &self.registry, compiled, pool: &self.pool, kept: &self.kept, imports: &[] };
        match table.backing(id)? {
            Backing::Graph(p) => Some(p),
            Backing::Import(_) => None,
        }
    }

    /// The texture behind a handle after the last frame (for tests and readback).
    pub fn physical_texture(&self, resource: Handle<Image>) -> Option<&wgpu::Texture> {
        Some(self.backing(resource.id)?.texture())
    }

    /// The buffer behind a handle after the last frame (for tests and readback).
    pub fn physical_buffer(&self, resource: Handle<Buffer>) -> Option<&wgpu::Buffer> {
        Some(self.backing(resource.id)?.buffer())
    }

    /// The texture labelled `label` after the last frame (for tools and tests).
    pub fn texture_by_label(&self, label: &str) -> Option<&wgpu::Texture> {
        self.physical_texture(self.find_image(label)?)
    }

    /// The buffer labelled `label` after the last frame (for tools and tests).
    pub fn buffer_by_label(&self, label: &str) -> Option<&wgpu::Buffer> {
        self.physical_buffer(self.find_buffer(label)?)
    }

    /// Records every scheduled pass into `encoder`.
    pub fn execute(
        &mut self,
        gpu: &Gpu,
        frame: &Frame<'_>,
        encoder: &mut wgpu::CommandEncoder,
        imports: &[ImportedTexture<'_>],
    ) -> Result<(), GraphError> {
        self.allocate(gpu, frame.size, frame.view)?;
        let compiled = self.compiled.as_ref().expect("allocated above");
        let table = ResourceTable { registry: &self.registry, compiled, pool: &self.pool, kept: &self.kept, imports };
        let order = compiled.order();
        if self.timing && self.timer.as_ref().is_none_or(|t| (t.capacity() as usize) < order.len()) {
            self.timer = GpuTimer::new(gpu, order.len() as u32);
        }
        // Disabled timing costs one branch per pass.
        let timer = if self.timing { self.timer.as_mut() } else { None };
        self.calls.clear();
        for (i, &index) in order.iter().enumerate() {
            let node = &mut self.passes[index].node;
            if let Some(t) = &timer {
                t.start(encoder, i);
            }
            encoder.push_debug_group(node.name());
            let mut ctx = PassContext { gpu, frame, encoder, resources: &table, calls: PassCalls::default() };
            node.run(&mut ctx);
            let calls = ctx.calls;
            encoder.pop_debug_group();
            if let Some(t) = &timer {
                t.end(encoder, i);
            }
            self.calls.push((index, calls));
        }
        if let Some(t) = timer {
            t.finish(encoder, order.iter().map(|&i| self.passes[i].node.name().to_owned()).collect());
        }
        // What was written as current is the previous of the next frame.
        self.kept.end_frame(&compiled.swapped);
        Ok(())
    }
}
