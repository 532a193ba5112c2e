//! Scheduling: dependency edges from declarations, a stable topological order, culling,
//! lifetimes, and the mapping of transient resources onto pooled physical ones.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap, HashSet};
use std::fmt;

use super::pool::ResourcePool;
use super::resource::ResourceDesc;
use super::PassDecl;

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
    DuplicatePass(String),
    /// The declarations order these passes in a circle.
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
            GraphError::DuplicatePass(name) => write!(f, "render graph: two passes are named '{name}'"),
            GraphError::Cycle { passes } => {
                write!(f, "render graph: dependency cycle between passes {}", passes.join(" -> "))
            }
        }
    }
}

impl std::error::Error for GraphError {}

#[derive(Debug)]
struct Transient {
    desc: ResourceDesc,
    /// Positions in `order` of the first and last pass touching it.
    first: usize,
    last: usize,
    slot: Option<usize>,
}

/// The result of [`CompiledGraph::compile`]: which passes run, in which order, and where each
/// transient resource lives.
#[derive(Debug)]
pub struct CompiledGraph {
    order: Vec<usize>,
    names: Vec<String>,
    transients: BTreeMap<String, Transient>,
}

impl CompiledGraph {
    /// Passes are given in registration order as `(name, declaration)`.
    pub fn compile(passes: &[(String, PassDecl)], imports: &[String]) -> Result<CompiledGraph, GraphError> {
        let n = passes.len();
        let mut seen = HashSet::new();
        for (name, _) in passes {
            if !seen.insert(name.as_str()) {
                return Err(GraphError::DuplicatePass(name.clone()));
            }
        }

        // Producers of each resource in registration order: its creator first, then writers.
        let mut creator: BTreeMap<&str, (usize, ResourceDesc)> = BTreeMap::new();
        for (i, (pass, decl)) in passes.iter().enumerate() {
            for (res, desc) in &decl.creates {
                if let Some((first, _)) = creator.get(res.as_str()) {
                    return Err(GraphError::CreatedTwice {
                        resource: res.clone(),
                        first: passes[*first].0.clone(),
                        second: pass.clone(),
                    });
                }
                creator.insert(res, (i, *desc));
            }
        }
        let known = |res: &str| creator.contains_key(res) || imports.iter().any(|i| i == res);
        let mut producers: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
        for (res, (i, _)) in &creator {
            producers.entry(res).or_default().push(*i);
        }
        for (i, (pass, decl)) in passes.iter().enumerate() {
            for res in decl.reads.iter().chain(&decl.writes) {
                if !known(res) {
                    return Err(GraphError::MissingInput { pass: pass.clone(), resource: res.clone() });
                }
            }
            for res in &decl.writes {
                producers.entry(res).or_default().push(i);
            }
        }
        for list in producers.values_mut() {
            list.sort_unstable();
            list.dedup();
        }

        // Edges: consecutive producers in registration order; every producer before each reader.
        let mut succ: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut pred: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut edge = |a: usize, b: usize| {
            if a != b && !succ[a].contains(&b) {
                succ[a].push(b);
                pred[b].push(a);
            }
        };
        for list in producers.values() {
            for w in list.windows(2) {
                edge(w[0], w[1]);
            }
        }
        for (i, (_, decl)) in passes.iter().enumerate() {
            for res in &decl.reads {
                for &p in producers.get(res.as_str()).into_iter().flatten() {
                    edge(p, i);
                }
            }
        }

        // Cull: keep only what leads to an import (the graph's outputs).
        let mut live = vec![false; n];
        let mut stack: Vec<usize> = (0..n)
            .filter(|&i| {
                let d = &passes[i].1;
                d.writes.iter().any(|w| imports.contains(w))
            })
            .collect();
        while let Some(i) = stack.pop() {
            if !live[i] {
                live[i] = true;
                stack.extend(pred[i].iter().copied());
            }
        }

        // Kahn's algorithm, lowest registration index first, so the order is stable.
        let mut indegree: Vec<usize> = (0..n).map(|i| pred[i].iter().filter(|&&p| live[p]).count()).collect();
        let mut ready: BinaryHeap<Reverse<usize>> =
            (0..n).filter(|&i| live[i] && indegree[i] == 0).map(Reverse).collect();
        let mut order = Vec::new();
        while let Some(Reverse(i)) = ready.pop() {
            order.push(i);
            for &s in &succ[i] {
                if live[s] {
                    indegree[s] -= 1;
                    if indegree[s] == 0 {
                        ready.push(Reverse(s));
                    }
                }
            }
        }
        let live_count = live.iter().filter(|&&l| l).count();
        if order.len() != live_count {
            let stuck: Vec<String> =
                (0..n).filter(|&i| live[i] && indegree[i] > 0).map(|i| passes[i].0.clone()).collect();
            return Err(GraphError::Cycle { passes: stuck });
        }

        // Lifetimes of transients used by scheduled passes.
        let mut transients = BTreeMap::new();
        for (pos, &i) in order.iter().enumerate() {
            let decl = &passes[i].1;
            let used = decl.reads.iter().chain(&decl.writes).chain(decl.creates.iter().map(|(r, _)| r));
            for res in used {
                if let Some((_, desc)) = creator.get(res.as_str()) {
                    let t = transients.entry(res.clone()).or_insert(Transient {
                        desc: *desc,
                        first: pos,
                        last: pos,
                        slot: None,
                    });
                    t.first = t.first.min(pos);
                    t.last = t.last.max(pos);
                }
            }
        }
        Ok(CompiledGraph { order, names: passes.iter().map(|(n, _)| n.clone()).collect(), transients })
    }

    /// Indices (registration order) of the passes to run, in execution order.
    pub fn order(&self) -> &[usize] {
        &self.order
    }

    /// Names of the passes to run, in execution order.
    pub fn order_names(&self) -> Vec<&str> {
        self.order.iter().map(|&i| self.names[i].as_str()).collect()
    }

    pub(crate) fn slot(&self, name: &str) -> Option<usize> {
        self.transients.get(name)?.slot
    }

    /// Gives every transient a pooled resource; two transients share one when their
    /// descriptors resolve equal and their lifetimes do not overlap.
    pub(crate) fn assign_slots(&mut self, pool: &mut ResourcePool, device: &wgpu::Device, view: (u32, u32)) {
        let mut by_first: Vec<(&String, &mut Transient)> = self.transients.iter_mut().collect();
        by_first.sort_by_key(|(name, t)| (t.first, (*name).clone()));
        pool.begin_frame_plan();
        for (name, t) in by_first {
            t.slot = Some(pool.acquire(device, name, t.desc.resolve(view), t.first, t.last));
        }
        pool.end_frame_plan();
    }
}
