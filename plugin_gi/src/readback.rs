//! Reading the GI's GPU results back, for tests and `bench` (blocks until the GPU is idle).

use engine::gpu::Gpu;
use engine::headless::{read_buffer, read_texture};
use engine::renderer::Renderer;

use crate::gpu_types::{names, ReflectionLight};

/// The reflection lights built in the last frame.
pub fn lights(gpu: &Gpu, renderer: &Renderer) -> Option<Vec<ReflectionLight>> {
    let args = read_buffer(gpu, renderer.graph().physical_buffer(names::DRAW_ARGS)?);
    let count = u32::from_le_bytes(args[4..8].try_into().ok()?) as usize;
    let bytes = read_buffer(gpu, renderer.graph().physical_buffer(names::LIGHTS)?);
    let all: &[ReflectionLight] = bytemuck::cast_slice(&bytes);
    Some(all[..count.min(all.len())].to_vec())
}

/// Σ Φ over the last frame's flux G-buffer, per channel (W), summed in f64.
pub fn gbuffer_flux(gpu: &Gpu, renderer: &Renderer) -> Option<[f64; 3]> {
    let bytes = read_texture(gpu, renderer.graph().physical_texture(names::FLUX)?);
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
