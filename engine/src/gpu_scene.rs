//! The scene's geometry and materials on the GPU: one vertex and one index buffer for the
//! whole level, one draw per mesh, one bind group per material.

use bytemuck::{Pod, Zeroable};
use scene::{Scene, Texture, Vertex};
use wgpu::util::DeviceExt;

use crate::globals::CoreLayouts;
use crate::gpu::Gpu;

/// The vertex layout matching `scene::Vertex` (position, normal, uv).
pub const VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<Vertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2],
};

#[derive(Clone, Copy, Debug)]
pub struct Draw {
    pub first_index: u32,
    pub index_count: u32,
    pub base_vertex: i32,
    pub material: usize,
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct MaterialUniform {
    base_color: [f32; 4],
    emissive: [f32; 4],
}

pub struct GpuScene {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub draws: Vec<Draw>,
    pub materials: Vec<wgpu::BindGroup>,
}

impl GpuScene {
    pub fn upload(gpu: &Gpu, layouts: &CoreLayouts, scene: &Scene) -> Self {
        let device = &gpu.device;
        let mut vertices: Vec<Vertex> = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        let mut draws = Vec::new();
        for mesh in &scene.meshes {
            if mesh.indices.is_empty() {
                continue;
            }
            draws.push(Draw {
                first_index: indices.len() as u32,
                index_count: mesh.indices.len() as u32,
                base_vertex: vertices.len() as i32,
                material: mesh.material,
            });
            vertices.extend_from_slice(&mesh.vertices);
            indices.extend_from_slice(&mesh.indices);
        }
        // Sorting by material keeps bind-group switches to one per material.
        draws.sort_by_key(|d| d.material);
        let vertex_bytes: &[u8] = if vertices.is_empty() { &[0; 32] } else { bytemuck::cast_slice(&vertices) };
        let index_bytes: &[u8] = if indices.is_empty() { &[0; 4] } else { bytemuck::cast_slice(&indices) };
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("scene vertices"),
            contents: vertex_bytes,
            usage: wgpu::BufferUsages::VERTEX,
        });
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("scene indices"),
            contents: index_bytes,
            usage: wgpu::BufferUsages::INDEX,
        });

        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("material"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let white = Texture { name: "white".into(), width: 1, height: 1, rgba8: vec![255; 4] };
        let textures: Vec<wgpu::TextureView> = scene.textures.iter().map(|t| upload_texture(gpu, t)).collect();
        let white = upload_texture(gpu, &white);
        let materials = scene
            .materials
            .iter()
            .map(|m| {
                let texture = m.base_color_texture.and_then(|i| textures.get(i));
                let uniform = MaterialUniform {
                    base_color: m.base_color,
                    emissive: [m.emissive[0], m.emissive[1], m.emissive[2], if texture.is_some() { 1.0 } else { 0.0 }],
                };
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(&m.name),
                    contents: bytemuck::bytes_of(&uniform),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(&m.name),
                    layout: &layouts.material,
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: wgpu::BindingResource::TextureView(texture.unwrap_or(&white)),
                        },
                        wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::Sampler(&sampler) },
                    ],
                })
            })
            .collect();
        Self { vertices, indices, draws, materials }
    }

    /// Draws every mesh; the caller has set the pipeline and group 0, materials go in group 1.
    pub fn draw_all(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        let mut bound = usize::MAX;
        for d in &self.draws {
            if d.material != bound {
                pass.set_bind_group(1, &self.materials[d.material], &[]);
                bound = d.material;
            }
            pass.draw_indexed(d.first_index..d.first_index + d.index_count, d.base_vertex, 0..1);
        }
    }
}

/// Uploads an sRGB texture with a box-filtered mip chain built on the CPU.
fn upload_texture(gpu: &Gpu, t: &Texture) -> wgpu::TextureView {
    let mip_count = 32 - t.width.max(t.height).max(1).leading_zeros();
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(&t.name),
        size: wgpu::Extent3d { width: t.width, height: t.height, depth_or_array_layers: 1 },
        mip_level_count: mip_count,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let (mut w, mut h, mut pixels) = (t.width, t.height, t.rgba8.clone());
    for level in 0..mip_count {
        gpu.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: level,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            &pixels,
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w * 4), rows_per_image: Some(h) },
            wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        );
        let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
        let mut next = vec![0u8; (nw * nh * 4) as usize];
        for y in 0..nh {
            for x in 0..nw {
                for c in 0..4 {
                    let mut sum = 0u32;
                    for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                        let sx = (x * 2 + dx).min(w - 1);
                        let sy = (y * 2 + dy).min(h - 1);
                        sum += pixels[((sy * w + sx) * 4 + c) as usize] as u32;
                    }
                    next[((y * nw + x) * 4 + c) as usize] = (sum / 4) as u8;
                }
            }
        }
        (w, h, pixels) = (nw, nh, next);
    }
    texture.create_view(&wgpu::TextureViewDescriptor::default())
}
