//! `headlamp render` as a user runs it: arbitrary glTF/OBJ files, radiometrically correct EXR,
//! and one clear line for every kind of bad input.

use std::f32::consts::PI;
use std::path::{Path, PathBuf};
use std::process::Output;

use glam::Vec3;
use gltf_conformance::{Bin, SAMPLES};
use serde_json::json;

mod common;

use common::{headlamp, scratch};

/// Writes the conformance sample `file` (a name in `gltf_conformance::SAMPLES`) into `dir`.
fn sample(dir: &Path, file: &str) -> PathBuf {
    let (_, doc) = SAMPLES.iter().find(|(name, _)| *name == file).expect("a sample of that name");
    gltf_conformance::write(dir, file, &doc())
}

/// Renders `level` from its own view (its first camera, else one framing it) to a 96×96 PNG.
fn render_png(level: &Path, png: &Path) -> image::RgbImage {
    let out =
        headlamp(&["render", "--level", level.to_str().unwrap(), "--out", png.to_str().unwrap(), "--size", "96x96"]);
    assert_ok(&out);
    image::open(png).unwrap().into_rgb8()
}

fn assert_ok(out: &Output) {
    assert!(out.status.success(), "headlamp failed: {}", String::from_utf8_lossy(&out.stderr));
}

/// A 40 m quad in the plane z = `z` facing +Z, albedo `rho`, as a base64-embedded glTF.
fn write_plane_gltf(path: &Path, z: f32, rho: f32) {
    let s = 20.0f32;
    let mut bin = Bin::default();
    let positions = bin.vec3(&[[-s, -s, z], [s, -s, z], [s, s, z], [-s, s, z]]);
    let indices = bin.u16s(&[0, 1, 2, 0, 2, 3]);
    let doc = bin.gltf(json!({
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": positions}, "indices": indices, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [rho, rho, rho, 1.0], "metallicFactor": 0.0}}],
    }));
    std::fs::write(path, serde_json::to_vec(&doc).unwrap()).unwrap();
}

/// glTF's BRDF for a rough dielectric (metallic 0, roughness 1: D = 1/π, V = 1/(2(n·l + n·v)))
/// of albedo `rho`, in sr⁻¹.
fn rough_dielectric(rho: f32, n_l: f32, n_v: f32, v_h: f32) -> f32 {
    let fresnel = 0.04 + 0.96 * (1.0 - v_h).powi(5);
    (1.0 - fresnel) * rho / PI + fresnel / PI * 0.5 / (n_l + n_v)
}

#[test]
fn exr_of_a_bare_gltf_reads_the_brdf_times_i_over_d_squared() {
    let dir = scratch("plane");
    let (d, rho) = (3.0f32, 0.6f32);
    let gltf = dir.join("plane.gltf");
    write_plane_gltf(&gltf, -d, rho);
    let exr = dir.join("direct.exr");
    let out = headlamp(&[
        "render",
        "--level",
        gltf.to_str().unwrap(),
        "--out",
        exr.to_str().unwrap(),
        "--size",
        "64x64",
        "--view",
        "direct",
        "--camera",
        "0,0,0:0,0,-1",
        "--fov",
        "50",
    ]);
    assert_ok(&out);
    let img = image::open(&exr).unwrap().into_rgb32f();
    let centre: f32 =
        [(31, 31), (32, 31), (31, 32), (32, 32)].iter().map(|&(x, y)| img.get_pixel(x, y)[0]).sum::<f32>() / 4.0;
    // A rough dielectric facing the lamp at the eye: f = (0.96·ρ + 0.01)/π.
    let want = rough_dielectric(rho, 1.0, 1.0, 1.0) / (d * d);
    assert!((centre - want).abs() / want < 0.01, "centre radiance {centre}, expected {want}");
}

#[test]
fn a_lamp_put_down_with_lamp_keeps_the_radiometry() {
    let dir = scratch("lamp");
    let (d, rho) = (3.0f32, 0.6f32);
    let gltf = dir.join("plane.gltf");
    write_plane_gltf(&gltf, -d, rho);
    let exr = dir.join("direct.exr");
    // Negative coordinates need no '=': the value starts with '-'.
    let lamp_x = -0.5f32;
    let out = headlamp(&[
        "render",
        "--level",
        gltf.to_str().unwrap(),
        "--out",
        exr.to_str().unwrap(),
        "--size",
        "64x64",
        "--view",
        "direct",
        "--camera",
        "0,0,0:0,0,-1",
        "--lamp",
        "-0.5,0,0:-0.5,0,-1",
        "--fov",
        "50",
    ]);
    assert_ok(&out);
    let img = image::open(&exr).unwrap().into_rgb32f();
    let centre: f32 =
        [(31, 31), (32, 31), (31, 32), (32, 32)].iter().map(|&(x, y)| img.get_pixel(x, y)[0]).sum::<f32>() / 4.0;
    // The centre sees (0, 0, -d); the lamp is off to the side: f · cos / r², f for the lamp's
    // direction l and the eye's v = +Z.
    let r2 = lamp_x * lamp_x + d * d;
    let l = Vec3::new(lamp_x, 0.0, d) / r2.sqrt();
    let h = (l + Vec3::Z).normalize();
    let want = rough_dielectric(rho, l.z, 1.0, h.z) * l.z / r2;
    assert!((centre - want).abs() / want < 0.01, "centre radiance {centre}, expected {want}");
}

#[test]
fn renders_the_conformance_boxes_and_cameras_in_view_and_lit() {
    let dir = scratch("conformance");
    // The box has no camera (the view frames it); the cameras sample is seen from its first.
    for file in ["red_box.gltf", "cameras.gltf"] {
        let png = dir.join(file.replace(".gltf", ".png"));
        let img = render_png(&sample(&dir, file), &png);
        let lit = img.pixels().filter(|p| p[0] > 10 || p[1] > 10 || p[2] > 10).count();
        assert!(lit > 96 * 96 / 20, "{file}: only {lit} lit pixels — the model is not in view or unlit");
    }
}

#[test]
fn a_textured_quad_seen_from_its_camera_is_upright() {
    let dir = scratch("texcoords");
    let img = render_png(&sample(&dir, "texture_coordinates.gltf"), &dir.join("texcoords.png"));
    // The quad fills the middle half of the frame (pixels 24 to 72 each way); the mean of an
    // 8×8 block at the middle of each quarter of it.
    let block = |cx: u32, cy: u32| {
        let mut sum = [0u32; 3];
        for y in cy - 4..cy + 4 {
            for x in cx - 4..cx + 4 {
                for (s, v) in sum.iter_mut().zip(img.get_pixel(x, y).0) {
                    *s += u32::from(v);
                }
            }
        }
        sum.map(|s| s / 64)
    };
    // The image's top-left is red, top-right green, bottom-left blue, bottom-right white.
    let dominant = |[r, g, b]: [u32; 3], channel: usize| {
        let c = [r, g, b][channel];
        c > 20 && (0..3).filter(|&k| k != channel).all(|k| c > 3 * [r, g, b][k])
    };
    let (top_left, top_right, bottom_left, bottom_right) = (block(36, 36), block(60, 36), block(36, 60), block(60, 60));
    assert!(dominant(top_left, 0), "top-left {top_left:?} is not red");
    assert!(dominant(top_right, 1), "top-right {top_right:?} is not green");
    assert!(dominant(bottom_left, 2), "bottom-left {bottom_left:?} is not blue");
    let [r, g, b] = bottom_right;
    assert!(
        r.min(g).min(b) > 20 && r.max(g).max(b) < 2 * r.min(g).min(b),
        "bottom-right {bottom_right:?} is not white"
    );
}

#[test]
fn renders_an_obj_and_every_view() {
    let dir = scratch("obj");
    let obj = dir.join("tri.obj");
    std::fs::write(&obj, "v -1 -1 -3\nv 1 -1 -3\nv 0 1 -3\nf 1 2 3\n").unwrap();
    for view in ["final", "direct", "albedo", "normal", "depth"] {
        let png = dir.join(format!("{view}.png"));
        let out = headlamp(&[
            "render",
            "--level",
            obj.to_str().unwrap(),
            "--out",
            png.to_str().unwrap(),
            "--size",
            "48x48",
            "--view",
            view,
        ]);
        assert_ok(&out);
        let img = image::open(&png).unwrap().into_rgba8();
        assert!(img.pixels().any(|p| p[0] > 0), "view {view} is black");
    }
}

/// Exits non-zero with exactly one line on stderr containing every `needles`, and no panic.
fn assert_one_line_error(args: &[&str], needles: &[&str]) {
    let out = headlamp(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} should fail");
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{args:?} should print one line, got:\n{stderr}");
    for n in needles {
        assert!(stderr.contains(n), "{args:?}: '{n}' missing from: {stderr}");
    }
}

#[test]
fn bad_input_gives_one_clear_line() {
    let dir = scratch("bad");
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    assert_one_line_error(
        &["render", "--level", "/nonexistent/level.gltf", "--out", out],
        &["/nonexistent/level.gltf"],
    );
    let corrupt = dir.join("corrupt.gltf");
    std::fs::write(&corrupt, "{ this is not json").unwrap();
    assert_one_line_error(&["render", "--level", corrupt.to_str().unwrap(), "--out", out], &["corrupt.gltf"]);
    let unknown = dir.join("scene.xyz");
    std::fs::write(&unknown, "hello").unwrap();
    assert_one_line_error(&["render", "--level", unknown.to_str().unwrap(), "--out", out], &["scene.xyz"]);
    let red_box = sample(&dir, "red_box.gltf");
    let good = red_box.to_str().unwrap();
    assert_one_line_error(&["render", "--level", good, "--out", out, "--size", "big"], &["big"]);
    assert_one_line_error(&["render", "--level", good, "--out", out, "--camera", "1,2:3"], &["1,2:3"]);
    assert_one_line_error(
        &["render", "--level", good, "--out", out, "--lamp", "1,2,x:3,4,5"],
        &["--lamp", "1,2,x:3,4,5"],
    );
    assert_one_line_error(
        &["render", "--level", good, "--out", out, "--lamp", "1,1,1:1,1,1"],
        &["--lamp", "same point"],
    );
    assert_one_line_error(&["render", "--level", good, "--out", "x.bmp"], &["x.bmp"]);
    assert_one_line_error(&["render", "--level", good, "--out", out, "--view", "sideways"], &["sideways"]);
    assert_one_line_error(&["render", "--level", good, "--out", out, "--bogus"], &["--bogus"]);
    assert_one_line_error(&["render", "--level", good, "--out", "/nonexistent-dir/x.png"], &["/nonexistent-dir/x.png"]);
}

/// A Cornell box (open towards +Z) as OBJ + MTL, written the way a modelling tool would.
fn write_cornell_obj(dir: &Path) -> PathBuf {
    std::fs::write(
        dir.join("box.mtl"),
        "newmtl white\nKd 0.75 0.75 0.75\nnewmtl red\nKd 0.75 0.1 0.1\nnewmtl green\nKd 0.1 0.7 0.1\n",
    )
    .unwrap();
    let obj = "mtllib box.mtl\n\
        v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\n\
        v -1 2 1\nv 1 2 1\nv 1 2 -1\nv -1 2 -1\n\
        v 0.1 0 0\nv 0.6 0 0\nv 0.6 0.6 0\nv 0.1 0.6 0\nv 0.1 0.6 -0.5\nv 0.6 0.6 -0.5\n\
        usemtl white\nf 1 2 3 4\nf 8 7 6 5\nf 4 3 7 8\nf 9 10 11 12\nf 12 11 14 13\n\
        usemtl red\nf 1 4 8 5\n\
        usemtl green\nf 3 2 6 7\n";
    let path = dir.join("cornell.obj");
    std::fs::write(&path, obj).unwrap();
    path
}

fn render_exr(level: &Path, out: &Path, view: &str, extra: &[&str]) -> image::Rgb32FImage {
    let mut args = vec!["render", "--level", level.to_str().unwrap(), "--out", out.to_str().unwrap()];
    args.extend(["--size", "96x72", "--view", view, "--camera", "0,1,3.4:0,1,0", "--fov", "50"]);
    args.extend(extra);
    let out_status = headlamp(&args);
    assert_ok(&out_status);
    image::open(out).unwrap().into_rgb32f()
}

#[test]
fn indirect_exr_of_an_unseen_obj_cornell_box_matches_the_brute_force_reference() {
    let dir = scratch("cornell");
    let obj = write_cornell_obj(&dir);
    let indirect = render_exr(&obj, &dir.join("indirect.exr"), "indirect", &[]);
    // The world-fixed reference (CPU) and the GPU's over the lamp view's texels: the same bounce.
    let reference = render_exr(&obj, &dir.join("reference.exr"), "reference", &[]);
    let screen = render_exr(&obj, &dir.join("reference_screen.exr"), "reference_screen", &[]);
    let total: f64 = reference.pixels().map(|p| p[0] as f64).sum();
    assert!(total > 0.0, "the reference must see indirect light");
    let rgba = |img: &image::Rgb32FImage| image::DynamicImage::ImageRgb32F(img.clone()).into_rgba32f();
    let error = plugin_gi::metrics::block_error(&rgba(&indirect), &rgba(&reference));
    assert!(error <= 0.10, "indirect differs from the brute-force reference by {error:.3}");
    let screen_error = plugin_gi::metrics::block_error(&rgba(&screen), &rgba(&reference));
    assert!(screen_error <= 0.05, "the two references differ by {screen_error:.3}");
    // With visibility the block shades the floor behind it and the walls beside it: no pixel
    // gains light, some lose it (the box's own corners see nothing in the way).
    let visible = render_exr(&obj, &dir.join("reference_vis.exr"), "reference_vis", &[]);
    let mut lost = 0;
    for (v, r) in visible.pixels().zip(reference.pixels()) {
        for c in 0..3 {
            assert!(v[c] <= r[c] * (1.0 + 1e-4) + 1e-9, "visibility added light: {} > {}", v[c], r[c]);
        }
        lost += usize::from(v[0] < r[0] * 0.99);
    }
    let (seen, all): (f64, f64) =
        (visible.pixels().map(|p| p[0] as f64).sum(), reference.pixels().map(|p| p[0] as f64).sum());
    println!(
        "reference_vis: {lost} pixels lose more than 1 %; {:.1} % of the bounce hidden",
        100.0 * (1.0 - seen / all)
    );
    assert!(lost > 100 && seen < 0.99 * all, "the block hides nothing: {lost} pixels, {seen} of {all}");
    // A PNG of it is the tonemapped picture.
    let png = dir.join("reference.png");
    let out = headlamp(&[
        "render",
        "--level",
        obj.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
        "--size",
        "48x36",
        "--view",
        "reference",
        "--patch-size",
        "0.05",
    ]);
    assert_ok(&out);
    let picture = image::open(&png).unwrap().into_rgba8();
    assert_eq!(picture.dimensions(), (48, 36));
    assert!(picture.pixels().any(|p| p[0] > 0), "some of it is lit");
}

#[test]
fn gi_flags_switch_and_tune_the_indirect_light() {
    let dir = scratch("giflags");
    let obj = write_cornell_obj(&dir);
    let direct = render_exr(&obj, &dir.join("direct.exr"), "direct", &[]);
    let off = render_exr(&obj, &dir.join("off.exr"), "final", &["--gi", "off"]);
    let on = render_exr(&obj, &dir.join("on.exr"), "final", &["--set", "gi.split_ratio=0.3", "--set", "gi.bounces=2"]);
    let sum = |img: &image::Rgb32FImage| img.pixels().map(|p| p[0] as f64 + p[1] as f64 + p[2] as f64).sum::<f64>();
    assert!((sum(&off) - sum(&direct)).abs() <= 1e-6 * sum(&direct), "--gi off leaves the direct light alone");
    assert!(sum(&on) > 1.05 * sum(&off), "the GI adds light: on {} off {}", sum(&on), sum(&off));
}

#[test]
fn bad_gi_flags_give_one_clear_line() {
    let dir = scratch("badgi");
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    let red_box = sample(&dir, "red_box.gltf");
    let good = red_box.to_str().unwrap();
    assert_one_line_error(
        &["render", "--level", good, "--out", out, "--set", "gi.split_ratio=lots"],
        &["gi.split_ratio", "lots"],
    );
    assert_one_line_error(
        &["render", "--level", good, "--out", out, "--set", "gi.bounces=9"],
        &["gi.bounces", "out of range"],
    );
    assert_one_line_error(&["render", "--level", good, "--out", out, "--set", "gi.colour=1"], &["gi.colour"]);
    assert_one_line_error(&["render", "--level", good, "--out", out, "--set", "budget=1"], &["budget"]);
    assert_one_line_error(&["render", "--level", good, "--out", out, "--gi", "maybe"], &["maybe"]);
}
