//! Render scale: view-sized graph textures at a fraction of the output, upsampled by the
//! present pass to a full-size picture that looks like the full-resolution one.

use std::f32::consts::PI;

use engine::camera::Camera;
use engine::frame::{Instance, ViewState};
use engine::glam::{Mat4, Vec3};
use engine::gpu::Gpu;
use engine::headlamp::Headlamp;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::primitives;
use engine::renderer::Renderer;
use engine::scene::{HeadlampProfile, Material, Mesh, Scene, Vertex};

const SIZE: (u32, u32) = (128, 96);
const FOV_Y: f32 = 60.0 * PI / 180.0;

fn gpu() -> Gpu {
    Gpu::headless().unwrap_or_else(|e| panic!("{e}"))
}

/// A corner of a room: floor, back wall and left wall, in three albedos.
fn room() -> Scene {
    let quad = |corners: [[f32; 3]; 4], normal: [f32; 3], material: usize| Mesh {
        name: format!("quad{material}"),
        vertices: corners.iter().map(|&position| Vertex::new(position, normal, [0.0; 2])).collect(),
        indices: vec![0, 1, 2, 0, 2, 3],
        material,
    };
    let material = |rgb: [f32; 3]| Material { base_color: [rgb[0], rgb[1], rgb[2], 1.0], ..Material::default() };
    Scene {
        meshes: vec![
            quad([[-3.0, 0.0, 1.0], [3.0, 0.0, 1.0], [3.0, 0.0, -5.0], [-3.0, 0.0, -5.0]], [0.0, 1.0, 0.0], 0),
            quad([[-3.0, 0.0, -5.0], [3.0, 0.0, -5.0], [3.0, 4.0, -5.0], [-3.0, 4.0, -5.0]], [0.0, 0.0, 1.0], 1),
            quad([[-3.0, 0.0, 1.0], [-3.0, 0.0, -5.0], [-3.0, 4.0, -5.0], [-3.0, 4.0, 1.0]], [1.0, 0.0, 0.0], 2),
        ],
        materials: vec![material([0.6, 0.6, 0.6]), material([0.7, 0.5, 0.3]), material([0.2, 0.4, 0.7])],
        ..Scene::default()
    }
}

fn scene_view(renderer: &mut Renderer, gpu: &Gpu) -> ViewState {
    let (vertices, indices) = primitives::uv_sphere(0.5, 24, 12);
    let sphere = renderer.add_mesh(gpu, &vertices, &indices);
    let instance = Instance {
        mesh: sphere,
        transform: Mat4::from_translation(Vec3::new(0.5, 0.5, -2.5)),
        base_color: [0.9, 0.2, 0.2],
        emissive: [0.0; 3],
    };
    let headlamp = Headlamp::new(HeadlampProfile { power: 3.0, fov_y: FOV_Y, ..HeadlampProfile::default() });
    ViewState {
        camera: Camera::look_at(Vec3::new(0.0, 1.6, 0.5), Vec3::new(0.0, 0.8, -4.0), FOV_Y),
        headlamp,
        lights: vec![],
        exposure: 8.0,
        instances: vec![instance],
        camera_flash: [0.0; 3],
        view_models: vec![],
    }
}

fn render(gpu: &Gpu, renderer: &mut Renderer, view: &ViewState, name: &str) -> image::RgbaImage {
    renderer.set_view(name).unwrap();
    let target = HeadlessTarget::new(gpu, SIZE.0, SIZE.1, ImageKind::Display);
    match target.render(gpu, renderer, view).unwrap() {
        RenderedImage::Display(img) => img,
        RenderedImage::Linear(_) => unreachable!("asked for a picture"),
    }
}

/// Mean absolute difference of the RGB channels, in 8-bit steps.
fn mean_difference(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    let sum: u64 =
        a.pixels().zip(b.pixels()).map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c]) as u64).sum::<u64>()).sum();
    sum as f64 / (a.width() * a.height() * 3) as f64
}

#[test]
fn half_scale_renders_a_full_size_picture_like_the_full_scale_one() {
    let gpu = gpu();
    let mut renderer = Renderer::new(&gpu, &room(), vec![]).unwrap();
    let view = scene_view(&mut renderer, &gpu);
    let full = render(&gpu, &mut renderer, &view, "final");
    renderer.set_render_scale(0.5);
    let half = render(&gpu, &mut renderer, &view, "final");
    let albedo = renderer.graph().physical_texture(renderer.core().gbuffer.albedo).unwrap();
    assert_eq!((albedo.width(), albedo.height()), (SIZE.0 / 2, SIZE.1 / 2), "the G-buffer is half size");
    assert_eq!(half.dimensions(), SIZE, "the picture is full size");
    let difference = mean_difference(&full, &half);
    let full_mean = full.pixels().map(|p| (p[0] as u64 + p[1] as u64 + p[2] as u64) as f64).sum::<f64>()
        / (SIZE.0 * SIZE.1 * 3) as f64;
    println!("scale 0.5 vs 1: mean difference {difference:.2} of 255 (picture mean {full_mean:.1})");
    assert!(full_mean > 40.0, "the scene must be lit for the comparison to mean something");
    // Measured on lavapipe: 1.2 bilinear, 2.0 nearest-texel.
    assert!(difference < 1.6, "half scale differs from full scale by {difference:.2} of 255 on average");

    // Back to full scale: exactly the frame of a renderer that was never scaled.
    renderer.set_render_scale(1.0);
    let again = render(&gpu, &mut renderer, &view, "final");
    assert!(again.as_raw() == full.as_raw(), "scale 1 after 0.5 differs from the first frame");
}

#[test]
fn the_scale_is_clamped_and_fixed_size_lamp_maps_are_shown_as_before() {
    let gpu = gpu();
    let mut renderer = Renderer::new(&gpu, &room(), vec![]).unwrap();
    renderer.set_render_scale(0.1);
    assert_eq!(renderer.render_scale(), 0.25);
    renderer.set_render_scale(3.0);
    assert_eq!(renderer.render_scale(), 1.0);
    renderer.set_render_scale(f32::NAN);
    assert_eq!(renderer.render_scale(), 1.0);

    // The detached lamp's maps do not depend on the render size: the same picture.
    let mut view = scene_view(&mut renderer, &gpu);
    view.headlamp.detach_looking_at(Vec3::new(1.0, 2.0, 0.0), Vec3::new(0.0, 0.5, -3.0));
    let full = render(&gpu, &mut renderer, &view, "lamp_albedo");
    renderer.set_render_scale(0.25);
    let quarter = render(&gpu, &mut renderer, &view, "lamp_albedo");
    let lamp = renderer.graph().physical_texture(renderer.core().lamp.albedo).unwrap();
    assert_eq!(lamp.width(), engine::passes::LAMP_MAP_SIZE, "lamp maps keep their size");
    assert!(full.as_raw() == quarter.as_raw(), "the lamp's view changed with the render scale");
    // While the camera's own views shrink to a quarter.
    render(&gpu, &mut renderer, &view, "albedo");
    let albedo = renderer.graph().physical_texture(renderer.core().gbuffer.albedo).unwrap();
    assert_eq!((albedo.width(), albedo.height()), (SIZE.0 / 4, SIZE.1 / 4));
}
