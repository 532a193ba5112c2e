//! The checks of a loaded level that only show in play: where the player starts, what can be
//! walked to, what can be won, and lights that give no light.

use std::path::PathBuf;

use glam::Vec3;
use physics::{CharacterConfig, LevelCollision};
use scene::{IntensityDistribution, Level, TextPos};

use super::diagnostic::Diagnostic;
use crate::sim::level_entities::LevelEntities;
use crate::sim::nav_grid::NavGrid;
use crate::sim::pickup::{GRAB_HEIGHT, GRAB_RADIUS};
use crate::sim::{enemy, start_pose, EXIT_HEIGHT};

/// A spawn this far above the floor below it drops the player: a likely typo in its height, m.
const HIGH_SPAWN: f32 = 0.6;
/// Lights further than this outside the level's box light nothing of it, m.
const FAR_OUTSIDE: f32 = 1.0;

pub fn check(level: &Level) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    let places = Places::new(level);
    let collision = match LevelCollision::from_scene(&level.scene) {
        Ok(c) => c,
        Err(e) => {
            found.push(Diagnostic::error(&level.scene_path, None, format!("cannot build collision geometry: {e}")));
            return found;
        }
    };
    lights(level, &collision, &places, &mut found);
    let entities = match LevelEntities::read(level) {
        Ok(e) => e,
        Err(e) => {
            let at = places.game_key(&e.message);
            found.push(Diagnostic::error(e.file, at, e.message));
            return found;
        }
    };
    let (feet, _, _) = start_pose(level);
    if !spawn_is_clear(&collision, feet, &places, &mut found) {
        return found;
    }
    reachability(level, &collision, &entities, feet, &places, &mut found);
    if entities.enemies.is_empty() && entities.exit.is_none() {
        found.push(Diagnostic::warning(
            &level.scene_path,
            None,
            "nothing to win: no crawler and no exit marker (the level is only walked)",
        ));
    }
    found
}

/// Where things are written: level.toml's keys when the level has one, else the scene file.
struct Places {
    toml: Option<(PathBuf, String)>,
    scene: PathBuf,
}

impl Places {
    fn new(level: &Level) -> Self {
        let toml = level.root.as_ref().and_then(|root| {
            let path = root.join("level.toml");
            std::fs::read_to_string(&path).ok().map(|text| (path, text))
        });
        Self { toml, scene: level.scene_path.clone() }
    }

    /// The file and place of a level.toml key, or the scene file when there is none.
    fn key(&self, key: &str) -> (PathBuf, Option<TextPos>) {
        match &self.toml {
            Some((path, text)) => (path.clone(), scene::key_place(text, key)),
            None => (self.scene.clone(), None),
        }
    }

    /// How many `[[lights]]` level.toml has.
    fn toml_lights(&self) -> usize {
        let Some((_, text)) = &self.toml else { return 0 };
        text.parse::<toml::Table>().ok().and_then(|t| t.get("lights")?.as_array().map(Vec::len)).unwrap_or(0)
    }

    /// The place of the `[game]` key a rules error names (`[game] lives: unknown key`).
    fn game_key(&self, message: &str) -> Option<TextPos> {
        let key = message.strip_prefix("[game] ")?.split(':').next()?;
        let (_, text) = self.toml.as_ref()?;
        scene::key_place(text, &format!("game.{key}"))
    }
}

/// The player fits where they start and stands on something.
fn spawn_is_clear(collision: &LevelCollision, feet: Vec3, places: &Places, found: &mut Vec<Diagnostic>) -> bool {
    let (file, at) = places.key("spawn.position");
    let player = CharacterConfig::default();
    // Lifted a little: feet resting exactly on the floor are not inside it.
    if !collision.capsule_fits(feet + Vec3::Y * 0.02, player.radius, player.height) {
        found.push(Diagnostic::error(
            file,
            at,
            format!("the spawn {} is inside the level's geometry: the player would start stuck", show(feet)),
        ));
        return false;
    }
    match collision.cast_ray(feet + Vec3::Y * 0.5, -Vec3::Y, 1000.0) {
        None => found.push(Diagnostic::warning(
            file,
            at,
            format!("no floor under the spawn {}: the player falls", show(feet)),
        )),
        Some(hit) if hit.distance - 0.5 > HIGH_SPAWN => found.push(Diagnostic::warning(
            file,
            at,
            format!("the spawn {} is {:.1} m above the floor below it", show(feet), hit.distance - 0.5),
        )),
        Some(_) => {}
    }
    true
}

/// Pickups and the exit can be walked to from the spawn (on the player's walk grid, crouching
/// allowed); each crawler can walk to the spawn and along its route.
fn reachability(
    level: &Level,
    collision: &LevelCollision,
    entities: &LevelEntities,
    feet: Vec3,
    places: &Places,
    found: &mut Vec<Diagnostic>,
) {
    let scene_file = &level.scene_path;
    let player = CharacterConfig::default();
    let grid = NavGrid::build(collision, player.radius, player.crouch_height);
    let Some(reach) = grid.reachable_from(feet) else {
        let (file, at) = places.key("spawn.position");
        found.push(Diagnostic::error(file, at, format!("the spawn {} is not on walkable floor", show(feet))));
        return;
    };
    for p in &entities.pickups {
        if !reach.comes_within(p.position, GRAB_RADIUS, GRAB_HEIGHT) {
            found.push(Diagnostic::error(
                scene_file,
                None,
                format!(
                    "node '{}': the {} pickup at {} cannot be walked to from the spawn",
                    p.name,
                    p.kind.name(),
                    show(p.position)
                ),
            ));
        }
    }
    if let Some(exit) = &entities.exit {
        if !reach.comes_within(exit.position, exit.radius, EXIT_HEIGHT) {
            found.push(Diagnostic::error(
                scene_file,
                None,
                format!("the exit at {} cannot be walked to from the spawn", show(exit.position)),
            ));
        }
    }
    if entities.enemies.is_empty() {
        return;
    }
    let body = enemy::body_config();
    let crawlers = NavGrid::build(collision, body.radius, body.height);
    for e in &entities.enemies {
        let at = |message: String| Diagnostic::warning(scene_file, None, format!("node '{}': {message}", e.name));
        let Some(reach) = crawlers.reachable_from(e.position) else {
            found.push(at(format!("this crawler at {} stands where a crawler cannot walk", show(e.position))));
            continue;
        };
        if !reach.contains(feet) {
            found.push(at(format!("this crawler at {} cannot walk to the player's spawn", show(e.position))));
        }
        if let Some(p) = e.route.iter().find(|p| !reach.contains(**p)) {
            found.push(at(format!("its route passes {}, where it cannot walk", show(*p))));
        }
    }
}

/// Lights that can light nothing: no power, or far outside the level.
fn lights(level: &Level, collision: &LevelCollision, places: &Places, found: &mut Vec<Diagnostic>) {
    let lamp = &level.headlamp;
    let dark_profile = match &lamp.distribution {
        IntensityDistribution::Image(img) => img.values.iter().flatten().all(|v| *v == 0.0),
        // Its own load warns when none of its light falls inside the frustum.
        IntensityDistribution::Photometric(_) => false,
        _ => false,
    };
    if lamp.power == 0.0 || lamp.color.iter().all(|c| *c == 0.0) || dark_profile {
        let key = if lamp.power == 0.0 {
            "headlamp.power"
        } else if dark_profile {
            "headlamp.profile"
        } else {
            "headlamp.color"
        };
        let (file, at) = places.key(key);
        found.push(Diagnostic::warning(file, at, "the headlamp gives no light (the GI has nothing to bounce)"));
    }
    let (lo, hi) = collision.bounds();
    // level.toml's `[[lights]]` come after the scene file's own.
    let from_file = level.scene.lights.len().saturating_sub(places.toml_lights());
    for (i, light) in level.scene.lights.iter().enumerate() {
        let (file, at) = match i.checked_sub(from_file) {
            Some(n) => places.key(&format!("lights[{n}]")),
            None => (level.scene_path.clone(), None),
        };
        if light.intensity == 0.0 || light.color.iter().all(|c| *c == 0.0) {
            found.push(Diagnostic::warning(file, at, format!("light '{}' has no intensity", light.name)));
            continue;
        }
        let outside = (lo - light.position).max(light.position - hi).max_element();
        if light.kind != scene::LightKind::Directional && outside > FAR_OUTSIDE {
            found.push(Diagnostic::warning(
                file,
                at,
                format!("light '{}' at {} is {outside:.1} m outside the level", light.name, show(light.position)),
            ));
        }
    }
}

fn show(p: Vec3) -> String {
    format!("({:.2}, {:.2}, {:.2})", p.x, p.y, p.z)
}
