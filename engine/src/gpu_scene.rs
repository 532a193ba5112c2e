//! The scene's geometry and materials on the GPU: one vertex and one index buffer for the
//! whole level, one draw per mesh, one bind group per material.

use std::collections::HashMap;

use bytemuck::{Pod, Zeroable};
use scene::{Filter, Material, Reflection, Scene, Texture, TextureRef, Vertex, Wrap};
use wgpu::util::DeviceExt;

use crate::globals::CoreLayouts;
use crate::gpu::Gpu;

/// The vertex layout matching `scene::Vertex` (position, normal, uv, uv1, colour) and
/// `VertexIn` in shaders/scene_surface.wgsl.
pub const VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<Vertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x2, 4 => Float32x4
    ],
};

/// How many ways a material is rasterised: opaque or alpha-tested (`fs_masked`, which
/// discards), times drawn from both sides or back faces culled. [`variant`] numbers them.
pub const VARIANTS: usize = 4;

/// The variant of a material: bit 0 alpha-tested (MASK, and BLEND drawn as MASK), bit 1
/// single-sided (back faces culled).
pub fn variant(material: &Material) -> usize {
    usize::from(material.alpha_cutoff().is_some()) | (usize::from(!material.double_sided) << 1)
}

/// Whether variant `v` discards fragments below the alpha cutoff.
pub fn variant_masked(v: usize) -> bool {
    v & 1 != 0
}

/// Whether variant `v` culls back faces.
pub fn variant_culls(v: usize) -> bool {
    v & 2 != 0
}

#[derive(Clone, Copy, Debug)]
pub struct Draw {
    pub first_index: u32,
    pub index_count: u32,
    pub base_vertex: i32,
    pub material: usize,
    /// The material's [`variant`]: which pipeline draws it.
    pub variant: usize,
}

crate::gpu_struct! {
    /// `Material` in shaders/scene_surface.wgsl.
    #[repr(C)]
    #[derive(Clone, Copy, Pod, Zeroable)]
    pub(crate) struct MaterialUniform as Material {
        base_color: [f32; 4],
        emissive: [f32; 4],
        /// The base colour texture's uv map: rows of a 2×3 matrix on (u, v, 1); row 0's w is
        /// the uv set (0 or 1).
        base_color_uv_0: [f32; 4],
        base_color_uv_1: [f32; 4],
        emissive_uv_0: [f32; 4],
        emissive_uv_1: [f32; 4],
        metallic_roughness_uv_0: [f32; 4],
        metallic_roughness_uv_1: [f32; 4],
        /// x: the alpha cutoff (read by `fs_masked` only).
        alpha: [f32; 4],
        /// x: metallic factor, y: roughness factor, z: 1 for the metallic-roughness BRDF, 0 for
        /// Lambertian; w: 1 when there is a metallic-roughness texture.
        reflection: [f32; 4],
    }
}

/// The uniform's `reflection` row.
fn reflection_row(r: &Reflection) -> [f32; 4] {
    match *r {
        Reflection::Lambertian => [0.0, 1.0, 0.0, 0.0],
        Reflection::MetallicRoughness { metallic, roughness, texture } => {
            [metallic, roughness, 1.0, if texture.is_some() { 1.0 } else { 0.0 }]
        }
    }
}

/// The uniform rows of a texture slot's uv map (identity on set 0 when there is no texture).
fn uv_rows(t: Option<&TextureRef>) -> [[f32; 4]; 2] {
    let (m, set) = match t {
        Some(t) => (t.transform.matrix(), t.tex_coord as f32),
        None => (scene::TextureTransform::IDENTITY.matrix(), 0.0),
    };
    [[m[0][0], m[0][1], m[0][2], set], [m[1][0], m[1][1], m[1][2], 0.0]]
}

fn sampler_descriptor(s: &scene::Sampler) -> wgpu::SamplerDescriptor<'static> {
    let address = |w: Wrap| match w {
        Wrap::Repeat => wgpu::AddressMode::Repeat,
        Wrap::ClampToEdge => wgpu::AddressMode::ClampToEdge,
        Wrap::MirroredRepeat => wgpu::AddressMode::MirrorRepeat,
    };
    let filter = |f: Filter| match f {
        Filter::Nearest => wgpu::FilterMode::Nearest,
        Filter::Linear => wgpu::FilterMode::Linear,
    };
    let (mipmap_filter, lod_max_clamp) = match s.mipmap_filter {
        Some(Filter::Nearest) => (wgpu::MipmapFilterMode::Nearest, 32.0),
        Some(Filter::Linear) => (wgpu::MipmapFilterMode::Linear, 32.0),
        // No mipmapping: the full-size level only.
        None => (wgpu::MipmapFilterMode::Nearest, 0.0),
    };
    wgpu::SamplerDescriptor {
        label: Some("material"),
        address_mode_u: address(s.wrap_u),
        address_mode_v: address(s.wrap_v),
        mag_filter: filter(s.mag_filter),
        min_filter: filter(s.min_filter),
        mipmap_filter,
        lod_max_clamp,
        ..Default::default()
    }
}

pub struct GpuScene {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    /// Sorted by variant, then material.
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
                variant: scene.materials.get(mesh.material).map_or(0, variant),
            });
            vertices.extend_from_slice(&mesh.vertices);
            indices.extend_from_slice(&mesh.indices);
        }
        // Sorting keeps pipeline switches to one per variant, bind-group switches to one per
        // material.
        draws.sort_by_key(|d| (d.variant, d.material));
        let placeholder = [0u8; std::mem::size_of::<Vertex>()];
        let vertex_bytes: &[u8] = if vertices.is_empty() { &placeholder } else { bytemuck::cast_slice(&vertices) };
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

        let mut samplers: HashMap<scene::Sampler, wgpu::Sampler> = HashMap::new();
        let mut sampler = |s: &scene::Sampler| -> wgpu::Sampler {
            samplers.entry(*s).or_insert_with(|| device.create_sampler(&sampler_descriptor(s))).clone()
        };
        let white = Texture { name: "white".into(), width: 1, height: 1, rgba8: vec![255; 4] };
        // Colour textures are sRGB-encoded, metallic-roughness ones linear (glTF's rule): each
        // image is uploaded in the encodings its uses need.
        let upload_as = |linear: bool| -> Vec<Option<wgpu::TextureView>> {
            let used: Vec<bool> = (0..scene.textures.len())
                .map(|i| {
                    scene.materials.iter().any(|m| {
                        let uses = |t: &TextureRef| t.texture == i;
                        if linear {
                            m.metallic_roughness_texture().is_some_and(uses)
                        } else {
                            m.base_color_texture.iter().chain(&m.emissive_texture).any(uses)
                        }
                    })
                })
                .collect();
            scene.textures.iter().zip(used).map(|(t, used)| used.then(|| upload_texture(gpu, t, linear))).collect()
        };
        let (srgb, linear) = (upload_as(false), upload_as(true));
        let white = upload_texture(gpu, &white, false);
        let materials = scene
            .materials
            .iter()
            .map(|m| {
                // A missing texture samples white: the factor alone.
                let mut slot = |t: Option<&TextureRef>, views: &[Option<wgpu::TextureView>]| {
                    let view = t.and_then(|t| views.get(t.texture)).and_then(Option::as_ref).unwrap_or(&white);
                    (view.clone(), sampler(&t.map(|t| t.sampler).unwrap_or_default()))
                };
                let (base_view, base_sampler) = slot(m.base_color_texture.as_ref(), &srgb);
                let (emissive_view, emissive_sampler) = slot(m.emissive_texture.as_ref(), &srgb);
                let (mr_view, mr_sampler) = slot(m.metallic_roughness_texture(), &linear);
                let [base_color_uv_0, base_color_uv_1] = uv_rows(m.base_color_texture.as_ref());
                let [emissive_uv_0, emissive_uv_1] = uv_rows(m.emissive_texture.as_ref());
                let [metallic_roughness_uv_0, metallic_roughness_uv_1] = uv_rows(m.metallic_roughness_texture());
                let uniform = MaterialUniform {
                    base_color: m.base_color,
                    emissive: [m.emissive[0], m.emissive[1], m.emissive[2], 0.0],
                    base_color_uv_0,
                    base_color_uv_1,
                    emissive_uv_0,
                    emissive_uv_1,
                    metallic_roughness_uv_0,
                    metallic_roughness_uv_1,
                    alpha: [m.alpha_cutoff().unwrap_or(0.0), 0.0, 0.0, 0.0],
                    reflection: reflection_row(&m.reflection),
                };
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(&m.name),
                    contents: bytemuck::bytes_of(&uniform),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                crate::globals::MATERIAL.bind(
                    device,
                    &layouts.material,
                    &[
                        ("material", (&buffer).into()),
                        ("base_color_texture", (&base_view).into()),
                        ("base_color_sampler", (&base_sampler).into()),
                        ("emissive_texture", (&emissive_view).into()),
                        ("emissive_sampler", (&emissive_sampler).into()),
                        ("metallic_roughness_texture", (&mr_view).into()),
                        ("metallic_roughness_sampler", (&mr_sampler).into()),
                    ],
                )
            })
            .collect();
        Self { vertices, indices, draws, materials }
    }

    /// Which of the [`VARIANTS`] some draw uses (a pass builds pipelines for those only).
    pub fn variants_used(&self) -> [bool; VARIANTS] {
        let mut used = [false; VARIANTS];
        for d in &self.draws {
            used[d.variant] = true;
        }
        used
    }

    /// Draws every mesh, each with `pipelines[its variant]` (built for every variant in
    /// [`Self::variants_used`]); the caller has set group 0, materials go in group 1.
    pub fn draw_all(&self, pass: &mut wgpu::RenderPass<'_>, pipelines: &[Option<wgpu::RenderPipeline>; VARIANTS]) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        let (mut bound, mut variant) = (usize::MAX, usize::MAX);
        for d in &self.draws {
            if d.variant != variant {
                let Some(pipeline) = &pipelines[d.variant] else {
                    panic!("no pipeline for scene variant {}", d.variant);
                };
                pass.set_pipeline(pipeline);
                variant = d.variant;
            }
            if d.material != bound {
                pass.set_bind_group(1, &self.materials[d.material], &[]);
                bound = d.material;
            }
            pass.draw_indexed(d.first_index..d.first_index + d.index_count, d.base_vertex, 0..1);
        }
    }
}

/// Uploads a texture, sRGB-encoded or `linear`, with a box-filtered mip chain built on the CPU.
fn upload_texture(gpu: &Gpu, t: &Texture, linear: bool) -> wgpu::TextureView {
    let mip_count = 32 - t.width.max(t.height).max(1).leading_zeros();
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(&t.name),
        size: wgpu::Extent3d { width: t.width, height: t.height, depth_or_array_layers: 1 },
        mip_level_count: mip_count,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: if linear { wgpu::TextureFormat::Rgba8Unorm } else { wgpu::TextureFormat::Rgba8UnormSrgb },
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
