//! The values that fill whole sections of the config file, with their own writers and readers:
//! the key bindings (`[bindings]`), the gamepad (`[gamepad]`, `[gamepad_bindings]`) and the GI
//! (`[gi]`, from [`GiSettings::FIELDS`]).

use std::fmt::Write;

use engine::gamepad::PadButton;
use plugin_gi::GiSettings;
use toml::{Spanned, Value};

use super::format::{number, range_text, unknown, File, ParseError};
use crate::bindings::{Action, Binding, KeyBindings, SLOTS};
use crate::pad_bindings::{self, GamepadSettings, PadBindings};

/// A value that fills sections of the file of its own.
pub(super) trait OwnSections {
    /// Its sections, in the file's order.
    const SECTIONS: &'static [&'static str];
    /// Writes its sections, each as a blank line, `[name]` and its lines.
    fn write(&self, out: &mut String);
    /// Takes what the file has of its sections; `self` starts as the default.
    fn read(&mut self, file: &File<'_>) -> Result<(), ParseError>;
}

impl OwnSections for KeyBindings {
    const SECTIONS: &'static [&'static str] = &["bindings"];

    fn write(&self, out: &mut String) {
        let _ = write!(
            out,
            "\n[bindings]\n\
             # Up to {SLOTS} keys or buttons per action, e.g. KeyW, Digit1, F5, Space, Tab, ShiftLeft,\n\
             # ControlLeft, AltLeft, ArrowUp, Comma, Numpad0, MouseLeft, MouseRight, MouseMiddle.\n"
        );
        for action in Action::ALL {
            let names: Vec<String> = self.bindings(action).map(|b| format!("\"{b}\"")).collect();
            let _ = writeln!(out, "{} = [{}]", action.name(), names.join(", "));
        }
    }

    /// Actions listed in the file take exactly the bindings listed; the others keep their
    /// defaults, less any key the listed ones took (so an older file never binds a key twice).
    fn read(&mut self, file: &File<'_>) -> Result<(), ParseError> {
        let mut listed: Vec<(Action, Vec<Binding>)> = Vec::new();
        for (key, value) in file.entries("bindings") {
            let fail = |problem: String| file.error(key, "bindings", problem);
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
        for action in Action::ALL {
            match listed.iter().find(|(a, _)| *a == action) {
                Some((_, bound)) => self.replace(action, bound),
                None => {
                    let kept: Vec<Binding> =
                        self.bindings(action).filter(|b| !listed.iter().any(|(_, l)| l.contains(b))).collect();
                    self.replace(action, &kept);
                }
            }
        }
        Ok(())
    }
}

impl OwnSections for GamepadSettings {
    const SECTIONS: &'static [&'static str] = &["gamepad", "gamepad_bindings"];

    fn write(&self, out: &mut String) {
        let names: Vec<&str> = PadButton::ALL
            .into_iter()
            .filter(|b| pad_bindings::is_bindable(*b))
            .map(pad_bindings::button_name)
            .collect();
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
            self.look_sensitivity,
            self.dead_zone,
            names.join(", "),
            base = GamepadSettings::BASE_RADIANS_PER_SECOND,
            sens = range_text(&GamepadSettings::SENSITIVITY_RANGE),
            dead = range_text(&GamepadSettings::DEAD_ZONE_RANGE),
        );
        for action in Action::ALL {
            let button = self.bindings.get(action).map(|b| format!("\"{}\"", pad_bindings::button_name(b)));
            let _ = writeln!(out, "{} = [{}]", action.name(), button.unwrap_or_default());
        }
    }

    fn read(&mut self, file: &File<'_>) -> Result<(), ParseError> {
        for (key, value) in file.entries("gamepad") {
            let value = value.get_ref();
            let set = match key.get_ref().as_str() {
                "look_sensitivity" => {
                    number(value, &GamepadSettings::SENSITIVITY_RANGE).map(|v| self.look_sensitivity = v)
                }
                "dead_zone" => number(value, &GamepadSettings::DEAD_ZONE_RANGE).map(|v| self.dead_zone = v),
                _ => Err(unknown(&["look_sensitivity", "dead_zone"])),
            };
            set.map_err(|problem| file.error(key, "gamepad", problem))?;
        }
        read_pad_bindings(&mut self.bindings, file)
    }
}

/// Like the key bindings, with one button per action: listed actions take what is listed (`[]`
/// unbinds), the others keep their defaults unless a listed action took their button.
fn read_pad_bindings(pad: &mut PadBindings, file: &File<'_>) -> Result<(), ParseError> {
    let mut listed: Vec<(Action, Option<PadButton>)> = Vec::new();
    for (key, value) in file.entries("gamepad_bindings") {
        let fail = |problem: String| file.error(key, "gamepad_bindings", problem);
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
    for action in Action::ALL {
        let button = match listed.iter().find(|(a, _)| *a == action) {
            Some((_, b)) => *b,
            None => pad.get(action).filter(|b| !listed.iter().any(|(_, l)| *l == Some(*b))),
        };
        pad.replace(action, button);
    }
    Ok(())
}

impl OwnSections for GiSettings {
    const SECTIONS: &'static [&'static str] = &["gi"];

    fn write(&self, out: &mut String) {
        let _ = write!(out, "\n[gi]\n# global illumination\nenabled = {}\n", self.enabled);
        for field in GiSettings::FIELDS {
            let v = self.get(field.name).expect("every entry of GiSettings::FIELDS has a value");
            if let Some(name) = field.choice_name(v) {
                let _ = writeln!(out, "# {} ({})", field.help, field.choices.join(", "));
                let _ = writeln!(out, "{} = \"{name}\"", field.name);
                continue;
            }
            let _ = writeln!(out, "# {} ({} to {})", field.help, field.min, field.max);
            if field.integer {
                let _ = writeln!(out, "{} = {}", field.name, v as i64);
            } else {
                let _ = writeln!(out, "{} = {:?}", field.name, v as f32);
            }
        }
    }

    fn read(&mut self, file: &File<'_>) -> Result<(), ParseError> {
        for (key, value) in file.entries("gi") {
            gi_setting(self, key.get_ref(), value.get_ref()).map_err(|problem| file.error(key, "gi", problem))?;
        }
        Ok(())
    }
}

fn gi_setting(gi: &mut GiSettings, name: &str, value: &Value) -> Result<(), String> {
    let text = match (name, value) {
        ("enabled", Value::Boolean(b)) => b.to_string(),
        ("enabled", other) => return Err(format!("expected true or false, found {}", other.type_str())),
        // A switch (`FieldInfo::is_switch`) takes true/false as well as 1/0.
        (_, Value::Boolean(b)) if GiSettings::FIELDS.iter().any(|f| f.name == name && f.is_switch()) => b.to_string(),
        // A choice (`FieldInfo::choices`) takes its name, as written, or its number.
        (_, Value::String(s)) if GiSettings::FIELDS.iter().any(|f| f.name == name && !f.choices.is_empty()) => {
            s.clone()
        }
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
