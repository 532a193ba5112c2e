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
                bounds::assert(bounds::at_least(format!("{name}: {key} GPU ms"), ms, 0.0));
            }
        }
        assert_eq!(report["per_frame"][0]["passes"].as_array().unwrap().len(), passes.len());
    } else {
        eprintln!("this adapter has no encoder timestamps: only CPU times were checked");
    }
    let number =
        |v: &serde_json::Value, what: &str| v.as_f64().unwrap_or_else(|| panic!("{what} is not a number: {v}"));
    let positive = f64::MIN_POSITIVE;
    bounds::assert_all([
        bounds::at_least(
            "the median CPU frame ms",
            number(&report["cpu_frame_ms"]["median"], "cpu_frame_ms"),
            positive,
        ),
        bounds::at_least("fps", number(&report["fps"], "fps"), positive),
        bounds::at_least(
            "reflection lights per tile",
            number(&report["reflection_lights"]["median"], "lights"),
            positive,
        ),
        bounds::at_least("GI draws", number(&report["gi_draws"], "gi_draws"), 1.0),
        bounds::at_least("GI dispatches", number(&report["gi_dispatches"], "gi_dispatches"), 1.0),
        // A figure, not a goal: any error short of a GI that lights nothing right.
        bounds::at_most(
            "the error against the reference",
            number(&report["error_vs_reference"]["relative_l2_block8"], "error"),
            1.0 - f64::EPSILON,
        ),
    ]);
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
    let scales: Vec<f64> =
        report["per_frame"].as_array().unwrap().iter().map(|f| f["render_scale"].as_f64().unwrap()).collect();
    bounds::assert_all([
        bounds::at_least("the lowest render scale", lowest, 0.25),
        bounds::at_most("the lowest render scale over the highest", lowest / highest, 1.0),
        bounds::at_most("the highest render scale", highest, 0.5),
        bounds::at_least("a frame's render scale, the least", bounds::least(scales.iter().copied()), lowest),
        bounds::at_most("a frame's render scale, the most", bounds::worst(scales), highest),
    ]);
}

#[test]
fn bench_pan_measures_against_the_world_reference_and_its_convergence() {
    let dir = scratch("pan_converge");
    let json = dir.join("out.json");
    let level = cellar();
    let out = headlamp(&[
        "bench",
        "--level",
        level.as_str(),
        "--pan",
        "--size",
        "320x96",
        "--frames",
        "3",
        "--patch-size",
        "0.08",
        "--reference-every",
        "2",
        "--converge",
        "--walk-cm",
        "2",
        "--lamp",
        "0,1.6,3.8:0,1,-4",
        // The reference without visibility, as the GI: four times cheaper, and the one
        // `--converge` is about (the visibility-correct one is tested below).
        "--set",
        "gi.visibility=off",
        "--out-dir",
        dir.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "bench --pan failed: {}\n{stdout}", String::from_utf8_lossy(&out.stderr));
    println!("{stdout}");
    for needle in [
        "reference: world-fixed patches of at most 8 cm, no visibility, on every 2nd 8x8 flicker block across and down",
        "| figure (8x8-block means) |",
        "the reference vs its 4 cm patches (8x8 blocks)",
        "the reference's own flicker against its 4 cm patches",
    ] {
        assert!(stdout.contains(needle), "the table lacks '{needle}':\n{stdout}");
    }
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(report["flicker_block"], 8, "1/40 of 320 pixels");
    assert_eq!(report["walk_cm"], 2.0);
    let lamp: Vec<f64> = report["lamp"]
        .as_array()
        .expect("the lamp set down")
        .iter()
        .flat_map(|p| p.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect::<Vec<_>>())
        .collect();
    let expected = [0.0, 1.6, 3.8, 0.0, 1.0, -4.0];
    let off = bounds::worst(lamp.iter().zip(expected).map(|(a, b)| (a - b).abs()));
    bounds::assert(bounds::at_most("the lamp's place off what was asked, metres", off, 1e-6));
    assert!(stdout.contains("walking forward 2 cm a frame") && stdout.contains("lamp set down at 0.00,1.60,3.80"));
    let reference = &report["reference"];
    assert_eq!(reference["every"], 2);
    assert_eq!(reference["visibility"], false);
    assert_eq!(reference["pixels"], 20 * 6 * 64, "every other block of 40x12, across and down");
    for key in ["receivers_per_frame", "lit_patches_per_frame", "patch_seconds_per_frame", "sum_seconds_per_frame"] {
        let per_frame = reference[key].as_array().unwrap_or_else(|| panic!("reference.{key}: {reference}"));
        assert_eq!(per_frame.len(), 3, "{key}");
        let least = bounds::least(per_frame.iter().map(|v| v.as_f64().unwrap_or(f64::NAN)));
        bounds::assert(bounds::at_least(format!("reference.{key}, the least frame"), least, f64::MIN_POSITIVE));
    }
    let converge = &report["converge"];
    assert_eq!(converge["patch_size_m"], 0.04);
    for key in ["flicker", "reference_flicker"] {
        let v = converge[key].as_f64().unwrap_or_else(|| panic!("converge.{key} is not a number: {converge}"));
        bounds::assert(bounds::at_least(format!("converge.{key}"), v, 0.0));
    }
    let lit = |r: &serde_json::Value| r["lit_patches_per_frame"][0].as_f64().unwrap();
    bounds::assert(bounds::at_least(
        "lit patches at half the size over the pan's",
        lit(converge) / lit(reference),
        3.0,
    ));
    for errors in [&report["error_per_frame"], &converge["error_per_frame"]] {
        let errors = errors.as_array().unwrap();
        assert_eq!(errors.len(), 3);
        let worst = bounds::worst(errors.iter().map(|e| e.as_f64().unwrap_or(f64::NAN)));
        bounds::assert(bounds::at_most("the error of the worst frame", worst, 1.0 - f64::EPSILON));
    }
    // The frames are written at the pan's size, black where the reference was not evaluated.
    let frame =
        image::open(dir.join("reference_half_002.exr")).expect("the finer reference's last frame").into_rgb32f();
    assert_eq!((frame.width(), frame.height()), (320, 96));
    assert!(frame.enumerate_pixels().all(|(x, y, p)| ((x / 8) % 2 == 0 && (y / 8) % 2 == 0) || p.0 == [0.0; 3]));
    let brightest = bounds::worst(frame.pixels().map(|p| f64::from(p[0])));
    bounds::assert(bounds::at_least("the finer reference's brightest red", brightest, f64::MIN_POSITIVE));
}

#[test]
fn bench_pan_with_visibility_measures_against_the_visibility_correct_reference() {
    // With gi.visibility on (the default) the GI's shadows are right, so the reference must
    // have them too, or they would count as error and their motion as flicker.
    let dir = scratch("pan_visibility");
    let json = dir.join("out.json");
    let level = cellar();
    let args = ["--pan", "--size", "160x48", "--frames", "2", "--patch-size", "0.08", "--reference-every", "2"];
    let out =
        headlamp(&[&["bench", "--level", level.as_str()][..], &args, &["--json", json.to_str().unwrap()]].concat());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "bench --pan failed: {}\n{stdout}", String::from_utf8_lossy(&out.stderr));
    assert!(
        stdout.contains("reference: world-fixed patches of at most 8 cm, each pair tested for what stands between"),
        "the report says which reference: {stdout}"
    );
    // Flicker blocks of 4 pixels (1/40 of 160): the error takes blocks that fit inside them.
    assert!(stdout.contains("error vs reference (4x4 blocks)"), "{stdout}");
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(report["reference"]["visibility"], true);
    let errors = report["error_per_frame"].as_array().unwrap();
    assert_eq!(errors.len(), 2);
    let worst = bounds::worst(errors.iter().map(|e| e.as_f64().unwrap_or(f64::NAN)));
    bounds::assert(bounds::at_most("the error of the worst frame", worst, 1.0 - f64::EPSILON));
}

#[test]
fn bench_rejects_bad_input_with_one_line() {
    let dir = scratch("bad");
    let missing = dir.join("nope.gltf");
    let bad_json = dir.join("no_such_dir").join("out.json");
    let cellar = cellar();
    let cases: [(Vec<&str>, &str); 9] = [
        (vec!["bench", "--level", missing.to_str().unwrap()], "nope.gltf"),
        (vec!["bench", "--level", &cellar, "--frames", "0"], "--frames"),
        (vec!["bench", "--level", &cellar, "--set", "gi.split_ratio=9"], "split_ratio"),
        (vec!["bench", "--level", &cellar, "--json", bad_json.to_str().unwrap()], "--json"),
        (vec!["bench", "--level", &cellar, "--target-fps", "5"], "--target-fps"),
        (vec!["bench", "--level", &cellar, "--pan", "--reference-every", "0"], "--reference-every"),
        (vec!["bench", "--level", &cellar, "--pan", "--patch-size", "0"], "--patch-size"),
        (vec!["bench", "--level", &cellar, "--pan", "--walk-cm", "500"], "--walk-cm"),
        (vec!["bench", "--level", &cellar, "--pan", "--lamp", "0,1,2"], "--lamp"),
    ];
    for (args, needle) in cases {
        let out = headlamp(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} should fail");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: expected one line, got:\n{stderr}");
        assert!(stderr.contains(needle), "{args:?}: '{stderr}' does not mention {needle}");
    }
}
