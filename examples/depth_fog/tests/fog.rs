//! The example plugin, built and rendered headless: with fog, every pixel is the fog-free
//! pixel seen through exp(−density·depth) of fog, the sky is the fog's own radiance, and the
//! pass runs after the lit frame is composed and before the view models.

use depth_fog_example::DepthFogPlugin;
use engine::camera::Camera;
use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::headless::{read_texture, HeadlessTarget, ImageKind, RenderedImage};
use engine::plugin::Plugin;
use engine::renderer::Renderer;
use engine::scene::{Material, Mesh, Scene, Vertex};
use engine::view_state::ViewState;

const FOG: DepthFogPlugin = DepthFogPlugin { radiance: [0.05, 0.06, 0.07], density: 0.2 };

/// A floor running 30 m ahead and a wall at its end, under the camera's headlamp.
fn corridor() -> Scene {
    let quad = |corners: [[f32; 3]; 4], normal: [f32; 3]| Mesh {
        name: "quad".into(),
        vertices: corners.iter().map(|&p| Vertex::new(p, normal, [0.0; 2])).collect(),
        indices: vec![0, 1, 2, 0, 2, 3],
        material: 0,
    };
    Scene {
        meshes: vec![
            quad([[-2.0, 0.0, 1.0], [2.0, 0.0, 1.0], [2.0, 0.0, -30.0], [-2.0, 0.0, -30.0]], [0.0, 1.0, 0.0]),
            quad([[-2.0, 0.0, -30.0], [2.0, 0.0, -30.0], [2.0, 3.0, -30.0], [-2.0, 3.0, -30.0]], [0.0, 0.0, 1.0]),
        ],
        materials: vec![Material { base_color: [0.8, 0.8, 0.8, 1.0], ..Material::default() }],
        ..Scene::default()
    }
}

/// The radiance of a frame (linear), and the view depth of each pixel.
fn render(gpu: &Gpu, plugins: Vec<Box<dyn Plugin>>) -> (Renderer, Vec<[f32; 4]>, Vec<f32>) {
    let mut renderer = Renderer::new(gpu, &corridor(), plugins).unwrap();
    let mut view = ViewState { exposure: 1.0, ..ViewState::default() };
    view.camera = Camera::look_at(Vec3::new(0.0, 1.5, 0.0), Vec3::new(0.0, 1.0, -10.0), view.camera.fov_y().unwrap());
    view.headlamp.profile.power = 40.0;
    let target = HeadlessTarget::new(gpu, 96, 64, ImageKind::Linear);
    let RenderedImage::Linear(image) = target.render(gpu, &mut renderer, &view).unwrap() else {
        panic!("a linear target rendered display values");
    };
    let position = renderer.graph().physical_texture(renderer.core().gbuffer.position).unwrap();
    // Rgba32Float texels: w, the view depth, is each one's last four bytes.
    let bytes = read_texture(gpu, position);
    let depth = bytes.chunks_exact(16).map(|t| f32::from_le_bytes([t[12], t[13], t[14], t[15]])).collect();
    (renderer, image.pixels().map(|p| p.0).collect(), depth)
}

#[test]
fn fog_blends_each_pixel_by_its_depth_after_the_lit_frame() {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let (_, clear, depth) = render(&gpu, vec![]);
    let (renderer, foggy, _) = render(&gpu, vec![Box::new(FOG)]);
    let (mut sky, mut near, mut far) = (0, 0, 0);
    for ((c, f), &d) in clear.iter().zip(&foggy).zip(&depth) {
        let t = if d > 0.0 { (-FOG.density * d).exp() } else { 0.0 };
        for k in 0..3 {
            let expected = c[k] * t + FOG.radiance[k] * (1.0 - t);
            // hdr is half float: 3 significant digits.
            assert!((f[k] - expected).abs() <= 2e-3 * expected.max(1e-3), "{f:?} vs {expected} at depth {d}");
        }
        match d {
            0.0 => sky += 1,
            d if d < 3.0 => near += 1,
            d if d > 15.0 => far += 1,
            _ => {}
        }
    }
    assert!(sky > 0 && near > 0 && far > 0, "the frame has sky {sky}, near {near} and far {far} pixels");
    let order = renderer.graph().compiled().unwrap().order_names();
    let at = |name: &str| order.iter().position(|n| *n == name).unwrap_or_else(|| panic!("{name} in {order:?}"));
    assert!(at("composite") < at("depth_fog") && at("depth_fog") < at("view_model"), "{order:?}");
}
