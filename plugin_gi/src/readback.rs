//! Reading the GI's GPU results back, for tests, `bench` and the overlay (blocks until the GPU
//! is idle).

use engine::gpu::Gpu;
use engine::headless::{read_buffer, read_texture};
use engine::renderer::Renderer;

use crate::gpu_types::{names, GatherStats, ReflectionLight};

/// The reflection lights that lit the tile at the centre of the view in the last frame: its
/// cut through the pyramid.
pub fn lights(gpu: &Gpu, renderer: &Renderer) -> Option<Vec<ReflectionLight>> {
    let count = gather_stats(gpu, renderer)?.instance_count as usize;
    let bytes = read_buffer(gpu, renderer.graph().buffer_by_label(names::LIGHTS)?);
    let all: &[ReflectionLight] = bytemuck::cast_slice(&bytes);
    Some(all[..count.min(all.len())].to_vec())
}

/// What the gather did in the last frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CutStats {
    /// Tiles of 8×8 receivers that saw geometry.
    pub tiles: u32,
    /// Reflection lights summed over those tiles (each tile its own cut through the pyramid).
    pub lights: u64,
    /// Tiles whose cut filled up (lights taken coarser than `split_ratio` asked).
    pub full_tiles: u32,
}

impl CutStats {
    /// Reflection lights per tile, on average.
    pub fn lights_per_tile(&self) -> f64 {
        self.lights as f64 / self.tiles.max(1) as f64
    }
}

pub fn cut_stats(gpu: &Gpu, renderer: &Renderer) -> Option<CutStats> {
    let stats = gather_stats(gpu, renderer)?;
    Some(CutStats { lights: stats.lights as u64, tiles: stats.tiles, full_tiles: stats.full })
}

/// What the article's method (`gi.method = article`) drew in the last frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct VolumeStats {
    /// Light volumes drawn (the instance stream's length).
    pub drawn: u32,
    /// Slots of the distribution table, both tiers.
    pub slots: u32,
}

/// The article's figures; read them only with `gi.method = article` (the cuts fill the same
/// counters with theirs: [`cut_stats`]).
pub fn volume_stats(gpu: &Gpu, renderer: &Renderer) -> Option<VolumeStats> {
    let stats = gather_stats(gpu, renderer)?;
    Some(VolumeStats { drawn: stats.lights, slots: stats.tiles })
}

/// The gather's counters of the last frame.
fn gather_stats(gpu: &Gpu, renderer: &Renderer) -> Option<GatherStats> {
    let bytes = read_buffer(gpu, renderer.graph().buffer_by_label(names::STATS)?);
    Some(bytemuck::pod_read_unaligned(bytes.get(..std::mem::size_of::<GatherStats>())?))
}

/// Σ Φ over the last frame's flux G-buffer, per channel (W), summed in f64.
pub fn gbuffer_flux(gpu: &Gpu, renderer: &Renderer) -> Option<[f64; 3]> {
    let bytes = read_texture(gpu, renderer.graph().texture_by_label(names::FLUX)?);
    let texels: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    Some(sum3(texels.iter().map(|t| [t[0], t[1], t[2]])))
}

/// Σ Φ carried by a set of lights, per channel.
pub fn lights_flux(lights: &[ReflectionLight]) -> [f64; 3] {
    sum3(lights.iter().map(|l| l.flux))
}

fn sum3(values: impl Iterator<Item = [f32; 3]>) -> [f64; 3] {
    values.fold([0.0; 3], |s, v| [s[0] + v[0] as f64, s[1] + v[1] as f64, s[2] + v[2] as f64])
}
