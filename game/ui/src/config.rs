//! The player's settings, kept in one human-readable TOML file between runs.
//!
//! Loading is strict (an unknown key or a bad value is an error naming the file, the line and
//! the key, so a typo is never silently ignored) but forgiving of age (a missing key takes its
//! default, so a file from an older version still loads). A bad file is never lost:
//! [`Config::load_or_default`] copies it aside before the game can save over it.

mod declare;
mod format;
mod sections;
#[cfg(test)]
mod tests;

use std::ffi::OsString;
use std::fmt;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

use plugin_gi::GiSettings;

use crate::bindings::KeyBindings;
use crate::pad_bindings::GamepadSettings;

declare::config_file! {
    /// The player's settings. Each key of the file is declared once, here: the field, its key
    /// (`as` when the names differ), type, default, range (`in`) and the comment written above
    /// it in the file (`{range}` stands for the range); `config/declare.rs` tells the syntax.
    #[derive(Clone, Debug, PartialEq)]
    pub struct Config {
        keys {
            [controls]
            /// Mouse look speed as a multiplier: 1.0 = [`Config::BASE_RADIANS_PER_PIXEL`].
            mouse_sensitivity as sensitivity: f32 = 1.0, in SENSITIVITY_RANGE = 0.1..=10.0,
                "mouse look speed, 1.0 = 0.0025 radians per pixel ({range})";
            /// Moving the mouse forward looks down.
            invert_y: bool = false;
            /// Vertical field of view, degrees, in [`Config::FOV_RANGE`]. The default is the engine's
            /// own (`start_view::DEFAULT_FOV_Y`): the game looks as before.
            fov_deg: f32 = 60.0, in FOV_RANGE = 50.0..=110.0, "vertical field of view, degrees ({range})";

            [video]
            /// The 3D view's resolution relative to the window, in [`Config::RENDER_SCALE_RANGE`].
            render_scale: f32 = 1.0, in RENDER_SCALE_RANGE = 0.25..=1.0,
                "3D view resolution relative to the window ({range})";
            /// Lower the render scale (down to 25 %, up to `render_scale`) to hold `target_fps`.
            dynamic_resolution: bool = false,
                "lower the render scale (to 25 % at least, to render_scale at most) to hold target_fps";
            /// The frame rate dynamic resolution holds, in [`Config::TARGET_FPS_RANGE`].
            target_fps: f32 = 30.0, in TARGET_FPS_RANGE = 10.0..=144.0,
                "frames per second that dynamic resolution holds ({range})";
            vsync: bool = true;
            /// The frame-rate counter in a corner.
            show_fps: bool = false;
            /// The note on a device that renders on the CPU has been shown (once per machine;
            /// Settings > Video keeps saying it).
            cpu_note_shown: bool = false,
                "the note on rendering on the CPU has been shown (false: it shows at the next start)";

            [comfort]
            /// Picture brightness in stops (exposure × 2^brightness), in [`Config::BRIGHTNESS_RANGE`].
            brightness: f32 = 0.0, in BRIGHTNESS_RANGE = -2.0..=2.0,
                "picture brightness in stops, 0 = as the level is lit ({range})";
            /// The brightness calibration screen has been through (it opens on a first start).
            calibrated: bool = false,
                "the brightness screen has been shown (false: it opens at the next start)";
            /// Tames what flashes: the low-battery flicker and the muzzle flash.
            reduce_flashing: bool = false, "tame the low-battery flicker and the muzzle flash";
            /// Writes what is heard and matters (a crawler noticing you: where, and if out of sight).
            captions: bool = true,
                "write what is heard and matters (a crawler noticing you: where, and if out of sight)";
            /// Size of the HUD (the menus keep theirs), in [`Config::HUD_SCALE_RANGE`].
            hud_scale: f32 = 1.0, in HUD_SCALE_RANGE = 0.75..=2.0, "size of the HUD ({range})";
            /// Size of the crosshair, in [`Config::CROSSHAIR_SCALE_RANGE`].
            crosshair_scale: f32 = 1.0, in CROSSHAIR_SCALE_RANGE = 0.5..=3.0, "size of the crosshair ({range})";

            [audio]
            /// Volumes in percent ([`Config::VOLUME_RANGE`]): everything, then the effects (shots,
            /// steps, crawlers, stings) and the ambience (the room's tone) under it.
            master_volume as master: f32 = 80.0, in VOLUME_RANGE = 0.0..=100.0,
                "volumes in percent ({range}): everything, the effects (shots, steps, crawlers, stings), \
                 the room's tone";
            effects_volume as effects: f32 = 100.0, in VOLUME_RANGE;
            ambience_volume as ambience: f32 = 100.0, in VOLUME_RANGE;
        }
        sections {
            bindings: KeyBindings = KeyBindings::default();
            /// The gamepad's buttons, look speed and dead zone (look follows `invert_y` too).
            gamepad: GamepadSettings = GamepadSettings::default();
            gi: GiSettings = GiSettings::default();
        }
    }
}

impl Config {
    /// View rotation per pixel of mouse motion at sensitivity 1.0 (what the game always used).
    pub const BASE_RADIANS_PER_PIXEL: f32 = 0.0025;
    /// How much of a flash `reduce_flashing` leaves: the muzzle flash's light, and the depth of
    /// the low-battery flicker.
    pub const REDUCED_FLASH: f32 = 0.25;

    /// The multiplier brightness applies to the level's exposure.
    pub fn exposure_scale(&self) -> f32 {
        self.brightness.exp2()
    }

    /// Radians of view rotation per pixel of mouse motion.
    pub fn radians_per_pixel(&self) -> f32 {
        self.mouse_sensitivity * Self::BASE_RADIANS_PER_PIXEL
    }

    /// The file's text, with a comment on each setting.
    pub fn to_toml(&self) -> String {
        format::write(self, PLAIN_SECTIONS, KEYS, OWNERS)
    }

    /// Reads a config from its text; `path` only names the file in errors.
    pub fn from_toml(text: &str, path: &Path) -> Result<Config, ConfigError> {
        format::parse(text, PLAIN_SECTIONS, KEYS, OWNERS).map_err(|e| ConfigError {
            path: path.to_owned(),
            line: e.line,
            key: e.key,
            problem: e.problem,
        })
    }

    /// Reads the config file; a missing file gives the defaults.
    pub fn load(path: &Path) -> Result<Config, ConfigError> {
        match engine::scene::limits::read_text(path, engine::scene::limits::MAX_TEXT_BYTES) {
            Ok(text) => Self::from_toml(&text, path),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(Config::default()),
            Err(e) => Err(ConfigError::io(path, "could not read it", &e)),
        }
    }

    /// [`Config::load`], falling back to the defaults on a bad file, with a warning for the
    /// player. The bad file is first copied to `<name>.bad` (`.bad2`, … if an older, different
    /// copy is there), so a later [`Config::save`] loses nothing the player wrote.
    pub fn load_or_default(path: &Path) -> (Config, Option<String>) {
        let error = match Config::load(path) {
            Ok(config) => return (config, None),
            Err(e) => e,
        };
        let warning = match keep_bad_file(path) {
            Ok(kept) => format!("{error}. Using the default settings; your file was kept as {}", kept.display()),
            Err(e) => format!(
                "{error}. Using the default settings; could not keep a copy of your file ({e}): \
                 changing a setting will replace it"
            ),
        };
        (Config::default(), Some(warning))
    }

    /// Writes the file atomically (a temporary file beside it, then a rename), so a crash
    /// mid-write leaves the old file or the new one, never half of one. Creates the folder.
    pub fn save(&self, path: &Path) -> Result<(), ConfigError> {
        // A rename would replace whatever is there: never a device, FIFO or folder.
        if fs::metadata(path).is_ok_and(|m| !m.is_file()) {
            let e = std::io::Error::new(std::io::ErrorKind::InvalidInput, "it is not a regular file");
            return Err(ConfigError::io(path, "will not write it", &e));
        }
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        fs::create_dir_all(dir).map_err(|e| ConfigError::io(path, "could not create its folder", &e))?;
        let name = path.file_name().unwrap_or_else(|| "config.toml".as_ref()).to_string_lossy();
        let temp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
        let written = (|| {
            let mut file = fs::File::create(&temp)?;
            file.write_all(self.to_toml().as_bytes())?;
            file.sync_all()?;
            fs::rename(&temp, path)
        })();
        written.map_err(|e| {
            let _ = fs::remove_file(&temp);
            ConfigError::io(path, "could not write it", &e)
        })
    }
}

/// Copies a bad config file aside and returns the copy's path; an identical copy already
/// there is reused rather than duplicated.
fn keep_bad_file(path: &Path) -> std::io::Result<PathBuf> {
    let original = engine::scene::limits::read_file(path, engine::scene::limits::MAX_TEXT_BYTES)?;
    let mut name = path.file_name().map(OsString::from).unwrap_or_else(|| "config.toml".into());
    name.push(".bad");
    for n in 1..100 {
        let mut candidate = name.clone();
        if n > 1 {
            candidate.push(n.to_string());
        }
        let candidate = path.with_file_name(candidate);
        match fs::read(&candidate) {
            Ok(existing) if existing == original => return Ok(candidate),
            Ok(_) => continue,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                fs::write(&candidate, &original)?;
                return Ok(candidate);
            }
            Err(e) => return Err(e),
        }
    }
    Err(std::io::Error::other("too many .bad copies beside it"))
}

/// Where the config lives: `$HEADLAMP_CONFIG` if set, else the platform's config folder +
/// `headlamp/config.toml`: `$XDG_CONFIG_HOME` or `~/.config` (Linux and other Unix),
/// `%APPDATA%` (Windows), `~/Library/Application Support` (macOS). `None` when the
/// environment names no home at all.
pub fn config_path() -> Option<PathBuf> {
    config_path_from(|name| std::env::var_os(name))
}

fn config_path_from(var: impl Fn(&str) -> Option<OsString>) -> Option<PathBuf> {
    let set = |name: &str| var(name).filter(|v| !v.is_empty()).map(PathBuf::from);
    if let Some(path) = set("HEADLAMP_CONFIG") {
        return Some(path);
    }
    let base = if cfg!(windows) {
        set("APPDATA")
    } else if cfg!(target_os = "macos") {
        set("HOME").map(|home| home.join("Library").join("Application Support"))
    } else {
        // The XDG spec says to ignore a relative XDG_CONFIG_HOME.
        set("XDG_CONFIG_HOME").filter(|p| p.is_absolute()).or_else(|| set("HOME").map(|home| home.join(".config")))
    };
    Some(base?.join("headlamp").join("config.toml"))
}

/// A config file that could not be read, parsed or written: one line naming the file, the
/// line in it and the key where known, and the problem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ConfigError {
    pub path: PathBuf,
    /// 1-based.
    pub line: Option<usize>,
    /// `section.key`, e.g. `controls.fov_deg`.
    pub key: Option<String>,
    pub problem: String,
}

impl ConfigError {
    fn io(path: &Path, what: &str, e: &std::io::Error) -> Self {
        Self { path: path.to_owned(), line: None, key: None, problem: format!("{what}: {e}") }
    }
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        if let Some(line) = self.line {
            write!(f, ": line {line}")?;
        }
        if let Some(key) = &self.key {
            write!(f, ": {key}")?;
        }
        write!(f, ": {}", self.problem)
    }
}

impl std::error::Error for ConfigError {}
