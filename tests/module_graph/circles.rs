//! The circles of a module graph: its strongly connected components (Tarjan), each a tangle
//! shown as circles that between them take every edge inside it, so that a report names every
//! import that has to move.

use std::collections::btree_map::Entry;
use std::collections::{BTreeMap, VecDeque};

use super::{Edge, ModuleGraph};

/// Modules each of which imports, through the others, every other.
pub struct Tangle {
    pub modules: Vec<usize>,
    pub circles: Vec<Circle>,
}

/// A circle of imports: edge `i` goes from the module edge `i - 1` went to.
pub struct Circle {
    pub edges: Vec<Edge>,
}

impl Tangle {
    /// The modules, then each circle.
    pub fn describe(&self, graph: &ModuleGraph) -> String {
        let names: Vec<String> = self.modules.iter().map(|&m| graph.name(m)).collect();
        let mut text = format!("{} modules in a tangle: {}", names.len(), names.join(", "));
        for circle in &self.circles {
            text += "
";
            text += &circle.describe(graph);
        }
        text
    }
}

impl Circle {
    /// `crate::a → crate::b → crate::a`, then the place of each edge on a line of its own.
    pub fn describe(&self, graph: &ModuleGraph) -> String {
        let mut names = vec![graph.name(self.edges[0].from)];
        names.extend(self.edges.iter().map(|e| graph.name(e.to)));
        let mut text = format!("  {}", names.join(" → "));
        for edge in &self.edges {
            let to = graph.name(edge.to);
            text += &format!(
                "
      {}:{} names {to} ({})",
                graph.modules[edge.from].file, edge.line, edge.via
            );
        }
        text
    }
}

/// The tangles of `graph` (its strongly connected components of more than one module), each
/// with the shortest circle through each of its edges that no circle listed before goes along.
pub fn tangles(graph: &ModuleGraph) -> Vec<Tangle> {
    let n = graph.modules.len();
    let mut out = Vec::new();
    for modules in strongly_connected(n, &graph.edges).into_iter().filter(|c| c.len() > 1) {
        let inside: Vec<&Edge> =
            graph.edges.iter().filter(|e| modules.contains(&e.from) && modules.contains(&e.to)).collect();
        let mut covered = vec![false; inside.len()];
        let mut circles = Vec::new();
        for first in 0..inside.len() {
            if covered[first] {
                continue;
            }
            // The edge, then the shortest way back from where it leads.
            let back =
                shortest_path(&inside, inside[first].to, inside[first].from).expect("a way back inside a tangle");
            let cycle: Vec<usize> = std::iter::once(first).chain(back).collect();
            for &e in &cycle {
                covered[e] = true;
            }
            circles.push(Circle { edges: cycle.into_iter().map(|e| inside[e].clone()).collect() });
        }
        out.push(Tangle { modules, circles });
    }
    out
}

/// The edges (indices into `edges`) of a shortest path from `from` to `to` (breadth first).
fn shortest_path(edges: &[&Edge], from: usize, to: usize) -> Option<Vec<usize>> {
    let mut reached_by: BTreeMap<usize, Option<usize>> = [(from, None)].into();
    let mut queue = VecDeque::from([from]);
    while let Some(m) = queue.pop_front() {
        if m == to {
            let mut path = Vec::new();
            let mut at = to;
            while let Some(Some(e)) = reached_by.get(&at) {
                path.push(*e);
                at = edges[*e].from;
            }
            path.reverse();
            return Some(path);
        }
        for (e, edge) in edges.iter().enumerate().filter(|(_, edge)| edge.from == m) {
            if let Entry::Vacant(first) = reached_by.entry(edge.to) {
                first.insert(Some(e));
                queue.push_back(edge.to);
            }
        }
    }
    None
}

/// Tarjan's algorithm: the strongly connected components of the graph of `n` nodes.
fn strongly_connected(n: usize, edges: &[Edge]) -> Vec<Vec<usize>> {
    struct State {
        next: Vec<Vec<usize>>,
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        counter: usize,
        components: Vec<Vec<usize>>,
    }

    fn visit(s: &mut State, v: usize) {
        s.index[v] = Some(s.counter);
        s.low[v] = s.counter;
        s.counter += 1;
        s.stack.push(v);
        s.on_stack[v] = true;
        for w in s.next[v].clone() {
            match s.index[w] {
                None => {
                    visit(s, w);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(index) if s.on_stack[w] => s.low[v] = s.low[v].min(index),
                Some(_) => {}
            }
        }
        // `v` is the first node of its component reached: the stack down to it is the component.
        if Some(s.low[v]) == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack[w] = false;
                component.push(w);
                if w == v {
                    break;
                }
            }
            component.sort();
            s.components.push(component);
        }
    }

    let mut next = vec![Vec::new(); n];
    for edge in edges {
        next[edge.from].push(edge.to);
    }
    let mut state = State {
        next,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        counter: 0,
        components: Vec::new(),
    };
    for v in 0..n {
        if state.index[v].is_none() {
            visit(&mut state, v);
        }
    }
    state.components
}
