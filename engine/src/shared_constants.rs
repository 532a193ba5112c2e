//! Numbers that Rust and WGSL both count with, named on both sides: a WGSL `const` that has a
//! Rust constant's value ([`SharedConstant`]), and the workgroup size of a compute entry point
//! that a Rust dispatch divides by ([`Workgroup`]). Each crate lists its own (the engine's in
//! [`CONSTANTS`]); the tests (engine/tests/shared_constants.rs, plugin_gi/tests/
//! shared_constants.rs) read the WGSL with naga and compare, so neither side can change alone.

/// A WGSL `const` that must have a Rust constant's value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SharedConstant {
    /// The WGSL constant's name, and the file that declares it (named as in the crate's list
    /// of shaders or includes).
    pub wgsl: &'static str,
    pub file: &'static str,
    /// The Rust constant as written (for messages), and its value.
    pub rust: &'static str,
    pub value: i64,
}

/// A compute entry point whose workgroup size a Rust dispatch counts with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Workgroup {
    pub file: &'static str,
    pub entry: &'static str,
    pub size: [u32; 3],
    /// The size as the Rust writes it (for messages).
    pub rust: &'static str,
}

/// `shared_constant!("file.wgsl", WGSL_NAME = rust::CONSTANT)`: a [`SharedConstant`].
#[macro_export]
macro_rules! shared_constant {
    ($file:literal, $wgsl:ident = $rust:path) => {
        $crate::shared_constants::SharedConstant {
            wgsl: stringify!($wgsl),
            file: $file,
            rust: stringify!($rust),
            value: $rust as i64,
        }
    };
}

/// `workgroup!("file.wgsl", "entry", [x, y, z])`: a [`Workgroup`] of the size the Rust
/// expressions `x`, `y`, `z` give.
#[macro_export]
macro_rules! workgroup {
    ($file:literal, $entry:literal, [$x:expr, $y:expr, $z:expr]) => {
        $crate::shared_constants::Workgroup {
            file: $file,
            entry: $entry,
            size: [$x, $y, $z],
            rust: stringify!([$x, $y, $z]),
        }
    };
}

/// The engine's: the codes its uniforms carry.
pub const CONSTANTS: &[SharedConstant] = &[
    shared_constant!("common.wgsl", LIGHT_POINT = crate::globals::LIGHT_POINT),
    shared_constant!("common.wgsl", LIGHT_SPOT = crate::globals::LIGHT_SPOT),
    shared_constant!("common.wgsl", LIGHT_DIRECTIONAL = crate::globals::LIGHT_DIRECTIONAL),
    shared_constant!("present.wgsl", VIEW_RADIANCE = crate::passes::VIEW_RADIANCE),
    shared_constant!("present.wgsl", VIEW_COLOR = crate::passes::VIEW_COLOR),
    shared_constant!("present.wgsl", VIEW_NORMAL = crate::passes::VIEW_NORMAL),
    shared_constant!("present.wgsl", VIEW_DEPTH = crate::passes::VIEW_DEPTH),
];
