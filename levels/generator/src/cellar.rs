//! "The Cellar", the first shipped level: a start room, a corridor, a red/green Cornell room,
//! a blue/yellow room, a tall hall with pillars and a dais, and a storeroom with the way out.
//! Lit by the headlamp and two dim lights. Textured: painted plaster, brick, concrete, wet
//! flagstones that glint in the beam, varnished crates, steel and copper.

use crate::geometry::Side;
use crate::layout::*;
use crate::materials::Material;
use serde_json::json;

/// The Cellar. `cargo run -p levelgen --release -- --map` prints a top-down view.
pub fn cellar() -> Level {
    use Material::*;
    // Walls are listed north, east, south, west.
    let rooms = vec![
        Room {
            name: "start",
            min: [-3.0, 0.0],
            max: [3.0, 5.0],
            height: 3.0,
            walls: [CellarPlaster, CellarPlaster, CellarPlaster, CellarPlaster],
            floor: VarnishedWood,
            ceiling: CellarPlaster,
        },
        Room {
            name: "corridor",
            min: [-1.0, -12.4],
            max: [1.0, -0.4],
            height: 3.0,
            walls: [CellarPlaster, CellarPlaster, CellarPlaster, CellarPlaster],
            floor: CellarConcrete,
            ceiling: CellarPlaster,
        },
        // Entered from the east: red on the left (south), green on the right (north).
        Room {
            name: "cornell",
            min: [-7.4, -10.0],
            max: [-1.4, -4.0],
            height: 3.0,
            walls: [GreenPlaster, CellarPlaster, RedPlaster, CellarPlaster],
            floor: FloorTile,
            ceiling: CellarPlaster,
        },
        // Entered from the west: a blue back wall meeting a yellow wall on the right.
        Room {
            name: "blue_yellow",
            min: [1.4, -12.4],
            max: [6.4, -4.0],
            height: 3.0,
            walls: [CellarPlaster, BluePlaster, YellowBrick, CellarPlaster],
            floor: CellarConcrete,
            ceiling: CellarPlaster,
        },
        Room {
            name: "hall",
            min: [-8.0, -26.8],
            max: [8.0, -12.8],
            height: 6.0,
            walls: [Brick, Brick, Brick, Brick],
            floor: WetStone,
            ceiling: CellarConcrete,
        },
        Room {
            name: "storeroom",
            min: [8.4, -22.0],
            max: [12.4, -18.0],
            height: 2.8,
            walls: [CellarConcrete, CellarConcrete, CellarConcrete, CellarConcrete],
            floor: CellarConcrete,
            ceiling: CellarPlaster,
        },
    ];

    let door = |a, b, center, width| Doorway { rooms: [a, b], center, width, height: DOOR_HEIGHT };
    let doorways = vec![
        door("start", "corridor", 0.0, 1.4),
        door("corridor", "cornell", -7.0, 1.4),
        door("corridor", "blue_yellow", -9.6, 1.4),
        door("corridor", "hall", 0.0, 1.6),
        door("blue_yellow", "hall", 4.6, 1.4),
        door("hall", "storeroom", -20.0, 1.4),
    ];

    #[rustfmt::skip]
    let props = vec![
        // Start room: two crates in the corners away from the door.
        prop("start_crate_ne", VarnishedWood, crate_at(2.4, 0.0, 0.6, 0.8)),
        prop("start_crate_sw", VarnishedWood, crate_at(-2.4, 0.0, 4.4, 0.8)),
        // Cornell room: the classic tall block (back left) and short block (front right).
        prop("cornell_tall_block", CellarPlaster, cuboid([-6.6, 0.0, -6.2], [-5.4, 2.0, -5.0])),
        prop("cornell_short_block", CellarPlaster, cuboid([-4.0, 0.0, -9.0], [-2.8, 1.0, -7.8])),
        // Blue/yellow room: a stack of crates in the blue/yellow corner, one more by the west wall.
        prop("blue_crate", VarnishedWood, crate_at(5.7, 0.0, -4.7, 1.0)),
        prop("blue_crate_top", VarnishedWood, crate_at(5.7, 1.0, -4.7, 0.6)),
        prop("blue_crate_west", VarnishedWood, crate_at(2.4, 0.0, -11.4, 0.8)),
        // Hall: four full-height pillars, crates for cover, a dais with a step and a ramp.
        prop("hall_pillar_sw", CellarConcrete, cuboid([-4.3, 0.0, -16.8], [-3.7, 6.0, -16.2])),
        prop("hall_pillar_se", CellarConcrete, cuboid([3.7, 0.0, -16.8], [4.3, 6.0, -16.2])),
        prop("hall_pillar_nw", CellarConcrete, cuboid([-4.3, 0.0, -22.8], [-3.7, 6.0, -22.2])),
        prop("hall_pillar_ne", CellarConcrete, cuboid([3.7, 0.0, -22.8], [4.3, 6.0, -22.2])),
        prop("hall_crate_stack", VarnishedWood, crate_at(-7.1, 0.0, -13.7, 1.0)),
        prop("hall_crate_stack_top", VarnishedWood, crate_at(-7.0, 1.0, -13.6, 0.6)),
        prop("hall_crate_mid", VarnishedWood, crate_at(-1.0, 0.0, -20.0, 1.0)),
        prop("hall_crate_long", VarnishedWood, cuboid([1.0, 0.0, -18.2], [2.6, 0.8, -17.4])),
        prop("hall_dais", CellarConcrete, cuboid([-4.0, 0.0, -26.8], [4.0, 0.4, -25.0])),
        prop("hall_dais_step", CellarConcrete, cuboid([-4.0, 0.0, -25.0], [4.0, 0.2, -24.6])),
        prop("hall_dais_ramp", CellarConcrete, ramp([4.0, 0.0, -26.8], [6.4, 0.4, -25.0], Side::West)),
        // Storeroom: crates along the east wall.
        prop("store_crate_big", VarnishedWood, crate_at(11.7, 0.0, -21.3, 1.0)),
        prop("store_crate_small", VarnishedWood, crate_at(11.8, 0.0, -18.6, 0.8)),
        // Metal that catches the lamp: a steel pipe along the hall's far wall, a copper pipe high
        // on the corridor's west wall (above the doorways), the steel door of the way out.
        prop("hall_pipe", Steel, cuboid([-8.0, 4.6, -26.8], [8.0, 4.8, -26.6])),
        prop("corridor_pipe", Copper, cuboid([-1.0, 2.55, -12.4], [-0.88, 2.67, -0.4])),
        prop("exit_door", Steel, cuboid([12.32, 0.0, -20.6], [12.4, 2.1, -19.4])),
    ];

    let spawn = Spawn { position: [0.0, 0.0, 3.8], yaw_deg: 0.0, pitch_deg: 0.0 };

    // Gameplay: pickups, crawlers and their patrol routes, the exit (see the game's
    // `sim::level_entities` for the marker contract).
    let marker = |name, position, yaw_deg, extras| Marker { name, position, yaw_deg, extras };
    let waypoint = |name, route: &str, order: u32, position| {
        marker(name, position, 0.0, json!({ "waypoint": route, "order": order }))
    };
    #[rustfmt::skip]
    let markers = vec![
        marker("spawn_player", spawn.position, spawn.yaw_deg, json!({ "spawn": "player" })),
        marker("pickup_battery_cornell", [-6.8, 0.0, -9.4], 0.0, json!({ "pickup": "battery" })),
        marker("pickup_battery_storeroom", [11.7, 1.0, -21.3], 0.0, json!({ "pickup": "battery" })),
        marker("pickup_battery_hall", [6.6, 0.0, -13.6], 0.0, json!({ "pickup": "battery" })),
        marker("pickup_ammo_blue_yellow", [5.7, 1.6, -4.7], 0.0, json!({ "pickup": "ammo" })),
        marker("pickup_ammo_hall", [-7.0, 1.6, -13.6], 0.0, json!({ "pickup": "ammo" })),
        marker("pickup_health_cornell", [-3.4, 1.0, -8.4], 0.0, json!({ "pickup": "health" })),
        marker("pickup_health_hall", [0.0, 0.4, -26.0], 0.0, json!({ "pickup": "health" })),
        // Guards the red/green room, facing its door.
        marker("enemy_crawler_cornell", [-5.0, 0.0, -8.6], -90.0, json!({ "enemy": "crawler" })),
        marker("enemy_crawler_blue_yellow", [3.9, 0.0, -6.0], 180.0, json!({ "enemy": "crawler", "route": "blue_yellow" })),
        waypoint("route_blue_yellow_1", "blue_yellow", 1, [3.9, 0.0, -6.0]),
        waypoint("route_blue_yellow_2", "blue_yellow", 2, [3.9, 0.0, -10.6]),
        marker("enemy_crawler_hall", [5.8, 0.0, -23.6], 90.0, json!({ "enemy": "crawler", "route": "hall" })),
        waypoint("route_hall_1", "hall", 1, [5.8, 0.0, -23.6]),
        waypoint("route_hall_2", "hall", 2, [-5.8, 0.0, -23.6]),
        waypoint("route_hall_3", "hall", 3, [-5.8, 0.0, -15.0]),
        waypoint("route_hall_4", "hall", 4, [5.8, 0.0, -15.0]),
        // Guards the way out, facing the storeroom door.
        marker("enemy_crawler_storeroom", [11.2, 0.0, -19.6], 90.0, json!({ "enemy": "crawler" })),
        // The way out; its sign faces the storeroom door (west).
        marker("exit", [10.6, 0.0, -20.0], 90.0, json!({ "exit": true, "radius": 1.0 })),
    ];

    let lights = vec![
        Light {
            name: "hall_lamp",
            kind: LightKind::Point,
            position: [0.0, 3.5, -20.0],
            yaw_deg: 0.0,
            pitch_deg: 0.0,
            color: [1.0, 0.75, 0.45],
            intensity: 0.3,
            range: 6.0,
        },
        Light {
            name: "storeroom_bulb",
            kind: LightKind::Spot { inner: 0.35, outer: 0.7 },
            position: [10.4, 2.7, -20.0],
            yaw_deg: 0.0,
            pitch_deg: -90.0,
            color: [0.65, 0.8, 1.0],
            intensity: 0.15,
            range: 4.0,
        },
    ];

    let camera = Camera::overview(&spawn);

    Level {
        id: "cellar",
        name: "The Cellar",
        description: "Four rooms under the house, a hall and a storeroom: four crawlers, one way out",
        // A white wall 4 m in front of a P = 40 headlamp has radiance 0.8 * 40 / (pi * 16) ≈ 0.64.
        // The renderer multiplies by the exposure and applies Narkowicz's ACES fit
        // (shaders/present.wgsl): 0.3 * 0.64 ≈ 0.19 → 0.28 linear ≈ 0.57 sRGB, a mid-grey;
        // 2 m away comes out ≈ 0.87 sRGB, 8 m away ≈ 0.25 sRGB (before indirect light).
        exposure: 0.3,
        rooms,
        doorways,
        props,
        markers,
        lights,
        toml_lights: Vec::new(),
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
            battery_seconds: 120.0,
            objective: "Put down the four crawlers, or get out through the storeroom",
        },
    }
}
