//! Dynamic mesh instances: drawn into the camera's G-buffer (their colour, lit by docs/gi.md's
//! radiometry, their emission) and into the detached lamp's view (they cast its shadows), with
//! normals transformed by the inverse-transpose; no instances leave the frame as it was.

use std::f32::consts::PI;

use engine::camera::Camera;
use engine::frame::{Instance, MeshId, ViewState};
use engine::glam::{Mat4, Quat, Vec3};
use engine::gpu::Gpu;
use engine::headlamp::Headlamp;
use engine::headless::{read_texture, HeadlessTarget, ImageKind, RenderedImage};
use engine::passes::LAMP_MAP_SIZE;
use engine::primitives;
use engine::renderer::Renderer;
use engine::scene::Scene;

mod common;

use common::{uniform_lamp, wall};

const SIZE: (u32, u32) = (96, 64);
const FOV_Y: f32 = 60.0 * PI / 180.0;
const POWER: f32 = 2.0;
const WALL_RHO: f32 = 0.5;
/// The cube's colour: distinct per channel, so a channel mix-up shows.
const CUBE_RHO: [f32; 3] = [0.8, 0.4, 0.2];

fn gpu() -> Gpu {
    Gpu::headless().unwrap_or_else(|e| panic!("{e}"))
}

fn view(camera: Camera, headlamp: Headlamp, instances: Vec<Instance>) -> ViewState {
    ViewState {
        camera,
        headlamp,
        lights: vec![],
        exposure: 1.0,
        instances,
        camera_flash: [0.0; 3],
        view_models: vec![],
    }
}

/// A renderer of `scene` with a unit cube (half extent 0.5) added.
fn renderer_with_cube(gpu: &Gpu, scene: &Scene) -> (Renderer, MeshId) {
    let mut renderer = Renderer::new(gpu, scene, vec![]).unwrap();
    let (vertices, indices) = primitives::cuboid(Vec3::splat(0.5));
    let cube = renderer.add_mesh(gpu, &vertices, &indices);
    (renderer, cube)
}

fn cube(mesh: MeshId, transform: Mat4) -> Instance {
    Instance { mesh, transform, base_color: CUBE_RHO, emissive: [0.0; 3] }
}

/// Linear RGBA of view `name`.
fn render(gpu: &Gpu, renderer: &mut Renderer, view: &ViewState, name: &str) -> image::Rgba32FImage {
    renderer.set_view(name).unwrap();
    let target = HeadlessTarget::new(gpu, SIZE.0, SIZE.1, ImageKind::Linear);
    match target.render(gpu, renderer, view).unwrap() {
        RenderedImage::Linear(img) => img,
        RenderedImage::Display(_) => unreachable!("asked for linear"),
    }
}

/// The pixel seeing world point `x`.
fn pixel(camera: &Camera, x: Vec3) -> (u32, u32) {
    let ndc = camera.view_projection(SIZE.0 as f32 / SIZE.1 as f32).project_point3(x);
    let px = ((ndc.x * 0.5 + 0.5) * SIZE.0 as f32).floor().clamp(0.0, SIZE.0 as f32 - 1.0);
    let py = ((0.5 - ndc.y * 0.5) * SIZE.1 as f32).floor().clamp(0.0, SIZE.1 as f32 - 1.0);
    (px as u32, py as u32)
}

/// Where the ray through the centre of pixel (x, y) meets the plane z = `z`.
fn seen_at_z(camera: &Camera, (x, y): (u32, u32), z: f32) -> Vec3 {
    let tan = (FOV_Y * 0.5).tan();
    let ndc_x = (x as f32 + 0.5) / SIZE.0 as f32 * 2.0 - 1.0;
    let ndc_y = 1.0 - (y as f32 + 0.5) / SIZE.1 as f32 * 2.0;
    let dir = camera.rotation * Vec3::new(ndc_x * tan * SIZE.0 as f32 / SIZE.1 as f32, ndc_y * tan, -1.0);
    camera.position + dir * ((z - camera.position.z) / dir.z)
}

fn rgb(img: &image::Rgba32FImage, (x, y): (u32, u32)) -> Vec3 {
    let p = img.get_pixel(x, y);
    Vec3::new(p[0], p[1], p[2])
}

fn assert_close(got: Vec3, want: Vec3, tolerance: f32, what: &str) {
    let rel = ((got - want).abs() / want.abs().max(Vec3::splat(1e-6))).max_element();
    assert!(rel <= tolerance, "{what}: got {got}, expected {want} (relative error {:.3} %)", rel * 100.0);
}

/// ρ/π · I · max(0, n·l) / d² for the uniform lamp at `lamp`.
fn lamp_radiance(rho: Vec3, n: Vec3, lamp: Vec3, x: Vec3) -> Vec3 {
    let to_lamp = lamp - x;
    let d2 = to_lamp.length_squared();
    rho / PI * POWER * n.dot(to_lamp / d2.sqrt()).max(0.0) / d2
}

#[test]
fn an_instance_in_front_of_the_attached_lamp_shows_its_colour_and_is_lit() {
    let gpu = gpu();
    let (mut renderer, mesh) = renderer_with_cube(&gpu, &wall(-4.0, WALL_RHO));
    let camera = Camera::perspective(Vec3::ZERO, Quat::IDENTITY, FOV_Y);
    // A 0.6 m cube 2 m ahead, a little off the axis: its front face is at z = -1.7.
    let transform = Mat4::from_scale_rotation_translation(Vec3::splat(0.6), Quat::IDENTITY, Vec3::new(0.2, 0.1, -2.0));
    let with = view(camera, uniform_lamp(POWER, FOV_Y), vec![cube(mesh, transform)]);
    let without = view(camera, uniform_lamp(POWER, FOV_Y), vec![]);

    let face = Vec3::new(0.25, 0.05, -1.7);
    let beside = Vec3::new(-1.5, 0.0, -4.0);
    let (on_face, on_wall) = (pixel(&camera, face), pixel(&camera, beside));
    let albedo = render(&gpu, &mut renderer, &with, "albedo");
    assert_close(rgb(&albedo, on_face), Vec3::from(CUBE_RHO), 1e-3, "albedo of the cube");
    assert_close(rgb(&albedo, on_wall), Vec3::splat(WALL_RHO), 1e-3, "albedo of the wall beside it");

    // Lit by the lamp at the eye: L = ρ/π · P · cos / d² at the point the pixel centre sees.
    let direct = render(&gpu, &mut renderer, &with, "direct");
    let want = lamp_radiance(Vec3::from(CUBE_RHO), Vec3::Z, Vec3::ZERO, seen_at_z(&camera, on_face, -1.7));
    assert_close(rgb(&direct, on_face), want, 0.01, "direct radiance of the cube's front face");
    let seen = seen_at_z(&camera, on_wall, -4.0);
    let want = lamp_radiance(Vec3::splat(WALL_RHO), Vec3::Z, Vec3::ZERO, seen);
    assert_close(rgb(&direct, on_wall), want, 0.01, "direct radiance of the wall beside the cube");

    // The final picture shows it too, and without instances the wall is back, exactly as a
    // renderer that never drew one renders it.
    let final_with = render(&gpu, &mut renderer, &with, "final");
    assert_close(rgb(&final_with, on_face), rgb(&direct, on_face), 1e-3, "final radiance of the cube");
    let after = render(&gpu, &mut renderer, &without, "final");
    let (mut fresh, _) = renderer_with_cube(&gpu, &wall(-4.0, WALL_RHO));
    let never = render(&gpu, &mut fresh, &without, "final");
    assert!(after.as_raw() == never.as_raw(), "a frame without instances differs after one with them");
    assert!(rgb(&after, on_face).x < rgb(&final_with, on_face).x, "the wall behind is darker than the cube");
}

#[test]
fn an_instance_between_a_detached_lamp_and_a_wall_casts_a_shadow_on_it() {
    let gpu = gpu();
    let (mut renderer, mesh) = renderer_with_cube(&gpu, &wall(-4.0, WALL_RHO));
    let mut lamp = uniform_lamp(POWER, FOV_Y);
    lamp.detach_looking_at(Vec3::ZERO, Vec3::new(0.0, 0.0, -4.0));
    // A 0.6 m cube halfway: its umbra on the wall is about |x|, |y| < 0.52 (its back face).
    let transform = Mat4::from_scale_rotation_translation(Vec3::splat(0.6), Quat::IDENTITY, Vec3::new(0.0, 0.0, -2.0));
    // From the side, so the cube does not hide its shadow.
    let camera = Camera::look_at(Vec3::new(2.0, 0.5, 0.0), Vec3::new(0.0, 0.0, -4.0), FOV_Y);
    let with = view(camera, lamp.clone(), vec![cube(mesh, transform)]);
    let direct = render(&gpu, &mut renderer, &with, "direct");

    let (shadowed, lit) = (pixel(&camera, Vec3::new(0.0, 0.0, -4.0)), pixel(&camera, Vec3::new(0.0, 1.2, -4.0)));
    assert_eq!(rgb(&direct, shadowed), Vec3::ZERO, "the wall behind the cube must be in its umbra");
    let want = lamp_radiance(Vec3::splat(WALL_RHO), Vec3::Z, Vec3::ZERO, seen_at_z(&camera, lit, -4.0));
    assert_close(rgb(&direct, lit), want, 0.01, "the wall outside the shadow");

    // The lamp's view holds the cube: its albedo at the centre of the lamp map.
    let texture = renderer.graph().physical_texture(renderer.core().lamp.albedo).unwrap();
    let bytes = read_texture(&gpu, texture);
    let i = ((LAMP_MAP_SIZE / 2) * LAMP_MAP_SIZE + LAMP_MAP_SIZE / 2) as usize * 8;
    let albedo: Vec<f32> =
        (0..3).map(|c| half::f16::from_le_bytes([bytes[i + 2 * c], bytes[i + 2 * c + 1]]).to_f32()).collect();
    assert_close(Vec3::from_slice(&albedo), Vec3::from(CUBE_RHO), 1e-3, "lamp-view albedo of the cube");

    // Without the cube the same spot is lit.
    let without = render(&gpu, &mut renderer, &view(camera, lamp, vec![]), "direct");
    let want = lamp_radiance(Vec3::splat(WALL_RHO), Vec3::Z, Vec3::ZERO, seen_at_z(&camera, shadowed, -4.0));
    assert_close(rgb(&without, shadowed), want, 0.01, "the wall with no cube in the way");
}

#[test]
fn an_emissive_instance_shows_its_emission() {
    let gpu = gpu();
    let (mut renderer, mesh) = renderer_with_cube(&gpu, &wall(-4.0, WALL_RHO));
    let camera = Camera::perspective(Vec3::ZERO, Quat::IDENTITY, FOV_Y);
    let mut lamp = uniform_lamp(POWER, FOV_Y);
    lamp.on = false;
    let glow = [2.0, 1.0, 0.25];
    let instance = Instance {
        mesh,
        transform: Mat4::from_translation(Vec3::new(0.0, 0.0, -2.0)),
        base_color: [0.1; 3],
        emissive: glow,
    };
    let img = render(&gpu, &mut renderer, &view(camera, lamp, vec![instance]), "final");
    // Lamp off: the cube is its emission, the wall is black.
    assert_eq!(rgb(&img, (SIZE.0 / 2, SIZE.1 / 2)), Vec3::from(glow), "the emissive cube");
    assert_eq!(rgb(&img, (2, 2)), Vec3::ZERO, "the unlit wall");
}

#[test]
fn instance_normals_follow_the_inverse_transpose_and_face_out_when_mirrored() {
    let gpu = gpu();
    let (mut renderer, mesh) = renderer_with_cube(&gpu, &wall(-30.0, WALL_RHO));
    // Rotated 45° about Z then stretched along X: the rotated +X face is no longer
    // perpendicular to M·(1, 0, 0); its normal is M⁻ᵀ·(1, 0, 0).
    let m = Mat4::from_scale(Vec3::new(2.0, 1.0, 1.0)) * Mat4::from_rotation_z(PI / 4.0);
    let transform = Mat4::from_translation(Vec3::new(0.0, 0.0, -3.0)) * m;
    let face_centre = transform.transform_point3(Vec3::new(0.5, 0.0, 0.0));
    let want = (transform.inverse().transpose().transform_vector3(Vec3::X)).normalize();
    let naive = transform.transform_vector3(Vec3::X).normalize();
    assert!(want.dot(naive) < 0.9, "the test needs a transform that tells them apart");
    let camera = Camera::look_at(face_centre + want * 2.0, face_centre, FOV_Y);
    let normals =
        render(&gpu, &mut renderer, &view(camera, uniform_lamp(POWER, FOV_Y), vec![cube(mesh, transform)]), "normal");
    let got = rgb(&normals, pixel(&camera, face_centre));
    assert!((got - want).length() < 2e-3, "normal of the stretched face: got {got}, expected {want}");

    // Mirrored (det < 0): the face towards the camera still has its normal towards it.
    let mirrored = Mat4::from_translation(Vec3::new(0.0, 0.0, -3.0)) * Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
    let camera = Camera::perspective(Vec3::ZERO, Quat::IDENTITY, FOV_Y);
    let normals =
        render(&gpu, &mut renderer, &view(camera, uniform_lamp(POWER, FOV_Y), vec![cube(mesh, mirrored)]), "normal");
    let got = rgb(&normals, (SIZE.0 / 2, SIZE.1 / 2));
    assert!((got - Vec3::Z).length() < 2e-3, "mirrored cube's front face: normal {got}, expected +Z");
}

#[test]
fn many_instances_of_several_meshes_grow_the_buffer_and_unknown_meshes_are_skipped() {
    let gpu = gpu();
    let (mut renderer, cube_mesh) = renderer_with_cube(&gpu, &wall(-6.0, WALL_RHO));
    let (vertices, indices) = primitives::uv_sphere(0.3, 12, 6);
    let sphere = renderer.add_mesh(&gpu, &vertices, &indices);
    let camera = Camera::perspective(Vec3::ZERO, Quat::IDENTITY, FOV_Y);
    // A 20 × 10 grid alternating cubes and spheres, beyond the initial buffer's capacity.
    let mut instances = Vec::new();
    for j in 0..10 {
        for i in 0..20 {
            let at = Vec3::new(-2.85 + i as f32 * 0.3, -1.35 + j as f32 * 0.3, -4.0);
            let mesh = if (i + j) % 2 == 0 { cube_mesh } else { sphere };
            let transform = Mat4::from_scale_rotation_translation(Vec3::splat(0.25), Quat::IDENTITY, at);
            instances.push(Instance { mesh, transform, base_color: [0.9, 0.1, 0.1], emissive: [0.0; 3] });
        }
    }
    let grid = view(camera, uniform_lamp(POWER, FOV_Y), instances.clone());
    let albedo = render(&gpu, &mut renderer, &grid, "albedo");
    let red = albedo.pixels().filter(|p| p[0] > 0.8 && p[1] < 0.2).count();
    println!("{red} of {} pixels show the grid", SIZE.0 * SIZE.1);
    assert!(red > (SIZE.0 * SIZE.1 / 6) as usize, "only {red} pixels show the grid");
    // A mesh id the renderer never handed out draws nothing (and does not panic).
    instances.push(Instance { mesh: MeshId(99), ..instances[0] });
    let with_unknown = render(&gpu, &mut renderer, &view(camera, uniform_lamp(POWER, FOV_Y), instances), "albedo");
    assert!(albedo.as_raw() == with_unknown.as_raw(), "an unknown mesh changed the frame");
}
