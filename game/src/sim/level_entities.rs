//! What a level places for the game — pickups, enemies with their patrol routes, the exit — and
//! the level's gameplay rules. Placement comes from marker nodes in the scene file (empties with
//! glTF `extras`, e.g. Blender custom properties), rules from `[game]` in level.toml, so a modder
//! moves an enemy by moving a node, never by touching code.
//!
//! | marker `extras`                                   | what it places                         |
//! |---------------------------------------------------|----------------------------------------|
//! | `{"pickup": "battery"}` (`"amount"`: 0.5)        | lamp battery refill, fraction of full  |
//! | `{"pickup": "ammo"}` (`"amount"`: 24)            | rounds for the reserve                 |
//! | `{"pickup": "health"}` (`"amount"`: 40)          | health points                          |
//! | `{"enemy": "crawler"}` (`"route"`: name)         | an enemy facing the node's −Z          |
//! | `{"waypoint": name, "order": n}`                 | point n of patrol route `name`         |
//! | `{"exit": true}` (`"radius"`: 1.2)               | reaching it wins the level             |
//!
//! `[game]` keys: `battery_seconds` (a full battery lasts this long lit, default 150),
//! `objective` (the HUD's objective line). Other `extras` keys are ignored, so files exported
//! with unrelated custom properties still load.

use std::fmt;
use std::path::PathBuf;

use glam::Vec3;
use scene::{Level, NodeExtras};
use serde_json::Value;

/// A marker or a `[game]` key the game cannot use: the file, then the node or key and what is
/// wrong with it.
#[derive(Clone, Debug, PartialEq)]
pub struct EntityError {
    pub file: PathBuf,
    pub message: String,
}

impl fmt::Display for EntityError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.file.display(), self.message)
    }
}

impl std::error::Error for EntityError {}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PickupKind {
    Battery,
    Ammo,
    Health,
}

impl PickupKind {
    pub fn name(self) -> &'static str {
        match self {
            PickupKind::Battery => "battery",
            PickupKind::Ammo => "ammo",
            PickupKind::Health => "health",
        }
    }

    fn default_amount(self) -> f32 {
        match self {
            PickupKind::Battery => 0.5,
            PickupKind::Ammo => 24.0,
            PickupKind::Health => 40.0,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct PickupSpawn {
    pub name: String,
    pub kind: PickupKind,
    pub position: Vec3,
    pub amount: f32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct EnemySpawn {
    pub name: String,
    /// Feet.
    pub position: Vec3,
    /// Radians, the player's convention: 0 faces −Z, positive turns left.
    pub yaw: f32,
    /// The patrol route's points in order; empty = guard the spot.
    pub route: Vec<Vec3>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exit {
    pub position: Vec3,
    pub radius: f32,
    /// Which way its sign faces, radians (the node's −Z, as for enemies).
    pub yaw: f32,
}

/// The `[game]` keys, for the level.toml reference (`headlamp check --reference`) and the
/// unknown-key message alike.
pub const GAME_KEYS: &[scene::KeyDoc] = &[
    scene::KeyDoc {
        key: "game.battery_seconds",
        kind: "seconds >= 1",
        default: "150",
        meaning: "a full lamp battery lasts this long lit",
        example: "120.0",
    },
    scene::KeyDoc {
        key: "game.objective",
        kind: "text",
        default: "from the markers (\"Find the exit\", \"Put down every crawler\", ...)",
        meaning: "the HUD's objective line",
        example: "\"Put down the four crawlers\"",
    },
];

#[derive(Clone, Debug, PartialEq)]
pub struct Rules {
    pub battery_seconds: f32,
    pub objective: String,
}

#[derive(Clone, Debug, PartialEq)]
pub struct LevelEntities {
    pub pickups: Vec<PickupSpawn>,
    pub enemies: Vec<EnemySpawn>,
    pub exit: Option<Exit>,
    pub rules: Rules,
}

impl LevelEntities {
    /// Reads the markers (in file order, so the simulation iterates them the same way every
    /// run) and the rules. Errors name the file and the node or key.
    pub fn read(level: &Level) -> Result<Self, EntityError> {
        let in_scene = |message: String| EntityError { file: level.scene_path.clone(), message };
        let mut pickups = Vec::new();
        let mut enemies = Vec::new();
        let mut routes: Vec<(String, i64, Vec3)> = Vec::new();
        let mut enemy_routes = Vec::new();
        let mut exit = None;
        for node in &level.scene.extras {
            let at = |msg: String| in_scene(format!("node '{}': {msg}", node.node_name));
            let Some(extras) = node.extras.as_object() else { continue };
            let position = node.world.w_axis.truncate();
            if let Some(kind) = extras.get("pickup") {
                let kind = match kind.as_str() {
                    Some("battery") => PickupKind::Battery,
                    Some("ammo") => PickupKind::Ammo,
                    Some("health") => PickupKind::Health,
                    _ => {
                        return Err(at(format!("unknown pickup {kind} (expected \"battery\", \"ammo\" or \"health\")")))
                    }
                };
                let amount = number(node, "amount", kind.default_amount()).map_err(at)?;
                pickups.push(PickupSpawn { name: node.node_name.clone(), kind, position, amount });
            } else if let Some(kind) = extras.get("enemy") {
                if kind.as_str() != Some("crawler") {
                    return Err(at(format!("unknown enemy {kind} (expected \"crawler\")")));
                }
                let route = match extras.get("route") {
                    None => None,
                    Some(Value::String(r)) => Some(r.clone()),
                    Some(other) => return Err(at(format!("\"route\" must be a route name, not {other}"))),
                };
                enemies.push(EnemySpawn { name: node.node_name.clone(), position, yaw: yaw(node), route: Vec::new() });
                enemy_routes.push(route);
            } else if let Some(route) = extras.get("waypoint") {
                let route = route.as_str().ok_or_else(|| at("\"waypoint\" must be a route name".into()))?;
                let order = extras
                    .get("order")
                    .and_then(Value::as_i64)
                    .ok_or_else(|| at("a waypoint needs a whole-number \"order\"".into()))?;
                routes.push((route.to_owned(), order, position));
            } else if extras.contains_key("exit") {
                if exit.is_some() {
                    return Err(at("a second exit (a level has one)".into()));
                }
                exit = Some(Exit { position, radius: number(node, "radius", 1.2).map_err(at)?, yaw: yaw(node) });
            }
        }
        routes.sort_by(|a, b| (&a.0, a.1).cmp(&(&b.0, b.1)));
        for (enemy, route) in enemies.iter_mut().zip(enemy_routes) {
            let Some(route) = route else { continue };
            enemy.route = routes.iter().filter(|r| r.0 == route).map(|r| r.2).collect();
            if enemy.route.is_empty() {
                return Err(in_scene(format!("node '{}': no waypoints of route '{route}'", enemy.name)));
            }
        }
        let rules = Rules::read(level, enemies.len(), exit.is_some())?;
        Ok(Self { pickups, enemies, exit, rules })
    }
}

/// The heading of a node's −Z axis, radians (0 faces −Z, positive turns left).
fn yaw(node: &NodeExtras) -> f32 {
    let forward = -node.world.z_axis.truncate();
    libm::atan2f(-forward.x, -forward.z)
}

/// An optional positive number in a marker's extras.
fn number(node: &NodeExtras, key: &str, default: f32) -> Result<f32, String> {
    match node.extras.get(key) {
        None => Ok(default),
        Some(v) => v
            .as_f64()
            .map(|v| v as f32)
            .filter(|v| v.is_finite() && *v > 0.0)
            .ok_or_else(|| format!("\"{key}\" must be a positive number, not {v}")),
    }
}

impl Rules {
    fn read(level: &Level, enemies: usize, has_exit: bool) -> Result<Self, EntityError> {
        let file = match &level.root {
            Some(root) => root.join("level.toml"),
            None => level.scene_path.clone(),
        };
        let mut rules = Rules {
            battery_seconds: 150.0,
            objective: match (enemies, has_exit) {
                (0, true) => "Find the exit".into(),
                (_, true) => "Put down every crawler — or find the exit".into(),
                _ => "Put down every crawler".into(),
            },
        };
        for (key, value) in &level.game {
            let at = |msg: &str| EntityError { file: file.clone(), message: format!("[game] {key}: {msg}") };
            match key.as_str() {
                "battery_seconds" => {
                    rules.battery_seconds = value
                        .as_float()
                        .or_else(|| value.as_integer().map(|i| i as f64))
                        .map(|v| v as f32)
                        .filter(|v| v.is_finite() && *v >= 1.0)
                        .ok_or_else(|| at("must be a number of seconds ≥ 1"))?;
                }
                "objective" => rules.objective = value.as_str().ok_or_else(|| at("must be text"))?.to_owned(),
                _ => {
                    let known: Vec<&str> = GAME_KEYS.iter().map(|k| k.key.trim_start_matches("game.")).collect();
                    return Err(at(&format!("unknown key (expected one of {})", known.join(", "))));
                }
            }
        }
        Ok(rules)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Mat4, Quat};
    use serde_json::json;

    fn level(markers: &[(&str, Mat4, Value)], game: &str) -> Level {
        let mut level = engine::scene::load_level(&crate::default_level()).unwrap();
        level.scene.extras = markers
            .iter()
            .map(|(name, world, extras)| NodeExtras {
                node_name: (*name).into(),
                world: *world,
                extras: extras.clone(),
            })
            .collect();
        level.game = game.parse().unwrap();
        level
    }

    fn at(x: f32, z: f32) -> Mat4 {
        Mat4::from_translation(Vec3::new(x, 0.0, z))
    }

    #[test]
    fn markers_place_pickups_enemies_routes_and_the_exit() {
        let turned = Mat4::from_rotation_translation(Quat::from_rotation_y(1.0), Vec3::new(5.0, 0.0, 0.0));
        let l = level(
            &[
                ("b", at(1.0, 2.0), json!({"pickup": "battery"})),
                ("w2", at(9.0, 9.0), json!({"waypoint": "r", "order": 2})),
                ("e", turned, json!({"enemy": "crawler", "route": "r"})),
                ("a", at(0.0, 0.0), json!({"pickup": "ammo", "amount": 10})),
                ("w1", at(8.0, 8.0), json!({"waypoint": "r", "order": 1})),
                ("x", at(3.0, 3.0), json!({"exit": true, "radius": 2})),
                ("other", at(0.0, 0.0), json!({"blender_prop": 1})),
            ],
            "battery_seconds = 60\nobjective = \"Run\"",
        );
        let e = LevelEntities::read(&l).unwrap();
        assert_eq!(e.pickups.len(), 2);
        assert_eq!(
            (e.pickups[0].kind, e.pickups[0].position, e.pickups[0].amount),
            (PickupKind::Battery, Vec3::new(1.0, 0.0, 2.0), 0.5)
        );
        assert_eq!((e.pickups[1].kind, e.pickups[1].amount), (PickupKind::Ammo, 10.0));
        assert_eq!(e.enemies.len(), 1);
        assert!((e.enemies[0].yaw - 1.0).abs() < 1e-5, "facing from the node's rotation: {}", e.enemies[0].yaw);
        assert_eq!(e.enemies[0].route, vec![Vec3::new(8.0, 0.0, 8.0), Vec3::new(9.0, 0.0, 9.0)], "in route order");
        assert_eq!(e.exit, Some(Exit { position: Vec3::new(3.0, 0.0, 3.0), radius: 2.0, yaw: 0.0 }));
        assert_eq!(e.rules, Rules { battery_seconds: 60.0, objective: "Run".into() });
    }

    #[test]
    fn mistakes_name_the_node_or_key() {
        for (markers, game, needle) in [
            (vec![("p", at(0.0, 0.0), json!({"pickup": "gold"}))], "", "node 'p': unknown pickup \"gold\""),
            (vec![("e", at(0.0, 0.0), json!({"enemy": "dragon"}))], "", "node 'e': unknown enemy"),
            (
                vec![("e", at(0.0, 0.0), json!({"enemy": "crawler", "route": "nowhere"}))],
                "",
                "no waypoints of route 'nowhere'",
            ),
            (vec![("w", at(0.0, 0.0), json!({"waypoint": "r"}))], "", "node 'w': a waypoint needs"),
            (vec![("p", at(0.0, 0.0), json!({"pickup": "ammo", "amount": -3}))], "", "\"amount\" must be a positive"),
            (
                vec![("x", at(0.0, 0.0), json!({"exit": true})), ("y", at(1.0, 0.0), json!({"exit": true}))],
                "",
                "node 'y': a second exit",
            ),
            (vec![], "battery_seconds = 0", "[game] battery_seconds: must be"),
            (vec![], "lives = 3", "[game] lives: unknown key"),
        ] {
            let e = LevelEntities::read(&level(&markers, game)).unwrap_err().to_string();
            assert!(e.contains(needle), "{e}");
        }
    }

    #[test]
    fn every_game_key_is_documented_and_reads_its_example() {
        let table: String =
            GAME_KEYS.iter().map(|k| format!("{} = {}\n", k.key.trim_start_matches("game."), k.example)).collect();
        LevelEntities::read(&level(&[], &table)).unwrap_or_else(|e| panic!("{e}"));
        let e = LevelEntities::read(&level(&[], "zzz = 1")).unwrap_err().to_string();
        assert!(e.ends_with("(expected one of battery_seconds, objective)"), "{e}");
    }

    #[test]
    fn the_cellar_places_its_things_in_the_level_file() {
        let level = engine::scene::load_level(&crate::default_level()).unwrap();
        let e = LevelEntities::read(&level).unwrap();
        assert!(
            e.enemies.len() >= 2 && e.pickups.len() >= 3,
            "{} enemies, {} pickups",
            e.enemies.len(),
            e.pickups.len()
        );
        assert!(e.exit.is_some());
    }
}
