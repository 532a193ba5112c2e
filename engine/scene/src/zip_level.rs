//! A level packed as a `.zip` of its folder, read in place (never unpacked to disk).
//!
//! The archive holds the folder's files either at its root (`level.toml`, `scene.gltf`, …) or
//! under one top folder (`gallery/level.toml`, as zipping the folder itself gives). Inside it,
//! files are named as if the archive were that folder: `levels/gallery.zip/scene.gltf`, so every
//! error names the archive and the member. A member name that leaves the folder (`..`, an
//! absolute path) is refused, as in a folder; an archive has no symlinks to follow.

use std::io::{Cursor, Read};
use std::path::{Component, Path, PathBuf};

use crate::error::{LoadError, LoadErrorKind};
use crate::limits::MAX_FILE_BYTES;

/// Most members an archive may list; a level has tens.
const MAX_MEMBERS: usize = 65_536;

pub(crate) struct ZipLevel {
    /// The archive file, which also stands for the level folder in every path.
    path: PathBuf,
    archive: zip::ZipArchive<Cursor<Vec<u8>>>,
    /// "" or "top/": where the level folder's files sit inside the archive.
    prefix: String,
}

/// Whether `path` names a zip archive (by extension, any case).
pub(crate) fn is_zip(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("zip"))
}

impl ZipLevel {
    /// Opens the archive (read whole: levels are small, and a file read once cannot change
    /// under the load) and finds its level.toml.
    pub fn open(path: &Path, bytes: Vec<u8>) -> Result<Self, LoadError> {
        let corrupt =
            |msg: String| LoadError::new(path, LoadErrorKind::Io(format!("not a readable zip archive: {msg}")));
        let archive = zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| corrupt(e.to_string()))?;
        if archive.len() > MAX_MEMBERS {
            return Err(LoadError::too_large(
                path,
                format!("{} files in the archive (limit {MAX_MEMBERS})", archive.len()),
            ));
        }
        let tomls: Vec<&str> = archive.file_names().filter(|n| n.rsplit('/').next() == Some("level.toml")).collect();
        let prefix = if tomls.contains(&"level.toml") {
            String::new()
        } else {
            match tomls.as_slice() {
                [one] if one.matches('/').count() == 1 => one.trim_end_matches("level.toml").to_owned(),
                [] => return Err(LoadError::new(path.join("level.toml"), LoadErrorKind::NotFound)),
                _ => return Err(corrupt(format!("it holds several levels ({})", tomls.join(", ")))),
            }
        };
        Ok(Self { path: path.to_path_buf(), archive, prefix })
    }

    /// `written` (relative to folder `base`, a path under the archive) as a path under the
    /// archive, or an error when it leaves the level.
    pub fn resolve(&self, referrer: &Path, base: &Path, written: &str) -> Result<PathBuf, LoadError> {
        let escapes = || LoadError::new(referrer, LoadErrorKind::EscapesFolder(written.to_string()));
        let inside = base.strip_prefix(&self.path).map_err(|_| escapes())?;
        let mut parts: Vec<String> = Vec::new();
        for c in inside.components().chain(Path::new(written).components()) {
            match c {
                Component::Normal(p) => parts.push(p.to_string_lossy().into_owned()),
                Component::CurDir => {}
                Component::ParentDir => {
                    parts.pop().ok_or_else(escapes)?;
                }
                Component::RootDir | Component::Prefix(_) => return Err(escapes()),
            }
        }
        Ok(parts.iter().fold(self.path.clone(), |p, part| p.join(part)))
    }

    /// The bytes of the member at `path` (a path under the archive).
    pub fn read(&mut self, path: &Path) -> Result<Vec<u8>, LoadError> {
        let member = path
            .strip_prefix(&self.path)
            .ok()
            .map(|p| p.components().map(|c| c.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("/"))
            .ok_or_else(|| LoadError::new(path, LoadErrorKind::NotFound))?;
        let name = format!("{}{member}", self.prefix);
        let mut file = match self.archive.by_name(&name) {
            Ok(f) => f,
            Err(zip::result::ZipError::FileNotFound) => return Err(LoadError::new(path, LoadErrorKind::NotFound)),
            Err(e) => return Err(LoadError::new(path, LoadErrorKind::Io(e.to_string()))),
        };
        if file.is_dir() {
            return Err(LoadError::new(path, LoadErrorKind::Io("is a directory, expected a file".into())));
        }
        if file.size() > MAX_FILE_BYTES {
            return Err(LoadError::too_large(path, format!("file is {} bytes (limit {MAX_FILE_BYTES})", file.size())));
        }
        // The stated size is not trusted further than the limit: a member that inflates past
        // it is refused rather than filling memory.
        let mut bytes = Vec::with_capacity(file.size().min(1 << 26) as usize);
        (&mut file).take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes).map_err(|e| LoadError::io(path, &e))?;
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(LoadError::too_large(path, format!("file inflates past {MAX_FILE_BYTES} bytes")));
        }
        Ok(bytes)
    }
}
