//! The goldens check what a player would notice, and nothing outside the test decides what they
//! check: changes a player sees in a real golden fail, every golden shows something, every
//! golden belongs to a shot, and the variable that once re-made goldens changes nothing.

use game::golden::{mean_luminance, srgb_to_linear, Difference};
use headlamp_tests::frames::{golden_names, SIZE};
use headlamp_tests::{check_golden, golden_path, goldens_dir};

fn golden(name: &str) -> image::RgbaImage {
    let path = golden_path(name);
    image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgba8()
}

/// `img` with its light scaled by `scale` in `region` (x, y, width, height): the sRGB pixels
/// decoded, scaled and encoded again.
fn scaled(img: &image::RgbaImage, scale: f64, region: (u32, u32, u32, u32)) -> image::RgbaImage {
    let to_srgb = |l: f64| {
        let l = l.clamp(0.0, 1.0);
        let c = if l <= 0.0031308 { 12.92 * l } else { 1.055 * l.powf(1.0 / 2.4) - 0.055 };
        (c * 255.0).round() as u8
    };
    let (x0, y0, w, h) = region;
    let mut out = img.clone();
    for y in y0..y0 + h {
        for x in x0..x0 + w {
            let p = out.get_pixel_mut(x, y);
            for c in 0..3 {
                p[c] = to_srgb(srgb_to_linear(p[c]) * scale);
            }
        }
    }
    out
}

/// The region of 5 % of the frame (a 72×40 block of 320×180) with the most light in it.
fn brightest_block(img: &image::RgbaImage) -> (u32, u32, u32, u32) {
    let (w, h) = (72, 40);
    assert_eq!(w * h * 20, SIZE.0 * SIZE.1, "5 % of the frame");
    let mut best = (0.0, (0, 0, w, h));
    for y in (0..=img.height() - h).step_by(4) {
        for x in (0..=img.width() - w).step_by(4) {
            let sum: f64 = (y..y + h)
                .flat_map(|yy| (x..x + w).map(move |xx| (xx, yy)))
                .map(|(xx, yy)| {
                    let p = img.get_pixel(xx, yy);
                    p[0] as f64 + p[1] as f64 + p[2] as f64
                })
                .sum();
            if sum > best.0 {
                best = (sum, (x, y, w, h));
            }
        }
    }
    best.1
}

/// The dark hall frame of the Cellar, where a mean FLIP alone once let 20 % less light pass.
const DARK_GOLDEN: &str = "cellar_hall_final";

#[test]
fn ten_percent_less_light_fails() {
    let g = golden(DARK_GOLDEN);
    let whole = (0, 0, g.width(), g.height());
    let (d, _) = Difference::between(&g, &scaled(&g, 0.9, whole));
    assert!(!d.exceeded().is_empty(), "10 % less light passes: {d}");
    // As does 10 % more; 1 % either way is within every bound.
    let (d, _) = Difference::between(&g, &scaled(&g, 1.1, whole));
    assert!(!d.exceeded().is_empty(), "10 % more light passes: {d}");
    let (d, _) = Difference::between(&g, &scaled(&g, 0.99, whole));
    assert!(d.exceeded().is_empty(), "1 % less light fails: {d}");
}

#[test]
fn a_change_over_five_percent_of_the_frame_fails() {
    let g = golden(DARK_GOLDEN);
    let block = brightest_block(&g);
    // The brightest 5 % of the frame half as bright (a shadow fallen over it), and with its
    // light gone (a thing in the beam missing).
    for scale in [0.5, 0.0] {
        let (d, _) = Difference::between(&g, &scaled(&g, scale, block));
        assert!(!d.exceeded().is_empty(), "{block:?} × {scale} passes: {d}");
        assert!(d.p99_flip > game::golden::P99_FLIP_TOLERANCE, "{block:?} × {scale}: the local bound must see it: {d}");
    }
}

#[test]
fn every_golden_shows_something_and_belongs_to_a_shot() {
    let names = golden_names();
    let mut on_disk: Vec<String> = std::fs::read_dir(goldens_dir())
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            let stem = p.file_stem()?.to_str()?.to_string();
            (p.extension()? == "png" && !stem.contains('.')).then_some(stem)
        })
        .collect();
    on_disk.sort();
    let mut wanted = names.clone();
    wanted.sort();
    assert_eq!(on_disk, wanted, "goldens/ holds exactly one golden per shot");
    for name in names {
        let g = golden(&name);
        let lit = g.pixels().filter(|p| p[0] > 8 || p[1] > 8 || p[2] > 8).count() as f64;
        let share = lit / (g.width() * g.height()) as f64;
        // A near-black golden checks almost nothing: at least a tenth of it lit, and a mean
        // luminance over 0.1 % of white (the darkest, the Cellar's hall, is 0.17 %; the frame
        // of the lamp just switched off, once a golden, was 0.0001 %).
        assert!(
            share > 0.1 && mean_luminance(&g) > 0.001,
            "{name}: near black ({:.1} % lit, luminance {:.5})",
            100.0 * share,
            mean_luminance(&g)
        );
    }
}

/// `HEADLAMP_UPDATE_GOLDENS=1` once turned every golden check into a pass that re-wrote the
/// golden; now nothing read from the environment changes a check.
#[test]
fn the_old_update_variable_changes_nothing() {
    for (name, value) in
        [("HEADLAMP_UPDATE_GOLDENS", "1"), ("HEADLAMP_GI_SET", "bounces=2"), ("SCENE_FUZZ_ROUNDS", "0")]
    {
        std::env::set_var(name, value);
    }
    let g = golden(DARK_GOLDEN);
    let before = std::fs::read(golden_path(DARK_GOLDEN)).unwrap();
    let dimmed = scaled(&g, 0.9, (0, 0, g.width(), g.height()));
    let e = check_golden(DARK_GOLDEN, &dimmed).expect_err("a dimmed frame must fail with the variable set");
    assert!(e.contains("luminance"), "{e}");
    assert_eq!(std::fs::read(golden_path(DARK_GOLDEN)).unwrap(), before, "the golden must not be re-written");
    // What the failure left beside the golden.
    for suffix in ["actual", "diff"] {
        std::fs::remove_file(goldens_dir().join(format!("{DARK_GOLDEN}.{suffix}.png"))).unwrap();
    }
}
