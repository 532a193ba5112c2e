//! Every key level.toml takes, described once: `headlamp check --reference` prints the
//! reference modders read from this table, and tests hold the table to the schema the loader
//! parses with (every key here parses, and every key the schema takes is here).

/// One key: its dotted name (`[[lights]]` entries as `lights[].KEY`), what it holds, its
/// default, what it means, and an example value (valid TOML).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct KeyDoc {
    pub key: &'static str,
    pub kind: &'static str,
    pub default: &'static str,
    pub meaning: &'static str,
    pub example: &'static str,
}

const fn key(
    key: &'static str,
    kind: &'static str,
    default: &'static str,
    meaning: &'static str,
    example: &'static str,
) -> KeyDoc {
    KeyDoc { key, kind, default, meaning, example }
}

/// level.toml's keys, in the order the reference lists them. `[game]` belongs to the game
/// (which documents its own keys); the engine keeps that table as written.
pub const LEVEL_KEYS: &[KeyDoc] = &[
    key("name", "text", "required", "the level's name (menus, HUD), not empty", "\"The Cellar\""),
    key("description", "text, one line", "none", "shown under the name in the level menu", "\"Four rooms and a hall\""),
    key(
        "scene",
        "path",
        "required",
        "the .gltf, .glb or .obj scene, relative to the level folder; may not leave it",
        "\"scene.gltf\"",
    ),
    key(
        "exposure",
        "number > 0",
        "from the scene's size and the lamp's power",
        "multiplies radiance before the tonemap",
        "0.3",
    ),
    key(
        "spawn.position",
        "[x, y, z] m",
        "the scene's camera, else a framing view",
        "the player's feet (eyes are 1.6 m above)",
        "[0.0, 0.0, 3.8]",
    ),
    key("spawn.yaw_deg", "degrees", "0", "0 looks down -Z, positive turns left", "0.0"),
    key("spawn.pitch_deg", "degrees in [-90, 90]", "0", "positive looks up", "0.0"),
    key(
        "headlamp.power",
        "W/sr >= 0",
        "1",
        "P in I(w) = P * T(w): the radiant intensity of the brightest direction",
        "40.0",
    ),
    key(
        "headlamp.fov_deg",
        "degrees in (1, 179)",
        "60",
        "vertical field of view of the lamp's frustum when put down",
        "70.0",
    ),
    key(
        "headlamp.profile",
        "\"uniform\", \"spot\" or a path",
        "\"uniform\"",
        "T: even, a spot cone, a PNG/EXR intensity texture over the frustum, or an IES (LM-63) photometric file",
        "\"spot\"",
    ),
    key("headlamp.inner_deg", "degrees >= 0", "20", "spot: full intensity inside this half-angle", "18.0"),
    key("headlamp.outer_deg", "degrees, > inner, <= 90", "30", "spot: no light beyond this half-angle", "34.0"),
    key("headlamp.color", "[r, g, b] >= 0", "[1, 1, 1]", "linear tint of T", "[1.0, 0.95, 0.85]"),
    key("lights[].name", "text", "\"level light N\"", "a name for messages", "\"lamp\""),
    key("lights[].kind", "\"point\", \"spot\" or \"directional\"", "required", "what kind of light", "\"spot\""),
    key("lights[].position", "[x, y, z] m", "required for point and spot", "where it is", "[0.0, 2.5, 0.0]"),
    key(
        "lights[].direction",
        "[x, y, z], not zero",
        "required for spot and directional",
        "where it shines (normalised on load)",
        "[0.0, -1.0, 0.0]",
    ),
    key("lights[].color", "[r, g, b] >= 0", "[1, 1, 1]", "linear colour", "[1.0, 0.6, 0.3]"),
    key("lights[].intensity", "number >= 0", "1", "W/sr (point, spot) or W/m2 (directional)", "2.0"),
    key("lights[].range", "m > 0", "none (no cut-off)", "the light ends here (glTF's range window)", "8.0"),
    key("lights[].inner_deg", "degrees >= 0", "0", "spot: full intensity inside this half-angle", "20.0"),
    key("lights[].outer_deg", "degrees, > inner, <= 90", "45", "spot: no light beyond this half-angle", "35.0"),
];

/// The tables level.toml has besides the top level (`[[lights]]` is an array of them).
pub const LEVEL_TABLES: &[&str] = &["spawn", "headlamp", "lights", "game"];

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;
    use std::path::Path;

    use super::*;
    use crate::level_toml::parse_level_toml;

    /// The table a key is in ("" for the top level) and its own name.
    fn split(key: &str) -> (&str, &str) {
        match key.split_once('.') {
            Some((table, name)) => (table.trim_end_matches("[]"), name),
            None => ("", key),
        }
    }

    /// A level.toml with every documented key set to its example, `extra` added to `table`.
    fn document(extra_in: &str, extra: &str) -> String {
        let mut out = String::new();
        for table in ["", "spawn", "headlamp", "lights"] {
            match table {
                "" => {}
                "lights" => out.push_str("\n[[lights]]\n"),
                t => out.push_str(&format!("\n[{t}]\n")),
            }
            for k in LEVEL_KEYS.iter().filter(|k| split(k.key).0 == table) {
                out.push_str(&format!("{} = {}\n", split(k.key).1, k.example));
            }
            if table == extra_in {
                out.push_str(extra);
            }
        }
        out
    }

    #[test]
    fn every_documented_key_parses_with_its_example() {
        let text = document("", "");
        let parsed =
            parse_level_toml(text.as_bytes(), Path::new("level.toml")).unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert!(parsed.warnings.is_empty(), "an example is ignored: {:?}", parsed.warnings);
    }

    #[test]
    fn every_key_the_schema_takes_is_documented() {
        for table in ["", "spawn", "headlamp", "lights"] {
            let text = document(table, "zzz = 1\n");
            let e = parse_level_toml(text.as_bytes(), Path::new("level.toml")).err().expect("an unknown key");
            let message = e.to_string();
            let expected = message.split("expected one of").nth(1).unwrap_or_else(|| panic!("{message}"));
            // The message ends quoting the offending line.
            let expected = expected.split(" (in `").next().unwrap_or(expected);
            let schema: BTreeSet<&str> = expected.split('`').skip(1).step_by(2).collect();
            let mut documented: BTreeSet<&str> =
                LEVEL_KEYS.iter().map(|k| split(k.key)).filter(|(t, _)| *t == table).map(|(_, n)| n).collect();
            if table.is_empty() {
                documented.extend(LEVEL_TABLES);
            }
            assert_eq!(schema, documented, "[{table}]: the schema's keys against the documented ones");
        }
    }
}
