//! The levels the level menu offers: the shipped ones, the user's levels folder and any
//! `--levels-dir`, each a folder holding `level.toml` or a `.zip` of one. Every level is loaded
//! and checked as `headlamp check` does, so a broken one is listed with its error instead of
//! failing when picked.

use std::path::{Path, PathBuf};

use crate::check::{self, Severity};

/// One level found.
#[derive(Clone, Debug, PartialEq)]
pub struct ListedLevel {
    pub path: PathBuf,
    pub name: String,
    pub description: String,
    /// "shipped", or the folder it was found in.
    pub location: String,
    /// The first error `check` finds; None: playable.
    pub error: Option<String>,
    /// What the level's files hash to (0 when it does not load): its thumbnail's cache key.
    pub content_hash: u64,
}

/// Where the user's own levels go: `$XDG_DATA_HOME/headlamp/levels` (else
/// `~/.local/share/headlamp/levels`), the platform's application-data folder elsewhere.
pub fn user_levels_dir() -> Option<PathBuf> {
    data_dir(|name| std::env::var_os(name)).map(|d| d.join("headlamp").join("levels"))
}

/// Where thumbnails are cached: `$XDG_CACHE_HOME/headlamp/thumbnails` (else `~/.cache/…`).
pub fn thumbnail_cache_dir() -> Option<PathBuf> {
    let var = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty()).map(PathBuf::from);
    let base = if cfg!(windows) {
        var("LOCALAPPDATA")
    } else if cfg!(target_os = "macos") {
        var("HOME").map(|home| home.join("Library").join("Caches"))
    } else {
        var("XDG_CACHE_HOME").filter(|p| p.is_absolute()).or_else(|| var("HOME").map(|home| home.join(".cache")))
    };
    Some(base?.join("headlamp").join("thumbnails"))
}

fn data_dir(var: impl Fn(&str) -> Option<std::ffi::OsString>) -> Option<PathBuf> {
    let set = |name: &str| var(name).filter(|v| !v.is_empty()).map(PathBuf::from);
    if cfg!(windows) {
        set("APPDATA")
    } else if cfg!(target_os = "macos") {
        set("HOME").map(|home| home.join("Library").join("Application Support"))
    } else {
        // The XDG spec says to ignore a relative XDG_DATA_HOME.
        set("XDG_DATA_HOME").filter(|p| p.is_absolute()).or_else(|| set("HOME").map(|home| home.join(".local/share")))
    }
}

/// The folders to look in: the shipped levels, the user's, then `extra`, each once.
pub fn level_dirs(extra: &[PathBuf]) -> Vec<(PathBuf, String)> {
    let mut dirs = Vec::new();
    if let Some(shipped) = crate::default_level().parent() {
        dirs.push((shipped.to_path_buf(), "shipped".to_owned()));
    }
    dirs.extend(user_levels_dir().map(|d| {
        let label = d.display().to_string();
        (d, label)
    }));
    dirs.extend(extra.iter().map(|d| (d.clone(), d.display().to_string())));
    let mut seen = Vec::new();
    dirs.retain(|(d, _)| {
        let key = d.canonicalize().unwrap_or_else(|_| d.clone());
        !seen.contains(&key) && {
            seen.push(key);
            true
        }
    });
    dirs
}

/// Every level in `dirs` (name order within each folder), loaded and checked. A folder that
/// does not exist has none; one that cannot be read is a listed error.
pub fn scan(dirs: &[(PathBuf, String)]) -> Vec<ListedLevel> {
    let mut out = Vec::new();
    for (dir, location) in dirs {
        let entries = match std::fs::read_dir(dir) {
            Ok(entries) => entries,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => continue,
            Err(e) => {
                out.push(unreadable(dir, location, format!("{}: cannot list the folder: {e}", dir.display())));
                continue;
            }
        };
        let mut paths: Vec<PathBuf> =
            entries.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| is_level(p)).collect();
        paths.sort();
        out.extend(paths.iter().map(|p| listed(p, location)));
    }
    out
}

/// A folder with a level.toml, or a .zip.
fn is_level(path: &Path) -> bool {
    path.join("level.toml").is_file()
        || (path.is_file() && path.extension().is_some_and(|e| e.eq_ignore_ascii_case("zip")))
}

fn listed(path: &Path, location: &str) -> ListedLevel {
    let level = match scene::load_level(path) {
        Ok(level) => level,
        Err(e) => return unreadable(path, location, check::load_error(&e).to_string()),
    };
    let error = check::check_loaded(&level).into_iter().find(|d| d.severity == Severity::Error).map(|d| d.to_string());
    ListedLevel {
        path: path.to_path_buf(),
        name: level.name,
        description: level.description,
        location: location.to_owned(),
        error,
        content_hash: level.content_hash,
    }
}

fn unreadable(path: &Path, location: &str, error: String) -> ListedLevel {
    ListedLevel {
        path: path.to_path_buf(),
        name: path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default(),
        description: String::new(),
        location: location.to_owned(),
        error: Some(error),
        content_hash: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_data_folder_follows_xdg_then_home() {
        if cfg!(any(windows, target_os = "macos")) {
            return;
        }
        let vars = |pairs: &'static [(&'static str, &'static str)]| {
            move |name: &str| pairs.iter().find(|(k, _)| *k == name).map(|(_, v)| (*v).into())
        };
        assert_eq!(data_dir(vars(&[("XDG_DATA_HOME", "/d"), ("HOME", "/h")])), Some(PathBuf::from("/d")));
        assert_eq!(data_dir(vars(&[("XDG_DATA_HOME", "rel"), ("HOME", "/h")])), Some(PathBuf::from("/h/.local/share")));
        assert_eq!(data_dir(vars(&[])), None);
    }

    #[test]
    fn the_shipped_levels_are_listed_playable_and_a_broken_one_with_its_error() {
        let dir = std::env::temp_dir().join(format!("headlamp-level-list-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("broken")).unwrap();
        std::fs::write(dir.join("broken/level.toml"), "name = \"Broken\"\nscene = \"missing.gltf\"\n").unwrap();
        std::fs::write(dir.join("notes.txt"), "not a level").unwrap();
        let shipped = crate::default_level().parent().unwrap().to_path_buf();
        let found = scan(&[(shipped, "shipped".into()), (dir.clone(), "mine".into()), (dir.join("none"), "x".into())]);
        let cellar = found.iter().find(|l| l.name == "The Cellar").expect("the Cellar is shipped");
        assert_eq!((cellar.location.as_str(), &cellar.error), ("shipped", &None));
        assert_ne!(cellar.content_hash, 0);
        let broken = found.iter().find(|l| l.location == "mine").expect("the broken level is listed");
        assert_eq!(broken.name, "broken");
        assert!(
            broken.error.as_deref().is_some_and(|e| e.contains("missing.gltf: error: file not found")),
            "{broken:?}"
        );
        assert_eq!(found.iter().filter(|l| l.location == "mine").count(), 1, "notes.txt is not a level");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
