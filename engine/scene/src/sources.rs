//! Every file a load touches goes through [`Sources`]: it reads the bytes, refuses paths that
//! leave the level folder, and folds each file into the level's content hash.
//!
//! Routing all reads through one place is what makes `Level::content_hash` trustworthy (no file
//! can be loaded without being hashed) and the folder confinement impossible to forget.

use std::path::{Component, Path, PathBuf};

use crate::error::{LoadError, LoadErrorKind, LoadWarning, TextPos};
use crate::limits::{read_file, MAX_FILE_BYTES, MAX_SCENE_TEXTURE_BYTES};
use crate::zip_level::ZipLevel;

/// 64-bit FNV-1a: tiny, dependency-free and stable across platforms and Rust versions, which
/// is what a hash stored in replay files needs (std's `DefaultHasher` promises none of that).
#[derive(Clone, Copy, Debug)]
pub struct Fnv1a(u64);

impl Default for Fnv1a {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv1a {
    pub fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    pub fn finish(&self) -> u64 {
        self.0
    }
}

/// The files a load has read, in order, and their running hash.
#[derive(Default)]
pub(crate) struct Sources {
    /// Canonical level folder; when set, every referenced path must resolve inside it.
    root: Option<PathBuf>,
    /// A zipped level: every file is read from the archive instead of the disk.
    zip: Option<ZipLevel>,
    files: Vec<PathBuf>,
    hash: Fnv1a,
    warnings: Vec<LoadWarning>,
    /// Bytes of the textures decoded so far, against [`MAX_SCENE_TEXTURE_BYTES`].
    texture_bytes: u64,
}

impl Sources {
    pub fn new(root: Option<PathBuf>) -> Self {
        Self { root, ..Self::default() }
    }

    /// Sources that read a zipped level from the archive at `path`, read and hashed whole
    /// here (as the level's only file: its members are its content).
    pub fn zipped(path: &Path) -> Result<Self, LoadError> {
        let mut sources = Self::default();
        let bytes = sources.read(path)?;
        sources.zip = Some(ZipLevel::open(path, bytes)?);
        Ok(sources)
    }

    /// Reads a whole file and adds it to the hash. Each file is hashed as its length (u64 LE)
    /// then its bytes, so that moving bytes from one file to the next changes the hash; a file
    /// read twice is hashed once.
    pub fn read(&mut self, path: &Path) -> Result<Vec<u8>, LoadError> {
        // A zipped level's content is the archive, hashed whole when it was opened.
        if let Some(zip) = &mut self.zip {
            return zip.read(path);
        }
        let bytes = read_file(path, MAX_FILE_BYTES).map_err(|e| match e.kind() {
            std::io::ErrorKind::InvalidData => LoadError::too_large(path, e),
            _ => LoadError::io(path, &e),
        })?;
        if !self.files.iter().any(|f| f == path) {
            self.hash.write(&(bytes.len() as u64).to_le_bytes());
            self.hash.write(&bytes);
            self.files.push(path.to_path_buf());
        }
        Ok(bytes)
    }

    /// Resolves a path written inside `referrer` (relative to folder `base`) and, inside a
    /// level, checks that it stays in the level folder. Symlinks are followed before the check
    /// (canonicalisation), so a link pointing outside is refused too.
    pub fn resolve(&self, referrer: &Path, base: &Path, written: &str) -> Result<PathBuf, LoadError> {
        if written.trim().is_empty() {
            return Err(LoadError::new(referrer, LoadErrorKind::Io("empty file path".into())));
        }
        if let Some(zip) = &self.zip {
            return zip.resolve(referrer, base, written);
        }
        let rel = Path::new(written);
        let Some(root) = &self.root else {
            // A bare scene file is trusted like any file the user opens: absolute paths allowed.
            return Ok(base.join(rel));
        };
        let escapes = || LoadError::new(referrer, LoadErrorKind::EscapesFolder(written.to_string()));
        if rel.components().any(|c| matches!(c, Component::Prefix(_) | Component::RootDir)) {
            return Err(escapes());
        }
        let joined = base.join(rel);
        let canonical = joined.canonicalize().map_err(|e| LoadError::io(&joined, &e))?;
        if !canonical.starts_with(root) {
            return Err(escapes());
        }
        Ok(joined)
    }

    pub fn hash(&self) -> u64 {
        self.hash.finish()
    }

    /// Notes what the load accepted but the author should hear about; logged at once (so
    /// `play` shows it in the terminal) and kept for [`crate::Level::warnings`]. A warning
    /// repeated word for word is kept once.
    pub fn warn(&mut self, path: &Path, at: Option<TextPos>, message: impl Into<String>) {
        let warning = LoadWarning { path: path.to_path_buf(), at, message: message.into() };
        if !self.warnings.contains(&warning) {
            log::warn!("{warning}");
            self.warnings.push(warning);
        }
    }

    pub fn take_warnings(&mut self) -> Vec<LoadWarning> {
        std::mem::take(&mut self.warnings)
    }

    /// Counts a decoded texture against the scene's budget: a scene of many large textures is
    /// refused at the one that passes it, naming it, instead of exhausting memory.
    pub fn hold_texture(&mut self, path: &Path, texture: &crate::Texture) -> Result<(), LoadError> {
        self.texture_bytes += texture.rgba8.len() as u64;
        if self.texture_bytes > MAX_SCENE_TEXTURE_BYTES {
            return Err(LoadError::too_large(
                path,
                format!(
                    "{} ({}x{}) takes the scene's textures past {MAX_SCENE_TEXTURE_BYTES} bytes",
                    texture.name, texture.width, texture.height
                ),
            ));
        }
        Ok(())
    }

    /// Every file the load read, in order (for a zipped level, the archive): what to watch
    /// for edits.
    pub fn files(&self) -> &[PathBuf] {
        &self.files
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn textures_past_the_scenes_budget_are_refused_naming_the_one_that_passes_it() {
        let mut sources = Sources::default();
        // Zeroed allocations are not touched: four of the largest textures cost nothing here.
        let largest = |name: &str| crate::Texture {
            name: name.into(),
            width: 8192,
            height: 8192,
            rgba8: vec![0; 8192 * 8192 * 4],
        };
        for i in 0..4 {
            sources.hold_texture(Path::new("scene.gltf"), &largest(&format!("t{i}"))).unwrap();
        }
        let e = sources.hold_texture(Path::new("scene.gltf"), &largest("t4")).unwrap_err().to_string();
        assert!(e.starts_with("scene.gltf: too large: t4 (8192x8192) takes the scene's textures past"), "{e}");
    }
}
