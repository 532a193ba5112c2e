//! The macro that turns the one list of GI settings (in `settings.rs`) into the struct and what
//! is derived from it, so that a setting's name, type, default, range and meaning are written
//! once.
//!
//! It names nothing of `settings.rs` (whose list invokes it): what its expansion needs,
//! [`FieldInfo`] and [`Number`], is here, so the two modules do not import each other.

/// What a settings UI or the command line needs to know about one numeric setting.
#[derive(Clone, Copy, Debug)]
pub struct FieldInfo {
    pub name: &'static str,
    pub min: f64,
    pub max: f64,
    pub integer: bool,
    /// Where the setting is one of a few named ways (e.g. `method`: cuts, article): their
    /// names, the value being the index of one; empty for a plain number.
    pub choices: &'static [&'static str],
    pub help: &'static str,
}

impl FieldInfo {
    /// A whole number from 0 to 1: an on/off switch (a checkbox; `--set` takes on/off too).
    pub fn is_switch(&self) -> bool {
        self.integer && self.min == 0.0 && self.max == 1.0 && self.choices.is_empty()
    }

    /// The name of value `v` of a setting with choices (None for a plain number).
    pub fn choice_name(&self, v: f64) -> Option<&'static str> {
        self.choices.get(v.round().max(0.0) as usize).copied()
    }
}

/// A numeric setting's type as access by name sees it: every value travels as an f64 (the
/// command line, sliders, config files and replays all share that), whole-number types round.
pub(crate) trait Number: Copy {
    /// Whole numbers only: a slider steps by 1, `--set` refuses a fraction.
    const INTEGER: bool;
    /// The names of the values 0, 1, … where the type is a choice among named ways.
    const CHOICES: &'static [&'static str] = &[];
    fn to_f64(self) -> f64;
    /// `v` already lies in the setting's range.
    fn from_f64(v: f64) -> Self;
}

impl Number for f32 {
    const INTEGER: bool = false;
    fn to_f64(self) -> f64 {
        self as f64
    }
    fn from_f64(v: f64) -> Self {
        v as f32
    }
}

impl Number for u32 {
    const INTEGER: bool = true;
    fn to_f64(self) -> f64 {
        self as f64
    }
    fn from_f64(v: f64) -> Self {
        v.round() as u32
    }
}

/// Declares the settings struct from one list: first the on/off switch `enabled`, then the
/// numeric settings, each as
///
/// ```text
/// /// What the code's reader should know (optional, any length).
/// name: f32 = default, min..=max, "one line for the F1 panel, config.toml and docs/gi.md";
/// ```
///
/// It gives the struct (the list's order is the field order, which serde, config files and
/// replays follow: append, don't reorder), its `Default`, `ENABLED_HELP`, `FIELDS`, `get` and
/// `set_number`. The one line becomes the first paragraph of the field's documentation.
macro_rules! settings {
    (
        $(#[$struct_attr:meta])*
        pub struct $name:ident {
            $(#[$enabled_attr:meta])*
            enabled: bool = $enabled:expr, $enabled_help:literal;
            $(
                $(#[$attr:meta])*
                $field:ident: $ty:ty = $default:expr, $min:literal..=$max:literal, $help:literal;
            )*
        }
    ) => {
        $(#[$struct_attr])*
        pub struct $name {
            #[doc = $enabled_help]
            #[doc = ""]
            $(#[$enabled_attr])*
            pub enabled: bool,
            $(
                #[doc = $help]
                #[doc = ""]
                $(#[$attr])*
                pub $field: $ty,
            )*
        }

        impl Default for $name {
            fn default() -> Self {
                Self { enabled: $enabled, $($field: $default,)* }
            }
        }

        impl $name {
            /// What the on/off switch `enabled` does, in one line.
            pub const ENABLED_HELP: &'static str = $enabled_help;

            /// The numeric settings, their valid ranges and meaning, in the list's order.
            pub const FIELDS: &'static [$crate::settings::declare::FieldInfo] = &[$(
                $crate::settings::declare::FieldInfo {
                    name: stringify!($field),
                    min: $min as f64,
                    max: $max as f64,
                    integer: <$ty as $crate::settings::declare::Number>::INTEGER,
                    choices: <$ty as $crate::settings::declare::Number>::CHOICES,
                    help: $help,
                },
            )*];

            /// The value of a numeric setting by name.
            pub fn get(&self, name: &str) -> Option<f64> {
                match name {
                    $(stringify!($field) => Some($crate::settings::declare::Number::to_f64(self.$field)),)*
                    _ => None,
                }
            }

            /// Sets a numeric setting, clamped to its range (for sliders); an unknown name does
            /// nothing.
            pub fn set_number(&mut self, name: &str, v: f64) {
                let Some(info) = Self::FIELDS.iter().find(|f| f.name == name) else { return };
                let v = v.clamp(info.min, info.max);
                match name {
                    $(stringify!($field) => self.$field = $crate::settings::declare::Number::from_f64(v),)*
                    _ => {}
                }
            }
        }
    };
}

pub(crate) use settings;
