//! Replay-based frame regression tests: each test replay in `replays/` is re-simulated headless
//! (every tick's state hash checked against the file) and the frames at chosen ticks are
//! compared with golden PNGs by FLIP (see harness.rs; `HEADLAMP_UPDATE_GOLDENS=1` re-makes
//! the replays from their scripts and the goldens from the renderer).

use headlamp_tests::{check_golden, replay_files};

/// Snapshot size: small, because lavapipe renders the GI on the CPU.
const SIZE: (u32, u32) = (320, 180);

/// Each replay and the ticks whose frames are checked (the frame after that many ticks), in the
/// order of their scripts' names.
const SHOTS: &[(&str, &[u32])] = &[
    // A crawler's body posed by the simulation: walking up; the strike drawn back mid-windup;
    // the blow at full reach as the windup ends; recovering.
    ("crawler_strike", &[230, 268, 280, 296]),
    // The Gallery won: the blue room's crawler seen through its door from the atrium; the first
    // shot's muzzle flash lighting the blue room; the vault's guard in its doorway; at the way
    // out, won.
    ("gallery_win", &[232, 235, 372, 560]),
    // The Hall won: on the west balcony at the top of the stairs; a shot from the balcony at the
    // nave's crawler below; a shot across the nave at the west arcade's crawler; the crypt's
    // guard in its doorway in the blue wall.
    ("hall_win", &[393, 490, 1075, 1430]),
    // In the corridor; near the top of the jump; crouched; standing again.
    ("jumping", &[60, 88, 161, 201]),
    // The moment the lamp is put down; backing out; in the corridor, the room lit by the lamp
    // left inside; turned a little.
    ("lamp_detach", &[229, 247, 265, 285]),
    // Lamp on; off (dark); on again; turned.
    ("lamp_toggle", &[30, 31, 61, 90]),
    ("turning", &[30, 60, 90, 120]),
    // The spawn view; backed against the south wall; pressed into the east wall; backed away
    // from that corner, looking at it.
    ("walls", &[0, 60, 120, 190]),
    // The Cellar won: the first shot's muzzle flash lighting the red/green room; that
    // crawler falling; the hall's crawler lying in the corridor; the storeroom's guard lying
    // in the storeroom, won.
    ("win", &[171, 189, 478, 795]),
];

fn mean_luminance(img: &image::RgbaImage) -> f32 {
    let sum: u64 = img.pixels().map(|p| (2 * p[0] as u64 + 5 * p[1] as u64 + p[2] as u64) / 8).sum();
    sum as f32 / (img.width() * img.height()) as f32
}

#[test]
fn every_test_replay_has_shots() {
    let shot: Vec<&str> = SHOTS.iter().map(|(n, _)| *n).collect();
    assert_eq!(replay_files::script_names(), shot, "every script in tests/replays is rendered");
    assert!(shot.len() >= 5);
}

#[test]
fn replay_frames_match_goldens() {
    let out = std::env::temp_dir().join(format!("headlamp-replay-frames-{}", std::process::id()));
    let mut failures = Vec::new();
    for (name, ticks) in SHOTS {
        let replay = replay_files::open(name);
        let dir = out.join(name);
        // Re-simulates every tick, checking the stored hashes, and renders the snapshots.
        let end = game::replay_cmd::headless(&replay, ticks, Some(&dir), SIZE).unwrap_or_else(|e| panic!("{e:#}"));
        assert_eq!(end.tick as usize, replay.commands.len());
        let mut luminance = Vec::new();
        for &t in *ticks {
            let path = dir.join(game::replay_cmd::snapshot_name(t));
            let img = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgba8();
            luminance.push(mean_luminance(&img));
            if let Err(e) = check_golden(&format!("replay_{name}_t{t:03}"), &img) {
                failures.push(e);
            }
        }
        // A black frame must never pass as "matching", even against a black golden; the one
        // frame with the lamp off must be the dark one.
        for (&t, &l) in ticks.iter().zip(&luminance) {
            let lamp_off = *name == "lamp_toggle" && t == 31;
            if lamp_off {
                assert!(
                    l < 0.2 * luminance[0],
                    "{name} t{t}: the lamp is off but the frame is lit ({l} vs {})",
                    luminance[0]
                );
            } else {
                assert!(l > 4.0, "{name} t{t}: frame is nearly black (mean luminance {l})");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&out);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
