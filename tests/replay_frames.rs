//! Replay-based frame regression tests: each test replay in `replays/` is re-simulated headless
//! (every tick's state hash checked against the file) and the frames at chosen ticks
//! (`frames.rs`) are compared with golden PNGs by `game::golden`'s metric.

use headlamp_tests::frames::{render_replay_ticks, replay_shot_name, REPLAY_SHOTS};
use headlamp_tests::{check_golden, replay_files};

/// Mean of (2R + 5G + B) / 8 over the frame, 0…255.
fn display_luminance(img: &image::RgbaImage) -> f32 {
    let sum: u64 = img.pixels().map(|p| (2 * p[0] as u64 + 5 * p[1] as u64 + p[2] as u64) / 8).sum();
    sum as f32 / (img.width() * img.height()) as f32
}

#[test]
fn every_test_replay_has_shots() {
    let shot: Vec<&str> = REPLAY_SHOTS.iter().map(|(n, _)| *n).collect();
    assert_eq!(replay_files::script_names(), shot, "every script in tests/replays is rendered");
    bounds::assert(bounds::at_least("test replays", shot.len() as f64, 5.0));
}

#[test]
fn replay_frames_match_goldens() {
    let mut failures = Vec::new();
    for (name, ticks) in REPLAY_SHOTS {
        for (t, img) in render_replay_ticks(name, ticks) {
            // A black frame must never pass as "matching", even against a black golden.
            let l = display_luminance(&img);
            bounds::assert(bounds::at_least(format!("{name} t{t}: the mean display luminance of 255"), l, 4.0));
            let golden = replay_shot_name(name, t);
            match check_golden(&golden, &img) {
                Ok(d) => println!("{golden}: {d}"),
                Err(e) => failures.push(e),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The one dark frame, the lamp just switched off, has no golden (black checks almost nothing):
/// it must be dark but for the pistol's glowing sight dots, and the frames around it lit.
#[test]
fn with_the_lamp_off_the_corridor_is_dark() {
    let frames = render_replay_ticks("lamp_toggle", &[30, 31]);
    let (on, off) = (display_luminance(&frames[0].1), display_luminance(&frames[1].1));
    bounds::assert_all([
        bounds::at_least("the lamp on: the mean display luminance of 255", on, 4.0),
        bounds::at_most("the lamp off: the mean display luminance over the lamp on's", off / on, 0.01),
    ]);
    let lit = frames[1].1.pixels().filter(|p| p[0] > 8 || p[1] > 8 || p[2] > 8).count();
    // The sight's three dots, a few pixels each at 320×180.
    bounds::assert_all([
        bounds::at_least("lit pixels with the lamp off (the sight dots)", lit as f64, 1.0),
        bounds::at_most("lit pixels with the lamp off (the sight dots alone)", lit as f64, 24.0),
    ]);
}
