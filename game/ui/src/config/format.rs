//! The config file's TOML, both ways. Parsing keeps every key's position (`toml::Spanned`) so
//! an error can name its line; it checks each value itself rather than through serde derives,
//! so the messages speak of keys and ranges, not of Rust types.

use std::collections::BTreeMap;
use std::fmt::Write;
use std::ops::{Range, RangeInclusive};
use std::path::Path;

use engine::gamepad::PadButton;
use plugin_gi::GiSettings;
use serde::Deserialize;
use toml::{Spanned, Value};

use super::{Config, ConfigError};
use crate::bindings::{Action, Binding, KeyBindings, SLOTS};
use crate::pad_bindings::{self, GamepadSettings, PadBindings};

/// A problem found in the text; [`ConfigError`] adds the file.
struct ParseError {
    line: Option<usize>,
    key: Option<String>,
    problem: String,
}

// Config's two TOML methods are written here, beside the format they are, so that the config's
// module does not import its own format back.
impl Config {
    /// The file's text, with a comment on each setting.
    pub fn to_toml(&self) -> String {
        write(self)
    }

    /// Reads a config from its text; `path` only names the file in errors.
    pub fn from_toml(text: &str, path: &Path) -> Result<Config, ConfigError> {
        parse(text).map_err(|e| ConfigError { path: path.to_owned(), line: e.line, key: e.key, problem: e.problem })
    }
}

const SECTIONS: [&str; 8] = ["controls", "video", "comfort", "audio", "bindings", "gamepad", "gamepad_bindings", "gi"];
const COMFORT: [&str; 6] = ["brightness", "calibrated", "reduce_flashing", "captions", "hud_scale", "crosshair_scale"];
const CONTROLS: [&str; 3] = ["sensitivity", "invert_y", "fov_deg"];
const GAMEPAD: [&str; 2] = ["look_sensitivity", "dead_zone"];
const VIDEO: [&str; 5] = ["render_scale", "dynamic_resolution", "target_fps", "vsync", "show_fps"];
const AUDIO: [&str; 3] = ["master", "effects", "ambience"];

fn write(c: &Config) -> String {
    let range = |r: &RangeInclusive<f32>| format!("{:?} to {:?}", r.start(), r.end());
    let mut out = String::new();
    // `{:?}` writes an f32 as the shortest text that reads back as the same f32, always
    // with a decimal point or exponent, so TOML keeps it a float.
    let _ = write!(
        out,
        "# Headlamp settings. The game writes this file when a setting changes; you may edit it.\n\
         # A missing key takes its default; an unknown key or a bad value is reported, and the\n\
         # file is then kept as config.toml.bad while the game runs with the defaults.\n\
         \n\
         [controls]\n\
         # mouse look speed, 1.0 = {base} radians per pixel ({sens})\n\
         sensitivity = {:?}\n\
         invert_y = {}\n\
         # vertical field of view, degrees ({fov})\n\
         fov_deg = {:?}\n\
         \n\
         [video]\n\
         # 3D view resolution relative to the window ({scale})\n\
         render_scale = {:?}\n\
         # lower the render scale (to 25 % at least, to render_scale at most) to hold target_fps\n\
         dynamic_resolution = {}\n\
         # frames per second that dynamic resolution holds ({fps})\n\
         target_fps = {:?}\n\
         vsync = {}\n\
         show_fps = {}\n\
         \n\
         [comfort]\n\
         # picture brightness in stops, 0 = as the level is lit ({bright})\n\
         brightness = {:?}\n\
         # the brightness screen has been shown (false: it opens at the next start)\n\
         calibrated = {}\n\
         # tame the low-battery flicker and the muzzle flash\n\
         reduce_flashing = {}\n\
         # write what is heard and matters (a crawler noticing you: where, and if out of sight)\n\
         captions = {}\n\
         # size of the HUD ({ui})\n\
         hud_scale = {:?}\n\
         # size of the crosshair ({cross})\n\
         crosshair_scale = {:?}\n\
         \n\
         [audio]\n\
         # volumes in percent ({volume}): everything, the effects (shots, steps, crawlers, stings), the room's tone\n\
         master = {:?}\n\
         effects = {:?}\n\
         ambience = {:?}\n\
         \n\
         [bindings]\n\
         # Up to {SLOTS} keys or buttons per action, e.g. KeyW, Digit1, F5, Space, Tab, ShiftLeft,\n\
         # ControlLeft, AltLeft, ArrowUp, Comma, Numpad0, MouseLeft, MouseRight, MouseMiddle.\n",
        c.mouse_sensitivity,
        c.invert_y,
        c.fov_deg,
        c.render_scale,
        c.dynamic_resolution,
        c.target_fps,
        c.vsync,
        c.show_fps,
        c.brightness,
        c.calibrated,
        c.reduce_flashing,
        c.captions,
        c.hud_scale,
        c.crosshair_scale,
        c.master_volume,
        c.effects_volume,
        c.ambience_volume,
        base = Config::BASE_RADIANS_PER_PIXEL,
        sens = range(&Config::SENSITIVITY_RANGE),
        fov = range(&Config::FOV_RANGE),
        scale = range(&Config::RENDER_SCALE_RANGE),
        fps = range(&Config::TARGET_FPS_RANGE),
        bright = range(&Config::BRIGHTNESS_RANGE),
        ui = range(&Config::HUD_SCALE_RANGE),
        cross = range(&Config::CROSSHAIR_SCALE_RANGE),
        volume = range(&Config::VOLUME_RANGE),
    );
    for action in Action::ALL {
        let names: Vec<String> = c.bindings.bindings(action).map(|b| format!("\"{b}\"")).collect();
        let _ = writeln!(out, "{} = [{}]", action.name(), names.join(", "));
    }
    write_gamepad(&mut out, &c.gamepad);
    let _ = write!(out, "\n[gi]\n# global illumination\nenabled = {}\n", c.gi.enabled);
    for field in GiSettings::FIELDS {
        let v = c.gi.get(field.name).expect("every entry of GiSettings::FIELDS has a value");
        let _ = writeln!(out, "# {} ({} to {})", field.help, field.min, field.max);
        if field.integer {
            let _ = writeln!(out, "{} = {}", field.name, v as i64);
        } else {
            let _ = writeln!(out, "{} = {:?}", field.name, v as f32);
        }
    }
    out
}

type Entries = BTreeMap<Spanned<String>, Spanned<Value>>;

/// Every top-level key, for unknown-section errors.
type Top = BTreeMap<Spanned<String>, Spanned<Value>>;

/// The sections with their keys' positions (unknown sections are caught via [`Top`]).
#[derive(Deserialize)]
struct Sections {
    #[serde(default)]
    controls: Entries,
    #[serde(default)]
    video: Entries,
    #[serde(default)]
    comfort: Entries,
    #[serde(default)]
    audio: Entries,
    #[serde(default)]
    bindings: Entries,
    #[serde(default)]
    gamepad: Entries,
    #[serde(default)]
    gamepad_bindings: Entries,
    #[serde(default)]
    gi: Entries,
}

fn parse(text: &str) -> Result<Config, ParseError> {
    let line_of = |span: Range<usize>| text[..span.start.min(text.len())].matches('\n').count() + 1;
    let syntax = |e: toml::de::Error| ParseError {
        line: e.span().map(line_of),
        key: None,
        problem: format!("not valid TOML: {}", e.message().trim().replace('\n', " ")),
    };
    let error = |key: &Spanned<String>, section: &str, problem: String| ParseError {
        line: Some(line_of(key.span())),
        key: Some(if section.is_empty() { key.get_ref().clone() } else { format!("{section}.{}", key.get_ref()) }),
        problem,
    };

    let top: Top = toml::from_str(text).map_err(syntax)?;
    for (key, value) in by_position(&top) {
        if !SECTIONS.contains(&key.get_ref().as_str()) {
            return Err(error(key, "", format!("unknown key (the sections are {})", list(&SECTIONS))));
        }
        if !value.get_ref().is_table() {
            return Err(error(key, "", format!("must be a section, [{}]", key.get_ref())));
        }
    }
    let sections: Sections = toml::from_str(text).map_err(syntax)?;

    let mut c = Config::default();
    for (key, value) in by_position(&sections.controls) {
        let value = value.get_ref();
        let set = match key.get_ref().as_str() {
            "sensitivity" => number(value, &Config::SENSITIVITY_RANGE).map(|v| c.mouse_sensitivity = v),
            "invert_y" => boolean(value).map(|v| c.invert_y = v),
            "fov_deg" => number(value, &Config::FOV_RANGE).map(|v| c.fov_deg = v),
            _ => Err(unknown(&CONTROLS)),
        };
        set.map_err(|problem| error(key, "controls", problem))?;
    }
    for (key, value) in by_position(&sections.video) {
        let value = value.get_ref();
        let set = match key.get_ref().as_str() {
            "render_scale" => number(value, &Config::RENDER_SCALE_RANGE).map(|v| c.render_scale = v),
            "dynamic_resolution" => boolean(value).map(|v| c.dynamic_resolution = v),
            "target_fps" => number(value, &Config::TARGET_FPS_RANGE).map(|v| c.target_fps = v),
            "vsync" => boolean(value).map(|v| c.vsync = v),
            "show_fps" => boolean(value).map(|v| c.show_fps = v),
            _ => Err(unknown(&VIDEO)),
        };
        set.map_err(|problem| error(key, "video", problem))?;
    }
    for (key, value) in by_position(&sections.comfort) {
        let value = value.get_ref();
        let set = match key.get_ref().as_str() {
            "brightness" => number(value, &Config::BRIGHTNESS_RANGE).map(|v| c.brightness = v),
            "calibrated" => boolean(value).map(|v| c.calibrated = v),
            "reduce_flashing" => boolean(value).map(|v| c.reduce_flashing = v),
            "captions" => boolean(value).map(|v| c.captions = v),
            "hud_scale" => number(value, &Config::HUD_SCALE_RANGE).map(|v| c.hud_scale = v),
            "crosshair_scale" => number(value, &Config::CROSSHAIR_SCALE_RANGE).map(|v| c.crosshair_scale = v),
            _ => Err(unknown(&COMFORT)),
        };
        set.map_err(|problem| error(key, "comfort", problem))?;
    }
    for (key, value) in by_position(&sections.audio) {
        let value = value.get_ref();
        let set = match key.get_ref().as_str() {
            "master" => number(value, &Config::VOLUME_RANGE).map(|v| c.master_volume = v),
            "effects" => number(value, &Config::VOLUME_RANGE).map(|v| c.effects_volume = v),
            "ambience" => number(value, &Config::VOLUME_RANGE).map(|v| c.ambience_volume = v),
            _ => Err(unknown(&AUDIO)),
        };
        set.map_err(|problem| error(key, "audio", problem))?;
    }
    c.bindings = bindings(&sections.bindings, &error)?;
    for (key, value) in by_position(&sections.gamepad) {
        let value = value.get_ref();
        let pad = &mut c.gamepad;
        let set = match key.get_ref().as_str() {
            "look_sensitivity" => number(value, &GamepadSettings::SENSITIVITY_RANGE).map(|v| pad.look_sensitivity = v),
            "dead_zone" => number(value, &GamepadSettings::DEAD_ZONE_RANGE).map(|v| pad.dead_zone = v),
            _ => Err(unknown(&GAMEPAD)),
        };
        set.map_err(|problem| error(key, "gamepad", problem))?;
    }
    c.gamepad.bindings = pad_bindings(&sections.gamepad_bindings, &error)?;
    for (key, value) in by_position(&sections.gi) {
        gi_setting(&mut c.gi, key.get_ref(), value.get_ref()).map_err(|problem| error(key, "gi", problem))?;
    }
    Ok(c)
}

/// Actions listed in the file take exactly the bindings listed; the others keep their
/// defaults, less any key the listed ones took (so an older file never binds a key twice).
fn bindings(
    entries: &Entries,
    error: &impl Fn(&Spanned<String>, &str, String) -> ParseError,
) -> Result<KeyBindings, ParseError> {
    let mut listed: Vec<(Action, Vec<Binding>)> = Vec::new();
    for (key, value) in by_position(entries) {
        let fail = |problem: String| error(key, "bindings", problem);
        let (action, names) =
            action_and_names(key, value, "names in quotes, like \"KeyW\"", list_expected(value)).map_err(&fail)?;
        if names.len() > SLOTS {
            return Err(fail(format!("at most {SLOTS} keys or buttons, found {}", names.len())));
        }
        let mut bound = Vec::new();
        for name in names {
            let binding: Binding = name.parse().map_err(|e| fail(format!("{e}")))?;
            if bound.contains(&binding) {
                return Err(fail(format!("'{name}' is listed twice")));
            }
            if let Some((other, _)) = listed.iter().find(|(_, b)| b.contains(&binding)) {
                return Err(fail(format!("'{name}' is also bound to {}; a key does one thing", other.name())));
            }
            bound.push(binding);
        }
        listed.push((action, bound));
    }
    let mut result = KeyBindings::default();
    for action in Action::ALL {
        match listed.iter().find(|(a, _)| *a == action) {
            Some((_, bound)) => result.replace(action, bound),
            None => {
                let kept: Vec<Binding> =
                    result.bindings(action).filter(|b| !listed.iter().any(|(_, l)| l.contains(b))).collect();
                result.replace(action, &kept);
            }
        }
    }
    Ok(result)
}

fn write_gamepad(out: &mut String, pad: &GamepadSettings) {
    let range = |r: &RangeInclusive<f32>| format!("{:?} to {:?}", r.start(), r.end());
    let names: Vec<&str> =
        PadButton::ALL.into_iter().filter(|b| pad_bindings::is_bindable(*b)).map(pad_bindings::button_name).collect();
    let _ = write!(
        out,
        "\n[gamepad]\n\
         # right-stick turn speed, 1.0 = {base:.4} radians per second at full deflection ({sens})\n\
         look_sensitivity = {:?}\n\
         # stick travel ignored around the centre, as a fraction of it ({dead})\n\
         dead_zone = {:?}\n\
         \n\
         [gamepad_bindings]\n\
         # One pad button per action, [] for none. The left stick walks, the right stick looks,\n\
         # Start pauses. Buttons by position: {}.\n",
        pad.look_sensitivity,
        pad.dead_zone,
        names.join(", "),
        base = GamepadSettings::BASE_RADIANS_PER_SECOND,
        sens = range(&GamepadSettings::SENSITIVITY_RANGE),
        dead = range(&GamepadSettings::DEAD_ZONE_RANGE),
    );
    for action in Action::ALL {
        let button = pad.bindings.get(action).map(|b| format!("\"{}\"", pad_bindings::button_name(b)));
        let _ = writeln!(out, "{} = [{}]", action.name(), button.unwrap_or_default());
    }
}

/// Like [`bindings`], with one button per action: listed actions take what is listed (`[]`
/// unbinds), the others keep their defaults unless a listed action took their button.
fn pad_bindings(
    entries: &Entries,
    error: &impl Fn(&Spanned<String>, &str, String) -> ParseError,
) -> Result<PadBindings, ParseError> {
    let mut listed: Vec<(Action, Option<PadButton>)> = Vec::new();
    for (key, value) in by_position(entries) {
        let fail = |problem: String| error(key, "gamepad_bindings", problem);
        let expected = format!(
            "expected a list of one gamepad button like [\"South\"] or [], found {}",
            value.get_ref().type_str()
        );
        let (action, names) =
            action_and_names(key, value, "a name in quotes, like \"South\"", expected).map_err(&fail)?;
        let button = match names.as_slice() {
            [] => None,
            [name] => Some(pad_bindings::parse_button(name).map_err(|e| fail(e.to_string()))?),
            more => return Err(fail(format!("one gamepad button per action, found {}", more.len()))),
        };
        if let Some(b) = button {
            if let Some((other, _)) = listed.iter().find(|(_, l)| *l == Some(b)) {
                let name = pad_bindings::button_name(b);
                return Err(fail(format!("'{name}' is also bound to {}; a button does one thing", other.name())));
            }
        }
        listed.push((action, button));
    }
    let mut result = PadBindings::default();
    for action in Action::ALL {
        let button = match listed.iter().find(|(a, _)| *a == action) {
            Some((_, b)) => *b,
            None => result.get(action).filter(|b| !listed.iter().any(|(_, l)| *l == Some(*b))),
        };
        result.replace(action, button);
    }
    Ok(result)
}

fn gi_setting(gi: &mut GiSettings, name: &str, value: &Value) -> Result<(), String> {
    let text = match (name, value) {
        ("enabled", Value::Boolean(b)) => b.to_string(),
        ("enabled", other) => return Err(format!("expected true or false, found {}", other.type_str())),
        (_, Value::Integer(i)) => i.to_string(),
        (_, Value::Float(f)) => format!("{f:?}"),
        (_, other) if GiSettings::FIELDS.iter().any(|f| f.name == name) => {
            return Err(format!("expected a number, found {}", other.type_str()))
        }
        _ => String::new(),
    };
    // `GiSettings::set` validates like `--set gi.NAME=VALUE`; its messages start with the key,
    // which the error names already.
    gi.set(name, &text).map_err(|e| e.strip_prefix(&format!("gi.{name}: ")).unwrap_or(&e).to_owned())
}

/// Entries in the order they appear in the file, so the first error reported is the first one.
fn by_position(entries: &Entries) -> Vec<(&Spanned<String>, &Spanned<Value>)> {
    let mut v: Vec<_> = entries.iter().collect();
    v.sort_by_key(|(k, _)| k.span().start);
    v
}

fn number(value: &Value, range: &RangeInclusive<f32>) -> Result<f32, String> {
    let v = match value {
        Value::Float(f) => *f,
        Value::Integer(i) => *i as f64,
        other => return Err(format!("expected a number, found {}", other.type_str())),
    };
    // Compared as the f32 it becomes: the file's "0.1" is the range's 0.1f32.
    if !range.contains(&(v as f32)) {
        return Err(format!("{v} is out of range ({:?} to {:?})", range.start(), range.end()));
    }
    Ok(v as f32)
}

fn boolean(value: &Value) -> Result<bool, String> {
    value.as_bool().ok_or_else(|| format!("expected true or false, found {}", value.type_str()))
}

/// A `[bindings]` or `[gamepad_bindings]` entry read: the action its key names and the names
/// its value gives (one in quotes, or a list of them); else the problem, `not_a_list` when the
/// value is neither.
fn action_and_names<'v>(
    key: &Spanned<String>,
    value: &'v Spanned<Value>,
    each: &str,
    not_a_list: String,
) -> Result<(Action, Vec<&'v str>), String> {
    let Some(action) = Action::from_name(key.get_ref()) else {
        let names: Vec<&str> = Action::ALL.iter().map(|a| a.name()).collect();
        return Err(unknown(&names));
    };
    let names = match value.get_ref() {
        Value::String(name) => vec![name.as_str()],
        Value::Array(items) => items
            .iter()
            .map(|v| v.as_str().ok_or_else(|| format!("expected {each}, found {}", v.type_str())))
            .collect::<Result<_, _>>()?,
        _ => return Err(not_a_list),
    };
    Ok((action, names))
}

fn list_expected(value: &Spanned<Value>) -> String {
    format!("expected a list of key or button names like [\"KeyW\"], found {}", value.get_ref().type_str())
}

fn unknown(known: &[&str]) -> String {
    format!("unknown key (known: {})", list(known))
}

fn list(names: &[&str]) -> String {
    names.join(", ")
}
