//! Bind groups declared once, by name. A pass lists a group's bindings as its WGSL declares
//! them, in `@binding` order: the name of each `var` and what it is. The layout is derived from
//! the list, a bind group is made from resources handed over by name, and a test reflects every
//! shader with naga against the lists (`engine/tests/binding_check`), so a name, a kind or an
//! order that drifts from the WGSL fails before anything renders.

use std::fmt;

/// What a binding is, as its WGSL declares it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BindingKind {
    /// `var<uniform>`.
    Uniform,
    /// `var<storage, read>` (`read_only`) or `var<storage, read_write>`.
    Storage { read_only: bool },
    /// A `texture_2d<f32>` read with `textureLoad` (unfilterable, so Rgba32Float works).
    Texture,
    /// A `texture_2d<f32>` read through a filtering sampler.
    FilteredTexture,
    /// A `texture_2d<u32>` read with `textureLoad`.
    UintTexture,
    /// A `texture_depth_2d`.
    DepthTexture,
    /// A filtering `sampler`.
    Sampler,
    /// A `sampler_comparison`.
    ComparisonSampler,
    /// A write-only `texture_storage_2d` of this format.
    StorageTexture(wgpu::TextureFormat),
}

/// One binding: the name of its WGSL `var` and what it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShaderBinding {
    pub name: &'static str,
    pub kind: BindingKind,
}

impl ShaderBinding {
    pub const fn uniform(name: &'static str) -> Self {
        Self { name, kind: BindingKind::Uniform }
    }
    /// `var<storage, read>`.
    pub const fn storage(name: &'static str) -> Self {
        Self { name, kind: BindingKind::Storage { read_only: true } }
    }
    /// `var<storage, read_write>`.
    pub const fn storage_rw(name: &'static str) -> Self {
        Self { name, kind: BindingKind::Storage { read_only: false } }
    }
    pub const fn texture(name: &'static str) -> Self {
        Self { name, kind: BindingKind::Texture }
    }
    pub const fn filtered_texture(name: &'static str) -> Self {
        Self { name, kind: BindingKind::FilteredTexture }
    }
    pub const fn uint_texture(name: &'static str) -> Self {
        Self { name, kind: BindingKind::UintTexture }
    }
    pub const fn depth_texture(name: &'static str) -> Self {
        Self { name, kind: BindingKind::DepthTexture }
    }
    pub const fn sampler(name: &'static str) -> Self {
        Self { name, kind: BindingKind::Sampler }
    }
    pub const fn comparison_sampler(name: &'static str) -> Self {
        Self { name, kind: BindingKind::ComparisonSampler }
    }
    pub const fn storage_texture(name: &'static str, format: wgpu::TextureFormat) -> Self {
        Self { name, kind: BindingKind::StorageTexture(format) }
    }

    fn entry(&self, binding: u32) -> wgpu::BindGroupLayoutEntry {
        let buffer = |ty| wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None };
        let texture = |sample_type| wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        };
        let ty = match self.kind {
            BindingKind::Uniform => buffer(wgpu::BufferBindingType::Uniform),
            BindingKind::Storage { read_only } => buffer(wgpu::BufferBindingType::Storage { read_only }),
            BindingKind::Texture => texture(wgpu::TextureSampleType::Float { filterable: false }),
            BindingKind::FilteredTexture => texture(wgpu::TextureSampleType::Float { filterable: true }),
            BindingKind::UintTexture => texture(wgpu::TextureSampleType::Uint),
            BindingKind::DepthTexture => texture(wgpu::TextureSampleType::Depth),
            BindingKind::Sampler => wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            BindingKind::ComparisonSampler => wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
            BindingKind::StorageTexture(format) => wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::WriteOnly,
                format,
                view_dimension: wgpu::TextureViewDimension::D2,
            },
        };
        // Vertex shaders may not write storage; every other binding is visible to every stage.
        let visibility = match self.kind {
            BindingKind::Storage { read_only: false } | BindingKind::StorageTexture(_) => {
                wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE
            }
            _ => wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE,
        };
        wgpu::BindGroupLayoutEntry { binding, visibility, ty, count: None }
    }
}

/// A bind group's bindings in `@binding` order (0, 1, …), under the label its layout and
/// groups get.
#[derive(Clone, Copy, Debug)]
pub struct Group {
    pub label: &'static str,
    pub bindings: &'static [ShaderBinding],
}

/// What is bound to a binding.
#[derive(Clone, Copy)]
pub enum Resource<'a> {
    Buffer(&'a wgpu::Buffer),
    View(&'a wgpu::TextureView),
    Sampler(&'a wgpu::Sampler),
}

impl<'a> From<&'a wgpu::Buffer> for Resource<'a> {
    fn from(b: &'a wgpu::Buffer) -> Self {
        Resource::Buffer(b)
    }
}

impl<'a> From<&'a wgpu::TextureView> for Resource<'a> {
    fn from(v: &'a wgpu::TextureView) -> Self {
        Resource::View(v)
    }
}

impl<'a> From<&'a wgpu::Sampler> for Resource<'a> {
    fn from(s: &'a wgpu::Sampler) -> Self {
        Resource::Sampler(s)
    }
}

impl Group {
    pub const fn new(label: &'static str, bindings: &'static [ShaderBinding]) -> Self {
        Self { label, bindings }
    }

    pub fn layout(&self, device: &wgpu::Device) -> wgpu::BindGroupLayout {
        let entries: Vec<_> = self.bindings.iter().zip(0..).map(|(b, i)| b.entry(i)).collect();
        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(self.label), entries: &entries })
    }

    /// A bind group of `layout` (made by [`Group::layout`]) with `resources`, each named as its
    /// binding is, in any order. A name missing, unknown or given twice is a mistake in the
    /// pass: it panics naming the group and the names.
    pub fn bind(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        resources: &[(&str, Resource<'_>)],
    ) -> wgpu::BindGroup {
        if let Err(e) = self.match_names(resources.iter().map(|(name, _)| *name)) {
            panic!("{e}");
        }
        let entries: Vec<wgpu::BindGroupEntry> = self
            .bindings
            .iter()
            .zip(0..)
            .map(|(b, i)| {
                let (_, resource) = resources.iter().find(|(name, _)| *name == b.name).expect("matched above");
                wgpu::BindGroupEntry {
                    binding: i,
                    resource: match *resource {
                        Resource::Buffer(buffer) => buffer.as_entire_binding(),
                        Resource::View(view) => wgpu::BindingResource::TextureView(view),
                        Resource::Sampler(sampler) => wgpu::BindingResource::Sampler(sampler),
                    },
                }
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some(self.label), layout, entries: &entries })
    }

    /// Whether `names` are this group's bindings, each once.
    fn match_names<'n>(&self, names: impl Iterator<Item = &'n str>) -> Result<(), NameMismatch> {
        let given: Vec<&str> = names.collect();
        let mut wrong = NameMismatch { group: self.label, ..Default::default() };
        for b in self.bindings {
            match given.iter().filter(|n| **n == b.name).count() {
                0 => wrong.missing.push(b.name.to_owned()),
                1 => {}
                _ => wrong.twice.push(b.name.to_owned()),
            }
        }
        wrong.unknown =
            given.iter().filter(|n| !self.bindings.iter().any(|b| b.name == **n)).map(|n| n.to_string()).collect();
        if wrong.missing.is_empty() && wrong.twice.is_empty() && wrong.unknown.is_empty() {
            Ok(())
        } else {
            Err(wrong)
        }
    }
}

/// Resources handed to [`Group::bind`] that are not its bindings, each once.
#[derive(Debug, Default, PartialEq)]
struct NameMismatch {
    group: &'static str,
    missing: Vec<String>,
    twice: Vec<String>,
    unknown: Vec<String>,
}

impl fmt::Display for NameMismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "bind group '{}':", self.group)?;
        for (what, names) in
            [("no resource for", &self.missing), ("twice", &self.twice), ("not a binding", &self.unknown)]
        {
            if !names.is_empty() {
                write!(f, " {what} {}", names.join(", "))?;
            }
        }
        Ok(())
    }
}

/// Where a [`Group`] is declared in WGSL: the file (a shader as its crate's `SHADERS` names it,
/// or an include, for every shader that includes it) and the `@group` index; and, where the
/// layout serves some entry points only, which (empty: every one).
#[derive(Clone, Copy, Debug)]
pub struct WgslGroup {
    pub shader: &'static str,
    pub group: u32,
    pub layout: &'static Group,
    pub entry_points: &'static [&'static str],
}

impl WgslGroup {
    pub const fn new(shader: &'static str, group: u32, layout: &'static Group) -> Self {
        Self { shader, group, layout, entry_points: &[] }
    }

    /// The layout serves `entry_points` alone: it may stop short of the WGSL's group, whose
    /// later bindings those entry points leave unread.
    pub const fn for_entry_points(self, entry_points: &'static [&'static str]) -> Self {
        Self { entry_points, ..self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GROUP: Group = Group::new(
        "test",
        &[ShaderBinding::uniform("params"), ShaderBinding::texture("normal"), ShaderBinding::texture("position")],
    );

    #[test]
    fn resources_are_matched_by_name_in_any_order_and_a_wrong_name_is_named() {
        assert_eq!(GROUP.match_names(["position", "params", "normal"].into_iter()), Ok(()));
        let e = GROUP.match_names(["params", "normal", "normal", "albedo"].into_iter()).unwrap_err();
        assert_eq!(e.to_string(), "bind group 'test': no resource for position twice normal not a binding albedo");
    }

    #[test]
    fn the_layout_numbers_the_bindings_in_order_and_keeps_writes_out_of_vertex_shaders() {
        let writes = ShaderBinding::storage_texture("out", wgpu::TextureFormat::Rgba32Float).entry(3);
        assert_eq!(writes.binding, 3);
        assert!(!writes.visibility.contains(wgpu::ShaderStages::VERTEX));
        assert!(ShaderBinding::storage("nodes").entry(0).visibility.contains(wgpu::ShaderStages::VERTEX));
    }
}
