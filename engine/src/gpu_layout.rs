//! Rust twins of WGSL structs. Every struct the CPU writes into a GPU buffer or reads back
//! from one is declared through [`gpu_struct!`](crate::gpu_struct), which records each field's
//! offset and size; the layout tests (engine/tests/gpu_layouts.rs, plugin_gi/tests/
//! gpu_layouts.rs) compare them with the layout naga gives the WGSL struct, so the two cannot
//! drift apart unnoticed. Every other WGSL struct is listed, with the reason it has no twin, in
//! a `GPU_ONLY` list ([`GPU_ONLY`] for the engine's shaders).
//!
//! A twin's field names are the WGSL member names. A `Pod` struct has no implicit padding, so
//! where WGSL aligns a member past the end of the one before, the twin spells the gap out as a
//! field whose name begins with `pad`: the test accepts such a field only over bytes that no
//! (non-`pad`) WGSL member occupies.

use bytemuck::Pod;

use crate::globals::{GlobalsUniform, GpuLight};
use crate::gpu_scene::MaterialUniform;
use crate::passes::PresentUniform;

/// One field of a Rust twin: its name, and where it lies, in bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    pub name: &'static str,
    pub offset: usize,
    pub size: usize,
}

/// A Rust twin's layout and the WGSL struct it mirrors.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Layout {
    /// The Rust struct's name (without its path).
    pub rust: &'static str,
    pub wgsl: &'static str,
    pub size: usize,
    pub fields: Vec<Field>,
}

/// A `#[repr(C)]` Pod struct with the layout of a WGSL struct. Implemented by
/// [`gpu_struct!`](crate::gpu_struct) from the struct's own field list.
pub trait GpuLayout: Pod {
    /// The name of the WGSL struct it mirrors.
    const WGSL: &'static str;

    /// Every field, in declaration order.
    fn fields() -> Vec<Field>;

    fn layout() -> Layout {
        let path = std::any::type_name::<Self>();
        Layout {
            rust: path.rsplit("::").next().unwrap_or(path),
            wgsl: Self::WGSL,
            size: std::mem::size_of::<Self>(),
            fields: Self::fields(),
        }
    }
}

/// Declares a struct and implements [`GpuLayout`] for it from the same field list, so no field
/// can be left out of the layout test. `struct Name as WgslName { … }` names the WGSL struct
/// when it is called differently; the attributes (`#[repr(C)]`, the `Pod` derive) are the
/// caller's, as on any struct.
///
/// ```
/// engine::gpu_struct! {
///     /// `Band` in a shader.
///     #[repr(C)]
///     #[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
///     pub struct BandUniform as Band {
///         pub first_row: u32,
///         pub rows: u32,
///         pub pad: [u32; 2],
///     }
/// }
/// use engine::gpu_layout::GpuLayout;
/// assert_eq!(BandUniform::layout().wgsl, "Band");
/// assert_eq!(BandUniform::fields()[1].offset, 4);
/// ```
#[macro_export]
macro_rules! gpu_struct {
    (
        $(#[$attr:meta])*
        $vis:vis struct $name:ident as $wgsl:ident {
            $( $(#[$field_attr:meta])* $field_vis:vis $field:ident : $ty:ty ),* $(,)?
        }
    ) => {
        $(#[$attr])*
        $vis struct $name {
            $( $(#[$field_attr])* $field_vis $field: $ty ),*
        }

        impl $crate::gpu_layout::GpuLayout for $name {
            const WGSL: &'static str = stringify!($wgsl);

            fn fields() -> ::std::vec::Vec<$crate::gpu_layout::Field> {
                ::std::vec![$($crate::gpu_layout::Field {
                    name: stringify!($field),
                    offset: ::std::mem::offset_of!($name, $field),
                    size: ::std::mem::size_of::<$ty>(),
                }),*]
            }
        }
    };
    // The WGSL struct has the Rust struct's name.
    (
        $(#[$attr:meta])*
        $vis:vis struct $name:ident { $($fields:tt)* }
    ) => {
        $crate::gpu_struct! { $(#[$attr])* $vis struct $name as $name { $($fields)* } }
    };
}

/// The twins of the structs in the engine's shaders (shaders/*.wgsl).
pub fn twins() -> Vec<Layout> {
    vec![GlobalsUniform::layout(), GpuLight::layout(), MaterialUniform::layout(), PresentUniform::layout()]
}

/// The structs in the engine's shaders that have no Rust twin, and why.
pub const GPU_ONLY: &[(&str, &str)] = &[
    ("VertexIn", "vertex input: located by gpu_scene::VERTEX_LAYOUT's attributes (tested), not by its layout"),
    ("InstanceIn", "vertex input: located by gpu_instances::INSTANCE_LAYOUT's attributes (tested), not by its layout"),
    ("VertexOut", "stage IO between vertex and fragment shaders"),
    ("InstanceOut", "stage IO between vertex and fragment shaders"),
    ("FullscreenOut", "stage IO between vertex and fragment shaders"),
    ("GBufferOut", "fragment shader output (render targets)"),
    ("LampOut", "fragment shader output (render targets)"),
    ("Surface", "a function's value, never in a buffer"),
    ("SurfaceReflection", "a function's value, never in a buffer"),
    ("Incident", "a function's value, never in a buffer"),
];
