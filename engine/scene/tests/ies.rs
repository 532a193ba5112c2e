//! IESNA LM-63 headlamp profiles: the parser, LM-63's symmetry rules, the lamp-frame mapping,
//! the normalised texture over the frustum, and every kind of bad file named in one error.

mod common;

use std::path::Path;

use common::*;
use glam::Vec3;
use scene::{ies_texture_size, load_level, IesProfile, IntensityDistribution, LoadError, LoadErrorKind};

/// An LM-63 file: `header` (identification and keyword lines), then `tilt` (the TILT line and
/// any tilt block), the two lines of numbers, the angles and one line of candela values per
/// horizontal angle.
fn lm63(header: &str, tilt: &str, multiplier: f32, vertical: &[f32], horizontal: &[f32], rows: &[&[f32]]) -> String {
    let list = |v: &[f32]| v.iter().map(|a| a.to_string()).collect::<Vec<_>>().join(" ");
    let mut s = format!(
        "{header}\n{tilt}\n1 -1 {multiplier} {} {} 1 2 0.1 0.1 0.05\n1.0 1.0 25\n{}\n{}\n",
        vertical.len(),
        horizontal.len(),
        list(vertical),
        list(horizontal)
    );
    for row in rows {
        s.push_str(&list(row));
        s.push('\n');
    }
    s
}

const HEADER_2002: &str = "IESNA:LM-63-2002\n[TEST] hand-written\n[MANUFAC] Headlamp tests\n[LUMCAT] X-1";
const HEADER_1995: &str = "IESNA:LM-63-1995\n[TEST] hand-written\n[LAMP] one";

const V: [f32; 5] = [0.0, 10.0, 20.0, 40.0, 90.0];
const H: [f32; 5] = [0.0, 90.0, 180.0, 270.0, 360.0];
/// One row per horizontal angle of `H` (the last repeats the first, as LM-63 asks).
const ROWS: [&[f32]; 5] = [
    &[1000.0, 800.0, 400.0, 0.0, 0.0],
    &[1000.0, 600.0, 250.0, 50.0, 0.0],
    &[1000.0, 700.0, 300.0, 20.0, 0.0],
    &[1000.0, 500.0, 100.0, 10.0, 0.0],
    &[1000.0, 800.0, 400.0, 0.0, 0.0],
];

fn full() -> String {
    lm63(HEADER_2002, "TILT=NONE", 1.0, &V, &H, &ROWS)
}

fn parse(text: &str) -> Result<IesProfile, LoadError> {
    IesProfile::parse(text.as_bytes(), Path::new("levels/x/lamp.ies"))
}

fn close(got: f32, want: f32, what: &str) {
    assert!((got - want).abs() <= 1e-3 * want.abs().max(1.0), "{what}: got {got}, expected {want}");
}

/// The lamp-frame direction at vertical angle `gamma` and horizontal angle `c`, degrees.
fn dir(gamma: f32, c: f32) -> Vec3 {
    let (g, c) = (gamma.to_radians(), c.to_radians());
    Vec3::new(g.sin() * c.cos(), g.sin() * c.sin(), -g.cos())
}

#[test]
fn reads_the_table_and_interpolates_bilinearly() {
    let p = parse(&full()).unwrap();
    assert_eq!(p.vertical_angles(), &V);
    assert_eq!(p.horizontal_angles(), &H);
    assert_eq!(p.max_candela(), 1000.0);
    close(p.candela(0.0, 0.0), 1000.0, "on the axis");
    close(p.candela(20.0, 90.0), 250.0, "a node");
    close(p.candela(15.0, 0.0), 600.0, "halfway between 10° and 20° at C = 0");
    close(p.candela(20.0, 45.0), 325.0, "halfway between C = 0 and C = 90 at 20°");
    close(p.candela(15.0, 45.0), 0.5 * (600.0 + 425.0), "bilinear in (γ, C)");
    close(p.candela(30.0, 270.0), 55.0, "between 20° and 40° at C = 270");
    close(p.candela(20.0, 315.0), 250.0, "between C = 270 and C = 360 (= C = 0)");
    close(p.candela(20.0, -45.0), 250.0, "a negative C turns the other way");
    close(p.candela(95.0, 0.0), 0.0, "beyond the last vertical angle");
}

#[test]
fn the_axis_is_minus_z_and_c_turns_from_plus_x_to_plus_y() {
    let p = parse(&full()).unwrap();
    close(p.candela_towards(Vec3::NEG_Z), 1000.0, "axis");
    close(p.candela_towards(dir(20.0, 0.0)), 400.0, "C = 0");
    for (c, want, side) in
        [(0.0, 400.0, Vec3::X), (90.0, 250.0, Vec3::Y), (180.0, 300.0, -Vec3::X), (270.0, 100.0, -Vec3::Y)]
    {
        // 20° off the axis towards `side`.
        let d = Vec3::NEG_Z * 20f32.to_radians().cos() + side * 20f32.to_radians().sin();
        close(p.candela_towards(d), want, &format!("C = {c}"));
    }
    close(p.candela_towards(Vec3::Z), 0.0, "behind the lamp");
}

#[test]
fn symmetry_rules_fill_the_whole_turn() {
    let rows: [&[f32]; 3] = [&[100.0, 50.0, 0.0], &[100.0, 30.0, 0.0], &[100.0, 10.0, 0.0]];
    let v = [0.0, 45.0, 90.0];
    // One horizontal angle: the same in every plane.
    let p = parse(&lm63(HEADER_2002, "TILT=NONE", 1.0, &v, &[0.0], &rows[..1])).unwrap();
    for c in [0.0, 77.0, 180.0, 300.0] {
        close(p.candela(45.0, c), 50.0, &format!("rotational, C = {c}"));
    }
    // 0..90: mirrored about the 0-180 and 90-270 planes.
    let p = parse(&lm63(HEADER_2002, "TILT=NONE", 1.0, &v, &[0.0, 45.0, 90.0], &rows)).unwrap();
    for (c, want) in [(45.0, 30.0), (135.0, 30.0), (180.0, 50.0), (225.0, 30.0), (270.0, 10.0), (315.0, 30.0)] {
        close(p.candela(45.0, c), want, &format!("quadrant, C = {c}"));
    }
    close(p.candela(45.0, 120.0), p.candela(45.0, 60.0), "quadrant, 120 mirrors 60");
    // 0..180: mirrored about the 0-180 plane.
    let p = parse(&lm63(HEADER_2002, "TILT=NONE", 1.0, &v, &[0.0, 90.0, 180.0], &rows)).unwrap();
    for (c, want) in [(90.0, 30.0), (180.0, 10.0), (270.0, 30.0), (225.0, 20.0)] {
        close(p.candela(45.0, c), want, &format!("half, C = {c}"));
    }
    // 90..270: mirrored about the 90-270 plane.
    let p = parse(&lm63(HEADER_2002, "TILT=NONE", 1.0, &v, &[90.0, 180.0, 270.0], &rows)).unwrap();
    for (c, want) in [(90.0, 50.0), (0.0, 30.0), (45.0, 40.0), (315.0, 20.0), (270.0, 10.0)] {
        close(p.candela(45.0, c), want, &format!("90-270 half, C = {c}"));
    }
}

#[test]
fn vertical_ranges_0_to_90_and_90_to_180() {
    let rows: [&[f32]; 1] = [&[100.0, 50.0, 20.0]];
    let p = parse(&lm63(HEADER_2002, "TILT=NONE", 1.0, &[0.0, 45.0, 90.0], &[0.0], &rows)).unwrap();
    close(p.candela(90.0, 0.0), 20.0, "down-light, 90°");
    close(p.candela(120.0, 0.0), 0.0, "down-light, nothing above the horizontal");
    let p = parse(&lm63(HEADER_2002, "TILT=NONE", 1.0, &[90.0, 135.0, 180.0], &[0.0], &rows)).unwrap();
    close(p.candela(30.0, 0.0), 0.0, "up-light, nothing below the horizontal");
    close(p.candela(180.0, 0.0), 20.0, "up-light, zenith");
    let p = parse(&lm63(HEADER_2002, "TILT=NONE", 1.0, &[0.0, 90.0, 180.0], &[0.0], &rows)).unwrap();
    close(p.candela(135.0, 0.0), 35.0, "0..180");
}

#[test]
fn versions_tilt_include_multiplier_and_layout_do_not_change_the_shape() {
    let base = parse(&full()).unwrap();
    let tilt = "TILT=INCLUDE\n1\n7\n0 15 30 45 60 75 90\n1.0 .95 .94 .90 .88 .87 .94";
    let variants = [
        lm63(HEADER_1995, "TILT=NONE", 1.0, &V, &H, &ROWS),
        lm63(HEADER_1995, tilt, 1.0, &V, &H, &ROWS),
        lm63(HEADER_2002, tilt, 1.0, &V, &H, &ROWS),
        // No identification line (LM-63-1986), lower case keyword.
        lm63("[TEST] old", "tilt = none", 1.0, &V, &H, &ROWS),
        // CRLF line endings and values wrapped over several lines, as tools write them.
        full().replace(" 800 400", "\r\n800\r\n400").replace('\n', "\r\n"),
    ];
    for (i, text) in variants.iter().enumerate() {
        let p = parse(text).unwrap_or_else(|e| panic!("variant {i}: {e}"));
        assert_eq!(p, base, "variant {i}");
    }
    // The multiplier scales every value alike; the normalised texture does not change.
    let scaled = parse(&lm63(HEADER_2002, "TILT=NONE", 2.5, &V, &H, &ROWS)).unwrap();
    assert_eq!(scaled.distribution(0.8, 1.0, 16, 16), base.distribution(0.8, 1.0, 16, 16));
}

#[test]
fn the_texture_is_normalised_and_laid_over_the_frustum_top_row_first() {
    let p = parse(&full()).unwrap();
    let (fov_y, aspect, w, h) = (60f32.to_radians(), 1.5, 48u32, 32u32);
    let img = p.distribution(fov_y, aspect, w, h);
    assert_eq!((img.width, img.height, img.values.len()), (w, h, (w * h) as usize));
    let (tan_y, tan_x) = ((fov_y * 0.5).tan(), (fov_y * 0.5).tan() * aspect);
    for y in 0..h {
        for x in 0..w {
            let ndc = ((x as f32 + 0.5) / w as f32 * 2.0 - 1.0, 1.0 - (y as f32 + 0.5) / h as f32 * 2.0);
            let want = p.candela_towards(Vec3::new(ndc.0 * tan_x, ndc.1 * tan_y, -1.0)) / 1000.0;
            let v = img.values[(y * w + x) as usize];
            assert!(v[0] == v[1] && v[1] == v[2], "grey");
            close(v[0], want, &format!("texel ({x}, {y})"));
        }
    }
    // The texels nearest the axis are 1.4° off it, where the table is already below its peak.
    let max = img.values.iter().map(|v| v[0]).fold(0.0, f32::max);
    assert!(max <= 1.0 && max > 0.95, "the brightest texel is near the peak, 1 (got {max})");
    // Rows a quarter from the top and bottom look 15° up (C = 90, 421 cd) and down (C = 270,
    // 296 cd); columns a quarter from the right and left 24° right (C = 0, 316 cd) and left
    // (C = 180, 241 cd).
    let texel = |x: u32, y: u32| img.values[(y * w + x) as usize][0];
    let (top, bottom) = (texel(w / 2, h / 4), texel(w / 2, h - 1 - h / 4));
    let (right, left) = (texel(w - 1 - w / 4, h / 2), texel(w / 4, h / 2));
    assert!(top > bottom, "top row is +Y: {top} vs {bottom}");
    assert!(right > left, "right column is +X (C = 0): {right} vs {left}");
}

/// Bilinear sampling with clamp-to-edge at uv, as the GPU's linear sampler does.
fn sample(img: &scene::DistributionImage, u: f32, v: f32) -> f32 {
    let (w, h) = (img.width as i32, img.height as i32);
    let (x, y) = (u * w as f32 - 0.5, v * h as f32 - 0.5);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let at = |i: i32, j: i32| img.values[(j.clamp(0, h - 1) * w + i.clamp(0, w - 1)) as usize][0];
    let (i, j) = (x0 as i32, y0 as i32);
    let top = at(i, j) * (1.0 - fx) + at(i + 1, j) * fx;
    let bottom = at(i, j + 1) * (1.0 - fx) + at(i + 1, j + 1) * fx;
    top * (1.0 - fy) + bottom * fy
}

#[test]
fn the_sampled_texture_is_within_two_percent_of_the_table() {
    // A steep, kinked table: 1000 cd to 250 cd over 20°, 0 at 40°, different in each azimuth.
    let v = [0.0, 5.0, 10.0, 20.0, 30.0, 40.0, 90.0];
    let hz = [0.0, 45.0, 90.0, 135.0, 180.0];
    let rows: [&[f32]; 5] = [
        &[1000.0, 900.0, 700.0, 250.0, 120.0, 0.0, 0.0],
        &[1000.0, 850.0, 600.0, 300.0, 100.0, 0.0, 0.0],
        &[1000.0, 950.0, 800.0, 400.0, 150.0, 0.0, 0.0],
        &[1000.0, 800.0, 500.0, 200.0, 80.0, 0.0, 0.0],
        &[1000.0, 900.0, 750.0, 350.0, 60.0, 0.0, 0.0],
    ];
    let p = parse(&lm63(HEADER_2002, "TILT=NONE", 1.0, &v, &hz, &rows)).unwrap();
    for fov_deg in [40.0f32, 60.0, 90.0, 120.0] {
        let fov_y = fov_deg.to_radians();
        let size = ies_texture_size(fov_y);
        let img = p.distribution(fov_y, 1.0, size, size);
        let tan = (fov_y * 0.5).tan();
        let (mut worst_abs, mut worst_rel) = (0.0f32, 0.0f32);
        // Directions on a grid finer than the texels and offset from them.
        let n = 301;
        for j in 0..n {
            for i in 0..n {
                let (u, vv) = ((i as f32 + 0.37) / n as f32, (j as f32 + 0.61) / n as f32);
                let d = Vec3::new((u * 2.0 - 1.0) * tan, (1.0 - vv * 2.0) * tan, -1.0);
                let exact = p.candela_towards(d) / 1000.0;
                let err = (sample(&img, u, vv) - exact).abs();
                worst_abs = worst_abs.max(err);
                if exact >= 0.1 {
                    worst_rel = worst_rel.max(err / exact);
                }
            }
        }
        println!(
            "fov {fov_deg}°: {size}² texels, worst error {worst_abs:.4} of the peak, {:.2} % where T ≥ 0.1",
            worst_rel * 100.0
        );
        assert!(worst_abs <= 0.02 && worst_rel <= 0.02, "fov {fov_deg}°: abs {worst_abs}, rel {worst_rel}");
    }
}

fn write_level(dir: &TempDir, headlamp: &str) {
    dir.write("scene.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    dir.write("level.toml", format!("name = \"I\"\nscene = \"scene.obj\"\n[headlamp]\n{headlamp}\n"));
}

#[test]
fn a_level_reads_an_ies_profile_by_extension_in_any_case() {
    let dir = TempDir::new("ies-level");
    write_level(&dir, "power = 3.0\nfov_deg = 50.0\nprofile = \"photometry/Lamp.IES\"");
    dir.write("photometry/Lamp.IES", full());
    let level = load_level(dir.path()).unwrap();
    assert_eq!(level.headlamp.power, 3.0, "power is the W/sr of the brightest direction, as written");
    let IntensityDistribution::Photometric(ies) = &level.headlamp.distribution else { panic!("expected a table") };
    assert_eq!(*ies, parse(&full()).unwrap());
    let size = ies_texture_size(50f32.to_radians());
    let img = ies.distribution(50f32.to_radians(), 1.0, size, size);
    // An odd size puts a texel centre on the axis, where this table peaks: the texture's max is 1.
    assert_eq!(size % 2, 1);
    assert_eq!(img.values[(size / 2 * size + size / 2) as usize][0], 1.0);
    assert_eq!(img.values.iter().map(|v| v[0]).fold(0.0, f32::max), 1.0);

    // The profile is part of the content hash.
    let before = level.content_hash;
    dir.write("photometry/Lamp.IES", full().replace("1000 800 400 0 0", "1000 800 401 0 0"));
    assert_ne!(load_level(dir.path()).unwrap().content_hash, before);

    // It must stay in the level folder like any other file.
    let outside = TempDir::new("ies-outside");
    outside.write("lamp.ies", full());
    write_level(&dir, &format!("profile = \"../{}/lamp.ies\"", outside.path().file_name().unwrap().to_string_lossy()));
    let e = load_level(dir.path()).unwrap_err();
    assert!(matches!(e.kind, LoadErrorKind::EscapesFolder(_)), "{e}");
}

#[test]
fn a_bad_ies_file_in_a_level_is_one_error_naming_it() {
    let dir = TempDir::new("ies-bad-level");
    write_level(&dir, "profile = \"lamp.ies\"");
    let path = dir.write("lamp.ies", full().replace("800 400 0 0", "800 oops 0 0"));
    let e = load_level(dir.path()).unwrap_err();
    assert_eq!(e.path, path);
    let msg = e.to_string();
    assert!(msg.starts_with(&path.display().to_string()) && msg.contains("oops"), "{msg}");
    assert_eq!(e.at.map(|p| p.line), Some(10), "{msg}");
    assert!(!msg.contains('\n'), "one line: {msg}");
}

/// Parses `text`, expecting an error whose message contains every one of `words`, on `line`.
fn refused(text: &str, words: &[&str], line: Option<usize>) -> LoadError {
    let e = parse(text).expect_err("a bad file must be refused");
    let msg = e.to_string();
    assert_eq!(e.path, Path::new("levels/x/lamp.ies"), "{msg}");
    assert!(msg.starts_with("levels/x/lamp.ies"), "names the file first: {msg}");
    for w in words {
        assert!(msg.contains(w), "`{w}` missing from: {msg}");
    }
    if line.is_some() {
        assert_eq!(e.at.map(|p| p.line), line, "{msg}");
    }
    assert!(!msg.contains('\n'), "one line: {msg}");
    e
}

#[test]
fn bad_files_are_refused_with_the_file_and_the_line() {
    let f = full();
    // Line 5 is TILT, 6 and 7 the numbers, 8 vertical, 9 horizontal angles, 10.. candela.
    refused(&f[..f.len() - 12], &["file ends", "candela"], None);
    refused("", &["TILT"], None);
    refused("\u{89}PNG\r\n\u{1a}\n binary", &["TILT"], None);
    refused(&f.replace("1000 600 250", "1000 six 250"), &["`six`", "candela"], Some(11));
    refused(&f.replace("1000 600 250", "1000 NaN 250"), &["`NaN`"], Some(11));
    refused(&f.replace("1000 600 250", "1000 inf 250"), &["`inf`"], Some(11));
    refused(&f.replace("1000 600 250", "1000 -600 250"), &["negative"], Some(11));
    refused(&f.replace("TILT=NONE", "TILT=lamp.tlt"), &["TILT=lamp.tlt", "not supported"], Some(5));
    refused(&f.replace("1 -1 1 5 5 1 2", "1 -1 1 5 5 2 2"), &["type B", "not supported", "type C"], Some(6));
    refused(&f.replace("1 -1 1 5 5 1 2", "1 -1 1 5 5 3 2"), &["type A", "not supported"], Some(6));
    refused(&f.replace("1 -1 1 5 5 1 2", "1 -1 1 5 5 7 2"), &["photometric type 7"], Some(6));
    refused(&f.replace("1 -1 1 5 5", "1 -1 0 5 5"), &["multiplier"], Some(6));
    refused(&f.replace("1 -1 1 5 5", "1 -1 1 5.5 5"), &["vertical angles", "whole number"], Some(6));
    // Wrong counts: the numbers no longer line up and the angles stop making sense.
    refused(&f.replace("1 -1 1 5 5", "1 -1 1 6 5"), &["vertical angles must increase"], Some(9));
    refused(&f.replace("1 -1 1 5 5", "1 -1 1 4 5"), &["vertical angles must run", "0 to 40"], Some(8));
    refused(&f.replace("0 90 180 270 360", "0 45 90 135 160"), &["horizontal angles must be", "0 to 160"], Some(9));
    refused(&f.replace("0 10 20 40 90", "0 20 10 40 90"), &["must increase", "20 then 10"], Some(8));
    refused(&lm63(HEADER_2002, "TILT=NONE", 1.0, &[0.0, 90.0], &[0.0], &[&[0.0, 0.0]]), &["no light"], None);
    refused(&format!("{HEADER_2002}\nTILT=INCLUDE\n1\n3\n0 45\n"), &["file ends", "tilt angle"], None);
}

#[test]
fn absurd_counts_are_refused_before_anything_is_allocated() {
    let f = full();
    let e = refused(&f.replace("1 -1 1 5 5", "1 -1 1 1000000000 5"), &["vertical angles", "1000000000"], Some(6));
    assert!(matches!(e.kind, LoadErrorKind::TooLarge(_)), "{e}");
    let e = refused(&f.replace("1 -1 1 5 5", "1 -1 1 4000 4000"), &["4000 × 4000"], None);
    assert!(matches!(e.kind, LoadErrorKind::TooLarge(_)), "{e}");
    refused(&lm63(HEADER_2002, "TILT=INCLUDE\n1\n1e9", 1.0, &V, &H, &ROWS), &["tilt angles"], None);
    // A large count with a short file ends in "file ends".
    refused(&format!("{HEADER_2002}\nTILT=NONE\n1 -1 1 2000 1 1 2 0 0 0\n1 1 0\n0 1 2\n"), &["file ends"], None);
}

#[test]
fn a_too_large_ies_file_is_refused_unread() {
    let dir = TempDir::new("ies-huge");
    write_level(&dir, "profile = \"lamp.ies\"");
    let path = dir.write("lamp.ies", "");
    std::fs::File::options().write(true).open(&path).unwrap().set_len(scene::MAX_IES_BYTES + 1).unwrap();
    let e = load_level(dir.path()).unwrap_err();
    assert_eq!(e.path, path);
    assert!(matches!(e.kind, LoadErrorKind::TooLarge(_)), "{e}");
}

#[test]
fn an_up_light_loads_with_a_warning_that_the_frustum_gets_nothing() {
    let dir = TempDir::new("ies-up");
    write_level(&dir, "profile = \"up.ies\"");
    let rows: [&[f32]; 1] = [&[100.0, 50.0, 20.0]];
    let path = dir.write("up.ies", lm63(HEADER_2002, "TILT=NONE", 1.0, &[90.0, 135.0, 180.0], &[0.0], &rows));
    let level = load_level(dir.path()).unwrap();
    let IntensityDistribution::Photometric(ies) = &level.headlamp.distribution else { panic!("expected a table") };
    let size = ies_texture_size(level.headlamp.fov_y);
    assert!(ies.distribution(level.headlamp.fov_y, 1.0, size, size).values.iter().all(|v| v[0] == 0.0));
    assert!(
        level.warnings.iter().any(|w| w.path == path && w.message.contains("no light inside the lamp frustum")),
        "{:?}",
        level.warnings
    );
}
