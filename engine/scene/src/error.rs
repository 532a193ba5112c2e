//! The one error type every loader returns.
//!
//! A modder sees these messages in a terminal, so each is a single line that starts with the
//! file at fault and then says what is wrong with it: `levels/x/scene.gltf: corrupt glTF: ...`.
//! The problem is kept as a structured [`LoadErrorKind`] so tests and tools can match on it.

use std::fmt;
use std::path::{Path, PathBuf};

/// A failure to load a level, scene, or texture, naming the file at fault and, in a text file
/// such as level.toml, where in it: `level.toml:4:1: invalid level: unknown field ...`, the
/// shape compilers use, so editors and `headlamp check --json` can jump to it.
#[derive(Debug, thiserror::Error)]
#[error("{}{}: {kind}", path.display(), at.map(|p| format!(":{}:{}", p.line, p.column)).unwrap_or_default())]
pub struct LoadError {
    /// The file the problem is in (or the file that was missing).
    pub path: PathBuf,
    /// Where in the file, when it is text and the place is known.
    pub at: Option<TextPos>,
    pub kind: LoadErrorKind,
}

/// Something a load accepted that is likely not what the author meant, or a feature of the
/// file that Headlamp ignores: logged when the game loads the level, listed by
/// `headlamp check`. Never silence, never a failure.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}{}: {message}", path.display(), at.map(|p| format!(":{}:{}", p.line, p.column)).unwrap_or_default())]
pub struct LoadWarning {
    pub path: PathBuf,
    pub at: Option<TextPos>,
    pub message: String,
}

/// A place in a text file: 1-based line and column (in characters).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextPos {
    pub line: usize,
    pub column: usize,
}

impl TextPos {
    /// The position of byte `offset` of `text` (clamped to its end, and back to a character
    /// boundary).
    pub fn of_offset(text: &str, offset: usize) -> Self {
        let mut offset = offset.min(text.len());
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &text[..offset];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Self { line: before.matches('\n').count() + 1, column: before[line_start..].chars().count() + 1 }
    }
}

/// What went wrong. Every message is one line (see [`one_line`]).
#[derive(Debug, thiserror::Error)]
pub enum LoadErrorKind {
    #[error("file not found")]
    NotFound,
    #[error("cannot read file: {0}")]
    Io(String),
    #[error("unknown scene file extension '{0}' (expected .gltf, .glb or .obj)")]
    UnknownExtension(String),
    #[error("corrupt glTF: {0}")]
    CorruptGltf(String),
    #[error("unsupported glTF: {0}")]
    UnsupportedGltf(String),
    #[error("corrupt OBJ: {0}")]
    CorruptObj(String),
    #[error("corrupt MTL: {0}")]
    CorruptMtl(String),
    #[error("cannot decode image: {0}")]
    Image(String),
    #[error("invalid TOML: {0}")]
    TomlSyntax(String),
    /// Well-formed TOML that does not follow the level.toml schema (unknown field, bad value).
    #[error("invalid level: {0}")]
    LevelSchema(String),
    /// A value that is the right type but makes no sense (negative power, outer <= inner...).
    #[error("invalid level: {0}")]
    InvalidLevel(String),
    #[error("path '{0}' escapes the level folder")]
    EscapesFolder(String),
    /// Absurd sizes are refused up front rather than exhausting memory.
    #[error("too large: {0}")]
    TooLarge(String),
}

impl LoadError {
    pub fn new(path: impl Into<PathBuf>, kind: LoadErrorKind) -> Self {
        Self { path: path.into(), at: None, kind }
    }

    /// The same error, placed at `at` in its file.
    pub fn at(self, at: Option<TextPos>) -> Self {
        Self { at, ..self }
    }

    /// Maps an I/O error on `path`, keeping "not found" distinct because it is the common case.
    pub fn io(path: &Path, err: &std::io::Error) -> Self {
        let kind = match err.kind() {
            std::io::ErrorKind::NotFound => LoadErrorKind::NotFound,
            _ => LoadErrorKind::Io(one_line(err)),
        };
        Self::new(path, kind)
    }

    pub(crate) fn gltf(path: &Path, msg: impl fmt::Display) -> Self {
        Self::new(path, LoadErrorKind::CorruptGltf(one_line(msg)))
    }

    pub(crate) fn too_large(path: &Path, msg: impl fmt::Display) -> Self {
        Self::new(path, LoadErrorKind::TooLarge(one_line(msg)))
    }

    pub(crate) fn level(path: &Path, msg: impl fmt::Display) -> Self {
        Self::new(path, LoadErrorKind::InvalidLevel(one_line(msg)))
    }
}

/// Collapses a (possibly multi-line) message from a dependency into one line, so that the
/// "file: problem" shape of every error survives third-party Display impls.
pub(crate) fn one_line(msg: impl fmt::Display) -> String {
    let s = msg.to_string();
    let mut out = String::with_capacity(s.len());
    for part in s.split(['\n', '\r']).map(str::trim).filter(|p| !p.is_empty()) {
        if !out.is_empty() {
            out.push(' ');
        }
        out.push_str(part);
    }
    out
}
