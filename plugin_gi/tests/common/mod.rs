//! Scenes and render helpers shared by the GI tests.
#![allow(dead_code)]

use engine::camera::Camera;
use engine::frame::ViewState;
use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::headlamp::Headlamp;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::scene::{HeadlampProfile, IntensityDistribution, Material, Mesh, Scene, Vertex};
#[allow(unused_imports)] // Not every test file compares images.
pub use plugin_gi::metrics::block_error;
use plugin_gi::{GiHandle, GiPlugin, GiSettings};

pub const FOV_Y: f32 = 50.0 * std::f32::consts::PI / 180.0;

/// The article's transport, every light seen by every receiver (`gi.visibility` off): what
/// the references these tests compare with (`reference_screen`, the CPU's sums) compute. The
/// visibility-correct reference is the game's (`game/tests/gi_visibility.rs`).
pub fn unoccluded() -> GiSettings {
    GiSettings { visibility: 0, ..GiSettings::default() }
}

pub fn gpu() -> Gpu {
    Gpu::lavapipe().unwrap_or_else(|e| panic!("{e}"))
}

/// Appends a quad (corners counter-clockwise seen from the side its normal points to).
fn quad(scene: &mut Scene, corners: [Vec3; 4], material: usize) {
    let n = (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalize();
    let vertices = corners.iter().map(|p| Vertex::new(p.to_array(), n.to_array(), [0.0; 2])).collect();
    scene.meshes.push(Mesh {
        name: format!("quad{}", scene.meshes.len()),
        vertices,
        indices: vec![0, 1, 2, 0, 2, 3],
        material,
    });
}

fn material(name: &str, rgb: [f32; 3]) -> Material {
    Material { name: name.into(), base_color: [rgb[0], rgb[1], rgb[2], 1.0], ..Material::default() }
}

/// A Cornell-like box, open towards +Z: x ∈ [-1, 1], y ∈ [0, 2], z ∈ [-1, 1]; red left wall,
/// green right wall, white floor, ceiling and back wall, and a white block on the floor.
pub fn cornell_box() -> Scene {
    let mut s = Scene {
        materials: vec![
            material("white", [0.75, 0.75, 0.75]),
            material("red", [0.75, 0.1, 0.1]),
            material("green", [0.1, 0.7, 0.1]),
        ],
        ..Scene::default()
    };
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    quad(&mut s, [v(-1.0, 0.0, 1.0), v(1.0, 0.0, 1.0), v(1.0, 0.0, -1.0), v(-1.0, 0.0, -1.0)], 0); // floor, up
    quad(&mut s, [v(-1.0, 2.0, -1.0), v(1.0, 2.0, -1.0), v(1.0, 2.0, 1.0), v(-1.0, 2.0, 1.0)], 0); // ceiling, down
    quad(&mut s, [v(-1.0, 0.0, -1.0), v(1.0, 0.0, -1.0), v(1.0, 2.0, -1.0), v(-1.0, 2.0, -1.0)], 0); // back, +z
    quad(&mut s, [v(-1.0, 0.0, 1.0), v(-1.0, 0.0, -1.0), v(-1.0, 2.0, -1.0), v(-1.0, 2.0, 1.0)], 1); // left red, +x
    quad(&mut s, [v(1.0, 0.0, -1.0), v(1.0, 0.0, 1.0), v(1.0, 2.0, 1.0), v(1.0, 2.0, -1.0)], 2); // right green, -x
                                                                                                 // A block 0.6 m tall: its front (+z) and left (-x) faces and its top.
    let (x0, x1, z0, z1, h) = (0.1, 0.6, -0.5, 0.0, 0.6);
    quad(&mut s, [v(x0, 0.0, z1), v(x1, 0.0, z1), v(x1, h, z1), v(x0, h, z1)], 0);
    quad(&mut s, [v(x0, 0.0, z0), v(x0, 0.0, z1), v(x0, h, z1), v(x0, h, z0)], 0);
    quad(&mut s, [v(x0, h, z1), v(x1, h, z1), v(x1, h, z0), v(x0, h, z0)], 0);
    s
}

/// A uniform lamp of power `power` attached to a camera looking into the box from the front.
pub fn cornell_view(power: f32) -> ViewState {
    let profile =
        HeadlampProfile { power, fov_y: FOV_Y, color: [1.0; 3], distribution: IntensityDistribution::Uniform };
    ViewState {
        camera: Camera::look_at(Vec3::new(0.0, 1.0, 3.4), Vec3::new(0.0, 1.0, 0.0), FOV_Y),
        headlamp: Headlamp::new(profile),
        lights: vec![],
        exposure: 1.0,
        instances: vec![],
        camera_flash: [0.0; 3],
        view_models: vec![],
    }
}

pub struct GiRender {
    pub renderer: Renderer,
    pub handle: GiHandle,
}

pub fn renderer(gpu: &Gpu, scene: &Scene, settings: GiSettings) -> GiRender {
    let plugin = GiPlugin::new(settings);
    let handle = plugin.handle();
    let renderer = Renderer::new(gpu, scene, vec![Box::new(plugin)]).unwrap();
    GiRender { renderer, handle }
}

/// Linear RGBA of `view` at `size`.
pub fn render_linear(
    gpu: &Gpu,
    r: &mut GiRender,
    view: &ViewState,
    name: &str,
    size: (u32, u32),
) -> image::Rgba32FImage {
    r.renderer.set_view(name).unwrap();
    let target = HeadlessTarget::new(gpu, size.0, size.1, ImageKind::Linear);
    match target.render(gpu, &mut r.renderer, view).unwrap() {
        RenderedImage::Linear(img) => img,
        RenderedImage::Display(_) => unreachable!(),
    }
}

/// Tonemapped sRGB picture of `view` at `size`, for looking at.
pub fn render_display(gpu: &Gpu, r: &mut GiRender, view: &ViewState, name: &str, size: (u32, u32)) -> image::RgbaImage {
    r.renderer.set_view(name).unwrap();
    let target = HeadlessTarget::new(gpu, size.0, size.1, ImageKind::Display);
    match target.render(gpu, &mut r.renderer, view).unwrap() {
        RenderedImage::Display(img) => img,
        RenderedImage::Linear(_) => unreachable!(),
    }
}
