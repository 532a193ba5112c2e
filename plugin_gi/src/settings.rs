//! The few global variables of the technique (the article keeps them deliberately few).
//! Each is declared once, in the list below, which gives the struct (serde-able for config
//! files), `--set gi.NAME=VALUE` by name, [`GiSettings::FIELDS`] (so a UI can show sliders and a
//! config file comments without knowing the struct) and the table in `docs/gi.md`.

mod declare;

pub use declare::FieldInfo;

use engine::graph::SizeRule;
use serde::{Deserialize, Serialize};

// One entry a setting: `name: type = default, min..=max, "one line"`, the line being what the
// F1 panel, config.toml and docs/gi.md say of it (`declare.rs` tells the rest). Replay headers
// and config files are written in this order: add at the end.
declare::settings! {
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct GiSettings {
        /// `--gi off` on the command line; off leaves the direct-lit renderer.
        enabled: bool = true, "indirect light on or off";
        /// Children merge only if their normals are within this angle (degrees) of their mean.
        merge_normal_deg: f32 = 25.0, 0.0..=90.0, "max normal deviation (degrees) for texels to merge";
        /// …and their positions within this fraction of their distance from the lamp.
        merge_distance: f32 = 0.15, 0.0..=2.0, "max position deviation, as a fraction of distance to the lamp";
        /// A reflection light is split into its four children while its size exceeds this
        /// fraction of its distance to the receivers it lights: smaller is more exact and slower.
        split_ratio: f32 = 0.45, 0.05..=4.0, "split a light while its size exceeds this fraction of its distance";
        /// 1 is the article's one bounce; 2–3 feed the indirect light back as flux.
        bounces: u32 = 1, 1..=3, "number of light bounces";
        /// At least `min_rows` rows, whatever this says.
        resolution_scale: f32 = 0.125, 0.0625..=1.0, "indirect target size relative to the view";
        /// 2: the receivers of each 2×2 share the evaluation of their tile's lights (each
        /// evaluates a quarter and borrows the rest from neighbours on its surface): about 4×
        /// faster on smooth surfaces. 1: every receiver evaluates every light. (A 4×4 pattern's
        /// wider reconstruction costs more than it saves, and its error is larger.)
        interleave: u32 = 2, 1..=2, "2: neighbours share the evaluation of lights (faster); 1: each does all";
        /// Fewer only when the view has fewer: the light's variation across a room needs about
        /// this many. Lower is faster and blurrier; the CPU preset uses 84.
        min_rows: u32 = 90, 16..=360, "fewest rows of the indirect target, whatever the scale";
        /// Each frame's indirect light is this much last frames' (reprojected to the same
        /// world points) and the rest its own gather: the gather's lights sit in screen space,
        /// so its small errors move with the view, and averaging holds them still. 0: none.
        history: f32 = 0.5, 0.0..=0.95, "share of the indirect light kept from earlier frames (0: none)";
        /// Each reflection light's light reaches a receiver only where the segment between
        /// them passes no surface the camera sees (a march through its depth): no light
        /// through walls. 0 is the article's model, every light seen by every receiver.
        visibility: u32 = 1, 0..=1, "the reflection lights' light is stopped by the surfaces between (no light through walls)";
        /// The article's own pipeline beside ours, to run and to measure against (docs/gi.md,
        /// "The article's method"): its distribution table, instance stream and light volumes.
        method: Method = Method::Cuts, 0..=1, "cuts: each tile gathers its own cut of the pyramid; article: the distribution table's lights drawn as light volumes";
        /// The article's light budget: the slots the distribution table takes from the
        /// pyramid (an incoherent slot is drawn as up to 16 finer lights).
        light_budget: u32 = 1024, 64..=4096, "article method: reflection lights the distribution table takes from the pyramid";
        /// Interleaved sampling (Segovia et al. 2006): the lights are dealt into N×N subsets,
        /// each drawn into its own sub-image of every N-th receiver, so a light shades 1/N² of
        /// them; the sub-images are then put back together, each receiver summing the subsets
        /// from its neighbours on its surface.
        article_interleave: u32 = 4, 1..=4, "article method: lights dealt over N×N sub-images, each light shading 1/N² of the receivers";
        /// The article's cutoff, made one that loses nothing: a fine light's volume is the
        /// sphere of this many sizes of the coarse light it refines, around that light; beyond
        /// it the coarse light carries its flux. Larger is closer to every light drawn
        /// everywhere, and slower (100 is that, in any room).
        volume_reach: f32 = 2.5, 1.0..=100.0, "article method: a fine light's volume, in sizes of the coarse light it refines (beyond, the coarse light carries its flux)";
        /// With `visibility`: a segment the camera's depth finds clear is also marched through
        /// the level's surfaces as voxels, built when the level loads, so walls the camera
        /// does not see stop light too. What moves stops light through the camera's depth only.
        world_sight: u32 = 1, 0..=1, "with visibility, light is also stopped by the level's walls the camera does not see (a march through its voxels)";
    }
}

/// How the first bounce is gathered (`gi.method`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Each 8×8 tile of receivers takes its own cut through the pyramid and sums it.
    #[default]
    Cuts,
    /// The article's pipeline: the distribution table's slots of the pyramid become an
    /// instance stream on the GPU, drawn as light volumes, deferred and additive.
    Article,
}

impl declare::Number for Method {
    const INTEGER: bool = true;
    const CHOICES: &'static [&'static str] = &["cuts", "article"];
    fn to_f64(self) -> f64 {
        match self {
            Method::Cuts => 0.0,
            Method::Article => 1.0,
        }
    }
    fn from_f64(v: f64) -> Self {
        if v.round() >= 1.0 {
            Method::Article
        } else {
            Method::Cuts
        }
    }
}

/// Settings that older replays and config files name and the GI does not have (a fixed
/// cutoff and minimum distance): accepted and ignored.
pub const RETIRED: &[&str] = &["cutoff", "d_min"];

impl GiSettings {
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
            log::info!("gi.{name} is not a setting of this GI (it gathers from a light pyramid); ignored");
            return Ok(());
        }
        let Some(info) = Self::FIELDS.iter().find(|f| f.name == name) else {
            let known: Vec<&str> = std::iter::once("enabled").chain(Self::FIELDS.iter().map(|f| f.name)).collect();
            return Err(format!("unknown setting 'gi.{name}' (known: {})", known.join(", ")));
        };
        let switch = match value.trim() {
            "on" | "true" if info.is_switch() => Some(1.0),
            "off" | "false" if info.is_switch() => Some(0.0),
            word => info.choices.iter().position(|c| *c == word).map(|i| i as f64),
        };
        if switch.is_none() && !info.choices.is_empty() && value.trim().parse::<f64>().is_err() {
            return Err(format!("gi.{name}: '{value}' is not one of {}", info.choices.join(", ")));
        }
        let v: f64 = match switch {
            Some(v) => v,
            None => value.trim().parse().map_err(|_| format!("gi.{name}: '{value}' is not a number"))?,
        };
        if !v.is_finite() || v < info.min || v > info.max || (info.integer && v.fract() != 0.0) {
            let kind = if info.integer { "a whole number" } else { "a number" };
            return Err(format!("gi.{name}: {value} is out of range ({kind} from {} to {})", info.min, info.max));
        }
        self.set_number(name, v);
        Ok(())
    }

    /// The indirect target's size rule: `resolution_scale` of the view, but at least
    /// `min_rows` pixels high, as the light's variation across a room needs that many
    /// receivers whatever the output size.
    pub fn indirect_size(&self) -> SizeRule {
        SizeRule::ViewScaledAtLeast(self.resolution_scale, self.min_rows)
    }

    /// What a CPU device (Mesa's lavapipe) gets by default: fewer rows of receivers, so that
    /// the Cellar plays at 15 fps or more with the GI on (with the game's CPU render scale and
    /// dynamic resolution), and still as many as hold its flicker under 1 % and its error
    /// under 5 % (72: 0.84 % and 4.1 %; 45: 1.19 % and 5.4 %, docs/benchmarks.md), and with
    /// visibility within 8 % of the visibility-correct reference (84; 72 gave 10.3 % in the
    /// red/green room, where the light's steep rise into the ceiling's crease needs them).
    pub fn cpu_preset() -> Self {
        Self { min_rows: 84, ..Self::default() }
    }

    /// The table of settings in `docs/gi.md` (a test holds the file to it): name, default,
    /// range and meaning, in the list's order.
    pub fn markdown_table() -> String {
        let defaults = Self::default();
        let on_off = |on: bool| if on { "on" } else { "off" };
        let mut table = String::from("| setting | default | range | meaning |\n| --- | --- | --- | --- |\n");
        table += &format!("| `gi.enabled` | {} | on, off | {} |\n", on_off(defaults.enabled), Self::ENABLED_HELP);
        for f in Self::FIELDS {
            let v = defaults.get(f.name).expect("every entry of FIELDS has a value");
            // As the setting's own type prints it: 0.15, not the f64 of an f32 (0.15000000596…).
            if f.is_switch() {
                table += &format!("| `gi.{}` | {} | on, off (1, 0) | {} |\n", f.name, on_off(v == 1.0), f.help);
                continue;
            }
            if let Some(default) = f.choice_name(v) {
                table += &format!("| `gi.{}` | {default} | {} | {} |\n", f.name, f.choices.join(", "), f.help);
                continue;
            }
            let default = if f.integer { (v as i64).to_string() } else { (v as f32).to_string() };
            table += &format!("| `gi.{}` | {default} | {} to {} | {} |\n", f.name, f.min, f.max, f.help);
        }
        table
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
    fn a_switch_takes_on_and_off_and_nothing_else() {
        let mut s = GiSettings::default();
        assert_eq!(s.visibility, 1, "on by default");
        s.set("visibility", "off").unwrap();
        assert_eq!(s.visibility, 0);
        s.set("visibility", "true").unwrap();
        assert_eq!(s.visibility, 1);
        s.set("visibility", "0").unwrap();
        assert_eq!(s.visibility, 0);
        assert!(s.set("visibility", "2").unwrap_err().contains("out of range"));
        assert!(s.set("visibility", "maybe").unwrap_err().contains("not a number"));
        // Only switches take words: a count does not.
        assert!(s.set("bounces", "on").unwrap_err().contains("not a number"));
    }

    #[test]
    fn a_choice_takes_its_names_and_its_numbers() {
        let mut s = GiSettings::default();
        assert_eq!(s.method, Method::Cuts, "cuts by default");
        s.set("method", "article").unwrap();
        assert_eq!(s.method, Method::Article);
        s.set("method", "0").unwrap();
        assert_eq!(s.method, Method::Cuts);
        let e = s.set("method", "volumes").unwrap_err();
        assert!(e.contains("not one of cuts, article"), "{e}");
        assert!(s.set("method", "2").unwrap_err().contains("out of range"));
        let info = GiSettings::FIELDS.iter().find(|f| f.name == "method").unwrap();
        assert!(!info.is_switch(), "a choice of two is not an on/off switch");
        assert_eq!(info.choice_name(1.0), Some("article"));
        let text = toml::to_string(&GiSettings { method: Method::Article, ..GiSettings::default() }).unwrap();
        assert!(text.contains("method = \"article\""), "{text}");
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
    fn the_list_gives_every_field_its_access_by_name() {
        let mut s = GiSettings::default();
        let names: Vec<&str> = GiSettings::FIELDS.iter().map(|f| f.name).collect();
        // The list's order, which replays and config files follow.
        let order = [
            "merge_normal_deg",
            "merge_distance",
            "split_ratio",
            "bounces",
            "resolution_scale",
            "interleave",
            "min_rows",
            "history",
            "visibility",
            "method",
            "light_budget",
            "article_interleave",
            "volume_reach",
            "world_sight",
        ];
        assert_eq!(names, order);
        assert_eq!(
            GiSettings::FIELDS.iter().filter(|f| f.integer).count(),
            8,
            "bounces, interleave, min_rows, visibility, method, light_budget, article_interleave, world_sight"
        );
        // Compared as f32: an f32 setting holds the f64 bound to f32 precision.
        let get = |s: &GiSettings, name| s.get(name).map(|v| v as f32);
        for f in GiSettings::FIELDS {
            s.set_number(f.name, f.max + 1.0);
            assert_eq!(get(&s, f.name), Some(f.max as f32), "{} clamps to its top", f.name);
            s.set_number(f.name, f.min);
            assert_eq!(get(&s, f.name), Some(f.min as f32), "{} reaches its bottom", f.name);
        }
        s.set_number("bounces", 2.4);
        assert_eq!(s.bounces, 2, "whole-number settings round");
        assert_eq!(s.get("enabled"), None, "the switch is not a number");
        assert_eq!(GiSettings::default().get("min_rows"), Some(90.0));
    }

    #[test]
    fn the_settings_table_in_the_docs_is_the_list() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/gi.md");
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
        let expected = GiSettings::markdown_table();
        // The table is the run of `|` lines that starts with the header row.
        let header = expected.lines().next().unwrap();
        let found: String = text
            .lines()
            .skip_while(|l| *l != header)
            .take_while(|l| l.starts_with('|'))
            .map(|l| format!("{l}\n"))
            .collect();
        assert!(
            found == expected,
            "docs/gi.md's settings table is not GiSettings::markdown_table(); put this there:\n\n{expected}"
        );
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
