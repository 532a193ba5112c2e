//! One finding of `check`, and how it reads on a line.

use std::path::PathBuf;

use scene::TextPos;
use serde::Serialize;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    Error,
    Warning,
}

/// One finding about a level, placed in the file it is about.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub file: PathBuf,
    pub at: Option<TextPos>,
    pub severity: Severity,
    pub message: String,
}

impl std::fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(at) = self.at {
            write!(f, ":{}:{}", at.line, at.column)?;
        }
        let severity = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        write!(f, ": {severity}: {}", self.message)
    }
}

impl Diagnostic {
    pub fn error(file: impl Into<PathBuf>, at: Option<TextPos>, message: impl Into<String>) -> Self {
        Self { file: file.into(), at, severity: Severity::Error, message: message.into() }
    }

    pub fn warning(file: impl Into<PathBuf>, at: Option<TextPos>, message: impl Into<String>) -> Self {
        Self { file: file.into(), at, severity: Severity::Warning, message: message.into() }
    }
}
