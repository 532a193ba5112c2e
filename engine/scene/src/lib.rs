//! The scene the renderer draws, and the loaders that build it from files.
//!
//! Everything here is plain CPU data in SI units (metres, radians, watts per steradian),
//! +Y up, right-handed, as glTF. Geometry is baked to world space at load time: levels are
//! static, and a flat list of triangles is what both the renderer and collision want.
//!
//! Entry points: [`load_level`] (a level folder or a bare scene file), [`load_scene_file`]
//! (by extension), [`load_gltf`], [`load_obj`], [`load_texture`]. Every failure is a
//! [`LoadError`] naming the file and the problem on one line; no input makes them panic.

mod distribution_image;
mod error;
mod geometry;
mod gltf_accessor;
mod gltf_container;
mod gltf_loader;
mod gltf_unsupported;
mod headlamp_profile;
mod ies;
mod image_loader;
mod level;
mod level_keys;
mod level_toml;
pub mod limits;
mod obj_loader;
mod sources;
mod spawn;
mod toml_place;
mod types;
mod zip_level;

pub use distribution_image::DistributionImage;
pub use error::{LoadError, LoadErrorKind, LoadWarning, TextPos};
pub use gltf_container::{encode_base64, pack_glb};
pub use gltf_loader::load_gltf;
pub use headlamp_profile::{HeadlampProfile, IntensityDistribution};
pub use ies::{ies_texture_size, IesProfile, MAX_IES_ANGLES, MAX_IES_BYTES, MAX_IES_VALUES};
pub use image_loader::{load_texture, texture_from_image};
pub use level::{load_level, load_scene_file, Level};
pub use level_keys::{KeyDoc, LEVEL_KEYS, LEVEL_TABLES};
pub use obj_loader::load_obj;
pub use sources::Fnv1a;
pub use spawn::{Spawn, DEFAULT_EYE_HEIGHT};
pub use toml_place::key_place;
pub use types::*;
