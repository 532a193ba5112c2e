//! The few global variables of the technique (the article keeps them deliberately few).
//! Serde-able for config files, settable by name for `--set gi.NAME=VALUE`, and described by
//! [`GiSettings::FIELDS`] so a UI can show sliders without knowing the struct.

use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GiSettings {
    /// Indirect light on or off (`--gi off`); off leaves the direct-lit renderer.
    pub enabled: bool,
    /// Target number of reflection lights per bounce.
    pub light_budget: u32,
    /// Children merge only if their normals are within this angle (degrees) of their mean.
    pub merge_normal_deg: f32,
    /// …and their positions within this fraction of their distance from the lamp.
    pub merge_distance: f32,
    /// A reflection light's volume ends where its irradiance falls below this fraction of
    /// E_ref = Φ_total/(π d̄²), the irradiance all the reflected flux gives at the mean distance
    /// from the lamp. Relative, so it means the same in any scene and at any light count.
    pub cutoff: f32,
    /// Minimum distance (m) in the 1/d² of a reflection light, against the point-light singularity.
    pub d_min: f32,
    /// Light bounces: 1 is the article's one bounce; 2–3 feed the indirect light back as flux.
    pub bounces: u32,
    /// Size of the indirect-light target relative to the view.
    pub resolution_scale: f32,
}

impl Default for GiSettings {
    fn default() -> Self {
        Self {
            enabled: true,
            light_budget: 1024,
            merge_normal_deg: 25.0,
            merge_distance: 0.15,
            cutoff: 1e-3,
            d_min: 0.1,
            bounces: 1,
            resolution_scale: 0.5,
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

impl GiSettings {
    /// The numeric fields, their valid ranges and meaning (`enabled` is the on/off switch).
    pub const FIELDS: &'static [FieldInfo] = &[
        field("light_budget", 16.0, 65536.0, true, "target number of reflection lights per bounce"),
        field("merge_normal_deg", 0.0, 90.0, false, "max normal deviation (degrees) for texels to merge"),
        field("merge_distance", 0.0, 2.0, false, "max position deviation, as a fraction of distance to the lamp"),
        field("cutoff", 1e-7, 1.0, false, "where a light's volume ends, relative to the scene's mean irradiance"),
        field("d_min", 0.001, 2.0, false, "minimum distance (m) in a reflection light's 1/d²"),
        field("bounces", 1.0, 3.0, true, "number of light bounces"),
        field("resolution_scale", 0.125, 1.0, false, "indirect target size relative to the view"),
    ];

    /// The value of a numeric field by name.
    pub fn get(&self, name: &str) -> Option<f64> {
        Some(match name {
            "light_budget" => self.light_budget as f64,
            "merge_normal_deg" => self.merge_normal_deg as f64,
            "merge_distance" => self.merge_distance as f64,
            "cutoff" => self.cutoff as f64,
            "d_min" => self.d_min as f64,
            "bounces" => self.bounces as f64,
            "resolution_scale" => self.resolution_scale as f64,
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
            "light_budget" => self.light_budget = v.round() as u32,
            "merge_normal_deg" => self.merge_normal_deg = v as f32,
            "merge_distance" => self.merge_distance = v as f32,
            "cutoff" => self.cutoff = v as f32,
            "d_min" => self.d_min = v as f32,
            "bounces" => self.bounces = v.round() as u32,
            "resolution_scale" => self.resolution_scale = v as f32,
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_by_name_validates() {
        let mut s = GiSettings::default();
        s.set("light_budget", "256").unwrap();
        assert_eq!(s.light_budget, 256);
        s.set("enabled", "off").unwrap();
        assert!(!s.enabled);
        assert!(s.set("light_budget", "2.5").unwrap_err().contains("whole number"));
        assert!(s.set("bounces", "4").unwrap_err().contains("out of range"));
        assert!(s.set("d_min", "abc").unwrap_err().contains("not a number"));
        assert!(s.set("nope", "1").unwrap_err().contains("unknown setting 'gi.nope'"));
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
}
