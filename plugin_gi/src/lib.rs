//! Deferred rendered radiosity from first-person perspective: the global-illumination plugin.
//!
//! It registers its passes through `engine::plugin::Plugin` and reads the engine's G-buffer by
//! the names in `engine::passes::names`, adding indirect light into the HDR target.

mod settings;

pub use settings::{FieldInfo, GiSettings};
