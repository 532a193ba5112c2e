//! `cargo run --release -p headlamp-tests --bin update-goldens [NAME_PREFIX...]`: the one way
//! to re-make the frame tests' goldens. It re-records every test replay from its script
//! (`replays/NAME.txt` → `NAME.replay`: a change to the simulation or a level changes their
//! hashes), then renders every golden frame whose name starts with one of the prefixes (all
//! without one) into `goldens/`, removing goldens no shot renders any more. Look at each frame
//! it writes before committing it.

use std::process::ExitCode;

use headlamp_tests::frames::{self, LEVEL_SHOTS, REPLAY_SHOTS};
use headlamp_tests::{golden_path, goldens_dir, load_level, replay_files};

fn main() -> ExitCode {
    match run(std::env::args().skip(1).collect()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("update-goldens: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(prefixes: Vec<String>) -> Result<(), String> {
    if let Some(flag) = prefixes.iter().find(|p| p.starts_with('-')) {
        return Err(format!("unknown option '{flag}' (usage: update-goldens [NAME_PREFIX...])"));
    }
    let names = frames::golden_names();
    let wanted = |name: &str| prefixes.is_empty() || prefixes.iter().any(|p| name.starts_with(p.as_str()));
    if let Some(p) = prefixes.iter().find(|p| !names.iter().any(|n| n.starts_with(p.as_str()))) {
        return Err(format!("no golden is named '{p}…' (they are: {})", names.join(", ")));
    }

    for name in replay_files::script_names() {
        let path = replay_files::path(&name);
        std::fs::write(&path, replay_files::record_script(&name)).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("{}: recorded from its script", path.display());
    }

    let write = |name: &str, image: &image::RgbaImage| -> Result<(), String> {
        let path = golden_path(name);
        game::golden::write(&path, image)?;
        println!("{}: written (mean luminance {:.4})", path.display(), game::golden::mean_luminance(image));
        Ok(())
    };
    let gpu = engine::gpu::Gpu::lavapipe().map_err(|e| e.to_string())?;
    for (id, shots) in LEVEL_SHOTS {
        if !shots.iter().any(|s| wanted(s.name)) {
            continue;
        }
        let level = load_level(id);
        for shot in shots.iter().filter(|s| wanted(s.name)) {
            write(shot.name, &frames::render_level_shot(&gpu, &level, shot))?;
        }
    }
    for (name, ticks) in REPLAY_SHOTS {
        let ticks: Vec<u32> = ticks.iter().copied().filter(|&t| wanted(&frames::replay_shot_name(name, t))).collect();
        if ticks.is_empty() {
            continue;
        }
        for (t, image) in frames::render_replay_ticks(name, &ticks) {
            write(&frames::replay_shot_name(name, t), &image)?;
        }
    }

    if prefixes.is_empty() {
        let dir = goldens_dir();
        let entries = std::fs::read_dir(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        for path in entries.filter_map(|e| e.ok().map(|e| e.path())) {
            let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or_default();
            let golden = path.extension().is_some_and(|x| x == "png") && !stem.contains('.');
            if golden && !names.iter().any(|n| n == stem) {
                std::fs::remove_file(&path).map_err(|e| format!("{}: {e}", path.display()))?;
                println!("{}: removed (no shot renders it)", path.display());
            }
        }
    }
    Ok(())
}
