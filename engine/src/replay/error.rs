use std::fmt;
use std::path::{Path, PathBuf};

/// Why a replay file cannot be used, naming the file.
#[derive(Debug)]
pub struct ReplayError {
    pub path: PathBuf,
    pub kind: ReplayErrorKind,
}

#[derive(Debug)]
pub enum ReplayErrorKind {
    Io(std::io::Error),
    NotAReplay,
    UnknownVersion(u32),
    /// The file ends before the header or the ticks it announces do.
    Truncated {
        needed: u64,
        found: u64,
    },
    TrailingBytes {
        expected: u64,
        found: u64,
    },
    ChecksumMismatch {
        stored: u64,
        computed: u64,
    },
    BadHeader(String),
}

impl ReplayError {
    pub fn new(path: &Path, kind: ReplayErrorKind) -> Self {
        Self { path: path.to_owned(), kind }
    }
}

impl fmt::Display for ReplayError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.path.display())?;
        match &self.kind {
            ReplayErrorKind::Io(e) => write!(f, "{e}"),
            ReplayErrorKind::NotAReplay => write!(f, "not a Headlamp replay (the file does not start with HLREPLAY)"),
            ReplayErrorKind::UnknownVersion(v) => write!(
                f,
                "replay format version {v} is not one this build reads (it reads version {})",
                super::FORMAT_VERSION
            ),
            ReplayErrorKind::Truncated { needed, found } => {
                write!(f, "truncated: the file ends after {found} bytes, its header needs at least {needed}")
            }
            ReplayErrorKind::TrailingBytes { expected, found } => {
                write!(f, "corrupted: the header announces {expected} bytes but the file has {found}")
            }
            ReplayErrorKind::ChecksumMismatch { stored, computed } => write!(
                f,
                "corrupted: checksum {computed:016x} does not match the stored {stored:016x} (the file was damaged or edited)"
            ),
            ReplayErrorKind::BadHeader(what) => write!(f, "corrupted header: {what}"),
        }
    }
}

impl std::error::Error for ReplayError {}
