//! Offscreen rendering: a target texture read back to the CPU, no window or display needed.

use crate::gpu::Gpu;
use crate::renderer::Renderer;
use crate::view_state::ViewState;

/// The two kinds of picture a view can be read back as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageKind {
    /// Tonemapped, sRGB-encoded 8-bit RGBA.
    Display,
    /// Linear 32-bit float RGBA (radiance in W·sr⁻¹·m⁻² for radiance views).
    Linear,
}

impl ImageKind {
    pub fn format(self) -> wgpu::TextureFormat {
        match self {
            ImageKind::Display => wgpu::TextureFormat::Rgba8UnormSrgb,
            ImageKind::Linear => wgpu::TextureFormat::Rgba32Float,
        }
    }
}

pub enum RenderedImage {
    Display(image::RgbaImage),
    Linear(image::Rgba32FImage),
}

pub struct HeadlessTarget {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    pub kind: ImageKind,
}

impl HeadlessTarget {
    pub fn new(gpu: &Gpu, width: u32, height: u32, kind: ImageKind) -> Self {
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("headless target"),
            size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: kind.format(),
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        Self { texture, view, kind }
    }

    /// Renders one frame into this target and reads it back. A GPU error on the way (a size
    /// past the device's memory or limits) is an error naming the size, not a panic.
    pub fn render(&self, gpu: &Gpu, renderer: &mut Renderer, view: &ViewState) -> anyhow::Result<RenderedImage> {
        let (w, h) = (self.texture.width(), self.texture.height());
        let largest = gpu.device.limits().max_texture_dimension_2d;
        if w.max(h) > largest {
            anyhow::bail!("a {w}x{h} frame is larger than this GPU's largest texture ({largest} pixels across)");
        }
        gpu.checked(&format!("rendering a {w}x{h} frame"), || renderer.render(gpu, view, &self.texture, &self.view))??;
        Ok(self.read_back(gpu))
    }

    pub fn read_back(&self, gpu: &Gpu) -> RenderedImage {
        let (width, height) = (self.texture.width(), self.texture.height());
        let bytes = read_texture(gpu, &self.texture);
        match self.kind {
            ImageKind::Display => {
                RenderedImage::Display(image::RgbaImage::from_raw(width, height, bytes).expect("size matches"))
            }
            ImageKind::Linear => {
                let floats: Vec<f32> =
                    bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
                RenderedImage::Linear(image::Rgba32FImage::from_raw(width, height, floats).expect("size matches"))
            }
        }
    }
}

/// Copies a buffer (which needs COPY_SRC usage) back to the CPU.
pub fn read_buffer(gpu: &Gpu, buffer: &wgpu::Buffer) -> Vec<u8> {
    let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: buffer.size(),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
    gpu.queue.submit([encoder.finish()]);
    let slice = staging.slice(..);
    slice.map_async(wgpu::MapMode::Read, |r| r.expect("map readback buffer"));
    gpu.wait_idle();
    let bytes = slice.get_mapped_range().expect("readback buffer is mapped").to_vec();
    staging.unmap();
    bytes
}

/// Copies a 2D texture's first mip into tightly packed bytes (rows top to bottom).
pub fn read_texture(gpu: &Gpu, texture: &wgpu::Texture) -> Vec<u8> {
    let (width, height) = (texture.width(), texture.height());
    let bpp = texture.format().block_copy_size(None).expect("colour format");
    let row = width * bpp;
    let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: (padded * height) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
    );
    gpu.queue.submit([encoder.finish()]);
    let slice = buffer.slice(..);
    slice.map_async(wgpu::MapMode::Read, |r| r.expect("map readback buffer"));
    gpu.wait_idle();
    let mapped = slice.get_mapped_range().expect("readback buffer is mapped");
    let mut out = Vec::with_capacity((row * height) as usize);
    for y in 0..height as usize {
        let start = y * padded as usize;
        out.extend_from_slice(&mapped[start..start + row as usize]);
    }
    drop(mapped);
    buffer.unmap();
    out
}
