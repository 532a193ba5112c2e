//! The project's own glTF 2.0 conformance inputs and the tiny glTF writer they are built with.
//!
//! Every sample is declared here in code, so a test can derive what a loader must produce from
//! the same constants, and nothing is read from outside the repository. Dev-only: the scene
//! crate's loader tests and the game's command-line tests use it; it must not depend on `scene`
//! (which dev-depends on it), hence its own base64 encoder.

mod samples;
mod writer;

pub use samples::*;
pub use writer::*;
