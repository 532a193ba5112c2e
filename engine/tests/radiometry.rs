//! Direct light matches docs/gi.md's radiometry: L_d = ρ/π · I(ω) · max(0, n·l) / d², read back
//! as linear radiance (the values `headlamp render --view direct --out x.exr` writes).

use std::f32::consts::PI;

use engine::camera::Camera;
use engine::frame::ViewState;
use engine::glam::{Quat, Vec3};
use engine::gpu::Gpu;
use engine::headlamp::Headlamp;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::scene::Scene;

mod common;

use common::{grey, plane, uniform_lamp};

const SIZE: (u32, u32) = (96, 64);
const FOV_Y: f32 = 60.0 * PI / 180.0;

/// Linear direct radiance seen from the origin looking down -Z.
fn render_direct(scene: &Scene, lamp: Headlamp) -> image::Rgba32FImage {
    render_direct_with_flash(scene, lamp, [0.0; 3])
}

/// The same with a camera flash of radiant intensity `flash` (W/sr).
fn render_direct_with_flash(scene: &Scene, lamp: Headlamp, flash: [f32; 3]) -> image::Rgba32FImage {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let mut renderer = Renderer::new(&gpu, scene, vec![]).unwrap();
    renderer.set_view("direct").unwrap();
    let view = ViewState {
        camera: Camera::perspective(Vec3::ZERO, Quat::IDENTITY, FOV_Y),
        headlamp: lamp,
        lights: vec![],
        exposure: 1.0,
        instances: vec![],
        camera_flash: flash,
        view_models: vec![],
    };
    let target = HeadlessTarget::new(&gpu, SIZE.0, SIZE.1, ImageKind::Linear);
    match target.render(&gpu, &mut renderer, &view).unwrap() {
        RenderedImage::Linear(img) => img,
        RenderedImage::Display(_) => unreachable!("asked for linear"),
    }
}

/// Mean red radiance of the 2×2 centre texels (the exact centre lies between texels).
fn centre(img: &image::Rgba32FImage) -> f32 {
    centre_channel(img, 0)
}

fn centre_channel(img: &image::Rgba32FImage, channel: usize) -> f32 {
    let (cx, cy) = (SIZE.0 / 2, SIZE.1 / 2);
    let mut sum = 0.0;
    for (x, y) in [(cx - 1, cy - 1), (cx, cy - 1), (cx - 1, cy), (cx, cy)] {
        sum += img.get_pixel(x, y)[channel];
    }
    sum / 4.0
}

/// The cosine between the view axis and the ray through the centre of pixel (x, y).
fn pixel_cos(x: u32, y: u32) -> f32 {
    let tan_half = (FOV_Y * 0.5).tan();
    let aspect = SIZE.0 as f32 / SIZE.1 as f32;
    let ndc_x = (x as f32 + 0.5) / SIZE.0 as f32 * 2.0 - 1.0;
    let ndc_y = 1.0 - (y as f32 + 0.5) / SIZE.1 as f32 * 2.0;
    -Vec3::new(ndc_x * tan_half * aspect, ndc_y * tan_half, -1.0).normalize().z
}

fn assert_close(got: f32, want: f32, what: &str) {
    let rel = (got - want).abs() / want;
    assert!(rel <= 0.01, "{what}: got {got}, expected {want} (relative error {:.3}%)", rel * 100.0);
}

#[test]
fn facing_plane_radiance_is_rho_over_pi_d_squared() {
    for (d, rho, power) in [(2.0_f32, 0.5_f32, 1.0_f32), (5.0, 0.8, 3.0)] {
        let img = render_direct(&plane(Vec3::new(0.0, 0.0, -d), Vec3::Z, grey(rho)), uniform_lamp(power, FOV_Y));
        // The 2×2 centre texels are half a pixel off-axis: account for cos³ of that angle.
        let texel_angle = ((FOV_Y * 0.5).tan() / (SIZE.1 as f32 / 2.0) * 0.5 * 2f32.sqrt()).atan();
        let want = rho * power / (PI * d * d) * texel_angle.cos().powi(3);
        assert_close(centre(&img), want, &format!("plane at {d} m, albedo {rho}, power {power}"));
    }
}

#[test]
fn radiance_falls_off_as_cos_cubed_across_a_facing_plane() {
    let (d, rho) = (3.0, 0.6);
    let img = render_direct(&plane(Vec3::new(0.0, 0.0, -d), Vec3::Z, grey(rho)), uniform_lamp(1.0, FOV_Y));
    for px in [4u32, 20, 70, 90] {
        let y = SIZE.1 / 2;
        let cos = pixel_cos(px, y);
        // n·l = cos and d = d0/cos, so L = ρ cos³ / (π d0²).
        let want = rho / (PI * d * d) * cos.powi(3);
        assert_close(img.get_pixel(px, y)[0], want, &format!("pixel x={px}"));
    }
}

#[test]
fn tilted_plane_radiance_follows_the_cosine() {
    let (d, rho) = (2.5, 0.7);
    for degrees in [30.0_f32, 60.0] {
        let normal = Quat::from_rotation_y(degrees.to_radians()) * Vec3::Z;
        let img = render_direct(&plane(Vec3::new(0.0, 0.0, -d), normal, grey(rho)), uniform_lamp(1.0, FOV_Y));
        // On the axis the lamp direction is +Z: n·l = cos(tilt), distance d.
        let want_axis = rho / (PI * d * d) * degrees.to_radians().cos();
        // The 2×2 centre average straddles the axis symmetrically in x, so first-order terms
        // cancel; allow for the small second-order remainder within the 1 % bound.
        assert_close(centre(&img), want_axis, &format!("plane tilted {degrees}°"));
    }
}

#[test]
fn lamp_off_gives_black_and_outside_the_frustum_gets_nothing() {
    let mut lamp = uniform_lamp(1.0, FOV_Y);
    lamp.on = false;
    let img = render_direct(&plane(Vec3::new(0.0, 0.0, -2.0), Vec3::Z, grey(0.5)), lamp);
    assert!(img.pixels().all(|p| p[0] == 0.0));

    // A detached lamp pointing away (+Z) lights nothing in front of the camera.
    let mut lamp = uniform_lamp(1.0, FOV_Y);
    lamp.attached = false;
    lamp.rotation = Quat::from_rotation_y(PI);
    let img = render_direct(&plane(Vec3::new(0.0, 0.0, -2.0), Vec3::Z, grey(0.5)), lamp);
    assert!(img.pixels().all(|p| p[0] == 0.0));
}

#[test]
fn the_camera_flash_adds_rho_over_pi_i_cos_over_d_squared() {
    let flash = [3.0, 1.5, 0.5];
    // cos³ of the 2×2 centre texels' angle off the axis, as above.
    let texel_angle = ((FOV_Y * 0.5).tan() / (SIZE.1 as f32 / 2.0) * 0.5 * 2f32.sqrt()).atan();
    for (d, degrees) in [(2.5_f32, 0.0_f32), (4.0, 60.0)] {
        let rho = 0.6;
        let normal = Quat::from_rotation_y(degrees.to_radians()) * Vec3::Z;
        let scene = plane(Vec3::new(0.0, 0.0, -d), normal, grey(rho));
        let without = render_direct(&scene, uniform_lamp(1.0, FOV_Y));
        let with = render_direct_with_flash(&scene, uniform_lamp(1.0, FOV_Y), flash);
        // Facing: n·l = cos and d = d0/cos off the axis (cos³); tilted: the 2×2 mean is the
        // on-axis value to within the 1 % bound (see tilted_plane_radiance_follows_the_cosine).
        let off_axis = if degrees == 0.0 { texel_angle.cos().powi(3) } else { 1.0 };
        for (c, &intensity) in flash.iter().enumerate() {
            let added = centre_channel(&with, c) - centre_channel(&without, c);
            let want = rho / PI * intensity * degrees.to_radians().cos() / (d * d) * off_axis;
            assert_close(added, want, &format!("flash channel {c} on a plane at {d} m tilted {degrees}°"));
        }
    }
    // The flash alone, with the lamp off or put down facing away: the same light, no shadow
    // test (a detached lamp's shadow map says nothing about a light at the eye).
    let scene = plane(Vec3::new(0.0, 0.0, -2.0), Vec3::Z, grey(0.5));
    let want = 0.5 / PI * flash[0] / 4.0 * texel_angle.cos().powi(3);
    let mut off = uniform_lamp(1.0, FOV_Y);
    off.on = false;
    assert_close(centre(&render_direct_with_flash(&scene, off, flash)), want, "flash with the lamp off");
    let mut away = uniform_lamp(1.0, FOV_Y);
    away.attached = false;
    away.rotation = Quat::from_rotation_y(PI);
    assert_close(centre(&render_direct_with_flash(&scene, away, flash)), want, "flash with the lamp put down");
}

#[test]
fn the_camera_flash_falls_off_as_cos_cubed_and_zero_changes_nothing() {
    let (d, rho, intensity) = (3.0, 0.6, 2.0);
    let mut lamp = uniform_lamp(1.0, FOV_Y);
    lamp.on = false;
    let scene = plane(Vec3::new(0.0, 0.0, -d), Vec3::Z, grey(rho));
    let img = render_direct_with_flash(&scene, lamp.clone(), [intensity; 3]);
    for px in [4u32, 20, 70, 90] {
        let y = SIZE.1 / 2;
        let cos = pixel_cos(px, y);
        let want = rho * intensity / (PI * d * d) * cos.powi(3);
        assert_close(img.get_pixel(px, y)[0], want, &format!("pixel x={px}"));
    }
    let lit = uniform_lamp(1.0, FOV_Y);
    let zero = render_direct_with_flash(&scene, lit.clone(), [0.0; 3]);
    assert!(zero.as_raw() == render_direct(&scene, lit).as_raw(), "a zero flash must change nothing");
}
