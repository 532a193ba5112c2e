//! The shipped test replays: `replays/NAME.txt` is the hand-written input script,
//! `replays/NAME.replay` the replay `headlamp script` made of it (with its per-tick hashes).
//! `update-goldens` re-makes the replays from their scripts, with the goldens.
//!
//! A script plays the shipped level its leading comments name with a `# level: ID` line (a
//! folder under `levels/`: `# level: gallery`); one that names none plays the Cellar.

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

/// The level a script names on a `# level: ID` line among its leading comment lines (before
/// its first step), if any.
pub fn named_level(script: &str) -> Option<String> {
    script
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map_while(|l| l.strip_prefix('#'))
        .find_map(|comment| Some(comment.trim().strip_prefix("level:")?.trim().to_string()))
}

/// The id of the shipped level `replays/NAME.txt` plays: the one it names, else the Cellar.
pub fn script_level(name: &str) -> String {
    let path = replays_dir().join(format!("{name}.txt"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    named_level(&text).unwrap_or_else(|| "cellar".to_string())
}

/// The replay file `headlamp script` makes of `replays/NAME.txt` (seed 1, default settings), on
/// the level the script plays ([`script_level`]).
pub fn record_script(name: &str) -> Vec<u8> {
    let dir = replays_dir();
    let commands = game::script::read(&dir.join(format!("{name}.txt"))).unwrap_or_else(|e| panic!("{e}"));
    let id = script_level(name);
    let level = crate::load_level(&id);
    let gi = plugin_gi::GiSettings::default();
    let out = dir.join(format!("{name}.replay"));
    let recorder = game::replay_cmd::record_commands(&level, &crate::level_path(&id), &commands, 1, &gi, out).unwrap();
    recorder.writer().to_bytes()
}

/// Opens `replays/NAME.replay` as `headlamp replay` does (its level found by id).
pub fn open(name: &str) -> LoadedReplay {
    LoadedReplay::open(&path(name), None).unwrap_or_else(|e| panic!("{e:#}"))
}

pub fn path(name: &str) -> PathBuf {
    replays_dir().join(format!("{name}.replay"))
}

#[cfg(test)]
mod tests {
    use super::named_level;

    #[test]
    fn a_script_names_its_level_in_its_leading_comments() {
        assert_eq!(named_level("# level: gallery\n# what it does\n60 forward\n").as_deref(), Some("gallery"));
        assert_eq!(named_level("# what it does\n\n#level:hall\n60 forward\n").as_deref(), Some("hall"));
        assert_eq!(named_level("# what it does\n60 forward\n# level: hall\n"), None, "only before the first step");
        assert_eq!(named_level("60 forward\n"), None);
    }
}
