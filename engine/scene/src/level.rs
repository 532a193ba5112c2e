//! The level contract: a folder with `level.toml` and a scene, or a bare scene file.
//!
//! `level.toml` (all SI units, every field but `name` and `scene` optional):
//!
//! ```toml
//! name = "The Cellar"
//! description = "Four rooms..."   # one line, shown under the name in the level menu
//! scene = "scene.gltf"            # relative to the folder; may not leave it
//! exposure = 8.0                  # > 0; absent = renderer picks
//!
//! [spawn]                         # absent = renderer frames the scene
//! position = [0.0, 0.0, 4.0]      # the player's FEET, metres
//! yaw_deg = 0.0                   # 0 looks down -Z, positive turns left (CCW seen from above)
//! pitch_deg = 0.0                 # positive looks up, within [-90, 90]
//!
//! [headlamp]
//! power = 1.0                     # P in I(w) = P * T(uv(w)), W/sr, >= 0
//! fov_deg = 60.0                  # vertical FOV of the lamp frustum, in (1, 179)
//! profile = "uniform"             # "uniform" | "spot" | path to a PNG/EXR intensity texture
//!                                 # | path to an IESNA LM-63 file (.ies, any case; see ies.rs)
//! inner_deg = 20.0                # spot: full intensity inside this half-angle
//! outer_deg = 30.0                # spot: zero beyond this half-angle (> inner, <= 90)
//! color = [1.0, 1.0, 1.0]         # linear tint multiplying T
//!
//! [[lights]]                      # appended to the scene file's own lights
//! name = "lamp"                   # optional
//! kind = "spot"                   # "point" | "spot" | "directional"
//! position = [0.0, 2.5, 0.0]      # required for point and spot
//! direction = [0.0, -1.0, 0.0]    # required for spot and directional; normalised on load
//! color = [1.0, 0.6, 0.3]         # default white
//! intensity = 2.0                 # W/sr (point, spot) or W/m² (directional); default 1
//! range = 8.0                     # optional, > 0
//! inner_deg = 20.0                # spot only; default 0
//! outer_deg = 35.0                # spot only; default 45; > inner, <= 90
//!
//! [game]                          # free-form; kept for the game, not interpreted here
//! ```
//!
//! Unknown keys are errors (a typo must not be silently ignored). Every file the level loads
//! must resolve inside the level folder, symlinks included.

use std::path::{Path, PathBuf};

use crate::error::{LoadError, LoadErrorKind, LoadWarning};
use crate::gltf_loader::load_gltf_with;
use crate::headlamp_profile::HeadlampProfile;
use crate::level_toml::parse_level_toml;
use crate::obj_loader::load_obj_with;
use crate::sources::Sources;
use crate::spawn::Spawn;
use crate::zip_level::is_zip;
use crate::Scene;

/// A loaded level: the scene plus everything `level.toml` says about playing it.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    pub name: String,
    /// One line for the level menu; empty when level.toml gives none.
    pub description: String,
    /// The level folder; None when a bare scene file was loaded.
    pub root: Option<PathBuf>,
    pub scene_path: PathBuf,
    /// The scene, with level.toml's `[[lights]]` appended to `scene.lights`.
    pub scene: Scene,
    pub exposure: Option<f32>,
    /// None: the renderer frames the scene.
    pub spawn: Option<Spawn>,
    pub headlamp: HeadlampProfile,
    /// The `[game]` table, untouched.
    pub game: toml::Table,
    /// 64-bit FNV-1a over level.toml and every file the level loaded (scene, buffers,
    /// textures, .mtl, headlamp profile), each as its length (u64 LE) then its bytes, in load
    /// order. Replays use it to notice that a level changed.
    pub content_hash: u64,
    /// What the load accepted but the author should hear about (ignored keys and glTF
    /// features, a missing .mtl), in load order; already logged.
    pub warnings: Vec<LoadWarning>,
    /// Every file the load read (for a zipped level, the archive): what live reload watches.
    pub files: Vec<PathBuf>,
}

/// Loads a level from a folder holding `level.toml`, from the `level.toml` file itself, from a
/// `.zip` of such a folder (read in place), or from a bare .gltf/.glb/.obj file (then named
/// after the file, with default settings).
pub fn load_level(path: &Path) -> Result<Level, LoadError> {
    let meta = std::fs::metadata(path).map_err(|e| LoadError::io(path, &e))?;
    if meta.is_dir() {
        return load_level_folder(path);
    }
    if path.file_name().is_some_and(|n| n.eq_ignore_ascii_case("level.toml")) {
        return load_level_folder(path.parent().unwrap_or(Path::new(".")));
    }
    if is_zip(path) {
        return load_level_in(path, &mut Sources::zipped(path)?);
    }
    let mut sources = Sources::new(None);
    let scene = load_scene_with(path, &mut sources)?;
    Ok(Level {
        name: path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
        description: String::new(),
        root: None,
        scene_path: path.to_path_buf(),
        scene,
        exposure: None,
        spawn: None,
        headlamp: HeadlampProfile::default(),
        game: toml::Table::new(),
        content_hash: sources.hash(),
        warnings: sources.take_warnings(),
        files: sources.files().to_vec(),
    })
}

/// Loads a scene file, choosing the loader by extension (case-insensitive).
pub fn load_scene_file(path: &Path) -> Result<Scene, LoadError> {
    load_scene_with(path, &mut Sources::new(None))
}

pub(crate) fn load_scene_with(path: &Path, sources: &mut Sources) -> Result<Scene, LoadError> {
    let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    match ext.as_str() {
        "gltf" | "glb" => load_gltf_with(path, sources),
        "obj" => load_obj_with(path, sources),
        _ => Err(LoadError::new(path, LoadErrorKind::UnknownExtension(ext))),
    }
}

fn load_level_folder(dir: &Path) -> Result<Level, LoadError> {
    let root = dir.canonicalize().map_err(|e| LoadError::io(dir, &e))?;
    load_level_in(dir, &mut Sources::new(Some(root)))
}

/// Loads the level whose folder (or archive standing for it) is `dir`, reading through
/// `sources`, which keep every file inside it.
fn load_level_in(dir: &Path, sources: &mut Sources) -> Result<Level, LoadError> {
    let toml_path = dir.join("level.toml");
    let bytes = sources.read(&toml_path)?;
    // Cheap checks first: a typo in level.toml fails before a large scene is loaded.
    let mut parsed = parse_level_toml(&bytes, &toml_path)?;
    for (at, message) in std::mem::take(&mut parsed.warnings) {
        sources.warn(&toml_path, at, message);
    }
    let scene_path = sources.resolve(&toml_path, dir, &parsed.scene)?;
    let mut scene = load_scene_with(&scene_path, sources)?;
    let headlamp = parsed.headlamp(&toml_path, dir, sources)?;
    scene.lights.extend(parsed.lights);
    Ok(Level {
        name: parsed.name,
        description: parsed.description,
        root: Some(dir.to_path_buf()),
        scene_path,
        scene,
        exposure: parsed.exposure,
        spawn: parsed.spawn,
        headlamp,
        game: parsed.game,
        content_hash: sources.hash(),
        warnings: sources.take_warnings(),
        files: sources.files().to_vec(),
    })
}
