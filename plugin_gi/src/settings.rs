//! The few global variables of the technique (the article keeps them deliberately few).
//! Serde-able for config files, settable by name for `--set gi.NAME=VALUE`, and described by
//! [`GiSettings::FIELDS`] so a UI can show sliders without knowing the struct.

use engine::graph::SizeRule;
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GiSettings {
    /// Indirect light on or off (`--gi off`); off leaves the direct-lit renderer.
    pub enabled: bool,
    /// Children merge only if their normals are within this angle (degrees) of their mean.
    pub merge_normal_deg: f32,
    /// …and their positions within this fraction of their distance from the lamp.
    pub merge_distance: f32,
    /// A reflection light is split into its four children while its size exceeds this
    /// fraction of its distance to the receivers it lights: smaller is more exact and slower.
    pub split_ratio: f32,
    /// Light bounces: 1 is the article's one bounce; 2–3 feed the indirect light back as flux.
    pub bounces: u32,
    /// Size of the indirect-light target relative to the view.
    pub resolution_scale: f32,
    /// 2: the receivers of each 2×2 share the evaluation of their tile's lights (each evaluates
    /// a quarter and borrows the rest from neighbours on its surface): about 4× faster on
    /// smooth surfaces. 1: every receiver evaluates every light. (A 4×4 pattern was tried: its
    /// wider reconstruction cost more than it saved, and the error grew.)
    pub interleave: u32,
    /// The fewest rows of receivers the indirect target has, whatever `resolution_scale` says
    /// (fewer only when the view has fewer): the light's variation across a room needs about
    /// this many. Lower is faster and blurrier; the CPU preset uses 45.
    pub min_rows: u32,
}

impl Default for GiSettings {
    fn default() -> Self {
        Self {
            enabled: true,
            merge_normal_deg: 25.0,
            merge_distance: 0.15,
            split_ratio: 0.45,
            bounces: 1,
            resolution_scale: 0.125,
            interleave: 2,
            min_rows: 90,
        }
    }
}

/// What a settings UI or the command line needs to know about one field.
#[derive(Clone, Copy, Debug)]
pub struct FieldInfo {
    pub name: &'static str,
    pub min: f64,
    pub max: f64,
    pub integer: bool,
    pub help: &'static str,
}

const fn field(name: &'static str, min: f64, max: f64, integer: bool, help: &'static str) -> FieldInfo {
    FieldInfo { name, min, max, integer, help }
}

/// Settings of the light-volume GI (before the pyramid gather) that older replays and config
/// files still name: accepted and ignored.
pub const RETIRED: &[&str] = &["light_budget", "cutoff", "d_min"];

impl GiSettings {
    /// The numeric fields, their valid ranges and meaning (`enabled` is the on/off switch).
    pub const FIELDS: &'static [FieldInfo] = &[
        field("merge_normal_deg", 0.0, 90.0, false, "max normal deviation (degrees) for texels to merge"),
        field("merge_distance", 0.0, 2.0, false, "max position deviation, as a fraction of distance to the lamp"),
        field("split_ratio", 0.05, 4.0, false, "split a light while its size exceeds this fraction of its distance"),
        field("bounces", 1.0, 3.0, true, "number of light bounces"),
        field("resolution_scale", 0.0625, 1.0, false, "indirect target size relative to the view"),
        field("interleave", 1.0, 2.0, true, "2: neighbours share the evaluation of lights (faster); 1: each does all"),
        field("min_rows", 16.0, 360.0, true, "fewest rows of the indirect target, whatever the scale"),
    ];

    /// The value of a numeric field by name.
    pub fn get(&self, name: &str) -> Option<f64> {
        Some(match name {
            "merge_normal_deg" => self.merge_normal_deg as f64,
            "merge_distance" => self.merge_distance as f64,
            "split_ratio" => self.split_ratio as f64,
            "bounces" => self.bounces as f64,
            "resolution_scale" => self.resolution_scale as f64,
            "interleave" => self.interleave as f64,
            "min_rows" => self.min_rows as f64,
            _ => return None,
        })
    }

    /// Sets a field from text, as `--set gi.NAME=VALUE` does; the error says what is wrong.
    pub fn set(&mut self, name: &str, value: &str) -> Result<(), String> {
        if name == "enabled" {
            self.enabled = match value.trim() {
                "true" | "on" | "1" => true,
                "false" | "off" | "0" => false,
                _ => return Err(format!("gi.enabled: '{value}' is not on/off/true/false")),
            };
            return Ok(());
        }
        if RETIRED.contains(&name) {
            log::info!("gi.{name} no longer exists (the GI gathers from a light pyramid); ignored");
            return Ok(());
        }
        let Some(info) = Self::FIELDS.iter().find(|f| f.name == name) else {
            let known: Vec<&str> = std::iter::once("enabled").chain(Self::FIELDS.iter().map(|f| f.name)).collect();
            return Err(format!("unknown setting 'gi.{name}' (known: {})", known.join(", ")));
        };
        let v: f64 = value.trim().parse().map_err(|_| format!("gi.{name}: '{value}' is not a number"))?;
        if !v.is_finite() || v < info.min || v > info.max || (info.integer && v.fract() != 0.0) {
            let kind = if info.integer { "a whole number" } else { "a number" };
            return Err(format!("gi.{name}: {value} is out of range ({kind} from {} to {})", info.min, info.max));
        }
        self.set_number(name, v);
        Ok(())
    }

    /// Sets a numeric field, clamped to its range (for sliders).
    pub fn set_number(&mut self, name: &str, v: f64) {
        let Some(info) = Self::FIELDS.iter().find(|f| f.name == name) else { return };
        let v = v.clamp(info.min, info.max);
        match name {
            "merge_normal_deg" => self.merge_normal_deg = v as f32,
            "merge_distance" => self.merge_distance = v as f32,
            "split_ratio" => self.split_ratio = v as f32,
            "bounces" => self.bounces = v.round() as u32,
            "resolution_scale" => self.resolution_scale = v as f32,
            "interleave" => self.interleave = v.round() as u32,
            "min_rows" => self.min_rows = v.round() as u32,
            _ => {}
        }
    }

    /// The indirect target's size rule: `resolution_scale` of the view, but at least
    /// `min_rows` pixels high, as the light's variation across a room needs that many
    /// receivers whatever the output size.
    pub fn indirect_size(&self) -> SizeRule {
        SizeRule::ViewScaledAtLeast(self.resolution_scale, self.min_rows)
    }

    /// What a CPU device (Mesa's lavapipe) gets by default: fewer rows of receivers, so that
    /// the Cellar plays at 15 fps or more with the GI on (with the game's CPU render scale).
    pub fn cpu_preset() -> Self {
        Self { min_rows: 45, ..Self::default() }
    }
}

/// The pyramid level below which lights are not split: the footprint of one receiver of the
/// indirect target (finer senders would be finer than the receivers sampling them).
pub fn min_level(view_height: u32, indirect_height: u32) -> u32 {
    (view_height as f32 / indirect_height.max(1) as f32).log2().floor().clamp(0.0, 3.0) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_by_name_validates() {
        let mut s = GiSettings::default();
        s.set("split_ratio", "0.25").unwrap();
        assert_eq!(s.split_ratio, 0.25);
        s.set("enabled", "off").unwrap();
        assert!(!s.enabled);
        assert!(s.set("bounces", "2.5").unwrap_err().contains("whole number"));
        assert!(s.set("bounces", "4").unwrap_err().contains("out of range"));
        assert!(s.set("split_ratio", "abc").unwrap_err().contains("not a number"));
        assert!(s.set("nope", "1").unwrap_err().contains("unknown setting 'gi.nope'"));
    }

    #[test]
    fn retired_settings_of_old_replays_and_configs_are_ignored() {
        let mut s = GiSettings::default();
        for name in RETIRED {
            s.set(name, "7").unwrap();
        }
        assert_eq!(s, GiSettings::default());
    }

    #[test]
    fn every_field_round_trips_through_get_and_toml() {
        let s = GiSettings::default();
        for f in GiSettings::FIELDS {
            let v = s.get(f.name).unwrap();
            assert!(v >= f.min && v <= f.max, "{} default {v} outside its range", f.name);
        }
        let text = toml::to_string(&s).unwrap();
        assert_eq!(toml::from_str::<GiSettings>(&text).unwrap(), s);
        assert!(toml::from_str::<GiSettings>("lite_budget = 3").is_err());
    }

    #[test]
    fn receivers_footprint_sets_the_finest_split() {
        assert_eq!((min_level(360, 360), min_level(360, 180), min_level(360, 90), min_level(720, 90)), (0, 1, 2, 3));
        assert_eq!(min_level(100, 90), 0);
    }

    #[test]
    fn the_indirect_target_keeps_enough_receivers() {
        let s = GiSettings::default();
        assert_eq!(s.indirect_size().resolve((1920, 1080)), (240, 135));
        assert_eq!(s.indirect_size().resolve((1280, 720)), (160, 90));
        assert_eq!(s.indirect_size().resolve((640, 360)), (160, 90));
        assert_eq!(s.indirect_size().resolve((160, 120)), (120, 90));
        assert_eq!(s.indirect_size().resolve((64, 48)), (64, 48));
    }
}
