//! What a hostile or careless user can feed the command line: devices, FIFOs, endless or huge
//! inputs, an output naming its input. Each is one clear line and exit 1, at once: no panic, no
//! unbounded read, no endless wait.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;

use common::{cellar, scratch};

/// Runs headlamp, failing the test if it takes more than 30 s (a hang is the bug looked for).
fn headlamp_within(args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_headlamp"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run headlamp");
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > Duration::from_secs(30) {
            let _ = child.kill();
            panic!("headlamp {args:?} still runs after 30 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("output")
}

/// One line on stderr containing every needle, exit code 1, no panic.
fn refused(args: &[&str], needles: &[&str]) {
    let out = headlamp_within(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: one line: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: no '{n}' in {err}");
    }
}

#[cfg(unix)]
#[test]
fn devices_and_fifos_are_refused_at_once() {
    let dir = scratch("devices");
    let fifo = dir.join("scene.obj");
    assert!(Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()));
    let fifo = fifo.to_str().unwrap();
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    refused(&["replay", "/dev/zero", "--verify"], &["/dev/zero", "not a regular file"]);
    refused(&["script", "/dev/zero", "--level", &cellar(), "--out", out], &["/dev/zero", "not a regular file"]);
    refused(&["script", "/dev/urandom", "--level", &cellar(), "--out", out], &["/dev/urandom", "not a regular file"]);
    refused(&["render", "--level", fifo, "--out", out, "--size", "32x18"], &["scene.obj", "not a regular file"]);
    std::fs::create_dir_all(dir.join("level")).unwrap();
    std::fs::write(dir.join("level/level.toml"), "name = \"F\"\nscene = \"s.obj\"\n").unwrap();
    assert!(Command::new("mkfifo").arg(dir.join("level/s.obj")).status().is_ok_and(|s| s.success()));
    let check = headlamp_within(&["check", dir.join("level").to_str().unwrap()]);
    assert_eq!(check.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&check.stdout).contains("s.obj: error: cannot read file: is not a regular file"));
}

#[test]
fn a_script_may_not_overwrite_itself_nor_run_for_days() {
    let dir = scratch("script");
    let script = dir.join("walk.txt");
    std::fs::write(&script, "10 forward\n").unwrap();
    let s = script.to_str().unwrap();
    refused(&["script", s, "--level", &cellar(), "--out", s], &["is the script itself"]);
    assert_eq!(std::fs::read_to_string(&script).unwrap(), "10 forward\n", "the script is untouched");
    std::fs::write(&script, "10 forward\n100000000 wait\n").unwrap();
    let out = dir.join("x.replay");
    refused(&["script", s, "--level", &cellar(), "--out", out.to_str().unwrap()], &["walk.txt:2:", "ticks"]);
}

#[test]
fn a_huge_profile_image_is_refused_before_it_is_decoded() {
    let dir = scratch("profile");
    let level = dir.join("level");
    std::fs::create_dir_all(&level).unwrap();
    std::fs::write(level.join("s.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(level.join("level.toml"), "name = \"P\"\nscene = \"s.obj\"\n[headlamp]\nprofile = \"wide.png\"\n")
        .unwrap();
    // 16385 × 1: tiny to store, past every limit across.
    image::GrayImage::new(16385, 1).save(level.join("wide.png")).unwrap();
    let out = headlamp_within(&["check", level.to_str().unwrap()]);
    let printed = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{printed}");
    assert!(printed.contains("wide.png: error: too large: image exceeds 2048x2048 pixels"), "{printed}");
    assert!(Path::new(&level).exists());
}

/// A frame too large for the device is one line naming the size (wgpu's default would panic).
/// On lavapipe the G-buffer alone outgrows what it can allocate; a device that can render it
/// must then write the file.
#[test]
fn a_frame_too_large_for_the_device_is_an_error_not_a_panic() {
    let dir = scratch("huge");
    let out = dir.join("huge.png");
    let run = headlamp_within(&[
        "render",
        "--level",
        &cellar(),
        "--out",
        out.to_str().unwrap(),
        "--size",
        "16384x16384",
        "--gi",
        "off",
    ]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(!err.contains("panicked"), "{err}");
    match run.status.code() {
        Some(0) => assert!(out.exists(), "rendered, so written"),
        Some(1) => {
            assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
            assert!(err.contains("the GPU failed rendering a 16384x16384 frame"), "{err}");
        }
        other => panic!("exit {other:?}: {err}"),
    }
}
