//! The GI against the exact one bounce: transport of docs/gi.md's formulas, on lavapipe.

mod common;

use common::*;
use engine::camera::Camera;
use engine::glam::{DVec3, Vec3, Vec4};
use engine::headless::read_texture;
use plugin_gi::{names, readback, GiSettings};

const SIZE: (u32, u32) = (128, 96);

bounds::tolerance! {
    /// The defaults against `reference_screen`: block error (the goal: 5 %).
    DEFAULT_ERROR: at_most 0.05, measured 0.029
}
bounds::tolerance! {
    /// The defaults against `reference_screen`: energy (the goal: 3 %).
    DEFAULT_ENERGY: magnitude 0.03, measured 0.0205
}
bounds::tolerance! {
    /// Full-resolution receivers, split ratio 0.5, against `reference_screen`: block error.
    FULL_ERROR: at_most 0.04, measured 0.0211
}
bounds::tolerance! {
    /// Full-resolution receivers, split ratio 0.5, against `reference_screen`: energy (what is
    /// left is the grouping, and the GI's disc of a light's area next to a receiver where the
    /// reference takes the texel's footprint, long and thin on a grazing floor).
    FULL_ENERGY: magnitude 0.02, measured 0.0175
}
bounds::tolerance! {
    /// A tile's cut carries the G-buffer's flux: relative difference, any channel and split ratio.
    CARRIED: at_most 6e-8, measured 3.43e-8
}
bounds::tolerance! {
    /// A light as a disc of its area against a numerical integral of the disc: relative.
    DISC: at_most 1e-6, measured 5.45e-7
}
bounds::tolerance! {
    /// The flux G-buffer against the CPU's Φ = ρ·P·Ω: relative, the worst texel and channel.
    FLUX_CPU: at_most 8e-7, measured 4.29e-7
}
bounds::tolerance! {
    /// `reference_screen` against the CPU's sum: relative, the worst texel and channel.
    REFERENCE_CPU: at_most 8e-5, measured 4.77e-5
}
bounds::tolerance! {
    /// Two bounces at the finest settings against the CPU's: relative L2 over the texels.
    SECOND_BOUNCE: at_most 0.05, measured 0.026
}
bounds::tolerance! {
    /// The floor's red tint beside the red wall against the reference's: relative.
    TINT: at_most 0.004, measured 0.00213
}
bounds::tolerance! {
    /// A strided reference's block centres against the whole reference: relative.
    STRIDED: at_most 0.0, measured 0.0
}
bounds::tolerance! {
    /// The reference with 3× finer senders against 9×: relative L2 over smooth receivers.
    CONVERGED: at_most 0.02, measured 0.0126
}

fn settings(split_ratio: f32, resolution_scale: f32) -> GiSettings {
    GiSettings { split_ratio, resolution_scale, ..unoccluded() }
}

/// Relative block error of the plugin's indirect light against the exact one bounce, and the
/// bounced energy's relative difference.
fn error_with(settings: GiSettings) -> (f64, f64) {
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), settings);
    let view = cornell_view(4.0);
    let indirect = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    let reference = render_linear(&gpu, &mut r, &view, "reference_screen", SIZE);
    let sum = |img: &image::Rgba32FImage| img.pixels().map(|p| (p[0] + p[1] + p[2]) as f64).sum::<f64>();
    bounds::assert(bounds::at_least("the reference's indirect light", sum(&reference), f64::MIN_POSITIVE));
    (block_error(&indirect, &reference), sum(&indirect) / sum(&reference) - 1.0)
}

#[test]
fn indirect_matches_the_reference_and_improves_as_lights_split_finer() {
    let (at_default, energy) = error_with(unoccluded());
    bounds::assert_all([
        DEFAULT_ERROR.check("defaults: block error", at_default),
        DEFAULT_ENERGY.check("defaults: energy", energy),
    ]);
    // Receivers at full resolution: what is left is the lights' grouping.
    let errors: Vec<(f32, (f64, f64))> = [2.0, 1.0, 0.5].iter().map(|&s| (s, error_with(settings(s, 1.0)))).collect();
    println!("(error, energy) by split ratio: {errors:?}");
    for w in errors.windows(2) {
        let (finer, coarser) = (w[1].1 .0, w[0].1 .0);
        let figure = format!("the error at split {} less at split {}", w[1].0, w[0].0);
        bounds::assert(bounds::at_most(figure, finer - coarser, -f64::MIN_POSITIVE));
    }
    let (error, energy) = errors[2].1;
    // (Tighter on energy than the goal: with every receiver evaluated, what is left is the
    // grouping, and that the GI takes a light next to a receiver as the disc of its area where
    // the reference takes the texel's footprint, a quad, long and thin on a grazing floor:
    // +1.7 % here; against the world-fixed reference the GI's energy is the closer of the two.)
    bounds::assert_all([
        FULL_ERROR.check("full-resolution receivers: block error", error),
        FULL_ENERGY.check("full-resolution receivers: energy", energy),
    ]);
}

/// Every lit texel's flux reaches a tile exactly once through its cut: the lights of the centre
/// tile (those facing away from it included) carry all of the G-buffer's flux, also where a
/// cut outgrew its room and was built again coarser. The GI's calls per frame stay the same
/// however many lights the cuts hold, and a cut is the same list, in the same order, each time
/// it is built from the same frame (the gather's interleaved classes follow that order).
#[test]
fn a_tiles_cut_carries_all_of_the_gbuffer_flux_at_every_split_ratio() {
    let gpu = gpu();
    let (mut calls, mut per_tile, mut full) = (Vec::new(), Vec::new(), 0);
    for split_ratio in [4.0, 1.0, 0.5, 0.2, 0.05] {
        let mut r = renderer(&gpu, &cornell_box(), settings(split_ratio, 0.25));
        render_linear(&gpu, &mut r, &cornell_view(4.0), "final", SIZE);
        let lights = readback::lights(&gpu, &r.renderer).expect("gi ran");
        let carried = readback::lights_flux(&lights);
        let total = readback::gbuffer_flux(&gpu, &r.renderer).expect("gi ran");
        assert!(!lights.is_empty());
        for c in 0..3 {
            let rel = (carried[c] - total[c]).abs() / total[c];
            CARRIED.assert(format!("split {split_ratio}, channel {c}: the cut's flux against the G-buffer's"), rel);
        }
        let cut = readback::cut_stats(&gpu, &r.renderer).unwrap();
        let stats = plugin_gi::GiStats::of(&r.renderer);
        println!(
            "split {split_ratio}: centre tile {} lights, {:.0} per tile, {} tiles full, {} calls",
            lights.len(),
            cut.lights_per_tile(),
            cut.full_tiles,
            stats.dispatches + stats.draws
        );
        calls.push(stats.dispatches + stats.draws);
        per_tile.push(cut.lights_per_tile());
        full += cut.full_tiles;
        render_linear(&gpu, &mut r, &cornell_view(4.0), "final", SIZE);
        let again = readback::lights(&gpu, &r.renderer).expect("gi ran");
        assert!(again == lights, "split {split_ratio}: the centre tile's cut differs between two builds");
    }
    bounds::assert_all([
        bounds::at_least("tiles whose cut outgrew its room", f64::from(full), 1.0),
        bounds::at_least("lights per tile at split 0.05 over at split 4", per_tile[4] / per_tile[0], 5.0),
        bounds::at_most("GI calls per frame", f64::from(calls[0]), 8.0),
    ]);
    assert!(calls.iter().all(|&c| c == calls[0]), "GI calls per frame by split ratio: {calls:?}");
}

/// One visible texel as the CPU sees it (positions, normals and albedos from the rasteriser).
struct Texel {
    pixel: (u32, u32),
    x: Vec3,
    n: Vec3,
    rho: [f64; 3],
    /// Solid angle seen from the lamp (= camera), and the surface area the texel covers,
    /// Ω·d²/max(cos θ, 0.01).
    omega: f64,
    area: f64,
    /// The texel's footprint: where its four corner rays meet the plane of its sample.
    corners: [DVec3; 4],
}

/// The visible texels of the last frame, read back from the G-buffer.
fn texels(gpu: &engine::gpu::Gpu, r: &GiRender, (w, h): (u32, u32), camera: &Camera) -> Vec<Texel> {
    let graph = r.renderer.graph();
    let texture = |name: &str| read_texture(gpu, graph.texture_by_label(name).unwrap_or_else(|| panic!("{name}")));
    let (albedo, normal, position) =
        (texture("gbuffer.albedo"), texture("gbuffer.normal"), texture("gbuffer.position"));
    let halves = |bytes: &[u8], i: usize| {
        bytemuck::cast_slice::<u8, [u16; 4]>(bytes)[i].map(|b| half::f16::from_bits(b).to_f64())
    };
    let positions: &[[f32; 4]] = bytemuck::cast_slice(&position);
    let tan_y = (FOV_Y as f64 * 0.5).tan();
    let tan_x = tan_y * w as f64 / h as f64;
    let eye = camera.position;
    let rotation = camera.rotation.as_dquat();
    let (right, up, forward) = (rotation * DVec3::X, rotation * DVec3::Y, rotation * DVec3::NEG_Z);
    // The ray through a point of the image, (0, 0) its top left corner, in pixels.
    let ray =
        |u: f64, v: f64| forward + (u / w as f64 * 2.0 - 1.0) * tan_x * right + (1.0 - v / h as f64 * 2.0) * tan_y * up;
    let mut out = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let n = halves(&normal, i);
            if n[3] <= 0.0 {
                continue;
            }
            let a = halves(&albedo, i);
            // 1 + tan² of the centre ray's angle from the axis (the axes are orthonormal).
            let r2 = ray(x as f64 + 0.5, y as f64 + 0.5).length_squared();
            let p = Vec4::from(positions[i]).truncate();
            let normal = Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32);
            let omega = 4.0 * tan_x * tan_y / (w * h) as f64 / (r2 * r2.sqrt());
            let d2 = (p - eye).as_dvec3().length_squared();
            let cos = normal.as_dvec3().dot((eye - p).as_dvec3() / d2.sqrt()).max(0.01);
            let height = (p - eye).as_dvec3().dot(normal.as_dvec3());
            let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(cu, cv)| {
                let dir = ray(x as f64 + cu, y as f64 + cv);
                let slope = dir.dot(normal.as_dvec3()).min(-0.01 * dir.length());
                eye.as_dvec3() + dir * (height / slope)
            });
            out.push(Texel {
                pixel: (x, y),
                x: p,
                n: normal,
                rho: [a[0], a[1], a[2]],
                omega,
                area: omega * d2 / cos,
                corners,
            });
        }
    }
    out
}

/// Lambert's point-to-polygon form factor at x (normal n) of the quad `q`, clipped to x's
/// upper hemisphere: 1/2π · Σ over edges of the angle each subtends times n · its plane's normal.
fn quad_form_factor(q: &[DVec3; 4], x: DVec3, n: DVec3) -> f64 {
    let mut poly = Vec::with_capacity(5);
    for i in 0..4 {
        let (a, b) = (q[i] - x, q[(i + 1) % 4] - x);
        let (ha, hb) = (a.dot(n), b.dot(n));
        if ha >= 0.0 {
            poly.push(a);
        }
        if (ha >= 0.0) != (hb >= 0.0) {
            poly.push(a + (b - a) * (ha / (ha - hb)));
        }
    }
    let mut f = 0.0;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let c = a.cross(b);
        let s = c.length();
        if s > 1e-15 * a.length() * b.length() {
            f += s.atan2(a.dot(b)) * n.dot(c) / s;
        }
    }
    f.abs() / (2.0 * std::f64::consts::PI)
}

/// E at every texel from emitters of the given flux, each the small patch its texel covers:
/// the disc of its area (`disc_form`), and within 8 patch radii Φ/A times the form factor of
/// the texel's footprint; summed in f64.
fn cpu_irradiance(texels: &[Texel], flux: &[[f64; 3]]) -> Vec<[f64; 3]> {
    use std::f64::consts::PI;
    texels
        .iter()
        .map(|t| {
            let mut e = [0.0f64; 3];
            for (s, f) in texels.iter().zip(flux) {
                let v = (t.x - s.x).as_dvec3();
                let d2 = v.length_squared();
                if d2 == 0.0 {
                    continue;
                }
                let g = if d2 < 64.0 * s.area / PI {
                    let q = &s.corners;
                    let area = 0.5 * (q[2] - q[0]).cross(q[3] - q[1]).length();
                    if v.dot(s.n.as_dvec3()) <= 0.01 * area.sqrt() {
                        0.0
                    } else {
                        PI / area * quad_form_factor(q, t.x.as_dvec3(), t.n.as_dvec3())
                    }
                } else {
                    disc_form(v, s.n.as_dvec3(), t.n.as_dvec3(), s.area)
                };
                for c in 0..3 {
                    e[c] += f[c] / PI * g;
                }
            }
            e
        })
        .collect()
}

/// π/Φ times the irradiance at v (from the disc's centre; receiver normal n_x) from a
/// Lambertian disc of area `area` and normal n_r: the disc's vector irradiance, from the
/// closed-form point-to-disc form factors parallel and perpendicular to it, written the
/// textbook way (in f64 nothing cancels that matters here).
fn disc_form(v: DVec3, n_r: DVec3, n_x: DVec3, area: f64) -> f64 {
    let a2 = area / std::f64::consts::PI;
    let h = v.dot(n_r);
    if h <= 0.0 {
        return 0.0;
    }
    let s = v - h * n_r;
    let l2 = s.length_squared();
    let q = l2 + h * h + a2;
    let root = (q * q - 4.0 * a2 * l2).sqrt();
    let parallel = 0.5 * (1.0 - (q - 2.0 * a2) / root);
    // F⊥ / |s|, which tends to a finite value on the axis.
    let across = if l2 > 0.0 { h / (2.0 * l2) * (q / root - 1.0) } else { 0.0 };
    (std::f64::consts::PI / area * (parallel * n_x.dot(-n_r) - across * n_x.dot(s))).max(0.0)
}

/// The disc form (the GI's and the reference's transport, twinned above) against a numeric
/// integral of cos·cos/(π d²) over the disc, for receivers close by and far off, facing it,
/// across it and askew: wherever the disc lies wholly above the receiver's plane it is exact.
#[test]
fn the_disc_form_equals_the_integral_over_the_disc() {
    use std::f64::consts::PI;
    let (area, n_r) = (0.04f64, DVec3::new(0.0, 0.0, 1.0));
    let radius = (area / PI).sqrt();
    // Midpoint rule on a polar grid of 400 × 400 cells.
    let integral = |x: DVec3, n_x: DVec3| -> f64 {
        let (rings, sectors) = (400, 400);
        let mut f = 0.0;
        for i in 0..rings {
            let (r0, r1) = (radius * i as f64 / rings as f64, radius * (i + 1) as f64 / rings as f64);
            let r = 0.5 * (r0 + r1);
            let cell = 0.5 * (r1 * r1 - r0 * r0) * 2.0 * PI / sectors as f64;
            for j in 0..sectors {
                let a = 2.0 * PI * (j as f64 + 0.5) / sectors as f64;
                let v = x - DVec3::new(r * a.cos(), r * a.sin(), 0.0);
                let d2 = v.length_squared();
                let w = v / d2.sqrt();
                f += n_r.dot(w).max(0.0) * n_x.dot(-w).max(0.0) / (PI * d2) * cell;
            }
        }
        // π/Φ times the irradiance: the form factor over the disc, times π/A.
        f * PI / area
    };
    let cases = [
        (DVec3::new(0.0, 0.0, 0.05), DVec3::new(0.0, 0.0, -1.0)),
        (DVec3::new(0.3, 0.0, 0.02), DVec3::new(-1.0, 0.0, 0.0)),
        (DVec3::new(0.15, 0.1, 0.2), DVec3::new(-0.6, -0.2, -0.77).normalize()),
        (DVec3::new(0.0, 0.25, 0.3), DVec3::new(0.0, -0.7, -0.7).normalize()),
        (DVec3::new(2.0, -1.0, 1.5), DVec3::new(-0.8, 0.4, -0.45).normalize()),
    ];
    for (x, n_x) in cases {
        // (The disc's lowest point along n_x stays above x's plane.)
        let spread = radius * (1.0 - n_x.dot(n_r).powi(2)).sqrt();
        bounds::assert(bounds::at_least(
            format!("at {x}: the disc's lowest point above the plane"),
            n_x.dot(-x) - spread,
            f64::MIN_POSITIVE,
        ));
        let (exact, form) = (integral(x, n_x), disc_form(x, n_r, n_x, area));
        DISC.assert(format!("at {x}, facing {n_x}: the disc form against the integral"), form / exact - 1.0);
    }
}

/// The flux G-buffer and the GPU reference, recomputed independently on the CPU from the
/// rasterised positions, normals and albedos: Φ = ρ·P·Ω (uniform lamp), then Σ over all texels.
#[test]
fn flux_and_reference_match_a_cpu_computation_of_the_formulas() {
    let size = (48u32, 36u32);
    let view = cornell_view(4.0);
    let (texels, _) = check_reference_against_the_cpu(&view, size, unoccluded());
    bounds::assert(bounds::at_least("the box's share of the view", texels as f64 / f64::from(size.0 * size.1), 0.5));
}

/// The same past 65,535 senders, where a CPU device stops a loop nest without a word: the box
/// seen from afar, low in a 320×240 view, so its lit texels lie beyond that many.
#[test]
fn the_reference_sums_every_sender_at_large_sizes() {
    let size = (320u32, 240u32);
    let mut view = cornell_view(4.0);
    // 20° above the box's centre: the box fills rows ~190 to the bottom.
    let eye = Vec3::new(0.0, 1.0, 8.0);
    view.camera =
        engine::camera::Camera::look_at(eye, Vec3::new(0.0, 1.0 + 8.0 * 20f32.to_radians().tan(), 0.0), FOV_Y);
    // Receivers at full resolution, so that the flux G-buffer is not subsampled either.
    let settings = GiSettings { resolution_scale: 1.0, ..unoccluded() };
    let (_, beyond) = check_reference_against_the_cpu(&view, size, settings);
    bounds::assert(bounds::at_least("lit texels past the 65,535th", beyond as f64, 1000.0));
}

/// Checks flux and reference per texel against the CPU; returns the visible texels, and how
/// many of them come after the 65,535th.
fn check_reference_against_the_cpu(
    view: &engine::frame::ViewState,
    size: (u32, u32),
    settings: GiSettings,
) -> (usize, usize) {
    let gpu = gpu();
    let power = view.headlamp.profile.power as f64;
    let mut r = renderer(&gpu, &cornell_box(), settings);
    // The flux G-buffer is the gather's input (the reference computes its own, per texel).
    render_linear(&gpu, &mut r, view, "indirect", size);
    let flux_bytes = read_texture(&gpu, r.renderer.graph().texture_by_label(names::FLUX).unwrap());
    let reference = render_linear(&gpu, &mut r, view, "reference_screen", size);
    let texels = texels(&gpu, &r, size, &view.camera);
    let beyond = texels.iter().filter(|t| t.pixel.1 * size.0 + t.pixel.0 > 65_535).count();
    println!("{} visible texels, {beyond} of them past the 65,535th", texels.len());
    let flux_gpu: &[[f32; 4]] = bytemuck::cast_slice(&flux_bytes);
    let flux: Vec<[f64; 3]> = texels.iter().map(|t| t.rho.map(|rho| rho * power * t.omega)).collect();
    // Relative, of what the CPU says; a texel the CPU gives (next to) nothing is held absolutely.
    let relative = |got: f32, want: f64, floor: f64| (f64::from(got) - want).abs() / want.max(floor);
    let flux_error = bounds::worst(texels.iter().zip(&flux).flat_map(|(t, f)| {
        let got = flux_gpu[(t.pixel.1 * size.0 + t.pixel.0) as usize];
        (0..3).map(move |c| relative(got[c], f[c], 1e-9))
    }));
    FLUX_CPU.assert(format!("{size:?}: the flux G-buffer against the CPU, worst texel"), flux_error);
    let reference_error = bounds::worst(texels.iter().zip(cpu_irradiance(&texels, &flux)).flat_map(|(t, e)| {
        let got = reference.get_pixel(t.pixel.0, t.pixel.1).0;
        (0..3).map(move |c| relative(got[c], t.rho[c] / std::f64::consts::PI * e[c], 1e-6))
    }));
    REFERENCE_CPU.assert(format!("{size:?}: reference_screen against the CPU, worst texel"), reference_error);
    (texels.len(), beyond)
}

/// The plugin at its finest: lights split down to single texels wherever they are not tiny
/// against their distance, receivers at full resolution, each evaluating every light.
fn finest(bounces: u32) -> GiSettings {
    GiSettings { split_ratio: 0.1, resolution_scale: 1.0, bounces, interleave: 1, ..unoccluded() }
}

/// Two bounces against a CPU computation: Φ₂ = ρ·E₁·A with A = Ω·d²/max(cos θ, 0.01).
#[test]
fn second_bounce_matches_a_cpu_computation() {
    let gpu = gpu();
    let size = (48u32, 36u32);
    let power = 4.0f64;
    let view = cornell_view(power as f32);
    let mut r = renderer(&gpu, &cornell_box(), finest(2));
    let indirect = render_linear(&gpu, &mut r, &view, "indirect", size);
    let texels = texels(&gpu, &r, size, &cornell_view(1.0).camera);
    let flux1: Vec<[f64; 3]> = texels.iter().map(|t| t.rho.map(|rho| rho * power * t.omega)).collect();
    let e1 = cpu_irradiance(&texels, &flux1);
    let flux2: Vec<[f64; 3]> =
        texels.iter().zip(&e1).map(|(t, e)| [0, 1, 2].map(|c| t.rho[c] * e[c] * t.area)).collect();
    let e2 = cpu_irradiance(&texels, &flux2);
    let (mut num, mut den, mut second) = (0.0, 0.0, 0.0);
    for ((t, a), b) in texels.iter().zip(&e1).zip(&e2) {
        let got = indirect.get_pixel(t.pixel.0, t.pixel.1);
        for c in 0..3 {
            let want = t.rho[c] / std::f64::consts::PI * (a[c] + b[c]);
            num += (got[c] as f64 - want).powi(2);
            den += want * want;
            second += t.rho[c] / std::f64::consts::PI * b[c];
        }
    }
    let error = (num / den).sqrt();
    println!("two bounces: the second adds {second:.4}");
    bounds::assert(bounds::at_least("the second bounce's light", second, f64::MIN_POSITIVE));
    // Even at its finest the GI groups lights (a tile's cut holds at most 768 of these 1,700
    // texels), and the second bounce inherits the first's grouping.
    SECOND_BOUNCE.assert("two bounces against the CPU: relative L2", error);
}

#[test]
fn more_bounces_add_less_and_less_light() {
    let gpu = gpu();
    let view = cornell_view(4.0);
    let sums: Vec<f64> = (1..=3)
        .map(|bounces| {
            let mut r = renderer(&gpu, &cornell_box(), GiSettings { bounces, ..unoccluded() });
            let img = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
            let stats = plugin_gi::GiStats::of(&r.renderer);
            println!("bounces {bounces}: {stats:?}");
            img.pixels().map(|p| (p[0] + p[1] + p[2]) as f64).sum()
        })
        .collect();
    println!("indirect totals by bounces: {sums:?}");
    let (d2, d3) = (sums[1] - sums[0], sums[2] - sums[1]);
    // Albedo < 1: each bounce adds less than the one before, and something.
    bounds::assert_all([
        bounds::at_least("the third bounce's light", d3, f64::MIN_POSITIVE),
        bounds::at_most("the third bounce's light over the second's", d3 / d2, 1.0 - f64::EPSILON),
        bounds::at_most("the second bounce's light over the first's", d2 / sums[0], 1.0 - f64::EPSILON),
    ]);
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
    let mut r = renderer(&gpu, &cornell_box(), unoccluded());
    let view = cornell_view(4.0);
    let indirect = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    let reference = render_linear(&gpu, &mut r, &view, "reference_screen", SIZE);
    let at = |img: &image::Rgba32FImage, x: f32, z: f32| {
        let (px, py) = project(&view, Vec3::new(x, 0.0, z), SIZE);
        img.get_pixel(px, py).0
    };
    // Red over green beside the red wall, green over red beside the green wall, neutral between.
    for (img, what) in [(&indirect, "plugin"), (&reference, "reference")] {
        let (red, green, middle) = (at(img, -0.85, -0.3), at(img, 0.85, 0.5), at(img, -0.2, 0.6));
        println!("{what}: floor near red {red:?}, near green {green:?}, middle {middle:?}");
        let tint = |p: [f32; 4]| f64::from(p[0] / p[1]);
        bounds::assert_all([
            bounds::at_least(format!("{what}: red over green beside the red wall"), tint(red), 1.15),
            bounds::at_least(format!("{what}: green over red beside the green wall"), 1.0 / tint(green), 1.15),
            bounds::at_least(
                format!("{what}: the tint beside the red wall over the middle's"),
                tint(red) / tint(middle),
                1.0 + f64::EPSILON,
            ),
            bounds::at_least(
                format!("{what}: the tint in the middle over beside the green wall"),
                tint(middle) / tint(green),
                1.0 + f64::EPSILON,
            ),
        ]);
    }
    let ratio = |img: &image::Rgba32FImage, x, z| {
        let p = at(img, x, z);
        p[0] / p[1]
    };
    let (got, want) = (ratio(&indirect, -0.85, -0.3), ratio(&reference, -0.85, -0.3));
    TINT.assert("the red tint against the reference's", f64::from((got - want).abs() / want));
}

#[test]
fn nothing_is_tinted_by_a_wall_the_lamp_does_not_see() {
    // The red wall is behind the camera: it receives no lamp light and reflects nothing.
    let gpu = gpu();
    let mut scene = cornell_box();
    scene.meshes.retain(|m| m.material != 2); // no green wall
    let mut view = cornell_view(4.0);
    view.camera = engine::camera::Camera::look_at(Vec3::new(-0.6, 1.2, 0.0), Vec3::new(0.9, 0.2, 0.0), FOV_Y);
    let mut r = renderer(&gpu, &scene, unoccluded());
    let indirect = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    let (red, green): (f64, f64) = indirect.pixels().fold((0.0, 0.0), |(r, g), p| (r + p[0] as f64, g + p[1] as f64));
    bounds::assert_all([
        bounds::at_least("the white surfaces' light on each other", red, f64::MIN_POSITIVE),
        bounds::at_most("red over green without a lit red surface", red / green, 1.02),
    ]);
}

#[test]
fn a_lamp_facing_the_void_lights_nothing_indirectly() {
    // Camera and lamp turned away from the open box: they see nothing, so there is no
    // reflected flux, no reflection light and no indirect light anywhere.
    let gpu = gpu();
    let mut view = cornell_view(4.0);
    view.camera = engine::camera::Camera::look_at(Vec3::new(0.0, 1.0, 3.4), Vec3::new(0.0, 1.0, 6.0), FOV_Y);
    let mut r = renderer(&gpu, &cornell_box(), unoccluded());
    let indirect = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    assert!(indirect.pixels().all(|p| p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0));
    assert!(readback::lights(&gpu, &r.renderer).unwrap().is_empty(), "no flux, no lights");
    // Turned back towards the box, the same renderer lights it again.
    let lit = render_linear(&gpu, &mut r, &cornell_view(4.0), "indirect", SIZE);
    let brightest = bounds::worst(lit.pixels().map(|p| f64::from(p[0])));
    bounds::assert(bounds::at_least("the box lit again: its brightest red", brightest, f64::MIN_POSITIVE));
}

/// The reference converges as the lamp view's resolution rises: rendered at 3× and 9× the
/// size, the pixel at the centre of each 3×3 (9×9) block looks along the same ray as the
/// coarse pixel, so the receivers are the same points and only the senders get finer. The
/// finest is taken as the truth: the 3× picture must lie much closer to it than the 1× one.
/// Receivers at a silhouette or a fold are left out (rasterised at three sizes, a ray that
/// grazes an edge may land on either side of it).
/// `GiHandle::set_reference_stride(3)` at 3× the size evaluates only
/// the centre pixel of each 3×3 block: those must be exactly the pixels the whole reference has
/// there (same receiver, same senders, same sum), and the rest of each block black.
#[test]
fn a_strided_reference_evaluates_the_block_centres_exactly() {
    let gpu = gpu();
    let size = (72u32, 54u32);
    let view = cornell_view(4.0);
    let mut r = renderer(&gpu, &cornell_box(), unoccluded());
    let whole = render_linear(&gpu, &mut r, &view, "reference_screen", size);
    r.handle.set_reference_stride(3);
    let strided = render_linear(&gpu, &mut r, &view, "reference_screen", size);
    let (mut centres, mut lit, mut differences) = (0, 0, Vec::new());
    for (x, y, p) in strided.enumerate_pixels() {
        if x % 3 == 1 && y % 3 == 1 {
            let q = whole.get_pixel(x, y);
            differences.extend((0..3).map(|c| f64::from((p[c] - q[c]).abs()) / f64::from(q[c].abs()).max(1e-6)));
            centres += 1;
            lit += usize::from(q[0] + q[1] + q[2] > 0.0);
        } else {
            assert_eq!(&p.0[..3], &[0.0; 3], "({x}, {y}) is not a block's centre and must stay black");
        }
    }
    assert_eq!(centres, 24 * 18);
    STRIDED.assert("the block centres against the whole reference, worst", bounds::worst(differences));
    bounds::assert(bounds::at_least("the lit share of the centres", lit as f64 / centres as f64, 0.5));
}

#[test]
fn the_reference_converges_as_the_lamp_view_gets_finer() {
    let gpu = gpu();
    let base = (24u32, 18u32);
    let mut r = renderer(&gpu, &cornell_box(), unoccluded());
    let view = cornell_view(4.0);
    let pictures: Vec<image::Rgba32FImage> = [1, 3, 9]
        .iter()
        .map(|&k| render_linear(&gpu, &mut r, &view, "reference_screen", (base.0 * k, base.1 * k)))
        .collect();
    // The pixel of picture `level` (k = 3^level) on the ray of coarse pixel (x, y).
    let at = |level: usize, x: u32, y: u32, dx: i32, dy: i32| -> [f32; 4] {
        let k = 3u32.pow(level as u32);
        let (px, py) = ((x * k + k / 2) as i32 + dx, (y * k + k / 2) as i32 + dy);
        pictures[level].get_pixel(px as u32, py as u32).0
    };
    let lum = |p: [f32; 4]| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64;
    let (mut coarse, mut middle, mut truth, mut kept, mut lit) = (0.0, 0.0, 0.0, 0, 0);
    for y in 0..base.1 {
        for x in 0..base.0 {
            let centre = lum(at(2, x, y, 0, 0));
            lit += usize::from(centre > 0.0);
            // A smooth neighbourhood in the finest picture: no silhouette, fold or empty pixel.
            let smooth = centre > 0.0
                && (-1..=1).all(|dy| (-1..=1).all(|dx| (lum(at(2, x, y, dx, dy)) - centre).abs() <= 0.1 * centre));
            if !smooth {
                continue;
            }
            kept += 1;
            coarse += (lum(at(0, x, y, 0, 0)) - centre).powi(2);
            middle += (lum(at(1, x, y, 0, 0)) - centre).powi(2);
            truth += centre * centre;
        }
    }
    let (coarse, middle) = ((coarse / truth).sqrt(), (middle / truth).sqrt());
    println!("{kept} of {lit} lit receivers; relative L2 from the 9× senders: 1× {coarse:.4}, 3× {middle:.4}");
    bounds::assert_all([
        bounds::at_least("the share of lit receivers kept", kept as f64 / lit as f64, 0.75),
        bounds::at_most("the 3× senders' error over the 1×'s", middle / coarse, 0.5),
        CONVERGED.check("3× senders against 9×", middle),
    ]);
}
