//! The GI against brute force: one-bounce transport of DESIGN.md's formulas, on lavapipe.

mod common;

use common::*;
use engine::glam::{Vec3, Vec4};
use engine::headless::read_texture;
use plugin_gi::{names, readback, GiSettings};

const SIZE: (u32, u32) = (128, 96);

fn settings(budget: u32) -> GiSettings {
    GiSettings { light_budget: budget, ..GiSettings::default() }
}

/// Relative block error of the plugin's indirect light against the brute-force reference.
fn error_at(budget: u32) -> f64 {
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), settings(budget));
    let view = cornell_view(4.0);
    let indirect = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    let reference = render_linear(&gpu, &mut r, &view, "reference", SIZE);
    assert!(reference.pixels().map(|p| p[0] as f64).sum::<f64>() > 0.0, "the reference must see indirect light");
    block_error(&indirect, &reference)
}

#[test]
fn indirect_matches_the_reference_and_improves_with_the_budget() {
    let default_budget = GiSettings::default().light_budget;
    let at_default = error_at(default_budget);
    println!("budget {default_budget}: relative L2 error of 8×8 block means {at_default:.4}");
    assert!(at_default <= 0.10, "error {at_default:.4} at the default budget exceeds 10 %");
    let errors: Vec<(u32, f64)> = [32, 128, 512].iter().map(|&b| (b, error_at(b))).collect();
    println!("errors by budget: {errors:?}");
    for w in errors.windows(2) {
        assert!(w[1].1 < w[0].1, "error must fall as the budget grows: {errors:?}");
    }
}

#[test]
fn reflection_lights_carry_all_of_the_gbuffer_flux_at_every_budget() {
    let gpu = gpu();
    for budget in [16, 64, 256, 1024, 4096] {
        let mut r = renderer(&gpu, &cornell_box(), settings(budget));
        render_linear(&gpu, &mut r, &cornell_view(4.0), "final", SIZE);
        let lights = readback::lights(&gpu, &r.renderer).expect("gi ran");
        let carried = readback::lights_flux(&lights);
        let total = readback::gbuffer_flux(&gpu, &r.renderer).expect("gi ran");
        assert!(!lights.is_empty());
        for c in 0..3 {
            let rel = (carried[c] - total[c]).abs() / total[c];
            assert!(rel < 0.01, "budget {budget}, channel {c}: lights carry {} W of {} W", carried[c], total[c]);
        }
        println!("budget {budget}: {} lights, {} slots", lights.len(), r.handle.stats().slots);
    }
}

/// The flux G-buffer and the GPU reference, recomputed independently on the CPU from the
/// rasterised positions, normals and albedos: Φ = ρ·P·Ω (uniform lamp), then Σ over all texels.
#[test]
fn flux_and_reference_match_a_cpu_computation_of_the_formulas() {
    let gpu = gpu();
    let (w, h) = (48u32, 36u32);
    let power = 4.0f64;
    let mut r = renderer(&gpu, &cornell_box(), settings(256));
    let view = cornell_view(power as f32);
    let reference = render_linear(&gpu, &mut r, &view, "reference", (w, h));
    let graph = r.renderer.graph();
    let texture = |name: &str| read_texture(&gpu, graph.physical_texture(name).unwrap_or_else(|| panic!("{name}")));
    let albedo_bytes = texture(engine::passes::names::GBUFFER_ALBEDO);
    let albedo: &[[u16; 4]] = bytemuck::cast_slice(&albedo_bytes);
    let normal_bytes = texture(engine::passes::names::GBUFFER_NORMAL);
    let position_bytes = texture(engine::passes::names::GBUFFER_POSITION);
    let flux_bytes = texture(names::FLUX);
    let positions: &[[f32; 4]] = bytemuck::cast_slice(&position_bytes);
    let flux_gpu: &[[f32; 4]] = bytemuck::cast_slice(&flux_bytes);
    let halves: &[[u16; 4]] = bytemuck::cast_slice(&normal_bytes);
    let normal = |i: usize| {
        let n = halves[i].map(|b| half::f16::from_bits(b).to_f64());
        (Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32), n[3] > 0.0)
    };

    let tan_y = (FOV_Y as f64 * 0.5).tan();
    let tan_x = tan_y * w as f64 / h as f64;
    let mut emitters = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let (n, lit) = normal(i);
            if !lit {
                continue;
            }
            let rho: Vec<f64> = (0..3).map(|c| half::f16::from_bits(albedo[i][c]).to_f64()).collect();
            let ax = ((x as f64 + 0.5) / w as f64 * 2.0 - 1.0) * tan_x;
            let ay = (1.0 - (y as f64 + 0.5) / h as f64 * 2.0) * tan_y;
            let r2 = 1.0 + ax * ax + ay * ay;
            let omega = 4.0 * tan_x * tan_y / (w * h) as f64 / (r2 * r2.sqrt());
            let flux: Vec<f64> = rho.iter().map(|p| p * power * omega).collect();
            for c in 0..3 {
                let got = flux_gpu[i][c] as f64;
                assert!(
                    (got - flux[c]).abs() <= 2e-3 * flux[c] + 1e-12,
                    "flux texel ({x},{y}) channel {c}: gpu {got}, cpu {}",
                    flux[c]
                );
            }
            let p = Vec4::from(positions[i]).truncate();
            emitters.push((p, n, flux, rho));
        }
    }
    assert!(emitters.len() > (w * h / 2) as usize, "the box fills most of the view");
    let d_min2 = (GiSettings::default().d_min as f64).powi(2);
    let mut checked = 0;
    for (x, n_x, _, rho) in &emitters {
        let mut e = [0.0f64; 3];
        for (p, n_r, flux, _) in &emitters {
            let v = (*x - *p).as_dvec3();
            let d2 = v.length_squared();
            if d2 == 0.0 {
                continue;
            }
            let wv = v / d2.sqrt();
            let g = n_r.as_dvec3().dot(wv).max(0.0) * n_x.as_dvec3().dot(-wv).max(0.0) / d2.max(d_min2);
            for c in 0..3 {
                e[c] += flux[c] / std::f64::consts::PI * g;
            }
        }
        let pixel = project(&view, *x, (w, h));
        let got = reference.get_pixel(pixel.0, pixel.1);
        for c in 0..3 {
            let want = rho[c] / std::f64::consts::PI * e[c];
            assert!(
                (got[c] as f64 - want).abs() <= 2e-3 * want + 1e-9,
                "reference at {pixel:?} channel {c}: gpu {}, cpu {want}",
                got[c]
            );
        }
        checked += 1;
    }
    assert!(checked > 0);
}

/// Pixel of world point `x` for the view at `size`.
fn project(view: &engine::frame::ViewState, x: Vec3, size: (u32, u32)) -> (u32, u32) {
    let ndc = view.camera.view_projection(size.0 as f32 / size.1 as f32).project_point3(x);
    let px = ((ndc.x * 0.5 + 0.5) * size.0 as f32).floor().clamp(0.0, size.0 as f32 - 1.0);
    let py = ((0.5 - ndc.y * 0.5) * size.1 as f32).floor().clamp(0.0, size.1 as f32 - 1.0);
    (px as u32, py as u32)
}

#[test]
fn colour_bleeds_from_the_coloured_walls_onto_the_white_floor() {
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), GiSettings::default());
    let view = cornell_view(4.0);
    let indirect = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    let reference = render_linear(&gpu, &mut r, &view, "reference", SIZE);
    if let Ok(dir) = std::env::var("HEADLAMP_GI_DUMP") {
        let png = |name: &str| std::path::Path::new(&dir).join(name);
        render_display(&gpu, &mut r, &view, "final", SIZE).save(png("cornell_final.png")).unwrap();
        render_display(&gpu, &mut r, &view, "indirect", SIZE).save(png("cornell_indirect.png")).unwrap();
    }
    let at = |img: &image::Rgba32FImage, x: f32, z: f32| {
        let (px, py) = project(&view, Vec3::new(x, 0.0, z), SIZE);
        img.get_pixel(px, py).0
    };
    // Red over green beside the red wall, green over red beside the green wall, neutral between.
    for (img, what) in [(&indirect, "plugin"), (&reference, "reference")] {
        let (red, green, middle) = (at(img, -0.85, -0.3), at(img, 0.85, 0.5), at(img, -0.2, 0.6));
        println!("{what}: floor near red {red:?}, near green {green:?}, middle {middle:?}");
        assert!(red[0] > 1.15 * red[1], "{what}: floor beside the red wall must be tinted red: {red:?}");
        assert!(green[1] > 1.15 * green[0], "{what}: floor beside the green wall must be tinted green: {green:?}");
        let tint = |p: [f32; 4]| p[0] / p[1];
        assert!(tint(red) > tint(middle) && tint(middle) > tint(green), "{what}: the tint must fade across the floor");
    }
    let ratio = |img: &image::Rgba32FImage, x, z| {
        let p = at(img, x, z);
        p[0] / p[1]
    };
    let (got, want) = (ratio(&indirect, -0.85, -0.3), ratio(&reference, -0.85, -0.3));
    assert!((got - want).abs() / want < 0.05, "red tint {got} differs from the reference's {want}");
}

#[test]
fn nothing_is_tinted_by_a_wall_the_lamp_does_not_see() {
    // The red wall is behind the camera: it receives no lamp light and reflects nothing.
    let gpu = gpu();
    let mut scene = cornell_box();
    scene.meshes.retain(|m| m.material != 2); // no green wall
    let mut view = cornell_view(4.0);
    view.camera = engine::camera::Camera::look_at(Vec3::new(-0.6, 1.2, 0.0), Vec3::new(0.9, 0.2, 0.0), FOV_Y);
    let mut r = renderer(&gpu, &scene, GiSettings::default());
    let indirect = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    let (red, green): (f64, f64) = indirect.pixels().fold((0.0, 0.0), |(r, g), p| (r + p[0] as f64, g + p[1] as f64));
    assert!(red > 0.0, "the lit white surfaces still light each other");
    assert!(red <= green * 1.02, "no red tint without a lit red surface: red {red}, green {green}");
}
