//! "The Gallery": strongly coloured rooms — red plaster, yellow brick, green tile, blue plaster —
//! around a white atrium, with white exhibits standing in them, so the headlamp's bounce light
//! shows the walls' colours on everything white. Spotlights over the exhibits are level.toml
//! `[[lights]]` (a modder moves them without code); the vault's lamp is in the scene file.
//!
//! ```text
//!   yellow ──── green        vault (the way out)
//!     │           │            │
//!    red ────── atrium ────── blue
//!                 │
//!               foyer (spawn)
//! ```

use crate::layout::*;
use crate::materials::Material;
use serde_json::json;

pub fn gallery() -> Level {
    use Material::*;
    let room = |name, min, max, height, walls, floor| Room { name, min, max, height, walls, floor, ceiling: Plaster };
    // Walls are listed north, east, south, west. Each coloured room has its colour on the wall
    // facing its entrance and on the entrance wall; the two walls between them are white, so
    // when the lamp lights the coloured wall ahead, the white ones beside it (and the white
    // floor and ceiling) glow with its colour outside the beam.
    let (w, r, g, b, y) = (Plaster, RedPlaster, GreenTile, BluePlaster, YellowBrick);
    let rooms = vec![
        room("foyer", [-2.5, 0.0], [2.5, 4.5], 3.2, [w, w, w, w], Planks),
        room("atrium", [-5.0, -12.4], [5.0, -0.4], 5.0, [w, w, w, w], FloorTile),
        room("red", [-12.4, -10.4], [-5.4, -2.4], 4.0, [w, r, w, r], FloorTile),
        room("blue", [5.4, -10.4], [12.4, -2.4], 4.0, [w, b, w, b], FloorTile),
        room("yellow", [-12.4, -20.8], [-5.4, -10.8], 4.0, [y, w, y, w], FloorTile),
        room("green", [-5.0, -20.8], [5.0, -12.8], 4.0, [g, w, g, w], FloorTile),
        room("vault", [5.4, -16.8], [12.4, -10.8], 3.2, [w, w, w, w], Planks),
    ];

    let door = |a, b, center, width, height| Doorway { rooms: [a, b], center, width, height };
    let doorways = vec![
        door("foyer", "atrium", 0.0, 2.0, 2.6),
        // The red and blue rooms' doors face each other across the atrium: an enfilade.
        door("atrium", "red", -6.4, 2.0, 2.8),
        door("atrium", "blue", -6.4, 2.0, 2.8),
        door("atrium", "green", 0.0, 2.0, 2.8),
        door("red", "yellow", -8.9, 1.6, 2.6),
        door("yellow", "green", -16.8, 1.6, 2.6),
        door("blue", "vault", 8.9, 1.6, 2.4),
    ];

    // White exhibits catch the colour of the walls around them; a few coloured ones throw
    // theirs onto white.
    #[rustfmt::skip]
    let props = vec![
        // Atrium: a red cube on a white plinth under the skylight spot, benches by the walls.
        prop("atrium_plinth", White, block_at(0.0, 0.0, -6.4, [1.6, 0.5, 1.6])),
        prop("atrium_red_cube", Red, block_at(0.0, 0.5, -6.4, [0.8, 0.8, 0.8])),
        prop("atrium_bench_west", White, block_at(-4.2, 0.0, -3.2, [0.6, 0.45, 2.0])),
        prop("atrium_bench_east", White, block_at(4.2, 0.0, -3.2, [0.6, 0.45, 2.0])),
        prop("atrium_column_nw", White, block_at(-3.2, 0.0, -10.6, [0.7, 3.0, 0.7])),
        prop("atrium_column_ne", White, block_at(3.2, 0.0, -10.6, [0.7, 3.0, 0.7])),
        // Red room: a tall white monolith in line with the doors, a white cube by the wall.
        prop("red_monolith", White, block_at(-10.3, 0.0, -6.4, [0.7, 2.6, 0.7])),
        prop("red_cube", White, block_at(-7.4, 0.0, -3.4, [1.0, 1.0, 1.0])),
        // Blue room: a white monolith, and a yellow cube on a white plinth.
        prop("blue_monolith", White, block_at(10.3, 0.0, -6.4, [0.7, 2.6, 0.7])),
        prop("blue_plinth", White, block_at(7.6, 0.0, -9.2, [1.0, 0.6, 1.0])),
        prop("blue_yellow_cube", Yellow, block_at(7.6, 0.6, -9.2, [0.6, 0.6, 0.6])),
        // Yellow room: white cubes, one with a blue cube on it.
        prop("yellow_cube_big", White, block_at(-10.6, 0.0, -13.0, [1.2, 1.2, 1.2])),
        prop("yellow_plinth", White, block_at(-7.4, 0.0, -19.2, [0.9, 0.9, 0.9])),
        prop("yellow_blue_cube", Blue, block_at(-7.4, 0.9, -19.2, [0.5, 0.5, 0.5])),
        // Green room: a white monolith facing the atrium door, a long white bench.
        prop("green_monolith", White, block_at(0.0, 0.0, -19.4, [0.9, 2.8, 0.7])),
        prop("green_bench", White, block_at(3.4, 0.0, -15.4, [0.6, 0.45, 2.4])),
        // Vault: crates by the way out.
        prop("vault_crate", Wood, crate_at(11.7, 0.0, -16.1, 0.9)),
        prop("vault_crate_small", Wood, crate_at(6.1, 0.0, -16.2, 0.7)),
    ];

    let spawn = Spawn { position: [0.0, 0.0, 3.5], yaw_deg: 0.0, pitch_deg: 0.0 };

    let marker = |name, position, yaw_deg, extras| Marker { name, position, yaw_deg, extras };
    let waypoint = |name, route: &str, order: u32, position| {
        marker(name, position, 0.0, json!({ "waypoint": route, "order": order }))
    };
    #[rustfmt::skip]
    let markers = vec![
        marker("spawn_player", spawn.position, spawn.yaw_deg, json!({ "spawn": "player" })),
        marker("pickup_battery_atrium", [-4.2, 0.0, -11.6], 0.0, json!({ "pickup": "battery" })),
        marker("pickup_battery_yellow", [-11.6, 0.0, -20.0], 0.0, json!({ "pickup": "battery" })),
        marker("pickup_ammo_green", [4.2, 0.0, -20.0], 0.0, json!({ "pickup": "ammo" })),
        marker("pickup_ammo_red", [-7.4, 1.0, -3.4], 0.0, json!({ "pickup": "ammo" })),
        marker("pickup_health_blue", [11.6, 0.0, -3.2], 0.0, json!({ "pickup": "health" })),
        // Guards the red room, facing its door (east).
        marker("enemy_crawler_red", [-11.2, 0.0, -4.0], -90.0, json!({ "enemy": "crawler" })),
        // Walks the yellow and green rooms through the door between them.
        marker("enemy_crawler_yellow_green", [-8.6, 0.0, -13.2], 180.0, json!({ "enemy": "crawler", "route": "yellow_green" })),
        waypoint("route_yellow_green_1", "yellow_green", 1, [-10.0, 0.0, -15.0]),
        waypoint("route_yellow_green_2", "yellow_green", 2, [-9.0, 0.0, -19.6]),
        waypoint("route_yellow_green_3", "yellow_green", 3, [-3.0, 0.0, -16.8]),
        waypoint("route_yellow_green_4", "yellow_green", 4, [2.8, 0.0, -13.8]),
        waypoint("route_yellow_green_5", "yellow_green", 5, [-3.0, 0.0, -16.8]),
        // Walks the blue room round its monolith.
        marker("enemy_crawler_blue", [8.0, 0.0, -3.4], 90.0, json!({ "enemy": "crawler", "route": "blue" })),
        waypoint("route_blue_1", "blue", 1, [8.0, 0.0, -3.4]),
        waypoint("route_blue_2", "blue", 2, [11.4, 0.0, -4.0]),
        waypoint("route_blue_3", "blue", 3, [11.4, 0.0, -9.4]),
        waypoint("route_blue_4", "blue", 4, [9.4, 0.0, -9.6]),
        // Guards the vault, facing its door (south).
        marker("enemy_crawler_vault", [8.9, 0.0, -14.6], 180.0, json!({ "enemy": "crawler" })),
        // The way out, at the back of the vault; its sign faces the door.
        marker("exit", [10.6, 0.0, -15.4], 180.0, json!({ "exit": true, "radius": 1.0 })),
    ];

    // Spotlights over the exhibits, pointing straight down: their cones stay inside their rooms
    // (punctual lights cast no shadows, so a cone reaching through a wall would light the room
    // behind it). Warm white, like gallery lamps.
    let spot = |name, position: [f64; 3], intensity, range| Light {
        name,
        kind: LightKind::Spot { inner: 15f64.to_radians(), outer: 28f64.to_radians() },
        position,
        yaw_deg: 0.0,
        pitch_deg: -90.0,
        color: [1.0, 0.88, 0.7],
        intensity,
        range,
    };
    let toml_lights = vec![
        spot("atrium_spot", [0.0, 4.8, -6.4], 30.0, 7.0),
        spot("red_spot", [-10.3, 3.8, -6.4], 20.0, 5.0),
        spot("blue_spot", [10.3, 3.8, -6.4], 20.0, 5.0),
        spot("yellow_spot", [-8.9, 3.8, -15.8], 20.0, 5.0),
        spot("green_spot", [0.0, 3.8, -18.2], 20.0, 5.0),
    ];
    let lights = vec![Light {
        name: "vault_lamp",
        kind: LightKind::Point,
        position: [8.9, 2.9, -13.8],
        yaw_deg: 0.0,
        pitch_deg: 0.0,
        color: [0.7, 0.85, 1.0],
        intensity: 0.5,
        range: 4.0,
    }];

    let camera = Camera::overview(&spawn);

    Level {
        id: "gallery",
        name: "The Gallery",
        description: "Red, yellow, green and blue rooms round a white atrium: four crawlers among the exhibits",
        exposure: 0.8,
        rooms,
        doorways,
        props,
        markers,
        lights,
        toml_lights,
        camera,
        spawn,
        headlamp: Headlamp {
            power: 40.0,
            fov_deg: 70.0,
            profile: "spot",
            inner_deg: 18.0,
            outer_deg: 34.0,
            color: [1.0, 0.95, 0.85],
        },
        game: GameRules {
            battery_seconds: 150.0,
            objective: "Put down the four crawlers, or leave through the vault beyond the blue room",
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Side;

    fn saturated(m: Material) -> bool {
        let [r, g, b] = m.albedo();
        let (hi, lo) = (r.max(g).max(b), r.min(g).min(b));
        hi >= 0.7 && lo <= 0.2
    }

    fn white(m: Material) -> bool {
        m.albedo().iter().all(|&c| c >= 0.75)
    }

    /// Each coloured room puts a saturated colour on the wall facing its entrance from the
    /// atrium or the room before it, and keeps white walls, floor or ceiling beside it for the
    /// colour to bleed onto; every exhibit is white or saturated.
    #[test]
    fn coloured_rooms_face_their_entrances_with_colour_beside_white() {
        let level = gallery();
        let coloured: Vec<&Room> = level.rooms.iter().filter(|r| r.walls.iter().any(|&m| saturated(m))).collect();
        assert_eq!(coloured.len(), 4);
        for room in coloured {
            assert!(room.walls.iter().any(|&m| white(m)) || white(room.ceiling), "{}", room.name);
            let i = level.room_index(room.name).unwrap();
            let entrances: Vec<Side> = level
                .resolved_doorways()
                .iter()
                .filter_map(|d| (0..2).find(|&k| d.rooms[k] == i).map(|k| d.sides[k]))
                .collect();
            assert!(
                entrances.iter().any(|side| {
                    let opposite = Side::ALL[(side.index() + 2) % 4];
                    saturated(room.walls[side.index()]) && saturated(room.walls[opposite.index()])
                }),
                "{}: an entrance wall and the wall it faces are coloured",
                room.name
            );
        }
        for p in &level.props {
            assert!(white(p.material) || saturated(p.material) || p.material == Material::Wood, "{}", p.name);
        }
    }

    /// The spotlights are level.toml's, pointing straight down, and their cones reach the floor
    /// inside their own room (punctual lights cast no shadows, so a cone through a wall would
    /// light the room behind it).
    #[test]
    fn spotlights_stay_inside_their_rooms() {
        let level = gallery();
        assert!(level.toml_lights.len() >= 4 && !level.lights.is_empty());
        for l in &level.toml_lights {
            let LightKind::Spot { outer, .. } = l.kind else { panic!("{}: a spot", l.name) };
            assert_eq!(l.pitch_deg, -90.0, "{}", l.name);
            let room = level.rooms.iter().find(|r| r.interior().contains(l.position)).unwrap();
            let reach = l.position[1] * outer.tan();
            let [x, _, z] = l.position;
            assert!(
                x - reach >= room.min[0] - 1e-9
                    && x + reach <= room.max[0] + 1e-9
                    && z - reach >= room.min[1] - 1e-9
                    && z + reach <= room.max[1] + 1e-9,
                "{}: its cone ({reach:.2} m) leaves room {}",
                l.name,
                room.name
            );
        }
    }

    #[test]
    fn crawlers_patrol_on_the_floor_and_there_is_one_way_out() {
        let level = gallery();
        let on_floor = |m: &&Marker| m.extras.get("enemy").is_some() || m.extras.get("waypoint").is_some();
        assert!(level.markers.iter().filter(on_floor).all(|m| m.position[1] == 0.0));
        assert_eq!(level.markers.iter().filter(|m| m.extras.get("enemy").is_some()).count(), 4);
        let exits: Vec<&Marker> = level.markers.iter().filter(|m| m.extras.get("exit").is_some()).collect();
        assert_eq!(exits.len(), 1);
        let vault = level.rooms.iter().find(|r| r.name == "vault").unwrap();
        assert!(vault.interior().contains(exits[0].position));
    }
}
