//! View models (`ViewState::view_models`, a gun in hand): lit by the headlamp as the G-buffer's
//! surfaces are (L = ρ/π · I · cos / d², plus their emission), drawn over a wall nearer than
//! they are, and in neither the G-buffer nor the detached lamp's view (they neither hide the
//! wall there nor cast shadows on it).

use std::f32::consts::PI;

use engine::camera::Camera;
use engine::frame::{Instance, MeshId, ViewState};
use engine::glam::{Mat4, Quat, Vec3};
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::primitives;
use engine::renderer::Renderer;
use engine::scene::Scene;

mod common;

use common::{uniform_lamp, wall};

const SIZE: (u32, u32) = (96, 64);
const FOV_Y: f32 = 60.0 * PI / 180.0;
const POWER: f32 = 2.0;
const WALL_RHO: f32 = 0.5;
/// The view model's albedo, distinct per channel.
const HELD_RHO: [f32; 3] = [0.3, 0.2, 0.1];
/// How far in front of the camera the view model's front face is, m.
const HELD_AT: f32 = 0.5;

/// The origin looking down −Z, holding `view_models`.
fn view(view_models: Vec<Instance>) -> ViewState {
    ViewState {
        camera: Camera::perspective(Vec3::ZERO, Quat::IDENTITY, FOV_Y),
        headlamp: uniform_lamp(POWER, FOV_Y),
        lights: vec![],
        exposure: 1.0,
        instances: vec![],
        camera_flash: [0.0; 3],
        view_models,
    }
}

/// A renderer of `scene` with a 0.2 m box whose front face (+Z) is `HELD_AT` before the eye.
fn renderer_of(gpu: &Gpu, scene: &Scene) -> (Renderer, MeshId) {
    let mut renderer = Renderer::new(gpu, scene, vec![]).unwrap();
    let (vertices, indices) = primitives::cuboid(Vec3::splat(0.1));
    let mesh = renderer.add_mesh(gpu, &vertices, &indices);
    (renderer, mesh)
}

fn held(mesh: MeshId, emissive: [f32; 3]) -> Instance {
    let transform = Mat4::from_translation(Vec3::new(0.0, 0.0, -HELD_AT - 0.1));
    Instance { mesh, transform, base_color: HELD_RHO, emissive }
}

fn render(gpu: &Gpu, renderer: &mut Renderer, view: &ViewState, name: &str) -> image::Rgba32FImage {
    renderer.set_view(name).unwrap();
    let target = HeadlessTarget::new(gpu, SIZE.0, SIZE.1, ImageKind::Linear);
    match target.render(gpu, renderer, view).unwrap() {
        RenderedImage::Linear(img) => img,
        RenderedImage::Display(_) => unreachable!("asked for linear"),
    }
}

/// Mean of channel `c` over the 2×2 centre texels (the exact centre lies between them).
fn centre(img: &image::Rgba32FImage, c: usize) -> f32 {
    let (cx, cy) = (SIZE.0 / 2, SIZE.1 / 2);
    [(cx - 1, cy - 1), (cx, cy - 1), (cx - 1, cy), (cx, cy)].iter().map(|&(x, y)| img.get_pixel(x, y)[c]).sum::<f32>()
        / 4.0
}

/// ρ/π · P · cos / d² at the centre texels of a face `d` m ahead, as radiometry.rs has it.
fn facing_radiance(rho: f32, d: f32) -> f32 {
    let texel_angle = ((FOV_Y * 0.5).tan() / (SIZE.1 as f32 / 2.0) * 0.5 * 2f32.sqrt()).atan();
    rho * POWER / (PI * d * d) * texel_angle.cos().powi(3)
}

fn assert_close(got: f32, want: f32, what: &str) {
    let rel = (got - want).abs() / want;
    assert!(rel <= 0.01, "{what}: got {got}, expected {want} ({:.3} %)", rel * 100.0);
}

#[test]
fn a_view_model_is_lit_by_the_lamp_and_drawn_over_a_nearer_wall() {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let glow = [0.0, 0.0, 0.25];
    // A wall behind it, then a wall between the eye and it.
    for wall_at in [3.0, 0.3] {
        let (mut renderer, mesh) = renderer_of(&gpu, &wall(-wall_at, WALL_RHO));
        let with = view(vec![held(mesh, glow)]);
        let final_image = render(&gpu, &mut renderer, &with, "final");
        for c in 0..3 {
            let want = facing_radiance(HELD_RHO[c], HELD_AT) + glow[c];
            assert_close(centre(&final_image, c), want, &format!("wall at {wall_at} m, channel {c}"));
        }
        // Not in the G-buffer: there the wall is what the centre sees, lit as if alone.
        let albedo = render(&gpu, &mut renderer, &with, "albedo");
        assert_eq!(centre(&albedo, 0), WALL_RHO, "the view model in the G-buffer (wall at {wall_at} m)");
        let direct = render(&gpu, &mut renderer, &with, "direct");
        assert_close(centre(&direct, 0), facing_radiance(WALL_RHO, wall_at), "the wall's direct light");
    }
}

#[test]
fn a_view_model_casts_no_shadow_from_a_detached_lamp_and_is_shadowed_by_the_level() {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let (mut renderer, mesh) = renderer_of(&gpu, &wall(-3.0, WALL_RHO));
    // The lamp put down 1 m behind the eye, looking the same way: the view model stands in
    // its beam between it and the wall.
    let mut detached = view(vec![held(mesh, [0.0; 3])]);
    detached.headlamp.attached = false;
    detached.headlamp.position = Vec3::new(0.0, 0.0, 1.0);
    detached.headlamp.rotation = Quat::IDENTITY;
    let mut bare = detached.clone();
    bare.view_models.clear();
    let shadowless = render(&gpu, &mut renderer, &bare, "direct");
    let direct = render(&gpu, &mut renderer, &detached, "direct");
    assert_eq!(direct.as_raw(), shadowless.as_raw(), "the view model shadows the wall");
    // It is lit from 1.5 m (its face 0.5 m before the eye, the lamp 1 m behind).
    let final_image = render(&gpu, &mut renderer, &detached, "final");
    assert_close(centre(&final_image, 0), facing_radiance(HELD_RHO[0], HELD_AT + 1.0), "lit by the detached lamp");

    // A wall between the detached lamp and the view model: the lamp's shadow map hides it.
    let (mut behind, mesh) = renderer_of(&gpu, &wall(0.5, WALL_RHO));
    let mut shadowed = detached.clone();
    shadowed.view_models = vec![held(mesh, [0.0; 3])];
    let dark = render(&gpu, &mut behind, &shadowed, "final");
    assert_eq!(centre(&dark, 0), 0.0, "lit through the wall the lamp stands behind");
}
