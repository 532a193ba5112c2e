//! The import graph of a crate's modules, read from its source text, and the circles in it.
//!
//! Each file is a module (its inline `mod name { … }` blocks are part of it). An edge A → B
//! means file A names an item that module file B defines (B ≠ A), by:
//! - a `use` of an item (`use crate::a::Item`, `use super::Item`, a glob `use crate::a::*`);
//! - a path in code (`crate::a::f()`, `super::X`, `child::g()`, `alias::h()` where `alias` is a
//!   module brought in by `use`);
//! - a re-exported name (`pub use a::Item`) that the re-exporting file uses itself.
//!
//! Not edges, because they are the module tree rather than a dependency: `mod` declarations,
//! re-exports the file does not use itself, and `use` of a module as a whole (the paths
//! through it are what count). A path is resolved to the file that defines its item: through
//! the module files it walks, then through the `use` items and globs of the module where it
//! stops (so `crate::passes::Item`, re-exported by `passes/mod.rs` from `passes/x.rs`, is an
//! edge to `passes/x.rs`). Paths into other crates are not edges, comments and doc links are not
//! read, and test code (`#[cfg(test)]` items, `mod tests;` files) is left out.
//!
//! Without types, a method call is not seen: `self.f()` where `f` is written in another file's
//! `impl` names nothing. So a type's methods may live in a child module (`impl Config` in
//! `config/format.rs`) that uses the type, and the type's own module need not name the child.

mod circles;
mod syntax;
mod tokens;

pub use circles::{tangles, Circle, Tangle};

use std::collections::BTreeMap;

use syntax::{Scope, Syntax, UseLeaf};

/// One module file of the crate.
pub struct Module {
    /// The file's path as given to [`ModuleGraph::read`] (`engine/scene/src/level.rs`).
    pub file: String,
    /// Its module path from the crate root (`[]` for the root).
    pub path: Vec<String>,
    /// The index of its crate root (a package's library and binaries are crates of their own).
    pub root: usize,
    /// Its modules with a file, by the path from it (an inline module's ones: `[inline, name]`).
    children: Vec<(Vec<String>, usize)>,
    syntax: Syntax,
}

/// A → B: `from` names something of `to` on `line`, through `via` (as written).
#[derive(Clone, Debug)]
pub struct Edge {
    pub from: usize,
    pub to: usize,
    pub line: usize,
    pub via: String,
}

pub struct ModuleGraph {
    pub modules: Vec<Module>,
    /// At most one per pair of modules: the first place the file names the other.
    pub edges: Vec<Edge>,
}

/// What a path names, and in which module file.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Resolved {
    /// The module itself.
    Module(usize),
    /// An item the module defines.
    Found(usize),
    /// A name the module neither defines nor imports (made by a macro, say): taken to be its.
    Guessed(usize),
}

/// Deep enough for any chain of re-exports; past it a path resolves to nothing.
const MAX_HOPS: usize = 16;

impl ModuleGraph {
    /// The graph of the crates whose root files are `roots`, each file's text given by `source`
    /// (None: no such file). Fails if a `mod name;` has no file.
    pub fn read(roots: &[String], source: impl Fn(&str) -> Option<String>) -> Result<ModuleGraph, String> {
        let mut modules = Vec::new();
        for root_file in roots {
            let root = modules.len();
            let text = source(root_file).ok_or_else(|| format!("{root_file}: no such file"))?;
            modules.push(Module {
                file: root_file.clone(),
                path: Vec::new(),
                root,
                children: Vec::new(),
                syntax: Syntax::parse(&text),
            });
            let mut next = root;
            while next < modules.len() {
                let parent = next;
                next += 1;
                let dir = children_dir(&modules[parent].file, parent == root);
                let decls: Vec<_> =
                    modules[parent].syntax.mods.iter().map(|m| (m.scope.clone(), m.name.clone(), m.line)).collect();
                for (scope, name, line) in decls {
                    let dir = scope.iter().fold(dir.clone(), |dir, inline| format!("{dir}{inline}/"));
                    let candidates = [format!("{dir}{name}.rs"), format!("{dir}{name}/mod.rs")];
                    let Some((file, text)) = candidates.into_iter().find_map(|f| source(&f).map(|t| (f, t))) else {
                        return Err(format!("{}:{line}: `mod {name};` has no file", modules[parent].file));
                    };
                    let relative: Vec<String> = scope.into_iter().chain([name]).collect();
                    let path = modules[parent].path.iter().chain(&relative).cloned().collect();
                    let child = modules.len();
                    modules[parent].children.push((relative, child));
                    modules.push(Module { file, path, root, children: Vec::new(), syntax: Syntax::parse(&text) });
                }
            }
        }
        let mut graph = ModuleGraph { modules, edges: Vec::new() };
        graph.edges = graph.find_edges();
        Ok(graph)
    }

    /// A readable name of module `m`: `crate::a::b`, or for a binary's modules `main::a::b`.
    pub fn name(&self, m: usize) -> String {
        let module = &self.modules[m];
        let root = if module.root == 0 {
            "crate".to_string()
        } else {
            let file = &self.modules[module.root].file;
            file.rsplit('/').next().unwrap_or(file).trim_end_matches(".rs").to_string()
        };
        std::iter::once(root).chain(module.path.iter().cloned()).collect::<Vec<_>>().join("::")
    }

    fn find_edges(&self) -> Vec<Edge> {
        let mut edges: BTreeMap<(usize, usize), Edge> = BTreeMap::new();
        for (m, module) in self.modules.iter().enumerate() {
            // The first place `m` names `to` stands for the edge.
            let mut add = |to: usize, line: usize, via: String| {
                if to != m && edges.get(&(m, to)).is_none_or(|e| line < e.line) {
                    edges.insert((m, to), Edge { from: m, to, line, via });
                }
            };
            for leaf in &module.syntax.uses {
                let Some(path) = self.absolute(m, &leaf.scope, &leaf.segments, 0) else { continue };
                let to = match self.resolve(module.root, &path, 0) {
                    // A glob takes in a module's items; a plain `use` of a module names none.
                    Some(Resolved::Module(to)) if leaf.glob => to,
                    Some(Resolved::Module(_)) | None => continue,
                    Some(Resolved::Found(to) | Resolved::Guessed(to)) => to,
                };
                let via = leaf.segments.join("::") + if leaf.glob { "::*" } else { "" };
                if !leaf.public {
                    add(to, leaf.line, via);
                    continue;
                }
                // A re-export is an edge only where the file uses what it re-exports itself.
                let code = &module.syntax.names_in_code;
                let used = match &leaf.local {
                    Some(local) => code.get(local).copied(),
                    None if leaf.glob => {
                        self.modules[to].syntax.defined.iter().filter_map(|d| code.get(d)).min().copied()
                    }
                    None => None,
                };
                if let Some(line) = used {
                    add(to, line, format!("{via}, re-exported and used here"));
                }
            }
            for code in &module.syntax.paths {
                let Some(path) = self.absolute(m, &code.scope, &code.segments, 0) else { continue };
                if let Some(Resolved::Found(to) | Resolved::Guessed(to)) = self.resolve(module.root, &path, 0) {
                    add(to, code.line, code.segments.join("::"));
                }
            }
        }
        edges.into_values().collect()
    }

    /// `segments`, written in module `m` inside its inline modules `scope`, as a path from the
    /// crate root; None for paths into other crates and for `Self::…`.
    fn absolute(&self, m: usize, scope: &Scope, segments: &[String], hops: usize) -> Option<Vec<String>> {
        let module = &self.modules[m];
        let here = || module.path.iter().chain(scope).cloned().collect::<Vec<_>>();
        let (first, rest) = segments.split_first()?;
        let mut base = match first.as_str() {
            "crate" => Vec::new(),
            "self" => here(),
            "super" => {
                let mut base = here();
                base.pop()?;
                let supers = rest.iter().take_while(|s| *s == "super").count();
                for _ in 0..supers {
                    base.pop()?;
                }
                return Some(base.into_iter().chain(rest[supers..].iter().cloned()).collect());
            }
            _ => {
                if hops < MAX_HOPS {
                    // A name a `use` of this file brings in (not the leaf being read itself).
                    let alias =
                        module.syntax.uses.iter().find(|u| u.local.as_ref() == Some(first) && u.segments != segments);
                    if let Some(alias) = alias {
                        let mut base = self.absolute(m, &alias.scope, &alias.segments, hops + 1)?;
                        base.extend(rest.iter().cloned());
                        return Some(base);
                    }
                }
                let child: Vec<String> = scope.iter().chain([first]).cloned().collect();
                if !module.children.iter().any(|(relative, _)| *relative == child) {
                    return None;
                }
                let mut base = here();
                base.push(first.clone());
                base
            }
        };
        base.extend(rest.iter().cloned());
        Some(base)
    }

    /// Where the item at crate path `path` (from the crate of root `root`) is defined.
    fn resolve(&self, root: usize, path: &[String], hops: usize) -> Option<Resolved> {
        if hops > MAX_HOPS {
            return None;
        }
        // Down the module files as far as the path goes.
        let mut m = root;
        let mut at = 0;
        'walk: while at < path.len() {
            for (relative, child) in &self.modules[m].children {
                if path[at..].starts_with(relative) {
                    m = *child;
                    at += relative.len();
                    continue 'walk;
                }
            }
            break;
        }
        let Some(name) = path.get(at) else { return Some(Resolved::Module(m)) };
        let module = &self.modules[m];
        if module.syntax.defined.contains(name) {
            return Some(Resolved::Found(m));
        }
        // Brought in by a `use` of that module: followed to where it comes from.
        let named = |u: &&UseLeaf| u.local.as_ref() == Some(name);
        if let Some(leaf) = module.syntax.uses.iter().find(named) {
            let mut target = self.absolute(m, &leaf.scope, &leaf.segments, 0)?;
            target.extend(path[at + 1..].iter().cloned());
            return self.resolve(root, &target, hops + 1);
        }
        // Or by a glob, if one of the modules it takes in has the name.
        for glob in module.syntax.uses.iter().filter(|u| u.glob) {
            let Some(from) = self.absolute(m, &glob.scope, &glob.segments, 0) else { continue };
            let Some(Resolved::Module(g)) = self.resolve(root, &from, hops + 1) else { continue };
            let target: Vec<String> = self.modules[g].path.iter().chain(&path[at..]).cloned().collect();
            if let Some(found @ (Resolved::Found(_) | Resolved::Module(_))) = self.resolve(root, &target, hops + 1) {
                return Some(found);
            }
        }
        Some(Resolved::Guessed(m))
    }
}

/// The folder of the files of the modules that `file` declares.
fn children_dir(file: &str, is_root: bool) -> String {
    let dir = file.rsplit_once('/').map_or(String::new(), |(dir, _)| format!("{dir}/"));
    if is_root || file.ends_with("/mod.rs") || file == "mod.rs" {
        dir
    } else {
        format!("{}/", file.trim_end_matches(".rs"))
    }
}
