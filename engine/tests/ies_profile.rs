//! A level whose headlamp is an IES (LM-63) file lights a facing plane as the candela table
//! says: L = ρ/π · P · (I_table(ω) / I_max) · cosθ / d², read back as linear `direct` radiance,
//! with the lamp attached (its frustum the camera's) and put down at the eye (its own square
//! frustum of fov_deg).

use std::f32::consts::PI;
use std::path::PathBuf;

use engine::frame::ViewState;
use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::scene::{load_level, IntensityDistribution, Level};
use engine::start_view::{initial_view, ViewOverrides};

/// Odd, so one pixel centre lies on the axis.
const SIZE: u32 = 193;
const FOV_DEG: f32 = 80.0;
const POWER: f32 = 2.0;
const RHO: f32 = 0.5;
/// Distance from the eye (and lamp) to the plane.
const D: f32 = 2.0;

/// The candela table: vertical angles γ from the axis, and one column per horizontal angle C
/// (0 right, 90 up, 180 left, 270 down; 360 repeats 0). 1000 cd on the axis, 0 at 40°, and a
/// different value at 20° in each azimuth so that a turned or mirrored mapping shows.
const V: [f32; 4] = [0.0, 20.0, 40.0, 90.0];
const H: [f32; 5] = [0.0, 90.0, 180.0, 270.0, 360.0];
const COLUMNS: [[f32; 4]; 5] = [
    [1000.0, 250.0, 0.0, 0.0],
    [1000.0, 400.0, 0.0, 0.0],
    [1000.0, 300.0, 0.0, 0.0],
    [1000.0, 150.0, 0.0, 0.0],
    [1000.0, 250.0, 0.0, 0.0],
];
const MAX_CD: f32 = 1000.0;

fn ies_text() -> String {
    let list = |v: &[f32]| v.iter().map(|a| a.to_string()).collect::<Vec<_>>().join(" ");
    let mut s = String::from("IESNA:LM-63-2002\n[TEST] headlamp engine test\n[MANUFAC] none\nTILT=NONE\n");
    // Lumens and the multiplier are not used: only the shape is.
    s += &format!("1 4000 3.5 {} {} 1 2 0.1 0.1 0.05\n1 1 20\n", V.len(), H.len());
    s += &format!("{}\n{}\n", list(&V), list(&H));
    for c in &COLUMNS {
        s += &format!("{}\n", list(c));
    }
    s
}

/// The test's own reading of the table: bilinear in (γ, C), degrees.
fn table(gamma: f32, c: f32) -> f32 {
    let seg = |a: &[f32], x: f32| {
        let i = a.iter().rposition(|&v| v <= x).unwrap_or(0).min(a.len() - 2);
        (i, ((x - a[i]) / (a[i + 1] - a[i])).clamp(0.0, 1.0))
    };
    let (v, tv) = seg(&V, gamma);
    let (h, th) = seg(&H, c.rem_euclid(360.0));
    let col = |h: usize| COLUMNS[h][v] + (COLUMNS[h][v + 1] - COLUMNS[h][v]) * tv;
    col(h) + (col(h + 1) - col(h)) * th
}

/// A scratch level folder: the table, a 40 m plane at z = -D facing +Z, albedo RHO.
struct LevelDir(PathBuf);

impl LevelDir {
    fn new() -> Self {
        let dir = std::env::temp_dir().join(format!("headlamp-ies-profile-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let write = |name: &str, text: &str| std::fs::write(dir.join(name), text).unwrap();
        write(
            "level.toml",
            &format!(
                "name = \"IES\"\nscene = \"plane.obj\"\nexposure = 1.0\n\n[headlamp]\npower = {POWER}\n\
                 fov_deg = {FOV_DEG}\nprofile = \"beam.ies\"\n"
            ),
        );
        write("beam.ies", &ies_text());
        write(
            "plane.obj",
            &format!(
                "mtllib plane.mtl\nusemtl grey\nv -20 -20 {z}\nv 20 -20 {z}\nv 20 20 {z}\nv -20 20 {z}\nvn 0 0 1\n\
                 f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n",
                z = -D
            ),
        );
        write("plane.mtl", &format!("newmtl grey\nKd {RHO} {RHO} {RHO}\n"));
        Self(dir)
    }
}

impl Drop for LevelDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A rendered view: its size and vertical field of view, degrees (the camera's and, while
/// worn, the lamp's).
#[derive(Clone, Copy)]
struct Shot {
    width: u32,
    height: u32,
    fov_deg: f32,
}

impl Shot {
    fn tan_y(self) -> f32 {
        (self.fov_deg.to_radians() * 0.5).tan()
    }

    fn tan_x(self) -> f32 {
        self.tan_y() * self.width as f32 / self.height as f32
    }

    /// The ray through the centre of pixel (x, y) of the eye looking down -Z.
    fn pixel_dir(self, x: u32, y: u32) -> Vec3 {
        let ndc_x = (x as f32 + 0.5) / self.width as f32 * 2.0 - 1.0;
        let ndc_y = 1.0 - (y as f32 + 0.5) / self.height as f32 * 2.0;
        Vec3::new(ndc_x * self.tan_x(), ndc_y * self.tan_y(), -1.0).normalize()
    }

    /// The pixel whose ray is nearest vertical angle `gamma` and horizontal angle `c`
    /// (degrees); None outside the picture.
    fn pixel_towards(self, gamma: f32, c: f32) -> Option<(u32, u32)> {
        let (g, c) = (gamma.to_radians(), c.to_radians());
        let d = Vec3::new(g.sin() * c.cos(), g.sin() * c.sin(), -g.cos());
        let (ndc_x, ndc_y) = (d.x / -d.z / self.tan_x(), d.y / -d.z / self.tan_y());
        let x = ((ndc_x + 1.0) * 0.5 * self.width as f32 - 0.5).round();
        let y = ((1.0 - ndc_y) * 0.5 * self.height as f32 - 0.5).round();
        (x >= 0.0 && y >= 0.0 && x < self.width as f32 && y < self.height as f32).then_some((x as u32, y as u32))
    }

    /// Expected radiance at pixel (x, y): the plane point along its ray is lit from the eye,
    /// so the lamp direction is the ray, n·l = cosθ and the distance is D / cosθ.
    fn expected(self, x: u32, y: u32) -> (f32, f32, f32) {
        let d = self.pixel_dir(x, y);
        let cos = -d.z;
        let gamma = cos.clamp(-1.0, 1.0).acos().to_degrees();
        let c = d.y.atan2(d.x).to_degrees();
        let t = table(gamma, c) / MAX_CD;
        (RHO / PI * POWER * t * cos.powi(3) / (D * D), gamma, c)
    }
}

fn render(gpu: &Gpu, level: &Level, view: &ViewState, shot: Shot) -> image::Rgba32FImage {
    let mut renderer = Renderer::new(gpu, &level.scene, vec![]).unwrap();
    renderer.set_view("direct").unwrap();
    let target = HeadlessTarget::new(gpu, shot.width, shot.height, ImageKind::Linear);
    match target.render(gpu, &mut renderer, view).unwrap() {
        RenderedImage::Linear(img) => img,
        RenderedImage::Display(_) => unreachable!("asked for linear"),
    }
}

/// Checks every sample pixel of `img`; returns the worst relative error.
fn check(img: &image::Rgba32FImage, shot: Shot, setup: &str) -> f32 {
    let on_axis = shot.expected(shot.width / 2, shot.height / 2).0;
    let mut worst = 0.0f32;
    let mut failures = Vec::new();
    let mut targets = vec![(0.0, 0.0)];
    for gamma in [10.0, 20.0, 30.0] {
        for c in [0.0, 45.0, 90.0, 180.0, 270.0] {
            targets.push((gamma, c));
        }
    }
    for (gamma, c) in targets {
        let (x, y) =
            shot.pixel_towards(gamma, c).unwrap_or_else(|| panic!("{setup}: γ {gamma}° C {c}° is off the picture"));
        let (want, g, cc) = shot.expected(x, y);
        let got = img.get_pixel(x, y)[0];
        let rel = (got - want).abs() / want;
        worst = worst.max(rel);
        println!(
            "{setup}: γ {gamma:>4}° C {c:>5}° pixel ({x:>3}, {y:>3}) at γ {g:6.2}° C {cc:7.2}°: \
             got {got:.6}, want {want:.6}, error {:.2} %",
            rel * 100.0
        );
        // Written so that a NaN fails too.
        if rel.is_nan() || rel > 0.02 {
            failures.push(format!("γ {gamma}° C {c}°: got {got}, want {want} ({:.2} %)", rel * 100.0));
        }
    }
    // Beyond 40° the table gives nothing: checked wherever 45° off the axis is in the picture.
    let mut dark = 0;
    for c in [0.0, 45.0, 135.0, 180.0, 225.0, 315.0] {
        let Some((x, y)) = shot.pixel_towards(45.0, c) else { continue };
        dark += 1;
        let got = img.get_pixel(x, y)[0];
        if got.abs() > 1e-4 * on_axis {
            failures.push(format!("γ 45° C {c}°: got {got}, want 0"));
        }
    }
    assert!(dark >= 2, "{setup}: too few directions beyond the beam in the picture");
    assert!(failures.is_empty(), "{setup}: radiance off the IES table:\n{}", failures.join("\n"));
    worst
}

#[test]
fn a_facing_plane_is_lit_as_the_candela_table_says() {
    let dir = LevelDir::new();
    let level = load_level(&dir.0).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        matches!(level.headlamp.distribution, IntensityDistribution::Photometric(_)),
        "the .ies profile was not read"
    );
    assert_eq!(level.scene.materials.last().map(|m| m.base_color[0]), Some(RHO));
    // A missing adapter fails the test with the install advice (LAVAPIPE_HINT).
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));

    // Worn, the lamp's frustum is the camera's: a wide picture at another fov than fov_deg, so
    // the table must be laid over that frustum, not over the one fov_deg describes.
    let wide = Shot { width: 257, height: 145, fov_deg: 70.0 };
    let overrides = ViewOverrides { look: Some((Vec3::ZERO, Vec3::NEG_Z)), fov_y: Some(wide.fov_deg.to_radians()) };
    let mut view = initial_view(&level, &overrides);
    view.exposure = 1.0;
    assert!(view.headlamp.attached);
    let attached = check(&render(&gpu, &level, &view, wide), wide, "attached, 257x145 at 70°");

    // Put down at the eye, pointing the same way: its own frustum (fov_deg, square), shadow
    // map on, seen by a square camera of the same fov.
    let square = Shot { width: SIZE, height: SIZE, fov_deg: FOV_DEG };
    let overrides = ViewOverrides { look: Some((Vec3::ZERO, Vec3::NEG_Z)), fov_y: Some(FOV_DEG.to_radians()) };
    let mut view = initial_view(&level, &overrides);
    view.exposure = 1.0;
    view.headlamp.detach_looking_at(Vec3::ZERO, Vec3::NEG_Z);
    let detached = check(&render(&gpu, &level, &view, square), square, "detached");
    println!("worst relative error: attached {:.2} %, detached {:.2} %", attached * 100.0, detached * 100.0);
}
