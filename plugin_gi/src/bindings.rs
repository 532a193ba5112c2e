//! Bind group layouts and bind groups declared as one ordered list, so a pass's Rust side
//! reads like the `@binding(n)` list of its WGSL file.

use engine::wgpu;

/// The side of the square workgroups of the passes that take one texel an invocation (sight
/// depth, temporal, the sub-images' split and join).
pub const TEXEL_GROUP: u32 = 8;

#[derive(Clone, Copy)]
pub enum Slot {
    Uniform,
    Storage {
        read_only: bool,
    },
    /// A float texture read with `textureLoad`.
    Texture,
    /// A `texture_2d<u32>` read with `textureLoad`.
    UintTexture,
    StorageTexture(wgpu::TextureFormat),
}

pub enum Resource<'a> {
    Buffer(&'a wgpu::Buffer),
    View(&'a wgpu::TextureView),
}

pub fn layout(device: &wgpu::Device, label: &str, slots: &[Slot]) -> wgpu::BindGroupLayout {
    let visibility = wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE;
    let entries: Vec<wgpu::BindGroupLayoutEntry> = slots
        .iter()
        .enumerate()
        .map(|(i, slot)| {
            let buffer = |ty| wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None };
            let ty = match *slot {
                Slot::Uniform => buffer(wgpu::BufferBindingType::Uniform),
                Slot::Storage { read_only } => buffer(wgpu::BufferBindingType::Storage { read_only }),
                Slot::Texture => wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                Slot::UintTexture => wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Uint,
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                Slot::StorageTexture(format) => wgpu::BindingType::StorageTexture {
                    access: wgpu::StorageTextureAccess::WriteOnly,
                    format,
                    view_dimension: wgpu::TextureViewDimension::D2,
                },
            };
            // Storage writes are not allowed in vertex shaders.
            let visibility = match slot {
                Slot::Storage { read_only: false } | Slot::StorageTexture(_) => {
                    wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE
                }
                _ => visibility,
            };
            wgpu::BindGroupLayoutEntry { binding: i as u32, visibility, ty, count: None }
        })
        .collect();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries: &entries })
}

pub fn bind(device: &wgpu::Device, layout: &wgpu::BindGroupLayout, resources: &[Resource<'_>]) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry> = resources
        .iter()
        .enumerate()
        .map(|(i, r)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: match r {
                Resource::Buffer(b) => b.as_entire_binding(),
                Resource::View(v) => wgpu::BindingResource::TextureView(v),
            },
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor { label: None, layout, entries: &entries })
}

pub fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    module: &wgpu::ShaderModule,
    entry: &str,
    layouts: &[Option<&wgpu::BindGroupLayout>],
) -> wgpu::ComputePipeline {
    compute_pipeline_with(device, label, module, entry, layouts, &[])
}

/// A compute pipeline with values for the shader's override constants.
pub fn compute_pipeline_with(
    device: &wgpu::Device,
    label: &str,
    module: &wgpu::ShaderModule,
    entry: &str,
    layouts: &[Option<&wgpu::BindGroupLayout>],
    constants: &[(&str, f64)],
) -> wgpu::ComputePipeline {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: layouts,
        immediate_size: 0,
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(&layout),
        module,
        entry_point: Some(entry),
        compilation_options: wgpu::PipelineCompilationOptions { constants, ..Default::default() },
        cache: None,
    })
}

pub fn uniform_buffer(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}
