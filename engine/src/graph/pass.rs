//! What a pass is to the graph: a declaration of the resources it reads, creates and writes,
//! and a `run` that records it with the tokens the declaration made.

use super::context::PassContext;
use super::declare::PassDecl;

/// One node of the graph. `declare` is called every frame and must be cheap; what it declares
/// may change (with settings, the displayed view, [`PassDecl::view`]) and the graph
/// re-schedules when it does. What it returns, the pass's tokens, is handed to `run`.
pub trait RenderPass: 'static {
    /// The tokens of the resources the pass uses (a struct of [`Read`](super::Read)s and [`Write`](super::Write)s, or
    /// `()` for a pass that uses none).
    type Io: 'static;
    fn name(&self) -> &str;
    fn declare(&self, decl: &mut PassDecl<'_>) -> Self::Io;
    fn run(&mut self, io: &Self::Io, ctx: &mut PassContext<'_>);
}

/// A pass with its tokens, behind one object-safe interface.
pub(crate) trait Node {
    fn name(&self) -> &str;
    fn declare(&mut self, decl: &mut PassDecl<'_>);
    fn run(&mut self, ctx: &mut PassContext<'_>);
}

pub(crate) struct Declared<P: RenderPass> {
    pub pass: P,
    pub io: Option<P::Io>,
}

impl<P: RenderPass> Node for Declared<P> {
    fn name(&self) -> &str {
        self.pass.name()
    }
    fn declare(&mut self, decl: &mut PassDecl<'_>) {
        self.io = Some(self.pass.declare(decl));
    }
    fn run(&mut self, ctx: &mut PassContext<'_>) {
        let io = self.io.as_ref().expect("the graph declares every pass before it runs");
        self.pass.run(io, ctx);
    }
}

/// Explicit order between a new pass and passes of its stage, by name; returned by
/// `add_pass`. A name no pass has is an error when the graph is compiled.
pub struct PassOrder<'g> {
    pub(crate) name: String,
    pub(crate) edges: &'g mut Vec<(String, String)>,
}

impl PassOrder<'_> {
    /// The pass runs after `other`.
    pub fn after(self, other: &str) -> Self {
        self.edges.push((other.to_owned(), self.name.clone()));
        self
    }
    /// The pass runs before `other`.
    pub fn before(self, other: &str) -> Self {
        self.edges.push((self.name.clone(), other.to_owned()));
        self
    }
}
