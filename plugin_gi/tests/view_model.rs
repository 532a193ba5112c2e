//! View models (a gun in hand) and the GI: they are not in the lamp's view, so the reflected
//! flux and the indirect light are exactly those of the frame without them — where the same
//! mesh as a scene instance, 0.4 m before the attached lamp, changes both — and they receive the
//! GI's irradiance at their probe (`view_model.irradiance`), coloured by the walls they face.

mod common;

use common::*;
use engine::frame::{Instance, MeshId, ViewState};
use engine::glam::{Mat4, Quat, Vec3};
use engine::headless::read_buffer;
use engine::primitives;
use plugin_gi::{readback, GiSettings};

const SIZE: (u32, u32) = (80, 60);

bounds::tolerance! {
    /// The GI's light at the middle of the gun's top face against ρ/π·E of its irradiance probe:
    /// how far outside the frame's half-float rounding of it (2⁻¹¹ of each value, up to 14 % of
    /// the GI's share there), relative, any channel.
    TOP_FACE: at_most 0.0, measured 0.0
}

/// A pistol-sized box held low and right in front of `view`'s camera, like the game's gun.
fn gun(view: &ViewState, mesh: MeshId) -> Instance {
    let camera = &view.camera;
    let local = Mat4::from_translation(Vec3::new(0.12, -0.12, -0.4));
    let transform = Mat4::from_rotation_translation(camera.rotation, camera.position) * local;
    Instance { mesh, transform, base_color: [0.8, 0.8, 0.8], emissive: [0.0; 3] }
}

fn gun_renderer(gpu: &engine::gpu::Gpu, settings: GiSettings) -> (GiRender, MeshId) {
    let mut r = renderer(gpu, &cornell_box(), settings);
    let (vertices, indices) = primitives::cuboid(Vec3::new(0.02, 0.03, 0.1));
    let mesh = r.renderer.add_mesh(gpu, &vertices, &indices);
    (r, mesh)
}

fn equal(a: &image::Rgba32FImage, b: &image::Rgba32FImage) -> bool {
    a.as_raw() == b.as_raw()
}

#[test]
fn a_view_model_adds_no_flux_and_changes_no_indirect_light() {
    let gpu = gpu();
    let (mut r, mesh) = gun_renderer(&gpu, GiSettings::default());
    let plain = cornell_view(4.0);
    let mut held = plain.clone();
    held.view_models = vec![gun(&plain, mesh)];
    let mut in_scene = plain.clone();
    in_scene.instances = vec![gun(&plain, mesh)];

    // Each view's whole frame (every pass, the view-model pass included), its flux, then the
    // indirect light alone.
    // Each starts from no history, so the frames before it cannot tell the views apart.
    let mut frame = |view: &ViewState| {
        r.renderer.reset_history();
        let final_image = render_linear(&gpu, &mut r, view, "final", SIZE);
        let flux = readback::gbuffer_flux(&gpu, &r.renderer).unwrap();
        (final_image, flux, render_linear(&gpu, &mut r, view, "indirect", SIZE))
    };
    let (final_plain, flux, indirect) = frame(&plain);
    let (final_held, flux_held, indirect_held) = frame(&held);
    let (_, flux_scene, indirect_scene) = frame(&in_scene);
    println!("Σ Φ: without {flux:?}, held {flux_held:?}, as a scene instance {flux_scene:?}");
    assert_eq!(flux, flux_held, "the view model must not reflect the lamp's light");
    assert!(equal(&indirect, &indirect_held), "the view model changed the indirect light");
    // The control: in the lamp's view the same box reflects the light of the walls it hides,
    // from 0.4 m before the lamp: the flux and the indirect light change.
    let change = bounds::worst((0..3).map(|c| (flux_scene[c] - flux[c]).abs() / flux[c]));
    bounds::assert(bounds::at_least("the flux's change with the box as scene geometry", change, 1e-3));
    assert!(!equal(&indirect, &indirect_scene));

    // And it is drawn: the final frame differs from the one without it.
    let changed = final_plain.pixels().zip(final_held.pixels()).filter(|(a, b)| a != b).count();
    println!("the view model covers {changed} pixels");
    bounds::assert(bounds::at_least("pixels the view model changes", changed as f64, 21.0));
}

/// The ambient cube the GI wrote at the probe, for +X, −X, +Y, −Y, +Z, −Z.
fn ambient_cube(gpu: &engine::gpu::Gpu, r: &GiRender) -> [[f32; 3]; 6] {
    let buffer = r.renderer.graph().buffer_by_label("view_model.irradiance").expect("declared by the engine");
    let bytes = read_buffer(gpu, buffer);
    let v: &[[f32; 4]] = bytemuck::cast_slice(&bytes[..96]);
    std::array::from_fn(|i| [v[i][0], v[i][1], v[i][2]])
}

#[test]
fn a_view_model_receives_the_gi_coloured_by_the_walls_it_faces() {
    let gpu = gpu();
    let (mut r, mesh) = gun_renderer(&gpu, GiSettings::default());
    // Inside the box, turned towards the red (x = −1) wall, then towards the green (x = +1)
    // one, the lamp lighting each in turn: the gun's side facing that wall takes its colour.
    let mut view = cornell_view(4.0);
    view.camera.position = Vec3::new(0.0, 1.0, 0.6);
    let turned = |view: &ViewState, yaw_deg: f32| {
        let mut v = view.clone();
        v.camera.rotation = Quat::from_rotation_y(yaw_deg.to_radians());
        v.view_models = vec![gun(&v, mesh)];
        v
    };
    let mut cubes = Vec::new();
    for yaw in [40.0, -40.0] {
        render_linear(&gpu, &mut r, &turned(&view, yaw), "final", SIZE);
        let cube = ambient_cube(&gpu, &r);
        println!("turned {yaw}°: ambient cube (+X −X +Y −Y +Z −Z): {cube:?}");
        let least = bounds::least(cube.iter().flatten().map(|&e| f64::from(e)));
        bounds::assert(bounds::at_least(format!("turned {yaw}°: the ambient cube's least irradiance"), least, 0.0));
        cubes.push(cube);
    }
    let (red, green) = (cubes[0][1], cubes[1][0]);
    bounds::assert_all([
        bounds::at_least("facing the lit red wall: red over green", red[0] / red[1], 1.5),
        bounds::at_least("facing the lit green wall: green over red", green[1] / green[0], 1.5),
    ]);
    let view = turned(&view, 40.0);

    // The GI's share of the gun's light: with the GI off the cube stays zero and the gun's
    // pixels (where the frame differs from the one without it) are darker.
    let lit = render_linear(&gpu, &mut r, &view, "final", SIZE);
    let (mut off, mesh_off) = gun_renderer(&gpu, GiSettings { enabled: false, ..GiSettings::default() });
    let mut view = view;
    view.view_models = vec![gun(&view, mesh_off)];
    let unlit = render_linear(&gpu, &mut off, &view, "final", SIZE);
    assert_eq!(ambient_cube(&gpu, &off), [[0.0; 3]; 6], "without the GI nobody writes the cube");
    let mut bare = view.clone();
    bare.view_models.clear();
    let background = render_linear(&gpu, &mut off, &bare, "final", SIZE);
    let gun_pixels: Vec<(u32, u32)> = unlit
        .enumerate_pixels()
        .filter(|(x, y, p)| *p != background.get_pixel(*x, *y))
        .map(|(x, y, _)| (x, y))
        .collect();
    let sum = |img: &image::Rgba32FImage| {
        gun_pixels.iter().map(|&(x, y)| img.get_pixel(x, y).0[..3].iter().sum::<f32>() as f64).sum::<f64>()
    };
    let (a, b) = (sum(&lit), sum(&unlit));
    println!("the gun's {} pixels: GI on {a:.4}, off {b:.4}", gun_pixels.len());
    bounds::assert_all([
        bounds::at_least("the gun's pixels", gun_pixels.len() as f64, 21.0),
        bounds::at_least("the gun's light with the GI less without", a - b, f64::MIN_POSITIVE),
    ]);
    // Exactly: at the middle of the gun's top face (below the eye, it faces up), the GI adds
    // ρ/π · E(n), E the cube's irradiance for that normal.
    let n = view.camera.rotation * Vec3::Y;
    let cube = cubes[0];
    let face = |axis: f32, pos: [f32; 3], neg: [f32; 3]| if axis >= 0.0 { pos } else { neg };
    let e: Vec<f32> = (0..3)
        .map(|c| {
            n.x * n.x * face(n.x, cube[0], cube[1])[c]
                + n.y * n.y * face(n.y, cube[2], cube[3])[c]
                + n.z * n.z * face(n.z, cube[4], cube[5])[c]
        })
        .collect();
    let top_face = view.camera.position + view.camera.rotation * Vec3::new(0.12, -0.09, -0.4);
    let ndc = view.camera.view_projection(SIZE.0 as f32 / SIZE.1 as f32).project_point3(top_face);
    let (x, y) = (((ndc.x * 0.5 + 0.5) * SIZE.0 as f32) as u32, ((0.5 - ndc.y * 0.5) * SIZE.1 as f32) as u32);
    for (c, e) in e.iter().enumerate() {
        let (on, off) = (lit.get_pixel(x, y)[c], unlit.get_pixel(x, y)[c]);
        let want = 0.8 / std::f32::consts::PI * e;
        println!("pixel ({x}, {y}) channel {c}: the GI adds {:.5}, ρ/π·E = {want:.5}", on - off);
        // The frame's radiance is half floats: each value is rounded to 2⁻¹¹ of its size.
        let rounding = (on.abs() + off.abs()) / 2048.0;
        // How far the GI's light lies outside that rounding of ρ/π·E; `worst` keeps a NaN.
        let beyond = f64::from(((on - off - want).abs() - rounding) / want);
        let error = bounds::worst([beyond, 0.0]);
        TOP_FACE.assert(format!("channel {c}: the GI's light on the gun's top face against ρ/π·E"), error);
    }
}
