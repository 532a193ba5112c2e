//! The config file's TOML, both ways, as machinery that knows no [`Config`](super::Config): the
//! writer and the parser work from the tables that the list in `config.rs` declares (passed in
//! as arguments), so that this module names nothing of the config and the config, its macro
//! and the sections may all use it. Parsing keeps every key's position (`toml::Spanned`) so an
//! error can name its line; it checks each value itself rather than through serde derives, so
//! the messages speak of keys and ranges, not of Rust types.

use std::collections::BTreeMap;
use std::fmt::Write;
use std::ops::{Range, RangeInclusive};

use toml::{Spanned, Value};

/// One key of a plain section (`[controls]`, `[video]`, …) of a config `C`, as the file writes
/// and reads it.
pub(super) struct Key<C> {
    pub(super) section: &'static str,
    pub(super) name: &'static str,
    /// The comment line above the key, with `{range}` standing for its range; a key whose name
    /// says it all has none.
    pub(super) comment: Option<&'static str>,
    /// The values a number may take.
    pub(super) range: Option<RangeInclusive<f32>>,
    /// The key's value as the file writes it.
    pub(super) write: fn(&C) -> String,
    /// Takes the file's value for the key, or says what is wrong with it.
    pub(super) read: fn(&mut C, &Value, &Key<C>) -> Result<(), String>,
}

/// A field of a config `C` whose value fills whole sections of the file (the key bindings, the
/// gamepad, the GI): its type writes and reads them, through [`super::sections::OwnSections`].
pub(super) struct Owner<C> {
    pub(super) sections: &'static [&'static str],
    pub(super) write: fn(&C, &mut String),
    pub(super) read: fn(&mut C, &File<'_>) -> Result<(), ParseError>,
}

/// A problem found in the text; [`super::ConfigError`] adds the file.
pub(super) struct ParseError {
    pub line: Option<usize>,
    pub key: Option<String>,
    pub problem: String,
}

const HEADER: &str = "\
# Headlamp settings. The game writes this file when a setting changes; you may edit it.
# A missing key takes its default; an unknown key or a bad value is reported, and the
# file is then kept as config.toml.bad while the game runs with the defaults.
";

/// The file's text for `c`, with a comment on each setting: the plain sections in their order,
/// each with its keys, then the owners' sections.
pub(super) fn write<C>(c: &C, plain_sections: &[&str], keys: &[Key<C>], owners: &[Owner<C>]) -> String {
    let mut out = String::from(HEADER);
    for section in plain_sections {
        let _ = write!(out, "\n[{section}]\n");
        for key in keys.iter().filter(|k| k.section == *section) {
            if let Some(comment) = key.comment {
                let _ = writeln!(out, "# {}", with_range(comment, key));
            }
            let _ = writeln!(out, "{} = {}", key.name, (key.write)(c));
        }
    }
    for owner in owners {
        (owner.write)(c, &mut out);
    }
    out
}

/// A key's comment as written: `{range}` replaced by the key's range.
pub(super) fn with_range<C>(comment: &str, key: &Key<C>) -> String {
    match &key.range {
        Some(range) => comment.replace("{range}", &range_text(range)),
        None => comment.to_owned(),
    }
}

/// `0.1 to 10.0`, as comments and errors give a range.
pub(super) fn range_text(range: &RangeInclusive<f32>) -> String {
    format!("{:?} to {:?}", range.start(), range.end())
}

/// How a plain key's value is written and read: a number in its range, or true/false.
pub(super) trait KeyValue: Sized {
    fn write(&self) -> String;
    fn read<C>(value: &Value, key: &Key<C>) -> Result<Self, String>;
}

impl KeyValue for f32 {
    /// `{:?}` writes an f32 as the shortest text that reads back as the same f32, always with a
    /// decimal point or exponent, so TOML keeps it a float.
    fn write(&self) -> String {
        format!("{self:?}")
    }

    fn read<C>(value: &Value, key: &Key<C>) -> Result<Self, String> {
        let range = key.range.as_ref().unwrap_or_else(|| panic!("the number {} declares no range", key.name));
        number(value, range)
    }
}

impl KeyValue for bool {
    fn write(&self) -> String {
        self.to_string()
    }

    fn read<C>(value: &Value, _: &Key<C>) -> Result<Self, String> {
        boolean(value)
    }
}

type Entries = BTreeMap<Spanned<String>, Spanned<Value>>;

/// The file read: its sections with their keys' positions, and its text for line numbers.
pub(super) struct File<'t> {
    text: &'t str,
    sections: BTreeMap<String, Entries>,
}

impl File<'_> {
    /// A section's entries in the order they appear in the file (none when it is absent), so
    /// the first error reported is the first one.
    pub(super) fn entries(&self, section: &str) -> Vec<(&Spanned<String>, &Spanned<Value>)> {
        self.sections.get(section).map(by_position).unwrap_or_default()
    }

    /// The problem with `key` of `section`, with its line.
    pub(super) fn error(&self, key: &Spanned<String>, section: &str, problem: String) -> ParseError {
        key_error(self.text, key, section, problem)
    }
}

/// Every section that the file may have, in its order.
pub(super) fn section_names<C>(plain_sections: &[&'static str], owners: &[Owner<C>]) -> Vec<&'static str> {
    plain_sections.iter().copied().chain(owners.iter().flat_map(|o| o.sections.iter().copied())).collect()
}

/// Reads a config from the file's text: its default, with what the file says of each key.
pub(super) fn parse<C: Default>(
    text: &str,
    plain_sections: &[&'static str],
    keys: &[Key<C>],
    owners: &[Owner<C>],
) -> Result<C, ParseError> {
    let syntax = |e: toml::de::Error| ParseError {
        line: e.span().map(|span| line_of(text, span)),
        key: None,
        problem: format!("not valid TOML: {}", e.message().trim().replace('\n', " ")),
    };

    // Every top-level key first, so that a stray one is named rather than failing the sections.
    let top: Entries = toml::from_str(text).map_err(syntax)?;
    let known = section_names(plain_sections, owners);
    for (key, value) in by_position(&top) {
        if !known.contains(&key.get_ref().as_str()) {
            return Err(key_error(text, key, "", format!("unknown key (the sections are {})", list(&known))));
        }
        if !value.get_ref().is_table() {
            return Err(key_error(text, key, "", format!("must be a section, [{}]", key.get_ref())));
        }
    }
    let file = File { text, sections: toml::from_str(text).map_err(syntax)? };

    let mut c = C::default();
    for section in plain_sections {
        let keys: Vec<&Key<C>> = keys.iter().filter(|k| k.section == *section).collect();
        for (name, value) in file.entries(section) {
            let Some(key) = keys.iter().find(|k| k.name == name.get_ref()) else {
                let known: Vec<&str> = keys.iter().map(|k| k.name).collect();
                return Err(file.error(name, section, unknown(&known)));
            };
            (key.read)(&mut c, value.get_ref(), key).map_err(|problem| file.error(name, section, problem))?;
        }
    }
    for owner in owners {
        (owner.read)(&mut c, &file)?;
    }
    Ok(c)
}

fn line_of(text: &str, span: Range<usize>) -> usize {
    text[..span.start.min(text.len())].matches('\n').count() + 1
}

/// The problem with `key` of `section` (`""` for a top-level key), with its line.
fn key_error(text: &str, key: &Spanned<String>, section: &str, problem: String) -> ParseError {
    ParseError {
        line: Some(line_of(text, key.span())),
        key: Some(if section.is_empty() { key.get_ref().clone() } else { format!("{section}.{}", key.get_ref()) }),
        problem,
    }
}

/// Entries in the order they appear in the file, so the first error reported is the first one.
fn by_position(entries: &Entries) -> Vec<(&Spanned<String>, &Spanned<Value>)> {
    let mut v: Vec<_> = entries.iter().collect();
    v.sort_by_key(|(k, _)| k.span().start);
    v
}

pub(super) fn number(value: &Value, range: &RangeInclusive<f32>) -> Result<f32, String> {
    let v = match value {
        Value::Float(f) => *f,
        Value::Integer(i) => *i as f64,
        other => return Err(format!("expected a number, found {}", other.type_str())),
    };
    // Compared as the f32 it becomes: the file's "0.1" is the range's 0.1f32.
    if !range.contains(&(v as f32)) {
        return Err(format!("{v} is out of range ({})", range_text(range)));
    }
    Ok(v as f32)
}

fn boolean(value: &Value) -> Result<bool, String> {
    value.as_bool().ok_or_else(|| format!("expected true or false, found {}", value.type_str()))
}

pub(super) fn unknown(known: &[&str]) -> String {
    format!("unknown key (known: {})", list(known))
}

fn list(names: &[&str]) -> String {
    names.join(", ")
}
