//! The shipped test replays: `replays/NAME.txt` is the hand-written input script,
//! `replays/NAME.replay` the replay `headlamp script` made of it (with its per-tick hashes).
//! With `HEADLAMP_UPDATE_GOLDENS=1` the replays are re-made from their scripts, like goldens.

use std::path::PathBuf;

use game::recording::LoadedReplay;

pub fn replays_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/replays"))
}

/// Every script in `replays/`, sorted by name.
pub fn script_names() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(replays_dir())
        .expect("tests/replays")
        .filter_map(|e| {
            let p = e.ok()?.path();
            if p.extension()? != "txt" {
                return None;
            }
            Some(p.file_stem()?.to_string_lossy().into_owned())
        })
        .collect();
    names.sort();
    names
}

/// The replay file `headlamp script` makes of `replays/NAME.txt` (seed 1, default settings).
pub fn record_script(name: &str) -> Vec<u8> {
    let dir = replays_dir();
    let commands = game::script::read(&dir.join(format!("{name}.txt"))).unwrap_or_else(|e| panic!("{e}"));
    let level = crate::cellar();
    let gi = plugin_gi::GiSettings::default();
    let out = dir.join(format!("{name}.replay"));
    let recorder = game::replay_cmd::record_commands(&level, &crate::cellar_path(), &commands, 1, &gi, out).unwrap();
    recorder.writer().to_bytes()
}

/// Opens `replays/NAME.replay` as `headlamp replay` does (its level found by id), first
/// re-making it from its script when goldens are being updated.
pub fn open(name: &str) -> LoadedReplay {
    let path = path(name);
    if crate::updating_goldens() {
        std::fs::write(&path, record_script(name)).unwrap();
    }
    LoadedReplay::open(&path, None).unwrap_or_else(|e| panic!("{e:#}"))
}

pub fn path(name: &str) -> PathBuf {
    replays_dir().join(format!("{name}.replay"))
}
