//! `headlamp script`, `headlamp replay --verify` and `--headless` as a user runs them, and one
//! clear line (never a panic, never a silently wrong replay) for every kind of bad replay.

use std::path::{Path, PathBuf};
use std::process::Output;

mod common;

use common::{cellar, headlamp, scratch};

fn stdout(out: &Output) -> String {
    assert!(out.status.success(), "headlamp failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// One line on stderr, naming `needle`, exit code 1, no panic.
fn refused(out: &Output, needle: &str) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(1), "expected failure, got {:?}: {err}", out.status);
    assert!(err.contains(needle), "expected '{needle}' in: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    err
}

fn script(dir: &Path, text: &str, level: &str) -> (PathBuf, String) {
    let s = dir.join("walk.txt");
    std::fs::write(&s, text).unwrap();
    let replay = dir.join("walk.replay");
    let out = stdout(&headlamp(&["script", s.to_str().unwrap(), "--level", level, "--out", replay.to_str().unwrap()]));
    let hash = out.trim().rsplit(' ').next().unwrap().trim_end_matches(')').to_owned();
    (replay, hash)
}

const WALK: &str = "# into the corridor and back\n50 forward\n1 jump\n30 turn 180 lamp toggle\n50 forward sprint\n";

#[test]
fn script_then_verify_then_headless() {
    let dir = scratch("ok");
    let (replay, hash) = script(&dir, WALK, &cellar());
    let r = replay.to_str().unwrap();
    assert_eq!(stdout(&headlamp(&["replay", r, "--verify"])).trim(), "ok ticks=131 outcome=playing");
    // The level is found by its id, as a user in the project folder would run it.
    let out = stdout(&headlamp(&["replay", r, "--headless"]));
    assert_eq!(out.trim(), format!("ticks=131 hash={hash} outcome=playing"));
}

/// `--trace` shows the world after each line, with where each crawler is and how to aim at it.
#[test]
fn script_trace_describes_each_step() {
    let dir = scratch("trace");
    let s = dir.join("t.txt");
    std::fs::write(&s, "# look around\n30 forward\n\n10 turn 90\n").unwrap();
    let out = dir.join("t.replay");
    let text = stdout(&headlamp(&[
        "script",
        s.to_str().unwrap(),
        "--level",
        &cellar(),
        "--out",
        out.to_str().unwrap(),
        "--trace",
    ]));
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with("line 2: tick 30 at (0.00, "), "{text}");
    assert!(lines.iter().any(|l| l.starts_with("line 4: tick 40 ") && l.contains("yaw 90.0")), "{text}");
    assert_eq!(lines.iter().filter(|l| l.contains("crawler 0:") && l.contains("aim: turn")).count(), 2, "{text}");
    assert!(lines.last().unwrap().starts_with("wrote "), "{text}");
}

/// The shipped win replay plays the demo level from the start to a win, as a user (and CI)
/// checks it; headless, it never opens an audio device (CI has none), so it says nothing of sound.
#[test]
fn the_win_replay_wins() {
    let win = format!("{}/../tests/replays/win.replay", env!("CARGO_MANIFEST_DIR"));
    let run = headlamp(&["replay", &win, "--headless"]);
    let out = stdout(&run);
    assert!(out.trim().ends_with("outcome=won"), "{out}");
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(!err.contains("sound"), "a headless replay leaves the audio alone: {err}");
    let out = stdout(&headlamp(&["replay", &win, "--verify"]));
    assert!(out.trim().ends_with("outcome=won"), "{out}");
}

#[test]
fn headless_snapshots_are_pngs_of_the_game() {
    let dir = scratch("snap");
    let (replay, _) = script(&dir, WALK, &cellar());
    let shots = dir.join("shots");
    let out = headlamp(&[
        "replay",
        replay.to_str().unwrap(),
        "--headless",
        "--snapshots",
        "0,50",
        "--out-dir",
        shots.to_str().unwrap(),
        "--size",
        "160x90",
    ]);
    assert!(stdout(&out).starts_with("ticks=131 hash="));
    for t in ["tick_000000.png", "tick_000050.png"] {
        let img = image::open(shots.join(t)).unwrap().to_rgba8();
        assert_eq!(img.dimensions(), (160, 90));
        assert!(img.pixels().filter(|p| p[0] > 8 || p[1] > 8 || p[2] > 8).count() > 1000, "{t} is black");
    }
    let a = image::open(shots.join("tick_000000.png")).unwrap().to_rgba8();
    let b = image::open(shots.join("tick_000050.png")).unwrap().to_rgba8();
    assert_ne!(a, b, "50 ticks of walking change the view");
    let r = replay.to_str().unwrap();
    refused(&headlamp(&["replay", r, "--headless", "--snapshots", "500", "--out-dir", "x"]), "past the end");
    refused(&headlamp(&["replay", r, "--headless", "--snapshots", "5"]), "--out-dir");
}

#[test]
fn goldens_are_written_then_compared_and_a_changed_frame_fails() {
    let dir = scratch("goldens");
    let (replay, _) = script(&dir, WALK, &cellar());
    let (r, goldens) = (replay.to_str().unwrap(), dir.join("goldens"));
    let g = goldens.to_str().unwrap();
    refused(&headlamp(&["replay", r, "--goldens", g]), "no goldens");

    // Four frames spread over the replay, at the size asked for.
    let out = stdout(&headlamp(&["replay", r, "--goldens", g, "--update", "--size", "160x90"]));
    assert_eq!(out.lines().filter(|l| l.ends_with(": written")).count(), 4, "{out}");
    for t in ["tick_000000.png", "tick_000043.png", "tick_000087.png", "tick_000131.png"] {
        assert_eq!(image::image_dimensions(goldens.join(t)).unwrap(), (160, 90), "{t}");
    }

    // Compared at the goldens' own size: all match.
    let out = stdout(&headlamp(&["replay", r, "--goldens", g]));
    assert_eq!(out.lines().filter(|l| l.contains(": ok (mean FLIP")).count(), 4, "{out}");

    // A golden that no longer matches: a line naming it, the frame and the difference beside
    // it, exit 1.
    image::RgbaImage::from_pixel(160, 90, image::Rgba([255, 255, 255, 255]))
        .save(goldens.join("tick_000043.png"))
        .unwrap();
    let out = headlamp(&["replay", r, "--goldens", g]);
    let printed = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{printed}");
    assert!(printed.contains("tick_000043.png: the mean FLIP error") && printed.contains("luminance"), "{printed}");
    assert_eq!(printed.lines().filter(|l| l.contains(": ok (mean FLIP")).count(), 3, "{printed}");
    assert!(goldens.join("tick_000043.actual.png").exists() && goldens.join("tick_000043.diff.png").exists());
    refused(&out, "1 of 4 frames differ from their goldens");

    // --update re-makes the ticks already there (clearing what the failure left); then they
    // match again.
    stdout(&headlamp(&["replay", r, "--goldens", g, "--update"]));
    assert!(!goldens.join("tick_000043.actual.png").exists() && !goldens.join("tick_000043.diff.png").exists());
    stdout(&headlamp(&["replay", r, "--goldens", g]));
    refused(&headlamp(&["replay", r, "--snapshots", "5"]), "--snapshots needs --headless or --goldens");
}

#[test]
fn damaged_replays_are_refused_by_name() {
    let dir = scratch("bad");
    let (replay, _) = script(&dir, WALK, &cellar());
    let bytes = std::fs::read(&replay).unwrap();
    let write = |name: &str, b: &[u8]| {
        let p = dir.join(name);
        std::fs::write(&p, b).unwrap();
        p.to_str().unwrap().to_owned()
    };

    let cut = write("cut.replay", &bytes[..bytes.len() - 100]);
    refused(&headlamp(&["replay", &cut, "--verify"]), "truncated");
    refused(&headlamp(&["replay", &cut, "--headless"]), "cut.replay");

    // One command byte changed (a step forward became a step back): the checksum catches it...
    let tick0 = bytes.len() - 8 - 131 * 15;
    let mut edited = bytes.clone();
    edited[tick0 + 20 * 15] = (-127i8) as u8;
    let e = write("edited.replay", &edited);
    refused(&headlamp(&["replay", &e, "--verify"]), "checksum");
    // ...and with the checksum forged to match, the state hashes do, naming the tick.
    let n = edited.len();
    let mut sum = scene::Fnv1a::default();
    sum.write(&edited[..n - 8]);
    let sum = sum.finish();
    edited[n - 8..].copy_from_slice(&sum.to_le_bytes());
    let forged = write("forged.replay", &edited);
    refused(&headlamp(&["replay", &forged, "--verify"]), "diverged at tick 21");
    refused(&headlamp(&["replay", &forged, "--headless"]), "diverged at tick 21");

    let mut future = bytes.clone();
    future[8..12].copy_from_slice(&9u32.to_le_bytes());
    let f = write("future.replay", &future);
    refused(&headlamp(&["replay", &f, "--verify"]), "version 9");

    let png = write("picture.replay", b"\x89PNG\r\n\x1a\n....");
    refused(&headlamp(&["replay", &png, "--verify"]), "not a Headlamp replay");
    refused(&headlamp(&["replay", dir.join("missing.replay").to_str().unwrap(), "--verify"]), "missing.replay");
}

#[test]
fn a_changed_level_is_refused() {
    let dir = scratch("level");
    let level = dir.join("mycellar");
    std::fs::create_dir_all(&level).unwrap();
    // The level file, its scene, buffer and textures.
    for entry in std::fs::read_dir(cellar()).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, level.join(path.file_name().unwrap())).unwrap();
    }
    let (replay, _) = script(&dir, WALK, level.to_str().unwrap());
    let r = replay.to_str().unwrap();
    let l = level.to_str().unwrap();
    assert_eq!(stdout(&headlamp(&["replay", r, "--verify", "--level", l])).trim(), "ok ticks=131 outcome=playing");
    // Not shipped and not under ./levels: the replay cannot guess where it is.
    refused(&headlamp(&["replay", r, "--verify"]), "'mycellar'");
    let toml = std::fs::read_to_string(level.join("level.toml")).unwrap();
    std::fs::write(level.join("level.toml"), toml.replace("exposure = 0.3", "exposure = 0.4")).unwrap();
    refused(&headlamp(&["replay", r, "--verify", "--level", l]), "the level changed");
}

#[test]
fn script_mistakes_name_the_line() {
    let dir = scratch("script");
    let s = dir.join("s.txt");
    std::fs::write(&s, "60 forward\n10 forwrd\n").unwrap();
    let out = dir.join("s.replay");
    let o = headlamp(&["script", s.to_str().unwrap(), "--level", &cellar(), "--out", out.to_str().unwrap()]);
    refused(&o, "s.txt:2: unknown action 'forwrd'");
    assert!(!out.exists(), "no replay is written from a bad script");
}
