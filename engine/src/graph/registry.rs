//! The graph's resources by id: each one's label (for errors, debug views and menus), kind and
//! how long its contents live.

use super::handle::ResourceId;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Lifetime {
    /// Lives from its creator to its last reader within one frame; may share memory with
    /// other transients.
    Transient,
    /// Kept across frames while its descriptor stays the same.
    Persistent,
    /// One of a pair swapped every frame; `pair` is the other one.
    History { current: bool, pair: ResourceId },
    /// Supplied at execution (the output image).
    Imported,
}

pub(crate) struct ResourceInfo {
    pub label: String,
    pub lifetime: Lifetime,
}

#[derive(Default)]
pub(crate) struct Registry {
    resources: Vec<ResourceInfo>,
}

impl Registry {
    pub fn add(&mut self, label: &str, lifetime: Lifetime) -> ResourceId {
        self.resources.push(ResourceInfo { label: label.to_owned(), lifetime });
        ResourceId(self.resources.len() as u32 - 1)
    }

    /// Two ids, current then previous, of a new history pair.
    pub fn add_pair(&mut self, label: &str) -> (ResourceId, ResourceId) {
        let current = ResourceId(self.resources.len() as u32);
        let previous = ResourceId(current.0 + 1);
        self.add(label, Lifetime::History { current: true, pair: previous });
        self.add(&format!("{label}.previous"), Lifetime::History { current: false, pair: current });
        (current, previous)
    }

    pub fn label(&self, id: ResourceId) -> &str {
        &self.resources[id.0 as usize].label
    }

    pub fn lifetime(&self, id: ResourceId) -> Lifetime {
        self.resources[id.0 as usize].lifetime
    }

    /// Whether a pass must create it each frame (everything but imports and history's
    /// previous frames).
    pub fn created_by_passes(&self, id: ResourceId) -> bool {
        match self.lifetime(id) {
            Lifetime::Transient | Lifetime::Persistent => true,
            Lifetime::History { current, .. } => current,
            Lifetime::Imported => false,
        }
    }

    /// The id its physical memory is kept under: a history's current for both of the pair.
    pub fn primary(&self, id: ResourceId) -> ResourceId {
        match self.lifetime(id) {
            Lifetime::History { current: false, pair } => pair,
            _ => id,
        }
    }

    pub fn find(&self, label: &str) -> Option<ResourceId> {
        self.resources.iter().position(|r| r.label == label).map(|i| ResourceId(i as u32))
    }

    pub fn duplicate_label(&self) -> Option<&str> {
        let r = &self.resources;
        (0..r.len()).find(|&i| r[..i].iter().any(|o| o.label == r[i].label)).map(|i| r[i].label.as_str())
    }
}
