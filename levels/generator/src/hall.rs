//! "The Hall": one big open room, 22 m x 34 m and 9 m tall, with a U of balconies round three
//! sides on rows of stone pillars, stairs up to the west balcony and a ramp up to the east one,
//! brick walls and a deep blue wall at the far end. Crawlers walk the floor below: the walk grid
//! keeps one floor per column (the lowest storey), so the arcades under the balconies are theirs
//! and the balconies are not; the way out is the crypt behind the blue wall.
//!
//! ```text
//!                 crypt (the way out)
//!   ┌───────────────┴───────────────┐
//!   │ balcony ═══════════════════════ │   north balcony over the crypt door
//!   │ ║  P        P         P      ║ │
//!   │ ║                            ║ │   west/east balconies over arcades,
//!   │ ║  P    (the nave)       P   ║ │   pillars (P) under their edges
//!   │ ║                            ║ │
//!   │ ▲ stairs               ramp ▲ │
//!   └───────────────┬───────────────┘
//!                 porch (spawn)
//! ```

use crate::geometry::Side;
use crate::layout::*;
use crate::materials::Material;
use serde_json::json;

/// Top of the balconies' floor, m: 25 risers of 0.15 m.
pub const BALCONY_TOP: f64 = 3.75;
/// Thickness of the balconies' slab, m.
pub const BALCONY_SLAB: f64 = 0.4;
/// Steps of the stairs up to the west balcony.
pub const STAIR_STEPS: usize = 25;
/// Where the stairs and the ramp run: along the west and east walls from 1.2 m short of the
/// south wall (z = -4; room to step on from the south) to the balconies' south ends (z = -12).
pub const CLIMB_Z: [f64; 2] = [-12.0, -5.2];
/// The hall's interior.
const HALL_MIN: [f64; 2] = [-11.0, -38.0];
const HALL_MAX: [f64; 2] = [11.0, -4.0];
/// Depth of the west and east balconies, and of the north one.
const BALCONY_DEPTH: f64 = 3.0;
/// Width of the stairs and the ramp.
const CLIMB_WIDTH: f64 = 1.6;

pub fn hall() -> Level {
    use Material::*;
    let rooms = vec![
        Room {
            name: "porch",
            min: [-3.0, -3.6],
            max: [3.0, 2.4],
            height: 3.5,
            walls: [Brick, Brick, Brick, Brick],
            floor: Stone,
            ceiling: DarkPlanks,
        },
        // Walls north, east, south, west: the far (north) wall is a big blue one.
        Room {
            name: "hall",
            min: HALL_MIN,
            max: HALL_MAX,
            height: 9.0,
            walls: [BluePlaster, Brick, Brick, Brick],
            floor: Stone,
            ceiling: DarkPlanks,
        },
        Room {
            name: "crypt",
            min: [-3.0, -44.4],
            max: [3.0, -38.4],
            height: 3.2,
            walls: [Stone, Stone, Stone, Stone],
            floor: Stone,
            ceiling: Plaster,
        },
    ];
    let doorways = vec![
        Doorway { rooms: ["porch", "hall"], center: 0.0, width: 2.4, height: 3.0 },
        Doorway { rooms: ["hall", "crypt"], center: 0.0, width: 1.8, height: 2.4 },
    ];

    let (x0, x1) = (HALL_MIN[0], HALL_MAX[0]);
    let z_north = HALL_MIN[1];
    let (slab_y0, top) = (BALCONY_TOP - BALCONY_SLAB, BALCONY_TOP);
    let (inner_w, inner_e) = (x0 + BALCONY_DEPTH, x1 - BALCONY_DEPTH);
    let inner_n = z_north + BALCONY_DEPTH;
    let south_end = CLIMB_Z[0];
    let mut props = vec![
        // The U of balconies: west and east along the long walls, north across the blue wall.
        prop("balcony_west", DarkPlanks, cuboid([x0, slab_y0, z_north], [inner_w, top, south_end])),
        prop("balcony_north", DarkPlanks, cuboid([inner_w, slab_y0, z_north], [inner_e, top, inner_n])),
        prop("balcony_east", DarkPlanks, cuboid([inner_e, slab_y0, z_north], [x1, top, south_end])),
        // Parapets along their open edges, a metre high; the south ends are open where the
        // stairs and the ramp arrive.
        prop("parapet_west", Plaster, cuboid([inner_w - 0.15, top, inner_n], [inner_w, top + 1.0, south_end])),
        prop(
            "parapet_north",
            Plaster,
            cuboid([inner_w - 0.15, top, inner_n], [inner_e + 0.15, top + 1.0, inner_n + 0.15]),
        ),
        prop("parapet_east", Plaster, cuboid([inner_e, top, inner_n], [inner_e + 0.15, top + 1.0, south_end])),
        prop(
            "parapet_west_end",
            Plaster,
            cuboid([x0 + CLIMB_WIDTH, top, south_end - 0.15], [inner_w, top + 1.0, south_end]),
        ),
        prop(
            "parapet_east_end",
            Plaster,
            cuboid([inner_e, top, south_end - 0.15], [x1 - CLIMB_WIDTH, top + 1.0, south_end]),
        ),
        // The ramp up to the east balcony, along the east wall: 3.75 m over 6.8 m (29°).
        prop("ramp_east", Stone, ramp([x1 - CLIMB_WIDTH, 0.0, CLIMB_Z[0]], [x1, BALCONY_TOP, CLIMB_Z[1]], Side::North)),
    ];
    // The stairs up to the west balcony, along the west wall: 25 steps of 0.15 m.
    props.extend(stairs(
        "stairs_west",
        Stone,
        [x0, CLIMB_Z[0]],
        [x0 + CLIMB_WIDTH, CLIMB_Z[1]],
        Side::North,
        BALCONY_TOP,
        STAIR_STEPS,
    ));
    // Pillars under the balconies' inner edges, floor to ceiling.
    let pillar = |name: String, x: f64, z: f64| prop(&name, Stone, block_at(x, 0.0, z, [0.7, 9.0, 0.7]));
    for z in [-14.0, -20.0, -26.0, -32.0] {
        props.push(pillar(format!("pillar_west_{}", -z as i32), inner_w, z));
        props.push(pillar(format!("pillar_east_{}", -z as i32), inner_e, z));
    }
    for x in [inner_w, -4.0, 4.0, inner_e] {
        props.push(pillar(format!("pillar_north_{}", x as i32), x, inner_n));
    }
    #[rustfmt::skip]
    props.extend([
        // Banners on the long walls above the balconies: red on the west, yellow on the east.
        prop("banner_west_1", Red, cuboid([x0, 4.6, -20.8], [x0 + 0.06, 8.2, -19.2])),
        prop("banner_west_2", Red, cuboid([x0, 4.6, -28.8], [x0 + 0.06, 8.2, -27.2])),
        prop("banner_east_1", Yellow, cuboid([x1 - 0.06, 4.6, -20.8], [x1, 8.2, -19.2])),
        prop("banner_east_2", Yellow, cuboid([x1 - 0.06, 4.6, -28.8], [x1, 8.2, -27.2])),
        // Cover in the nave: stone blocks and crates.
        prop("nave_block_south", Stone, block_at(-3.5, 0.0, -16.0, [2.2, 1.2, 1.0])),
        prop("nave_block_middle", Stone, block_at(3.5, 0.0, -23.0, [2.2, 1.2, 1.0])),
        prop("nave_block_north", Stone, block_at(-2.5, 0.0, -29.5, [1.0, 1.2, 2.2])),
        prop("nave_crate_1", Wood, crate_at(5.6, 0.0, -8.0, 1.0)),
        prop("nave_crate_2", Wood, crate_at(5.5, 1.0, -8.1, 0.6)),
        prop("nave_crate_3", Wood, crate_at(-5.2, 0.0, -33.0, 0.9)),
        // The crypt: crates by the way out.
        prop("crypt_crate", Wood, crate_at(-2.2, 0.0, -43.6, 0.9)),
    ]);

    let spawn = Spawn { position: [0.0, 0.0, 1.2], yaw_deg: 0.0, pitch_deg: 0.0 };

    // One of the stairs' steps: its top and the middle of its tread (z).
    let step = |k: usize| {
        let tread = (CLIMB_Z[1] - CLIMB_Z[0]) / STAIR_STEPS as f64;
        ((k + 1) as f64 * BALCONY_TOP / STAIR_STEPS as f64, CLIMB_Z[1] - (k as f64 + 0.5) * tread)
    };
    let (step_y, step_z) = step(9);
    let marker = |name, position, yaw_deg, extras| Marker { name, position, yaw_deg, extras };
    let waypoint = |name, route: &str, order: u32, position| {
        marker(name, position, 0.0, json!({ "waypoint": route, "order": order }))
    };
    #[rustfmt::skip]
    let markers = vec![
        marker("spawn_player", spawn.position, spawn.yaw_deg, json!({ "spawn": "player" })),
        // Halfway up the stairs (1.5 m): within reach of the floor's walk grid.
        marker("pickup_battery_stairs", [x0 + 0.8, step_y, step_z], 0.0, json!({ "pickup": "battery" })),
        marker("pickup_battery_arcade", [-10.2, 0.0, -30.0], 0.0, json!({ "pickup": "battery" })),
        marker("pickup_ammo_block", [3.5, 1.2, -23.0], 0.0, json!({ "pickup": "ammo" })),
        marker("pickup_ammo_arcade", [10.2, 0.0, -24.0], 0.0, json!({ "pickup": "ammo" })),
        marker("pickup_health_crypt_door", [-1.8, 0.0, -36.6], 0.0, json!({ "pickup": "health" })),
        // The west arcade's crawler walks under the balcony and back up the nave.
        marker("enemy_crawler_west", [-9.6, 0.0, -16.0], 180.0, json!({ "enemy": "crawler", "route": "west" })),
        waypoint("route_west_1", "west", 1, [-9.6, 0.0, -34.0]),
        waypoint("route_west_2", "west", 2, [-5.5, 0.0, -34.5]),
        waypoint("route_west_3", "west", 3, [-5.5, 0.0, -13.0]),
        waypoint("route_west_4", "west", 4, [-9.6, 0.0, -14.0]),
        // The east arcade's, the other way round.
        marker("enemy_crawler_east", [9.6, 0.0, -33.0], 0.0, json!({ "enemy": "crawler", "route": "east" })),
        waypoint("route_east_1", "east", 1, [9.6, 0.0, -14.0]),
        waypoint("route_east_2", "east", 2, [5.5, 0.0, -13.0]),
        waypoint("route_east_3", "east", 3, [5.5, 0.0, -34.5]),
        waypoint("route_east_4", "east", 4, [9.6, 0.0, -34.0]),
        // Stands in the nave looking north at the blue wall.
        marker("enemy_crawler_nave", [0.5, 0.0, -26.0], 0.0, json!({ "enemy": "crawler" })),
        // Guards the crypt, facing its door.
        marker("enemy_crawler_crypt", [1.2, 0.0, -40.2], 180.0, json!({ "enemy": "crawler" })),
        // The way out, at the back of the crypt; its sign faces the door.
        marker("exit", [0.0, 0.0, -42.8], 180.0, json!({ "exit": true, "radius": 1.0 })),
    ];

    // The nave's lamps hang high and point straight down; their cones (40°) stay clear of the
    // balconies (punctual lights cast no shadows: a cone through a balcony would light the
    // arcade beneath it too).
    let down_spot = |name, position, intensity| Light {
        name,
        kind: LightKind::Spot { inner: 25f64.to_radians(), outer: 40f64.to_radians() },
        position,
        yaw_deg: 0.0,
        pitch_deg: -90.0,
        color: [1.0, 0.8, 0.55],
        intensity,
        range: 12.0,
    };
    // Uplights standing on the balconies, tilted at the banners on the wall behind them: lit
    // from below, nothing beneath the balconies is in their cones.
    let uplight = |name, position, yaw_deg| Light {
        name,
        kind: LightKind::Spot { inner: 20f64.to_radians(), outer: 35f64.to_radians() },
        position,
        yaw_deg,
        pitch_deg: 70.0,
        color: [1.0, 0.85, 0.6],
        intensity: 10.0,
        range: 7.0,
    };
    let lamp = |name, position, color, intensity, range| Light {
        name,
        kind: LightKind::Point,
        position,
        yaw_deg: 0.0,
        pitch_deg: 0.0,
        color,
        intensity,
        range,
    };
    let lights = vec![
        // Two lamps high over the nave, pointing down: pools of warm light on the floor.
        down_spot("nave_lamp_south", [0.0, 8.6, -13.0], 70.0),
        down_spot("nave_lamp_middle", [0.0, 8.6, -21.5], 70.0),
        down_spot("nave_lamp_north", [0.0, 8.6, -30.0], 70.0),
        uplight("uplight_west_1", [x0 + 0.6, top + 0.1, -20.0], 90.0),
        uplight("uplight_west_2", [x0 + 0.6, top + 0.1, -28.0], 90.0),
        uplight("uplight_east_1", [x1 - 0.6, top + 0.1, -20.0], -90.0),
        uplight("uplight_east_2", [x1 - 0.6, top + 0.1, -28.0], -90.0),
        lamp("porch_lamp", [0.0, 3.2, -0.6], [1.0, 0.75, 0.45], 0.4, 4.0),
        lamp("crypt_lamp", [0.0, 2.9, -41.4], [0.65, 0.8, 1.0], 0.5, 4.0),
    ];

    // The hall is longer than the default far plane reaches comfortably.
    let camera = Camera { zfar: 150.0, ..Camera::overview(&spawn) };

    Level {
        id: "hall",
        name: "The Hall",
        description: "A pillared hall with balconies, stairs and a ramp: four crawlers on the floor, the way out past the blue wall",
        exposure: 1.0,
        rooms,
        doorways,
        props,
        markers,
        lights,
        toml_lights: Vec::new(),
        camera,
        spawn,
        headlamp: Headlamp {
            power: 60.0,
            fov_deg: 70.0,
            profile: "spot",
            inner_deg: 18.0,
            outer_deg: 34.0,
            color: [1.0, 0.95, 0.85],
        },
        game: GameRules {
            battery_seconds: 150.0,
            objective: "Put down the four crawlers, or get out through the crypt beyond the blue wall",
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::{Shape, Solid};

    /// The game's walk grid (game/src/sim/nav_grid.rs) keeps one floor per 0.5 m column, found
    /// by a probe straight down from 2 m above the level's lowest point (the floor slabs'
    /// underside, -WALL), and joins neighbouring columns whose floors differ by at most 0.36 m.
    const PROBE_TOP: f64 = -WALL + 2.0;
    const CELL: f64 = 0.5;
    const MAX_STEP: f64 = 0.36;
    /// The player's step height and steepest walkable slope (engine/physics).
    const STEP_HEIGHT: f64 = 0.35;
    const MAX_SLOPE_DEG: f64 = 46.0;

    /// The height of the ramp's surface over (x, z), if it covers that point.
    fn ramp_top(bounds: &crate::geometry::Aabb, high: Side, x: f64, z: f64) -> Option<f64> {
        if x < bounds.min[0] || x > bounds.max[0] || z < bounds.min[2] || z > bounds.max[2] {
            return None;
        }
        let t = match high {
            Side::North => (bounds.max[2] - z) / (bounds.max[2] - bounds.min[2]),
            Side::South => (z - bounds.min[2]) / (bounds.max[2] - bounds.min[2]),
            Side::West => (bounds.max[0] - x) / (bounds.max[0] - bounds.min[0]),
            Side::East => (x - bounds.min[0]) / (bounds.max[0] - bounds.min[0]),
        };
        Some(bounds.min[1] + t * (bounds.max[1] - bounds.min[1]))
    }

    /// The walk grid's floor at (x, z): the highest solid top at or below the probe's start.
    fn probed_floor(level: &Level, solids: &[Solid], x: f64, z: f64) -> f64 {
        let boxes = solids
            .iter()
            .filter(|s| x > s.bounds.min[0] && x < s.bounds.max[0] && z > s.bounds.min[2] && z < s.bounds.max[2])
            .map(|s| s.bounds.max[1]);
        let ramps = level.props.iter().filter_map(|p| match &p.shape {
            Shape::Ramp { bounds, high } => ramp_top(bounds, *high, x, z),
            Shape::Cuboid(_) => None,
        });
        boxes.chain(ramps).filter(|&y| y <= PROBE_TOP).fold(f64::NEG_INFINITY, f64::max)
    }

    #[test]
    fn the_ground_under_the_balconies_is_the_walk_grids_floor_and_walkable() {
        let level = hall();
        let balconies: Vec<_> = level.props.iter().filter(|p| p.name.starts_with("balcony_")).collect();
        assert_eq!(balconies.len(), 3);
        for b in balconies {
            let bounds = b.shape.bounds();
            assert_eq!(bounds.max[1], BALCONY_TOP);
            // Above the probe's start (so the probe finds the ground beneath), and high enough
            // for a 1.8 m player to walk under.
            assert!(bounds.min[1] > PROBE_TOP, "{}: underside {} under the probe", b.name, bounds.min[1]);
            assert!(bounds.min[1] >= 3.0, "{}: underside {} m", b.name, bounds.min[1]);
        }
        let solids = level.solids();
        assert_eq!(probed_floor(&level, &solids, -9.6, -25.0), 0.0, "the west arcade");
        assert_eq!(probed_floor(&level, &solids, 9.6, -25.0), 0.0, "the east arcade");
        assert_eq!(probed_floor(&level, &solids, 0.0, -36.5), 0.0, "under the north balcony");
    }

    /// The stairs' and the ramp's lower parts join the floor on the walk grid (no two columns
    /// 0.5 m apart differ by more than 0.36 m), and the player can climb both.
    #[test]
    fn stairs_and_ramp_are_climbable_and_join_the_walk_grid() {
        let rise = BALCONY_TOP / STAIR_STEPS as f64;
        let tread = (CLIMB_Z[1] - CLIMB_Z[0]) / STAIR_STEPS as f64;
        assert!(rise <= STEP_HEIGHT, "riser {rise}");
        let risers_per_cell = (CELL / tread).ceil();
        assert!(risers_per_cell * rise <= MAX_STEP + 1e-9, "{risers_per_cell} risers of {rise} in a cell");
        let level = hall();
        let steps: Vec<_> = level.props.iter().filter(|p| p.name.starts_with("stairs_west_")).collect();
        assert_eq!(steps.len(), STAIR_STEPS);
        assert!(
            (steps.last().unwrap().shape.bounds().max[1] - BALCONY_TOP).abs() < 1e-9,
            "the top step meets the balcony"
        );
        let ramp = level.props.iter().find(|p| p.name == "ramp_east").unwrap().shape.bounds();
        let run = ramp.size()[2];
        let slope = (BALCONY_TOP / run).atan().to_degrees();
        assert!(slope <= MAX_SLOPE_DEG, "ramp slope {slope}°");
        assert!(BALCONY_TOP / run * CELL <= MAX_STEP, "ramp rises {} a cell", BALCONY_TOP / run * CELL);
        // Walking up either from the floor, column by column, while the probe still sees them.
        let solids = level.solids();
        for x in [-10.2, 10.2] {
            let mut z = CLIMB_Z[1] + 0.6;
            let mut floor = probed_floor(&level, &solids, x, z);
            assert_eq!(floor, 0.0);
            while z > CLIMB_Z[0] {
                z -= CELL;
                let next = probed_floor(&level, &solids, x, z);
                if next < floor - MAX_STEP {
                    break; // beyond the probe: the upper flight is not on the grid
                }
                assert!((next - floor).abs() <= MAX_STEP + 1e-9, "x {x} z {z}: {floor} to {next}");
                floor = next;
            }
            assert!(floor >= 1.5, "x {x}: the walk grid climbs to {floor} m");
        }
    }

    /// Crawlers start and patrol on the ground floor, in the open (not under the stairs or the
    /// ramp); pickups and the exit lie within reach of the walk grid, so `headlamp check` can
    /// tell they are reachable (a pickup on a balcony would be out of its sight).
    #[test]
    fn crawlers_walk_the_ground_and_everything_to_reach_is_within_the_walk_grids_reach() {
        let level = hall();
        let solids = level.solids();
        let mut crawlers = 0;
        for m in &level.markers {
            let [x, y, z] = m.position;
            let floor = probed_floor(&level, &solids, x, z);
            if m.extras.get("enemy").is_some() || m.extras.get("waypoint").is_some() {
                crawlers += m.extras.get("enemy").is_some() as usize;
                assert_eq!((y, floor), (0.0, 0.0), "{} is off the ground floor", m.name);
            }
            if m.extras.get("pickup").is_some() || m.extras.get("exit").is_some() {
                // GRAB_HEIGHT and EXIT_HEIGHT (game/src/sim): 1.6 m and 2 m.
                assert!(y - floor <= 1.6 && y < PROBE_TOP, "{} at {y} m over a walk-grid floor of {floor} m", m.name);
            }
        }
        assert_eq!(crawlers, 4);
        assert_eq!(level.markers.iter().filter(|m| m.extras.get("exit").is_some()).count(), 1);
    }

    /// The nave lamps' cones (straight down) reach the floor without touching a balcony, and
    /// the uplights point up: no punctual light shines through a balcony into an arcade.
    #[test]
    fn no_light_shines_through_a_balcony() {
        let level = hall();
        for l in &level.lights {
            let LightKind::Spot { outer, .. } = l.kind else { continue };
            if l.pitch_deg > 0.0 {
                assert!(l.position[1] > BALCONY_TOP && l.pitch_deg - outer.to_degrees() > 0.0, "{}", l.name);
                continue;
            }
            assert_eq!(l.pitch_deg, -90.0, "{}", l.name);
            let reach = (l.position[1] - BALCONY_TOP) * outer.tan();
            assert!(l.position[0].abs() + reach < HALL_MAX[0] - BALCONY_DEPTH, "{}", l.name);
            assert!(l.position[2] - reach > HALL_MIN[1] + BALCONY_DEPTH, "{}", l.name);
        }
    }
}
