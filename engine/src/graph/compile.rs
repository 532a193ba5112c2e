//! Scheduling: dependency edges from declarations, stages and explicit order; the checks that
//! make an unclear graph an error; culling; a stable order; lifetimes of transients.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};
use std::fmt;

use super::declare::{Stage, Use};
use super::handle::ResourceId;
use super::pool::ResourcePool;
use super::registry::{Lifetime, Registry};
use super::resource::ResourceDesc;

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum GraphError {
    /// A pass reads or writes a resource that no pass creates and that is not imported.
    MissingInput {
        pass: String,
        resource: String,
    },
    /// Two passes both create the same resource.
    CreatedTwice {
        resource: String,
        first: String,
        second: String,
    },
    /// A pass creates what the graph supplies: an import, or a history's previous frame.
    CreatesSupplied {
        pass: String,
        resource: String,
    },
    /// A uniform buffer is written by a pass besides its creator: one writer per frame.
    UniformWrittenTwice {
        resource: String,
        creator: String,
        writer: String,
    },
    /// Two passes write one resource and nothing says which goes first.
    AmbiguousOrder {
        resource: String,
        first: String,
        second: String,
    },
    DuplicatePass(String),
    /// Two resources have one label.
    DuplicateLabel(String),
    /// An explicit order, or a replacement, names a pass the graph does not have.
    UnknownPass(String),
    /// The declarations, stages and explicit orders put these passes in a circle.
    Cycle {
        passes: Vec<String>,
    },
}

impl fmt::Display for GraphError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GraphError::MissingInput { pass, resource } => {
                write!(f, "render graph: pass '{pass}' uses '{resource}', which no pass creates and nothing imports")
            }
            GraphError::CreatedTwice { resource, first, second } => {
                write!(f, "render graph: '{resource}' is created by both '{first}' and '{second}'")
            }
            GraphError::CreatesSupplied { pass, resource } => write!(
                f,
                "render graph: pass '{pass}' creates '{resource}', which the graph supplies (an import or last \
                 frame's history)"
            ),
            GraphError::UniformWrittenTwice { resource, creator, writer } => write!(
                f,
                "render graph: uniform '{resource}' is written by '{creator}' and '{writer}'; a uniform has one \
                 writer per frame"
            ),
            GraphError::AmbiguousOrder { resource, first, second } => write!(
                f,
                "render graph: '{first}' and '{second}' both write '{resource}' and nothing orders them; put them \
                 in different stages or declare one after the other"
            ),
            GraphError::DuplicatePass(name) => write!(f, "render graph: two passes are named '{name}'"),
            GraphError::DuplicateLabel(label) => write!(f, "render graph: two resources are labelled '{label}'"),
            GraphError::UnknownPass(name) => {
                write!(f, "render graph: an explicit order or a replacement names '{name}', no pass")
            }
            GraphError::Cycle { passes } => {
                write!(f, "render graph: dependency cycle between passes {}", passes.join(" -> "))
            }
        }
    }
}

impl std::error::Error for GraphError {}

/// A pass as the scheduler sees it.
pub(crate) struct PassInfo<'a> {
    pub name: &'a str,
    pub stage: Stage,
    pub uses: &'a [Use],
}

#[derive(Debug)]
pub(crate) struct Transient {
    pub desc: ResourceDesc,
    /// Positions in `order` of the first and last pass touching it.
    pub first: usize,
    pub last: usize,
    pub slot: Option<usize>,
}

/// The result of compiling: which passes run, in which order, the descriptors of what they
/// create, and the lifetimes of transients.
#[derive(Debug)]
pub struct CompiledGraph {
    order: Vec<usize>,
    names: Vec<String>,
    pub(crate) transients: BTreeMap<ResourceId, Transient>,
    /// Persistent resources and history pairs (by their `current`) created by scheduled passes.
    pub(crate) kept: BTreeMap<ResourceId, ResourceDesc>,
    /// History pairs whose current a scheduled pass creates: they swap after the frame.
    pub(crate) swapped: Vec<ResourceId>,
}

impl CompiledGraph {
    pub(crate) fn compile(
        passes: &[PassInfo<'_>],
        explicit: &[(String, String)],
        registry: &Registry,
    ) -> Result<CompiledGraph, GraphError> {
        let n = passes.len();
        let label = |id: ResourceId| registry.label(id).to_owned();
        for (i, p) in passes.iter().enumerate() {
            if passes[..i].iter().any(|q| q.name == p.name) {
                return Err(GraphError::DuplicatePass(p.name.to_owned()));
            }
        }
        if let Some(label) = registry.duplicate_label() {
            return Err(GraphError::DuplicateLabel(label.to_owned()));
        }

        // Who creates, writes and reads each resource.
        let mut creator: BTreeMap<ResourceId, (usize, ResourceDesc)> = BTreeMap::new();
        let mut writers: BTreeMap<ResourceId, Vec<usize>> = BTreeMap::new();
        let mut readers: BTreeMap<ResourceId, Vec<usize>> = BTreeMap::new();
        for (i, p) in passes.iter().enumerate() {
            for u in p.uses {
                match u {
                    Use::Create(id, desc) => {
                        if !registry.created_by_passes(*id) {
                            return Err(GraphError::CreatesSupplied { pass: p.name.into(), resource: label(*id) });
                        }
                        if let Some((first, _)) = creator.get(id) {
                            return Err(GraphError::CreatedTwice {
                                resource: label(*id),
                                first: passes[*first].name.into(),
                                second: p.name.into(),
                            });
                        }
                        creator.insert(*id, (i, *desc));
                    }
                    Use::Write(id) => writers.entry(*id).or_default().push(i),
                    Use::Read(id) => readers.entry(*id).or_default().push(i),
                }
            }
        }
        for p in passes {
            for u in p.uses {
                // A history's previous frame exists when its current has a creator.
                let id = registry.primary(u.id());
                if registry.created_by_passes(id) && !creator.contains_key(&id) {
                    return Err(GraphError::MissingInput { pass: p.name.into(), resource: label(id) });
                }
            }
        }
        // One writer per uniform a frame: its creator.
        for (id, list) in &writers {
            let Some(&(c, ResourceDesc::Buffer(desc))) = creator.get(id) else { continue };
            if desc.usage.contains(wgpu::BufferUsages::UNIFORM) {
                if let Some(&w) = list.iter().find(|&&w| w != c) {
                    return Err(GraphError::UniformWrittenTwice {
                        resource: label(*id),
                        creator: passes[c].name.into(),
                        writer: passes[w].name.into(),
                    });
                }
            }
        }

        // Data edges (what culling follows): the creator before every other user; every
        // writer before every pure reader.
        let mut data: Vec<Vec<usize>> = vec![Vec::new(); n];
        let add = |edges: &mut Vec<Vec<usize>>, a: usize, b: usize| {
            if a != b && !edges[a].contains(&b) {
                edges[a].push(b);
            }
        };
        for (id, list) in &readers {
            let producers: Vec<usize> = creator
                .get(id)
                .map(|c| c.0)
                .into_iter()
                .chain(writers.get(id).into_iter().flatten().copied())
                .collect();
            for &r in list {
                if producers.contains(&r) {
                    continue;
                }
                for &p in &producers {
                    add(&mut data, p, r);
                }
            }
        }
        for (id, list) in &writers {
            if let Some(&(c, _)) = creator.get(id) {
                for &w in list {
                    add(&mut data, c, w);
                }
            }
        }

        // Order edges: the data edges, explicit orders, and stages.
        let mut order_edges = data.clone();
        let index = |name: &str| {
            passes.iter().position(|p| p.name == name).ok_or_else(|| GraphError::UnknownPass(name.to_owned()))
        };
        for (before, after) in explicit {
            let (a, b) = (index(before)?, index(after)?);
            add(&mut order_edges, a, b);
        }
        for a in 0..n {
            for b in 0..n {
                if passes[a].stage < passes[b].stage {
                    add(&mut order_edges, a, b);
                }
            }
        }

        // Cull: keep what leads to an import (the graph's outputs) along data edges.
        let mut pred: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (a, succ) in data.iter().enumerate() {
            for &b in succ {
                pred[b].push(a);
            }
        }
        let mut live = vec![false; n];
        let mut stack: Vec<usize> = (0..n)
            .filter(|&i| {
                passes[i]
                    .uses
                    .iter()
                    .any(|u| matches!(u, Use::Write(id) if registry.lifetime(*id) == Lifetime::Imported))
            })
            .collect();
        while let Some(i) = stack.pop() {
            if !live[i] {
                live[i] = true;
                stack.extend(pred[i].iter().copied());
            }
        }

        // Kahn's algorithm over the live passes: earliest stage, then registration, first.
        let mut indegree = vec![0usize; n];
        for a in (0..n).filter(|&a| live[a]) {
            for &b in &order_edges[a] {
                indegree[b] += 1;
            }
        }
        let key = |i: usize| Reverse((passes[i].stage, i));
        let mut ready: BinaryHeap<Reverse<(Stage, usize)>> =
            (0..n).filter(|&i| live[i] && indegree[i] == 0).map(key).collect();
        let mut order = Vec::new();
        while let Some(Reverse((_, i))) = ready.pop() {
            order.push(i);
            for &s in &order_edges[i] {
                indegree[s] -= 1;
                if indegree[s] == 0 && live[s] {
                    ready.push(key(s));
                }
            }
        }
        if order.len() != live.iter().filter(|&&l| l).count() {
            let stuck = (0..n).filter(|&i| live[i] && !order.contains(&i)).map(|i| passes[i].name.to_owned());
            return Err(GraphError::Cycle { passes: stuck.collect() });
        }

        // Two live writers of one resource must be ordered by something they declared.
        let reach = reachability(&order_edges, &live);
        for (id, list) in &writers {
            let list: Vec<usize> = list.iter().copied().filter(|&w| live[w]).collect();
            for (k, &a) in list.iter().enumerate() {
                for &b in &list[k + 1..] {
                    if a != b && !reach[a][b] && !reach[b][a] {
                        return Err(GraphError::AmbiguousOrder {
                            resource: label(*id),
                            first: passes[a].name.into(),
                            second: passes[b].name.into(),
                        });
                    }
                }
            }
        }

        // Lifetimes of transients; descriptors of what is kept across frames.
        let mut transients = BTreeMap::new();
        let mut kept = BTreeMap::new();
        for (pos, &i) in order.iter().enumerate() {
            for u in passes[i].uses {
                let id = registry.primary(u.id());
                let Some(&(_, desc)) = creator.get(&id) else { continue };
                if registry.lifetime(id) != Lifetime::Transient {
                    kept.insert(id, desc);
                    continue;
                }
                let t = transients.entry(id).or_insert(Transient { desc, first: pos, last: pos, slot: None });
                t.first = t.first.min(pos);
                t.last = t.last.max(pos);
            }
        }
        let swapped = creator
            .iter()
            .filter(|(&id, &(c, _))| live[c] && matches!(registry.lifetime(id), Lifetime::History { .. }))
            .map(|(&id, _)| id)
            .collect();
        let names = passes.iter().map(|p| p.name.to_owned()).collect();
        Ok(CompiledGraph { order, names, transients, kept, swapped })
    }

    /// Indices (registration order) of the passes to run, in execution order.
    pub fn order(&self) -> &[usize] {
        &self.order
    }

    /// Names of the passes to run, in execution order.
    pub fn order_names(&self) -> Vec<&str> {
        self.order.iter().map(|&i| self.names[i].as_str()).collect()
    }

    pub(crate) fn slot(&self, id: ResourceId) -> Option<usize> {
        self.transients.get(&id)?.slot
    }

    /// Gives every transient a pooled resource; two transients share one when their
    /// descriptors resolve equal and their lifetimes do not overlap.
    pub(crate) fn assign_slots(
        &mut self,
        pool: &mut ResourcePool,
        device: &wgpu::Device,
        view: (u32, u32),
        registry: &Registry,
    ) {
        let mut by_first: Vec<(&ResourceId, &mut Transient)> = self.transients.iter_mut().collect();
        by_first.sort_by_key(|(id, t)| (t.first, **id));
        pool.begin_frame_plan();
        for (id, t) in by_first {
            t.slot = Some(pool.acquire(device, registry.label(*id), t.desc.resolve(view), t.first, t.last));
        }
        pool.end_frame_plan();
    }
}

/// `reach[a][b]`: a path leads from live pass `a` to live pass `b`.
fn reachability(edges: &[Vec<usize>], live: &[bool]) -> Vec<Vec<bool>> {
    let n = edges.len();
    let mut reach = vec![vec![false; n]; n];
    for start in (0..n).filter(|&i| live[i]) {
        let mut stack = edges[start].clone();
        while let Some(i) = stack.pop() {
            if live[i] && !reach[start][i] {
                reach[start][i] = true;
                stack.extend(edges[i].iter().copied());
            }
        }
    }
    reach
}
