//! The level's surfaces as voxels on the GPU, for the sight test's march through the world
//! (shaders/gi/world_sight.wgsl): built from the level's triangles when the renderer is made
//! (at each level load and live reload), and never changed after.

use engine::bindings::{Group, ShaderBinding as B};
use engine::scene::Scene;
use engine::wgpu;
use engine::wgpu::util::DeviceExt;
use occupancy::{Limits, Occupancy};

use crate::gpu_types::WorldGrid as WorldGridParams;

/// The grid's group (group 2 of sight.wgsl).
pub const WORLD: Group =
    Group::new("gi world grid", &[B::uniform("world"), B::storage("world_bits"), B::storage("world_distances")]);

pub struct WorldGrid {
    pub layout: wgpu::BindGroupLayout,
    pub group: wgpu::BindGroup,
}

impl WorldGrid {
    /// The grid of `scene`'s static meshes. A level too large for any grid gets an empty one
    /// (light then passes the walls the camera does not see), with the reason logged: `check`
    /// reports it too.
    pub fn new(device: &wgpu::Device, scene: &Scene) -> Self {
        let start = std::time::Instant::now();
        let grid = Occupancy::of_scene(scene, Limits::default()).unwrap_or_else(|e| {
            log::error!("gi: no world-space visibility: {e}");
            Occupancy::build(&[], Limits::default()).expect("an empty grid fits")
        });
        log::info!(
            "gi: occupancy grid of {} cm voxels, {}×{}×{} blocks, {:.1} MiB, in {} ms",
            grid.voxel * 100.0,
            grid.blocks.x,
            grid.blocks.y,
            grid.blocks.z,
            grid.bytes() as f64 / f64::from(1 << 20),
            start.elapsed().as_millis()
        );
        let params = WorldGridParams {
            origin: grid.origin.to_array(),
            voxel: grid.voxel,
            blocks: grid.blocks.to_array(),
            pad: 0,
        };
        let buffer = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(label), contents, usage })
        };
        let uniform = buffer("gi world grid", bytemuck::bytes_of(&params), wgpu::BufferUsages::UNIFORM);
        let bits = buffer("gi world bits", bytemuck::cast_slice(&grid.bits), wgpu::BufferUsages::STORAGE);
        let distances = grid.packed_block_distances();
        let distances = buffer("gi world distances", bytemuck::cast_slice(&distances), wgpu::BufferUsages::STORAGE);
        let layout = WORLD.layout(device);
        let group = WORLD.bind(
            device,
            &layout,
            &[("world", (&uniform).into()), ("world_bits", (&bits).into()), ("world_distances", (&distances).into())],
        );
        Self { layout, group }
    }
}
