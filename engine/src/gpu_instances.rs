//! Meshes added at run time and this frame's instances of them: a vertex and an index buffer
//! per mesh, and per-instance vertex buffers (transform and colours) rewritten every frame, one
//! for the scene's instances and one for the view models.

use std::ops::Range;

use bytemuck::{Pod, Zeroable};
use scene::Vertex;
use wgpu::util::DeviceExt;

use crate::gpu::Gpu;
use crate::view_state::{Instance, MeshId};

/// The per-instance vertex layout matching `InstanceIn` in shaders/scene_surface.wgsl: the
/// model matrix by columns, then albedo and emissive (locations after `VERTEX_LAYOUT`'s).
pub const INSTANCE_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<GpuInstance>() as u64,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![
        5 => Float32x4, 6 => Float32x4, 7 => Float32x4, 8 => Float32x4, 9 => Float32x4, 10 => Float32x4
    ],
};

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct GpuInstance {
    transform: [[f32; 4]; 4],
    base_color: [f32; 4],
    emissive: [f32; 4],
}

struct GpuMesh {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
}

/// Consecutive instances of one mesh in the instance buffer: one draw.
struct Run {
    mesh: usize,
    instances: Range<u32>,
}

pub struct GpuInstances {
    meshes: Vec<GpuMesh>,
    /// `ViewState::instances`: drawn into the G-buffer and the lamp's view.
    scene: Batch,
    /// `ViewState::view_models`: drawn by the view-model pass only.
    view_models: Batch,
}

/// One frame's placements of the meshes: an instance buffer and its draws.
struct Batch {
    buffer: wgpu::Buffer,
    /// Instances `buffer` holds.
    capacity: usize,
    runs: Vec<Run>,
}

impl GpuInstances {
    pub fn new(gpu: &Gpu) -> Self {
        Self { meshes: Vec::new(), scene: Batch::new(&gpu.device, 64), view_models: Batch::new(&gpu.device, 16) }
    }

    /// Uploads a mesh (`scene::Vertex` layout, triangle list; an instance's colours come from
    /// the instance, the vertices' `uv`, `uv1` and `color` are not read). Panics if an index
    /// is out of range: that is a bug in the code building the mesh.
    pub fn add_mesh(&mut self, gpu: &Gpu, vertices: &[Vertex], indices: &[u32]) -> MeshId {
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= vertices.len()) {
            panic!("add_mesh: index {bad} is out of range of {} vertices", vertices.len());
        }
        // Buffers may not be empty; an empty mesh keeps placeholders and is never drawn.
        let placeholder = [0u8; std::mem::size_of::<Vertex>()];
        let vertex_bytes: &[u8] = if vertices.is_empty() { &placeholder } else { bytemuck::cast_slice(vertices) };
        let index_bytes: &[u8] = if indices.is_empty() { &[0; 4] } else { bytemuck::cast_slice(indices) };
        let id = MeshId(self.meshes.len() as u32);
        let label = format!("mesh {}", id.0);
        let buffer = |contents, usage| {
            gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(&label), contents, usage })
        };
        self.meshes.push(GpuMesh {
            vertices: buffer(vertex_bytes, wgpu::BufferUsages::VERTEX),
            indices: buffer(index_bytes, wgpu::BufferUsages::INDEX),
            index_count: indices.len() as u32,
        });
        id
    }

    /// Writes this frame's instances and view models, grouped by mesh (one draw per mesh),
    /// growing the buffers when they no longer fit. Instances of unknown or empty meshes are
    /// dropped.
    pub fn upload(&mut self, gpu: &Gpu, instances: &[Instance], view_models: &[Instance]) {
        self.scene.upload(gpu, &self.meshes, instances);
        self.view_models.upload(gpu, &self.meshes, view_models);
    }

    /// No instances to draw into the scene this frame.
    pub fn is_empty(&self) -> bool {
        self.scene.runs.is_empty()
    }

    /// No view models to draw this frame.
    pub fn view_models_empty(&self) -> bool {
        self.view_models.runs.is_empty()
    }

    /// Draws every instance; the caller has set an instance pipeline and group 0.
    pub fn draw_all(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.scene.draw(pass, &self.meshes);
    }

    /// Draws every view model, as [`GpuInstances::draw_all`] does the instances.
    pub fn draw_view_models(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.view_models.draw(pass, &self.meshes);
    }
}

impl Batch {
    fn new(device: &wgpu::Device, capacity: usize) -> Self {
        Self { buffer: instance_buffer(device, capacity), capacity, runs: Vec::new() }
    }

    fn upload(&mut self, gpu: &Gpu, meshes: &[GpuMesh], instances: &[Instance]) {
        let mut drawn: Vec<&Instance> =
            instances.iter().filter(|i| meshes.get(i.mesh.0 as usize).is_some_and(|m| m.index_count > 0)).collect();
        // Stable: instances of one mesh keep the order they were given in.
        drawn.sort_by_key(|i| i.mesh.0);
        self.runs.clear();
        for (k, i) in drawn.iter().enumerate() {
            let k = k as u32;
            match self.runs.last_mut() {
                Some(run) if run.mesh == i.mesh.0 as usize => run.instances.end = k + 1,
                _ => self.runs.push(Run { mesh: i.mesh.0 as usize, instances: k..k + 1 }),
            }
        }
        if drawn.is_empty() {
            return;
        }
        if drawn.len() > self.capacity {
            self.capacity = drawn.len().next_power_of_two();
            self.buffer = instance_buffer(&gpu.device, self.capacity);
        }
        let data: Vec<GpuInstance> = drawn
            .iter()
            .map(|i| GpuInstance {
                transform: i.transform.to_cols_array_2d(),
                base_color: [i.base_color[0], i.base_color[1], i.base_color[2], 1.0],
                emissive: [i.emissive[0], i.emissive[1], i.emissive[2], 1.0],
            })
            .collect();
        gpu.queue.write_buffer(&self.buffer, 0, bytemuck::cast_slice(&data));
    }

    fn draw(&self, pass: &mut wgpu::RenderPass<'_>, meshes: &[GpuMesh]) {
        pass.set_vertex_buffer(1, self.buffer.slice(..));
        for run in &self.runs {
            let mesh = &meshes[run.mesh];
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..mesh.index_count, 0, run.instances.clone());
        }
    }
}

fn instance_buffer(device: &wgpu::Device, capacity: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("instances"),
        size: (capacity * std::mem::size_of::<GpuInstance>()) as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}
