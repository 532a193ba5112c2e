//! `level.toml`: the serde schema and its checks (the contract is documented in `level.rs`).
//!
//! Parsing happens in two steps so errors are precise: first as plain TOML (a syntax error
//! says "level.toml:3:9: invalid TOML: ..."), then into the schema with `deny_unknown_fields`
//! (a typo says "level.toml:4:1: invalid level: unknown field `powr`, expected one of ...").
//! Value checks that serde cannot express name the offending key, e.g. `headlamp.outer_deg`,
//! and are placed where that key is written.

use std::path::Path;

use glam::Vec3;
use serde::Deserialize;

use crate::distribution_image::DistributionImage;
use crate::error::{one_line, LoadError, LoadErrorKind, TextPos};
use crate::headlamp_profile::{HeadlampProfile, IntensityDistribution};
use crate::ies::{ies_texture_size, read_ies};
use crate::image_loader::decode_image;
use crate::limits::MAX_PROFILE_SIZE;
use crate::sources::Sources;
use crate::spawn::Spawn;
use crate::toml_place::{key_place, leading_key};
use crate::{LightKind, PunctualLight};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LevelToml {
    name: String,
    #[serde(default)]
    description: String,
    scene: String,
    exposure: Option<f32>,
    spawn: Option<SpawnToml>,
    #[serde(default)]
    headlamp: HeadlampToml,
    #[serde(default)]
    lights: Vec<LightToml>,
    #[serde(default)]
    game: toml::Table,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SpawnToml {
    position: [f32; 3],
    #[serde(default)]
    yaw_deg: f32,
    #[serde(default)]
    pitch_deg: f32,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(crate) struct HeadlampToml {
    power: Option<f32>,
    fov_deg: Option<f32>,
    profile: Option<String>,
    inner_deg: Option<f32>,
    outer_deg: Option<f32>,
    color: Option<[f32; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightToml {
    name: Option<String>,
    kind: LightKindToml,
    position: Option<[f32; 3]>,
    direction: Option<[f32; 3]>,
    color: Option<[f32; 3]>,
    intensity: Option<f32>,
    range: Option<f32>,
    inner_deg: Option<f32>,
    outer_deg: Option<f32>,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Debug)]
#[serde(rename_all = "lowercase")]
enum LightKindToml {
    Point,
    Spot,
    Directional,
}

/// level.toml after parsing and checking, except the headlamp profile image which is read
/// after the scene (so the content hash order is level.toml, scene files, profile).
pub(crate) struct ParsedLevel {
    pub name: String,
    pub description: String,
    pub scene: String,
    pub exposure: Option<f32>,
    pub spawn: Option<Spawn>,
    pub lights: Vec<PunctualLight>,
    pub game: toml::Table,
    headlamp: HeadlampToml,
    /// Keys that are legal but do nothing, placed in the file, for [`Sources::warn`].
    pub warnings: Vec<(Option<TextPos>, String)>,
}

pub(crate) fn parse_level_toml(bytes: &[u8], path: &Path) -> Result<ParsedLevel, LoadError> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let valid = std::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or("");
        LoadError::new(path, LoadErrorKind::TomlSyntax("not valid UTF-8".into()))
            .at(Some(TextPos::of_offset(valid, valid.len())))
    })?;
    if let Err(e) = text.parse::<toml::Table>() {
        let (at, message) = locate(text, &e);
        return Err(
            LoadError::new(path, LoadErrorKind::TomlSyntax(message)).at(at.or(Some(TextPos::of_offset(text, 0))))
        );
    }
    let raw: LevelToml = toml::from_str(text).map_err(|e| {
        let (at, message) = locate(text, &e);
        LoadError::new(path, LoadErrorKind::LevelSchema(message)).at(at)
    })?;
    let bad = |msg: String| {
        let at = key_place(text, leading_key(&msg));
        LoadError::level(path, msg).at(at)
    };

    if raw.name.trim().is_empty() {
        return Err(bad("name must not be empty".into()));
    }
    if let Some(e) = raw.exposure.filter(|e| !(*e > 0.0 && e.is_finite())) {
        return Err(bad(format!("exposure ({e}) must be greater than 0")));
    }
    let spawn = match raw.spawn {
        None => None,
        Some(s) => {
            check_finite(&s.position, "spawn.position").map_err(bad)?;
            if !s.yaw_deg.is_finite() {
                return Err(bad("spawn.yaw_deg must be a finite number".into()));
            }
            if s.pitch_deg.is_nan() || s.pitch_deg.abs() > 90.0 {
                return Err(bad(format!("spawn.pitch_deg ({}) must be within [-90, 90]", s.pitch_deg)));
            }
            Some(Spawn {
                position: Vec3::from(s.position),
                yaw: s.yaw_deg.to_radians(),
                pitch: s.pitch_deg.to_radians(),
            })
        }
    };
    let mut ignored = Vec::new();
    let lights = raw
        .lights
        .iter()
        .enumerate()
        .map(|(i, l)| light(i, l, &mut ignored).map_err(bad))
        .collect::<Result<Vec<_>, _>>()?;
    if raw.headlamp.profile.as_deref() != Some("spot") {
        for (key, value) in [("inner_deg", raw.headlamp.inner_deg), ("outer_deg", raw.headlamp.outer_deg)] {
            if value.is_some() {
                ignored.push(format!("headlamp.{key} is ignored: it only applies to profile = \"spot\""));
            }
        }
    }
    let warnings = ignored.into_iter().map(|msg| (key_place(text, leading_key(&msg)), msg)).collect();
    check_headlamp_values(&raw.headlamp).map_err(bad)?;
    if raw.description.contains('\n') {
        return Err(bad("description must be one line (the level menu shows it under the name)".into()));
    }
    Ok(ParsedLevel {
        name: raw.name,
        description: raw.description,
        scene: raw.scene,
        exposure: raw.exposure,
        spawn,
        lights,
        game: raw.game,
        headlamp: raw.headlamp,
        warnings,
    })
}

impl ParsedLevel {
    /// Builds the headlamp, reading the profile image or .ies file (inside the level folder) if
    /// one is named.
    pub fn headlamp(&self, toml_path: &Path, dir: &Path, sources: &mut Sources) -> Result<HeadlampProfile, LoadError> {
        let h = &self.headlamp;
        let defaults = HeadlampProfile::default();
        let profile = h.profile.as_deref().unwrap_or("uniform");
        let fov_y = h.fov_deg.map_or(defaults.fov_y, f32::to_radians);
        let distribution = match profile {
            "uniform" => IntensityDistribution::Uniform,
            "spot" => IntensityDistribution::Spot {
                inner: h.inner_deg.unwrap_or(20.0).to_radians(),
                outer: h.outer_deg.unwrap_or(30.0).to_radians(),
            },
            file if is_ies(file) => {
                let ies_path = sources.resolve(toml_path, dir, file)?;
                let ies = read_ies(&ies_path, sources)?;
                // Checked over the put-down lamp's frustum (fov_deg, square); the renderer
                // bakes it for each frustum the lamp has.
                let size = ies_texture_size(fov_y);
                if ies.distribution(fov_y, 1.0, size, size).values.iter().all(|v| v[0] == 0.0) {
                    let fov = fov_y.to_degrees();
                    sources.warn(&ies_path, None, format!("no light inside the lamp frustum (fov_deg = {fov})"));
                }
                IntensityDistribution::Photometric(ies)
            }
            file => {
                let image_path = sources.resolve(toml_path, dir, file)?;
                let bytes = sources.read(&image_path)?;
                IntensityDistribution::Image(distribution_image(&bytes, &image_path)?)
            }
        };
        Ok(HeadlampProfile {
            power: h.power.unwrap_or(defaults.power),
            fov_y,
            color: h.color.unwrap_or(defaults.color),
            distribution,
        })
    }
}

/// An IESNA LM-63 photometric file, by its extension (any case).
fn is_ies(file: &str) -> bool {
    Path::new(file).extension().is_some_and(|e| e.eq_ignore_ascii_case("ies"))
}

fn check_headlamp_values(h: &HeadlampToml) -> Result<(), String> {
    if let Some(p) = h.power.filter(|p| !(*p >= 0.0 && p.is_finite())) {
        return Err(format!("headlamp.power ({p}) must be >= 0"));
    }
    if let Some(f) = h.fov_deg.filter(|f| !(*f > 1.0 && *f < 179.0)) {
        return Err(format!("headlamp.fov_deg ({f}) must be between 1 and 179"));
    }
    if let Some(c) = &h.color {
        check_colour(c, "headlamp.color")?;
    }
    if h.profile.as_deref() == Some("spot") {
        check_cone(h.inner_deg.unwrap_or(20.0), h.outer_deg.unwrap_or(30.0), "headlamp")?;
    }
    Ok(())
}

/// A `[[lights]]` entry; keys it ignores are added to `ignored`, each message starting with
/// its key.
fn light(i: usize, l: &LightToml, ignored: &mut Vec<String>) -> Result<PunctualLight, String> {
    let at = format!("lights[{i}]");
    let kind_name = format!("{:?}", l.kind).to_lowercase();
    let color = l.color.unwrap_or([1.0; 3]);
    check_colour(&color, &format!("{at}.color"))?;
    let intensity = l.intensity.unwrap_or(1.0);
    if !(intensity >= 0.0 && intensity.is_finite()) {
        return Err(format!("{at}.intensity ({intensity}) must be >= 0"));
    }
    if let Some(r) = l.range.filter(|r| !(*r > 0.0 && r.is_finite())) {
        return Err(format!("{at}.range ({r}) must be greater than 0"));
    }
    let position = match (l.kind, l.position) {
        (_, Some(p)) => {
            check_finite(&p, &format!("{at}.position"))?;
            Vec3::from(p)
        }
        (LightKindToml::Directional, None) => Vec3::ZERO,
        (_, None) => return Err(format!("{at}: a {kind_name} light needs a position")),
    };
    let direction = match (l.kind, l.direction) {
        (LightKindToml::Point, d) => {
            if d.is_some() {
                ignored.push(format!("{at}.direction is ignored: a point light shines every way"));
            }
            Vec3::NEG_Z
        }
        (_, None) => return Err(format!("{at}: a {kind_name} light needs a direction")),
        (_, Some(d)) => Vec3::from(d)
            .try_normalize()
            .ok_or_else(|| format!("{at}.direction {d:?} must be a non-zero finite vector"))?,
    };
    let kind = match l.kind {
        LightKindToml::Point => LightKind::Point,
        LightKindToml::Directional => LightKind::Directional,
        LightKindToml::Spot => {
            let (inner, outer) = (l.inner_deg.unwrap_or(0.0), l.outer_deg.unwrap_or(45.0));
            check_cone(inner, outer, &at)?;
            LightKind::Spot { inner_cone: inner.to_radians(), outer_cone: outer.to_radians() }
        }
    };
    if l.kind != LightKindToml::Spot && (l.inner_deg.is_some() || l.outer_deg.is_some()) {
        return Err(format!("{at}: inner_deg/outer_deg only apply to spot lights"));
    }
    Ok(PunctualLight {
        name: l.name.clone().unwrap_or_else(|| format!("level light {i}")),
        kind,
        position,
        direction,
        color,
        intensity,
        range: l.range,
    })
}

fn check_cone(inner: f32, outer: f32, at: &str) -> Result<(), String> {
    if inner.is_nan() || inner < 0.0 {
        return Err(format!("{at}.inner_deg ({inner}) must be >= 0"));
    }
    if outer.is_nan() || outer <= inner {
        return Err(format!("{at}.outer_deg ({outer}) must be greater than inner_deg ({inner})"));
    }
    if outer > 90.0 {
        return Err(format!("{at}.outer_deg ({outer}) must be <= 90"));
    }
    Ok(())
}

fn check_finite(v: &[f32; 3], at: &str) -> Result<(), String> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(format!("{at} {v:?} must be finite"))
    }
}

fn check_colour(c: &[f32; 3], at: &str) -> Result<(), String> {
    if c.iter().all(|v| v.is_finite() && *v >= 0.0) {
        Ok(())
    } else {
        Err(format!("{at} {c:?} must be finite and >= 0"))
    }
}

/// Decodes a headlamp intensity texture. Integer formats are normalised (PNG 8-bit: v/255),
/// not sRGB-decoded, because they store intensities; float formats (EXR) are taken as is.
fn distribution_image(bytes: &[u8], path: &Path) -> Result<DistributionImage, LoadError> {
    let image = decode_image(bytes, path, "", MAX_PROFILE_SIZE)?.to_rgb32f();
    let (width, height) = image.dimensions();
    let values: Vec<[f32; 3]> = image.pixels().map(|p| p.0).collect();
    if values.iter().flatten().any(|v| !(v.is_finite() && *v >= 0.0)) {
        return Err(LoadError::new(
            path,
            LoadErrorKind::Image("intensity distribution has negative or non-finite values".into()),
        ));
    }
    Ok(DistributionImage { width, height, values })
}

/// Where a TOML error is and its message, quoting the offending line when the error is about
/// one line (toml's messages do not always say which key was wrong). A missing top-level key
/// has no place: the error spans the whole document.
fn locate(text: &str, e: &toml::de::Error) -> (Option<TextPos>, String) {
    let message = one_line(e.message());
    let Some(span) = e.span() else { return (None, message) };
    let start = span.start.min(text.len());
    let spanned = text.get(start..span.end.min(text.len())).unwrap_or("");
    let at = TextPos::of_offset(text, start);
    if message.starts_with("missing field") {
        return ((start > 0).then_some(at), message);
    }
    let source_line = text.lines().nth(at.line - 1).unwrap_or("").trim();
    if !spanned.trim_end().contains('\n') && !source_line.is_empty() && source_line.len() <= 120 {
        (Some(at), format!("{message} (in `{source_line}`)"))
    } else {
        (Some(at), message)
    }
}
