//! Live reload's trigger: the files a level was loaded from, polled for edits.
//!
//! Polling the few files a level read (one `stat` each, four times a second) sees a save
//! however the editor makes it — written in place, or a new file renamed over the old, which a
//! watch on the old file would lose — needs no platform watcher, and costs nothing measurable.

use std::path::PathBuf;
use std::time::SystemTime;

/// How often the files are looked at, s.
pub const POLL_SECONDS: f32 = 0.25;

/// A file's modification time and size; None while it is missing.
type Stamp = Option<(SystemTime, u64)>;

pub struct FileWatch {
    files: Vec<PathBuf>,
    seen: Vec<Stamp>,
    since_poll: f32,
    /// Something changed at the last poll: reload once it holds still for a poll, so a save
    /// written in several steps is read once, whole.
    settling: bool,
}

impl FileWatch {
    pub fn new(files: Vec<PathBuf>) -> Self {
        let seen = files.iter().map(|f| stamp(f)).collect();
        Self { files, seen, since_poll: 0.0, settling: false }
    }

    /// Also watches `file` (e.g. one a failed load could not find, so creating it reloads).
    pub fn add(&mut self, file: PathBuf) {
        if !self.files.contains(&file) {
            self.seen.push(stamp(&file));
            self.files.push(file);
        }
    }

    pub fn files(&self) -> &[PathBuf] {
        &self.files
    }

    /// Advances the clock by `dt` seconds; true when the files changed and have since held
    /// still: time to reload (within 2 × [`POLL_SECONDS`] of the last write).
    pub fn poll(&mut self, dt: f32) -> bool {
        self.since_poll += dt;
        if self.since_poll < POLL_SECONDS {
            return false;
        }
        self.since_poll = 0.0;
        let now: Vec<Stamp> = self.files.iter().map(|f| stamp(f)).collect();
        if now != self.seen {
            self.seen = now;
            self.settling = true;
            return false;
        }
        std::mem::take(&mut self.settling)
    }
}

fn stamp(path: &std::path::Path) -> Stamp {
    let meta = std::fs::metadata(path).ok()?;
    Some((meta.modified().ok()?, meta.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_save_is_reported_once_after_it_holds_still() {
        let dir = std::env::temp_dir().join(format!("headlamp-level-watch-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("level.toml");
        std::fs::write(&file, "a").unwrap();
        let mut watch = FileWatch::new(vec![file.clone()]);
        assert!(!watch.poll(1.0), "nothing changed");
        std::fs::write(&file, "a longer file").unwrap();
        assert!(!watch.poll(0.1), "not polled yet");
        assert!(!watch.poll(POLL_SECONDS), "changed: wait one poll for it to hold still");
        assert!(watch.poll(POLL_SECONDS), "held still: reload");
        assert!(!watch.poll(POLL_SECONDS), "once");
        // A file that appears (a missing texture created) counts as a change.
        let missing = dir.join("wall.png");
        watch.add(missing.clone());
        std::fs::write(&missing, "png").unwrap();
        assert!(!watch.poll(POLL_SECONDS));
        assert!(watch.poll(POLL_SECONDS));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
