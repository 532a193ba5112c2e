//! `headlamp bench` as a user runs it: a short timedemo of the shipped level, its table, its
//! JSON, and one clear line for bad input. Correctness of the figures, not speed.

mod common;

use common::{cellar, headlamp, scratch};

#[test]
fn bench_of_the_cellar_prints_the_table_and_writes_json() {
    let json = scratch("cellar").join("out.json");
    let level = cellar();
    let out = headlamp(&[
        "bench",
        "--level",
        level.as_str(),
        "--size",
        "96x54",
        "--frames",
        "3",
        "--json",
        json.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "bench failed: {}\n{stdout}", String::from_utf8_lossy(&out.stderr));
    println!("{stdout}");
    for needle in
        ["| pass |", "frame, CPU wall", "fps", "reflection lights", "GI calls per frame", "error vs brute-force"]
    {
        assert!(stdout.contains(needle), "the table lacks '{needle}':\n{stdout}");
    }

    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(report["frames"], 3);
    assert_eq!(report["size"], serde_json::json!([96, 54]));
    let passes = report["passes"].as_array().expect("passes");
    let timed = report["gpu_timestamps"].as_bool().expect("gpu_timestamps");
    if timed {
        for name in ["gbuffer", "direct_light", "gi_flux", "gi_gather", "gi_composite", "present"] {
            let pass = passes.iter().find(|p| p["name"] == name).unwrap_or_else(|| panic!("no entry for pass {name}"));
            for key in ["median", "p90", "mean", "min", "max"] {
                let ms = pass["gpu_ms"][key].as_f64().unwrap_or_else(|| panic!("{name}.{key} is not a number"));
                assert!(ms.is_finite() && ms >= 0.0, "{name}: {key} = {ms} ms");
            }
        }
        assert_eq!(report["per_frame"][0]["passes"].as_array().unwrap().len(), passes.len());
    } else {
        eprintln!("this adapter has no encoder timestamps: only CPU times were checked");
    }
    let cpu = report["cpu_frame_ms"]["median"].as_f64().unwrap();
    assert!(cpu.is_finite() && cpu > 0.0, "CPU frame time {cpu}");
    assert!(report["fps"].as_f64().unwrap() > 0.0);
    let lights = report["reflection_lights"]["median"].as_f64().expect("lights per tile");
    assert!(lights > 0.0, "no reflection lights");
    assert!(report["gi_draws"].as_u64().unwrap() > 0 && report["gi_dispatches"].as_u64().unwrap() > 0);
    let error = report["error_vs_reference"]["relative_l2_block8"].as_f64().expect("error figure");
    assert!((0.0..1.0).contains(&error), "error vs reference {error}");
}

#[test]
fn bench_with_a_target_frame_rate_reports_the_scales_dynamic_resolution_chose() {
    let json = scratch("dynamic").join("out.json");
    let level = cellar();
    let args = ["--size", "96x54", "--frames", "30", "--render-scale", "0.5", "--target-fps", "144"];
    let out = headlamp(&[&["bench", "--level", level.as_str(), "--json", json.to_str().unwrap()], &args[..]].concat());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "bench failed: {}\n{stdout}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("dynamic resolution holding 144 fps (render scale at most 0.5)"), "{stdout}");
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let d = &report["dynamic_resolution"];
    let (lowest, highest) = (d["lowest"].as_f64().unwrap(), d["highest"].as_f64().unwrap());
    assert!((0.25..=highest).contains(&lowest) && highest <= 0.5, "scales {lowest} to {highest}");
    for frame in report["per_frame"].as_array().unwrap() {
        let scale = frame["render_scale"].as_f64().unwrap();
        assert!((lowest..=highest).contains(&scale), "a frame at {scale}");
    }
}

#[test]
fn bench_pan_compares_against_the_reference_with_finer_senders_too() {
    let dir = scratch("pan_finer");
    let json = dir.join("out.json");
    let level = cellar();
    let out = headlamp(&[
        "bench",
        "--level",
        level.as_str(),
        "--pan",
        "--size",
        "32x24",
        "--frames",
        "3",
        "--reference-senders",
        "3",
        "--out-dir",
        dir.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "bench --pan failed: {}\n{stdout}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("against the reference with 3x3 as many senders"), "{stdout}");
    assert!(stdout.contains("the 32x24 reference's own flicker against it"), "{stdout}");
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let finer = &report["finer"];
    assert_eq!(finer["senders"], 3);
    for key in ["flicker", "reference_flicker"] {
        let v = finer[key].as_f64().unwrap_or_else(|| panic!("finer.{key} is not a number: {finer}"));
        assert!(v.is_finite() && v >= 0.0, "finer.{key} = {v}");
    }
    assert_eq!(finer["error_per_frame"].as_array().map(Vec::len), Some(3));
    // The finer reference's frames are written at the pan's size, beside the others.
    let frame = image::open(dir.join("reference_finer_002.exr")).expect("the finer reference's last frame");
    assert_eq!((frame.width(), frame.height()), (32, 24));
}

#[test]
fn bench_rejects_bad_input_with_one_line() {
    let dir = scratch("bad");
    let missing = dir.join("nope.gltf");
    let bad_json = dir.join("no_such_dir").join("out.json");
    let cellar = cellar();
    let cases: [(Vec<&str>, &str); 6] = [
        (vec!["bench", "--level", missing.to_str().unwrap()], "nope.gltf"),
        (vec!["bench", "--level", &cellar, "--frames", "0"], "--frames"),
        (vec!["bench", "--level", &cellar, "--set", "gi.split_ratio=9"], "split_ratio"),
        (vec!["bench", "--level", &cellar, "--json", bad_json.to_str().unwrap()], "--json"),
        (vec!["bench", "--level", &cellar, "--target-fps", "5"], "--target-fps"),
        (vec!["bench", "--level", &cellar, "--pan", "--reference-senders", "4"], "--reference-senders"),
    ];
    for (args, needle) in cases {
        let out = headlamp(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} should fail");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: expected one line, got:\n{stderr}");
        assert!(stderr.contains(needle), "{args:?}: '{stderr}' does not mention {needle}");
    }
}
