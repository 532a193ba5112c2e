//! Resources that outlive a frame: persistent ones and history pairs. Never shared with
//! another resource; re-created, zero, when their descriptor resolves differently (a resize)
//! and after a history reset.

use std::collections::BTreeMap;

use super::handle::ResourceId;
use super::pool::{create, Physical};
use super::resource::{ResolvedDesc, ResourceDesc};

struct Kept {
    key: ResolvedDesc,
    /// One, or two for a history pair.
    physical: Vec<Physical>,
    /// Which of a pair is this frame's current.
    flip: bool,
    /// Frames written since it was made: 0 means a history's previous holds zeros.
    age: u32,
}

#[derive(Default)]
pub(crate) struct KeptResources {
    kept: BTreeMap<ResourceId, Kept>,
    allocations: usize,
}

impl KeptResources {
    /// Makes sure each of `wanted` (by its primary id; `pair` says whether it is a history
    /// pair) exists with its descriptor resolved for a view of `view` pixels.
    pub fn prepare<'l>(
        &mut self,
        device: &wgpu::Device,
        wanted: impl Iterator<Item = (ResourceId, ResourceDesc, bool, &'l str)>,
        view: (u32, u32),
    ) {
        for (id, desc, pair, label) in wanted {
            let key = desc.resolve(view);
            if self.kept.get(&id).is_some_and(|k| k.key == key) {
                continue;
            }
            let count = if pair { 2 } else { 1 };
            self.allocations += count;
            let physical = (0..count).map(|_| create(device, label, key)).collect();
            self.kept.insert(id, Kept { key, physical, flip: false, age: 0 });
        }
    }

    /// The physical resource of `id` (a pair's current when `previous` is false).
    pub fn physical(&self, id: ResourceId, previous: bool) -> Option<&Physical> {
        let k = self.kept.get(&id)?;
        let index = if k.physical.len() == 2 { usize::from(k.flip ^ previous) } else { 0 };
        k.physical.get(index)
    }

    /// Frames of history behind `id`'s previous (0: zeros, made or reset since).
    pub fn age(&self, id: ResourceId) -> u32 {
        self.kept.get(&id).map_or(0, |k| k.age)
    }

    /// After a frame: each history pair whose current it wrote (`written`) swaps, the current
    /// becoming the previous; every other pair's previous is older than last frame, so it
    /// counts as no history (age 0) until written again.
    pub fn end_frame(&mut self, written: &[ResourceId]) {
        for (id, k) in &mut self.kept {
            if written.contains(id) {
                k.flip = !k.flip;
                k.age = k.age.saturating_add(1);
            } else if k.physical.len() == 2 {
                k.age = 0;
            }
        }
    }

    /// Forgets everything: the next frame starts from zeros.
    pub fn reset(&mut self) {
        self.kept.clear();
    }

    pub fn live(&self) -> usize {
        self.kept.values().map(|k| k.physical.len()).sum()
    }

    pub fn allocations(&self) -> usize {
        self.allocations
    }
}
