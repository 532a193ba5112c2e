//! A small render graph in the spirit of kajiya-rg and rend3: passes declare the named textures
//! and buffers they read, create and write; the graph orders them from those declarations,
//! culls passes whose results nobody uses, and backs transient resources with a pool keyed by
//! descriptor, aliasing resources whose lifetimes do not overlap.
//!
//! Ordering rule (documented because passes rely on it): for each resource, its creator and
//! then its writers run in registration order; every pure reader runs after all of them.

mod compile;
mod pool;
mod resource;

pub use compile::{CompiledGraph, GraphError};
pub use pool::{PoolStats, ResourcePool};
pub use resource::{BufferDesc, ResourceDesc, SizeRule, TextureDesc};

use crate::frame::Frame;
use crate::gpu::Gpu;
use crate::gpu_timer::GpuTimer;

/// What declarations may depend on besides a pass's own settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeclareContext {
    /// The headlamp sits at the camera (its view is the camera's G-buffer).
    pub lamp_attached: bool,
}

impl Default for DeclareContext {
    fn default() -> Self {
        Self { lamp_attached: true }
    }
}

/// What one pass reads, creates and writes; filled in by [`RenderPass::declare`].
#[derive(Default, Debug, Clone, PartialEq)]
pub struct PassDecl {
    context: DeclareContext,
    pub(crate) reads: Vec<String>,
    pub(crate) creates: Vec<(String, ResourceDesc)>,
    pub(crate) writes: Vec<String>,
}

impl PassDecl {
    pub fn new(context: DeclareContext) -> Self {
        Self { context, ..Self::default() }
    }
    /// The frame state declarations may depend on.
    pub fn context(&self) -> DeclareContext {
        self.context
    }
    /// Samples or loads `name`; runs after everything that creates or writes it.
    pub fn read(&mut self, name: &str) -> &mut Self {
        self.reads.push(name.to_owned());
        self
    }
    /// Creates the transient texture `name`; its contents are undefined until this pass writes them.
    pub fn create_texture(&mut self, name: &str, desc: TextureDesc) -> &mut Self {
        self.creates.push((name.to_owned(), ResourceDesc::Texture(desc)));
        self
    }
    /// Creates the transient buffer `name`.
    pub fn create_buffer(&mut self, name: &str, desc: BufferDesc) -> &mut Self {
        self.creates.push((name.to_owned(), ResourceDesc::Buffer(desc)));
        self
    }
    /// Writes (or blends into) a resource created by an earlier pass or imported.
    pub fn write(&mut self, name: &str) -> &mut Self {
        self.writes.push(name.to_owned());
        self
    }
}

/// One node of the graph. `declare` is called every frame and must be cheap; it may change
/// (with settings, the displayed view, [`PassDecl::context`]) and the graph re-schedules
/// when it does.
pub trait RenderPass {
    fn name(&self) -> &str;
    fn declare(&self, decl: &mut PassDecl);
    fn run(&mut self, ctx: &mut PassContext<'_>);
}

/// What a pass sees while recording.
pub struct PassContext<'a> {
    pub gpu: &'a Gpu,
    pub frame: &'a Frame<'a>,
    pub encoder: &'a mut wgpu::CommandEncoder,
    resources: &'a ResourceTable<'a>,
}

// Resources borrow from the graph for the whole execution ('a), not from the context, so a
// pass can hold a view while it records into the encoder.
impl<'a> PassContext<'a> {
    pub fn texture(&self, name: &str) -> &'a wgpu::Texture {
        self.resources.texture(name)
    }
    /// The default view (all mips) of a texture.
    pub fn view(&self, name: &str) -> &'a wgpu::TextureView {
        self.resources.view(name)
    }
    pub fn buffer(&self, name: &str) -> &'a wgpu::Buffer {
        self.resources.buffer(name)
    }
}

/// A texture owned outside the graph (the swapchain image, a readback target).
pub struct ImportedTexture<'a> {
    pub name: &'a str,
    pub texture: &'a wgpu::Texture,
    pub view: &'a wgpu::TextureView,
}

/// Maps names to the physical resources backing them for one execution.
pub(crate) struct ResourceTable<'a> {
    compiled: &'a CompiledGraph,
    pool: &'a ResourcePool,
    imports: &'a [ImportedTexture<'a>],
}

impl<'a> ResourceTable<'a> {
    fn imported(&self, name: &str) -> Option<&'a ImportedTexture<'a>> {
        self.imports.iter().find(|i| i.name == name)
    }
    fn texture(&self, name: &str) -> &'a wgpu::Texture {
        if let Some(i) = self.imported(name) {
            return i.texture;
        }
        self.pool.texture(self.compiled.slot(name).unwrap_or_else(|| undeclared(name)))
    }
    fn view(&self, name: &str) -> &'a wgpu::TextureView {
        if let Some(i) = self.imported(name) {
            return i.view;
        }
        self.pool.view(self.compiled.slot(name).unwrap_or_else(|| undeclared(name)))
    }
    fn buffer(&self, name: &str) -> &'a wgpu::Buffer {
        self.pool.buffer(self.compiled.slot(name).unwrap_or_else(|| undeclared(name)))
    }
}

fn undeclared(name: &str) -> ! {
    // A pass asked for a resource it never declared: a programming error in that pass.
    panic!("render graph: resource '{name}' was not declared by any scheduled pass")
}

/// The passes, the names imported from outside, the compiled schedule and the pool.
#[derive(Default)]
pub struct RenderGraph {
    passes: Vec<Box<dyn RenderPass>>,
    imports: Vec<String>,
    compiled: Option<CompiledGraph>,
    /// The declarations `compiled` was built from.
    declared: Vec<(String, PassDecl)>,
    /// The context of the frame being scheduled.
    context: DeclareContext,
    pool: ResourcePool,
    allocated_for: Option<(u32, u32)>,
    /// Whether to time passes; the timer is made on the first timed frame.
    timing: bool,
    timer: Option<GpuTimer>,
}

impl RenderGraph {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn add_pass(&mut self, pass: Box<dyn RenderPass>) {
        self.passes.push(pass);
        self.compiled = None;
    }

    /// Declares a resource supplied at execution time. Passes writing an import are the
    /// graph's roots: everything they depend on is kept, the rest is culled.
    pub fn import(&mut self, name: &str) {
        self.imports.push(name.to_owned());
        self.compiled = None;
    }

    /// Forces re-declaration and re-scheduling (after a pass changed what it declares).
    pub fn invalidate(&mut self) {
        self.compiled = None;
    }

    pub fn pass_names(&self) -> Vec<String> {
        self.passes.iter().map(|p| p.name().to_owned()).collect()
    }

    /// Orders, culls and checks the graph; errors name the pass and resource at fault.
    /// Re-schedules only when some pass's declaration changed since the last call.
    pub fn compile(&mut self) -> Result<&CompiledGraph, GraphError> {
        let decls: Vec<(String, PassDecl)> = self
            .passes
            .iter()
            .map(|p| {
                let mut d = PassDecl::new(self.context);
                p.declare(&mut d);
                (p.name().to_owned(), d)
            })
            .collect();
        if self.compiled.is_none() || decls != self.declared {
            self.compiled = None;
            self.compiled = Some(CompiledGraph::compile(&decls, &self.imports)?);
            self.declared = decls;
            self.allocated_for = None;
        }
        Ok(self.compiled.as_ref().expect("just compiled"))
    }

    /// Backs every transient resource for a view of `size`, reusing pooled ones.
    pub fn allocate(&mut self, gpu: &Gpu, size: (u32, u32)) -> Result<(), GraphError> {
        self.compile()?;
        if self.allocated_for != Some(size) {
            let compiled = self.compiled.as_mut().expect("compiled above");
            compiled.assign_slots(&mut self.pool, &gpu.device, size);
            self.allocated_for = Some(size);
        }
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

    pub fn pool_stats(&self) -> PoolStats {
        self.pool.stats()
    }

    /// The schedule of the last compile (see [`CompiledGraph::order_names`]).
    pub fn compiled(&self) -> Option<&CompiledGraph> {
        self.compiled.as_ref()
    }

    /// The id of the physical resource backing `name` (for tests and debugging).
    pub fn physical_slot(&self, name: &str) -> Option<usize> {
        self.compiled.as_ref()?.slot(name)
    }

    pub fn physical_texture(&self, name: &str) -> Option<&wgpu::Texture> {
        Some(self.pool.texture(self.physical_slot(name)?))
    }

    pub fn physical_buffer(&self, name: &str) -> Option<&wgpu::Buffer> {
        Some(self.pool.buffer(self.physical_slot(name)?))
    }

    /// Records every scheduled pass into `encoder`.
    pub fn execute(
        &mut self,
        gpu: &Gpu,
        frame: &Frame<'_>,
        encoder: &mut wgpu::CommandEncoder,
        imports: &[ImportedTexture<'_>],
    ) -> Result<(), GraphError> {
        self.context = DeclareContext { lamp_attached: frame.view.headlamp.attached };
        self.allocate(gpu, frame.size)?;
        let compiled = self.compiled.as_ref().expect("allocated above");
        let table = ResourceTable { compiled, pool: &self.pool, imports };
        let order = compiled.order();
        if self.timing && self.timer.as_ref().is_none_or(|t| (t.capacity() as usize) < order.len()) {
            self.timer = GpuTimer::new(gpu, order.len() as u32);
        }
        // Disabled timing costs one branch per pass.
        let timer = if self.timing { self.timer.as_mut() } else { None };
        for (i, &index) in order.iter().enumerate() {
            let pass = &mut self.passes[index];
            if let Some(t) = &timer {
                t.start(encoder, i);
            }
            encoder.push_debug_group(pass.name());
            let mut ctx = PassContext { gpu, frame, encoder, resources: &table };
            pass.run(&mut ctx);
            encoder.pop_debug_group();
            if let Some(t) = &timer {
                t.end(encoder, i);
            }
        }
        if let Some(t) = timer {
            t.finish(encoder, order.iter().map(|&i| self.passes[i].name().to_owned()).collect());
        }
        Ok(())
    }
}
