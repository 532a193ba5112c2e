//! The goldens check what a player would notice, and nothing outside the test decides what they
//! check: changes a player sees in a real golden fail — light lost or gained all over, a
//! shadow over the brightest 5 %, a 12×12 patch of the brightest area gone grey, a pickup taken
//! out of a replay's frame, a crawler's eyes dimmed by half — every golden shows something,
//! every golden belongs to a shot, and a failure never re-writes a golden.

use engine::frame::ViewState;
use engine::glam::Vec3;
use engine::gpu::Gpu;
use game::golden::{mean_luminance, srgb_to_linear, Difference, WINDOW};
use game::sim::WorldState;
use headlamp_tests::frames::{golden_names, replay_shot_name, LEVEL_SHOTS, SIZE};
use headlamp_tests::{check_golden, golden_path, goldens_dir, replay_files};

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
        let exceeded = d.exceeded();
        assert!(
            exceeded.iter().any(|e| e.contains("99th-percentile")),
            "{block:?} × {scale}: the percentile must see it: {d}"
        );
    }
}

/// `img` with the 12×12 patch of the most light (its pixels' summed luminance) painted the
/// frame's mean colour: 144 pixels, a quarter of the 1 % the percentile ignores.
fn brightest_patch_grey(img: &image::RgbaImage) -> image::RgbaImage {
    const SIDE: u32 = 12;
    let lum = |p: &image::Rgba<u8>| {
        0.2126 * srgb_to_linear(p[0]) + 0.7152 * srgb_to_linear(p[1]) + 0.0722 * srgb_to_linear(p[2])
    };
    let mut best = (f64::NEG_INFINITY, 0, 0);
    for y in 0..=img.height() - SIDE {
        for x in 0..=img.width() - SIDE {
            let sum: f64 = (y..y + SIDE)
                .flat_map(|v| (x..x + SIDE).map(move |u| (u, v)))
                .map(|(u, v)| lum(img.get_pixel(u, v)))
                .sum();
            if sum > best.0 {
                best = (sum, x, y);
            }
        }
    }
    let n = f64::from(img.width() * img.height());
    let mean = |c: usize| (img.pixels().map(|p| f64::from(p[c])).sum::<f64>() / n).round() as u8;
    let grey = image::Rgba([mean(0), mean(1), mean(2), 255]);
    let mut out = img.clone();
    for y in best.2..best.2 + SIDE {
        for x in best.1..best.1 + SIDE {
            out.put_pixel(x, y, grey);
        }
    }
    out
}

/// The bounds `d` exceeds, asserting that the worst window is one and naming `what`.
fn seen_by_the_window(what: &str, d: &Difference) -> Vec<String> {
    let exceeded = d.exceeded();
    let window = format!("{WINDOW}x{WINDOW} window");
    assert!(exceeded.iter().any(|e| e.contains(&window)), "{what} passes the worst window: {d}");
    exceeded
}

/// The pictures a player sees (every golden of the `final` view, every replay's): each fails
/// with its brightest 12×12 patch grey, which the mean and the percentile cannot see.
#[test]
fn a_twelve_pixel_patch_of_the_brightest_area_fails_every_picture_a_player_sees() {
    let debug_views: Vec<&str> =
        LEVEL_SHOTS.iter().flat_map(|(_, shots)| shots.iter()).filter(|s| s.view != "final").map(|s| s.name).collect();
    let mut names: Vec<String> = golden_names().into_iter().filter(|n| !debug_views.contains(&n.as_str())).collect();
    names.sort();
    bounds::assert(bounds::at_least("goldens a player sees", names.len() as f64, 40.0));
    for name in names {
        let g = golden(&name);
        let (d, _) = Difference::between(&g, &brightest_patch_grey(&g));
        seen_by_the_window(&format!("{name} with its brightest 12x12 patch grey"), &d);
    }
}

/// The frame after `tick` of the test replay `name`, its view edited by `edit` first.
fn edited_replay_frame(name: &str, tick: u32, edit: impl FnMut(&WorldState, &mut ViewState)) -> image::RgbaImage {
    let replay = replay_files::open(name);
    let mut frame = None;
    game::replay_frames::frames_edited(&replay, &[tick], SIZE, Gpu::lavapipe, edit, |_, image| {
        frame = Some(image.clone());
        Ok(())
    })
    .unwrap_or_else(|e| panic!("{name}: {e:#}"));
    frame.expect("the frame")
}

/// The Cellar won, the first shot: the medkit on the crate by the red/green room's crawler,
/// taken out of the frame (the pickup nearest the camera).
#[test]
fn a_pickup_taken_out_of_a_replay_frame_fails() {
    let (name, tick) = ("win", 171);
    let golden_name = replay_shot_name(name, tick);
    let mut taken = 0;
    let frame = edited_replay_frame(name, tick, |state, view| {
        let eye = view.camera.position;
        let spots: Vec<Vec3> = state.pickups.iter().filter(|p| !p.taken).map(|p| p.position).collect();
        let nearest =
            spots.iter().copied().min_by(|a, b| a.distance(eye).total_cmp(&b.distance(eye))).expect("a pickup");
        let before = view.instances.len();
        view.instances.retain(|i| {
            let at = i.transform.w_axis.truncate();
            !((at.x - nearest.x).abs() < 1e-3 && (at.z - nearest.z).abs() < 1e-3)
        });
        taken = before - view.instances.len();
    });
    assert_eq!(taken, 2, "the medkit and its cross taken out");
    let (d, _) = Difference::between(&golden(&golden_name), &frame);
    let exceeded = seen_by_the_window(&format!("{golden_name} without its nearest pickup"), &d);
    assert_eq!(exceeded.len(), 1, "the worst window alone sees it: {exceeded:?}");
}

/// The lamp put down in the red/green room, backing out: the crawler across the room, its eyes
/// glowing in the dark, dimmed by half.
#[test]
fn a_crawlers_eyes_dimmed_by_half_fail() {
    let (name, tick) = ("lamp_detach", 265);
    let golden_name = replay_shot_name(name, tick);
    let mut eyes = 0;
    let frame = edited_replay_frame(name, tick, |_, view| {
        for eye in view.instances.iter_mut().filter(|i| i.base_color == game::crawler_body::EYE_COLOR) {
            eye.emissive = eye.emissive.map(|e| 0.5 * e);
            eyes += 1;
        }
    });
    bounds::assert(bounds::at_least("crawlers' eyes dimmed", f64::from(eyes), 2.0));
    let (d, _) = Difference::between(&golden(&golden_name), &frame);
    let exceeded = seen_by_the_window(&format!("{golden_name} with the eyes dimmed by half"), &d);
    assert_eq!(exceeded.len(), 1, "the worst window alone sees it: {exceeded:?}");
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
        let share = lit / f64::from(g.width() * g.height());
        // A near-black golden checks almost nothing: at least a tenth of it lit, and a mean
        // luminance over 0.1 % of white (the darkest, the Cellar's hall, is 0.17 %; a frame of
        // the lamp just switched off reads 0.0001 %).
        bounds::assert_all([
            bounds::at_least(format!("{name}: the lit share"), share, 0.1),
            bounds::at_least(format!("{name}: the mean luminance"), mean_luminance(&g), 0.001),
        ]);
    }
}

/// A frame that fails leaves the golden as it was: only the one command re-makes goldens.
#[test]
fn a_failing_frame_never_rewrites_its_golden() {
    let g = golden(DARK_GOLDEN);
    let before = std::fs::read(golden_path(DARK_GOLDEN)).unwrap();
    let dimmed = scaled(&g, 0.9, (0, 0, g.width(), g.height()));
    let e = check_golden(DARK_GOLDEN, &dimmed).expect_err("a dimmed frame must fail");
    assert!(e.contains("luminance"), "{e}");
    assert_eq!(std::fs::read(golden_path(DARK_GOLDEN)).unwrap(), before, "the golden must not be re-written");
    // What the failure left beside the golden.
    for suffix in ["actual", "diff"] {
        std::fs::remove_file(goldens_dir().join(format!("{DARK_GOLDEN}.{suffix}.png"))).unwrap();
    }
}
