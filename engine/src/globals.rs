//! Group 0 of every core shader: the per-frame uniforms, the punctual lights and the lamp's
//! intensity distribution texture (see shaders/common.wgsl for the matching declarations).

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec4};
use scene::{LightKind, PunctualLight};

use crate::bindings::{Group, ShaderBinding};
use crate::gpu::Gpu;
use crate::headlamp::{distribution_texels, LampFrustum};
use crate::view_state::ViewState;

/// Bind group layouts shared by the engine's passes and plugins.
pub struct CoreLayouts {
    pub globals: wgpu::BindGroupLayout,
    pub material: wgpu::BindGroupLayout,
}

/// Group 0 of every shader that includes common.wgsl.
pub const GLOBALS: Group = Group::new(
    "globals",
    &[
        ShaderBinding::uniform("globals"),
        ShaderBinding::storage("lights"),
        ShaderBinding::filtered_texture("lamp_distribution"),
        ShaderBinding::sampler("linear_clamp"),
    ],
);

/// Group 1 of the scene's surfaces (scene_surface.wgsl): the material's factors, and each
/// texture with its sampler.
pub const MATERIAL: Group = Group::new(
    "material",
    &[
        ShaderBinding::uniform("material"),
        ShaderBinding::filtered_texture("base_color_texture"),
        ShaderBinding::sampler("base_color_sampler"),
        ShaderBinding::filtered_texture("emissive_texture"),
        ShaderBinding::sampler("emissive_sampler"),
        ShaderBinding::filtered_texture("metallic_roughness_texture"),
        ShaderBinding::sampler("metallic_roughness_sampler"),
    ],
);

impl CoreLayouts {
    pub fn new(device: &wgpu::Device) -> Self {
        Self { globals: GLOBALS.layout(device), material: MATERIAL.layout(device) }
    }
}

crate::gpu_struct! {
    /// `Globals` in shaders/common.wgsl.
    #[repr(C)]
    #[derive(Clone, Copy, Pod, Zeroable)]
    pub(crate) struct GlobalsUniform as Globals {
        view_proj: Mat4,
        inv_view_proj: Mat4,
        view: Mat4,
        lamp_view_proj: Mat4,
        camera_pos: Vec4,
        lamp_pos: Vec4,
        lamp_intensity: Vec4,
        viewport: Vec4,
        params: Vec4,
        camera_flash: Vec4,
    }
}

/// What a light is, in `Light.direction_kind.w` (`LIGHT_*` in shaders/common.wgsl).
pub const LIGHT_POINT: u32 = 0;
pub const LIGHT_SPOT: u32 = 1;
pub const LIGHT_DIRECTIONAL: u32 = 2;

crate::gpu_struct! {
    /// `Light` in shaders/common.wgsl.
    #[repr(C)]
    #[derive(Clone, Copy, Pod, Zeroable)]
    pub(crate) struct GpuLight as Light {
        position_range: [f32; 4],
        direction_kind: [f32; 4],
        color: [f32; 4],
        cone: [f32; 4],
    }
}

impl GpuLight {
    fn new(l: &PunctualLight) -> Self {
        let (kind, cone) = match l.kind {
            LightKind::Point => (LIGHT_POINT as f32, [-2.0, -1.0]),
            LightKind::Spot { inner_cone, outer_cone } => (LIGHT_SPOT as f32, [inner_cone.cos(), outer_cone.cos()]),
            LightKind::Directional => (LIGHT_DIRECTIONAL as f32, [-2.0, -1.0]),
        };
        let c = l.color;
        Self {
            position_range: [l.position.x, l.position.y, l.position.z, l.range.unwrap_or(0.0)],
            direction_kind: [l.direction.x, l.direction.y, l.direction.z, kind],
            color: [c[0] * l.intensity, c[1] * l.intensity, c[2] * l.intensity, 0.0],
            cone: [cone[0], cone[1], 0.0, 0.0],
        }
    }
}

/// Key of the uploaded distribution texture: it depends on the profile and the frustum shape.
#[derive(PartialEq, Clone)]
struct DistributionKey {
    distribution: scene::IntensityDistribution,
    fov_y: f32,
    aspect: f32,
}

pub struct GlobalsGpu {
    uniform: wgpu::Buffer,
    lights: wgpu::Buffer,
    lights_capacity: usize,
    distribution: wgpu::Texture,
    distribution_key: Option<DistributionKey>,
    sampler: wgpu::Sampler,
    pub bind_group: wgpu::BindGroup,
}

impl GlobalsGpu {
    pub fn new(gpu: &Gpu, layouts: &CoreLayouts) -> Self {
        let device = &gpu.device;
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("globals"),
            size: std::mem::size_of::<GlobalsUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let lights = lights_buffer(device, 4);
        let distribution = distribution_texture(device, 1, 1);
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("linear clamp"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let bind_group = bind(device, layouts, &uniform, &lights, &distribution, &sampler);
        Self { uniform, lights, lights_capacity: 4, distribution, distribution_key: None, sampler, bind_group }
    }

    /// Uploads this frame's uniforms for a view rendered at `size` pixels and shown with
    /// `aspect` (the output's, which a reduced render scale may round slightly differently);
    /// re-creates the lights buffer or distribution texture only when they no longer fit.
    pub fn update(
        &mut self,
        gpu: &Gpu,
        layouts: &CoreLayouts,
        view: &ViewState,
        lamp: &LampFrustum,
        size: (u32, u32),
        aspect: f32,
    ) {
        let device = &gpu.device;
        let mut rebind = false;
        if view.lights.len() > self.lights_capacity {
            self.lights_capacity = view.lights.len().next_power_of_two();
            self.lights = lights_buffer(device, self.lights_capacity);
            rebind = true;
        }
        let key = DistributionKey {
            distribution: view.headlamp.profile.distribution.clone(),
            fov_y: lamp.fov_y,
            aspect: lamp.aspect,
        };
        if self.distribution_key.as_ref() != Some(&key) {
            let (w, h, texels) = distribution_texels(&key.distribution, key.fov_y, key.aspect);
            self.distribution = distribution_texture(device, w, h);
            let halves: Vec<half::f16> = texels.iter().flatten().map(|&v| half::f16::from_f32(v)).collect();
            gpu.queue.write_texture(
                self.distribution.as_image_copy(),
                bytemuck::cast_slice(&halves),
                wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w * 8), rows_per_image: Some(h) },
                wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            );
            self.distribution_key = Some(key);
            rebind = true;
        }
        if rebind {
            self.bind_group = bind(device, layouts, &self.uniform, &self.lights, &self.distribution, &self.sampler);
        }

        let view_proj = view.camera.view_projection(aspect);
        let lamp_on = if view.headlamp.on { 1.0 } else { 0.0 };
        // Detached: the direct light pass tests `lamp.depth`, whose texels cover
        // 2·tan(fov/2)/LAMP_MAP_SIZE metres per metre of distance from the lamp.
        let (detached, lamp_texel) = if view.headlamp.attached {
            (0.0, 0.0)
        } else {
            (1.0, 2.0 * (lamp.fov_y * 0.5).tan() / crate::headlamp::LAMP_MAP_SIZE as f32)
        };
        let uniform = GlobalsUniform {
            view_proj,
            inv_view_proj: view_proj.inverse(),
            view: view.camera.view_matrix(),
            lamp_view_proj: lamp.view_proj,
            camera_pos: view.camera.position.extend(1.0),
            lamp_pos: lamp.position.extend(lamp_on),
            lamp_intensity: view.headlamp.intensity().extend(0.0),
            viewport: Vec4::new(size.0 as f32, size.1 as f32, 1.0 / size.0 as f32, 1.0 / size.1 as f32),
            params: Vec4::new(view.exposure, view.lights.len() as f32, detached, lamp_texel),
            camera_flash: glam::Vec3::from(view.camera_flash).extend(0.0),
        };
        gpu.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        if !view.lights.is_empty() {
            let lights: Vec<GpuLight> = view.lights.iter().map(GpuLight::new).collect();
            gpu.queue.write_buffer(&self.lights, 0, bytemuck::cast_slice(&lights));
        }
    }
}

fn lights_buffer(device: &wgpu::Device, capacity: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("punctual lights"),
        size: (capacity.max(1) * std::mem::size_of::<GpuLight>()) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn distribution_texture(device: &wgpu::Device, width: u32, height: u32) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("lamp intensity distribution"),
        size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba16Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

fn bind(
    device: &wgpu::Device,
    layouts: &CoreLayouts,
    uniform: &wgpu::Buffer,
    lights: &wgpu::Buffer,
    distribution: &wgpu::Texture,
    sampler: &wgpu::Sampler,
) -> wgpu::BindGroup {
    let view = distribution.create_view(&wgpu::TextureViewDescriptor::default());
    GLOBALS.bind(
        device,
        &layouts.globals,
        &[
            ("globals", uniform.into()),
            ("lights", lights.into()),
            ("lamp_distribution", (&view).into()),
            ("linear_clamp", sampler.into()),
        ],
    )
}
