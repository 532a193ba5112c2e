//! Physical GPU resources behind transient graph resources, kept across frames and resizes.

use super::resource::{ResolvedDesc, ResolvedTexture};

pub(crate) enum Physical {
    Texture { texture: wgpu::Texture, view: wgpu::TextureView },
    Buffer(wgpu::Buffer),
}

struct Slot {
    key: ResolvedDesc,
    physical: Physical,
    /// Last schedule position using it in the current plan; None = unused by the plan.
    busy_until: Option<usize>,
}

/// Counters for tests and the F3 overlay.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PoolStats {
    /// Physical resources alive now.
    pub live: usize,
    /// GPU allocations made since the pool was created.
    pub allocations: usize,
}

#[derive(Default)]
pub struct ResourcePool {
    slots: Vec<Option<Slot>>,
    allocations: usize,
}

impl ResourcePool {
    pub fn stats(&self) -> PoolStats {
        PoolStats { live: self.slots.iter().flatten().count(), allocations: self.allocations }
    }

    pub(crate) fn begin_frame_plan(&mut self) {
        for slot in self.slots.iter_mut().flatten() {
            slot.busy_until = None;
        }
    }

    /// A slot with this key free before `first`, else a new allocation.
    pub(crate) fn acquire(
        &mut self,
        device: &wgpu::Device,
        label: &str,
        key: ResolvedDesc,
        first: usize,
        last: usize,
    ) -> usize {
        let free = self
            .slots
            .iter()
            .position(|s| s.as_ref().is_some_and(|s| s.key == key && s.busy_until.is_none_or(|until| until < first)));
        let index = match free {
            Some(i) => i,
            None => {
                self.allocations += 1;
                let slot = Slot { key, physical: create(device, label, key), busy_until: None };
                match self.slots.iter().position(Option::is_none) {
                    Some(i) => {
                        self.slots[i] = Some(slot);
                        i
                    }
                    None => {
                        self.slots.push(Some(slot));
                        self.slots.len() - 1
                    }
                }
            }
        };
        self.slots[index].as_mut().expect("slot just filled").busy_until = Some(last);
        index
    }

    /// Frees what the new plan does not use (e.g. the old size after a resize).
    pub(crate) fn end_frame_plan(&mut self) {
        for slot in &mut self.slots {
            if slot.as_ref().is_some_and(|s| s.busy_until.is_none()) {
                *slot = None;
            }
        }
    }

    pub(crate) fn physical(&self, index: usize) -> &Physical {
        &self.slots[index].as_ref().expect("render graph slot in use").physical
    }
}

// Handles are typed, so a texture's handle always finds a texture: the panics below would
// be bugs of the graph itself.
impl Physical {
    pub(crate) fn texture(&self) -> &wgpu::Texture {
        match self {
            Physical::Texture { texture, .. } => texture,
            Physical::Buffer(_) => unreachable!("a texture handle names a buffer"),
        }
    }

    pub(crate) fn view(&self) -> &wgpu::TextureView {
        match self {
            Physical::Texture { view, .. } => view,
            Physical::Buffer(_) => unreachable!("a texture handle names a buffer"),
        }
    }

    pub(crate) fn buffer(&self) -> &wgpu::Buffer {
        match self {
            Physical::Buffer(b) => b,
            Physical::Texture { .. } => unreachable!("a buffer handle names a texture"),
        }
    }
}

pub(crate) fn create(device: &wgpu::Device, label: &str, key: ResolvedDesc) -> Physical {
    match key {
        ResolvedDesc::Texture(ResolvedTexture { format, width, height, usage, mip_levels }) => {
            let texture = device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
                mip_level_count: mip_levels,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            });
            let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
            Physical::Texture { texture, view }
        }
        ResolvedDesc::Buffer(desc) => Physical::Buffer(device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: desc.size,
            usage: desc.usage,
            mapped_at_creation: false,
        })),
    }
}
