//! Headless frames of the shipped levels against golden PNGs (the shots are in `frames.rs`,
//! the metric in `game::golden`; `update-goldens` re-makes them).

use engine::gpu::Gpu;
use headlamp_tests::frames::{level_shots, render_level_shot, SIZE};
use headlamp_tests::{check_golden, engine, load_level};

/// Renders each shot of the shipped level `id` and compares it with its golden.
fn check_frames(id: &str) {
    let gpu = Gpu::lavapipe().unwrap_or_else(|e| panic!("{e}"));
    let level = load_level(id);
    let mut failures = Vec::new();
    for shot in level_shots(id) {
        let img = render_level_shot(&gpu, &level, shot);
        // A black frame must never pass as "matching", even against a black golden.
        let lit = img.pixels().filter(|p| p[0] > 8 || p[1] > 8 || p[2] > 8).count();
        let share = lit as f64 / f64::from(SIZE.0 * SIZE.1);
        bounds::assert(bounds::at_least(format!("{}: the lit share of the frame", shot.name), share, 0.1));
        match check_golden(shot.name, &img) {
            Ok(d) => println!("{}: {d}", shot.name),
            Err(e) => failures.push(e),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn cellar_frames_match_goldens() {
    check_frames("cellar");
}

#[test]
fn gallery_frames_match_goldens() {
    check_frames("gallery");
}

#[test]
fn hall_frames_match_goldens() {
    check_frames("hall");
}
