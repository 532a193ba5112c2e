//! "The Cellar" as data — rooms with their wall colours, the doorways between them, props, marker
//! nodes and lights — and the expansion of that data into solid boxes.
//!
//! Conventions: metres, +Y up, the main floor at y = 0, north = -Z (where yaw 0 looks), east = +X.
//! A room is described by its *interior* rectangle. Each room owns its four walls, which sit just
//! outside the interior and are `WALL` thick; its floor and ceiling slabs cover the interior plus
//! the walls. Two connected rooms therefore lie exactly `2 * WALL` apart, back to back, and a
//! doorway is cut through both walls (each wall split into segments plus a lintel).

use crate::geometry::{Aabb, Material, Side};
use serde_json::{json, Value};

/// Thickness of walls, floors and ceilings.
pub const WALL: f64 = 0.2;
/// Clear height of every doorway.
pub const DOOR_HEIGHT: f64 = 2.2;
/// The narrowest doorway allowed (player capsule radius is 0.3 m).
pub const MIN_DOOR_WIDTH: f64 = 1.2;
/// Height of the player's eyes above their feet (player is 1.8 m tall).
pub const EYE_HEIGHT: f64 = 1.6;

const EPS: f64 = 1e-9;

#[derive(Clone, Debug)]
pub struct Room {
    pub name: &'static str,
    /// Interior corner with the smallest (x, z).
    pub min: [f64; 2],
    /// Interior corner with the largest (x, z).
    pub max: [f64; 2],
    /// Floor-to-ceiling height of the interior.
    pub height: f64,
    /// Wall materials indexed by `Side::index()` (north, east, south, west).
    pub walls: [Material; 4],
    pub floor: Material,
    pub ceiling: Material,
}

impl Room {
    /// The air inside the room.
    pub fn interior(&self) -> Aabb {
        Aabb::new([self.min[0], 0.0, self.min[1]], [self.max[0], self.height, self.max[1]])
    }

    /// Interior plus walls, floor and ceiling.
    pub fn shell(&self) -> Aabb {
        Aabb::new(
            [self.min[0] - WALL, -WALL, self.min[1] - WALL],
            [self.max[0] + WALL, self.height + WALL, self.max[1] + WALL],
        )
    }
}

/// An opening between two rooms. The rooms must be back to back (`2 * WALL` apart); the wall they
/// share is found automatically. `center` is the world coordinate of the opening's middle along the
/// shared wall (x for north/south walls, z for east/west walls).
#[derive(Clone, Debug)]
pub struct Doorway {
    pub rooms: [&'static str; 2],
    pub center: f64,
    pub width: f64,
    pub height: f64,
}

/// A doorway resolved against the rooms.
#[derive(Clone, Debug)]
pub struct ResolvedDoorway {
    pub name: String,
    pub rooms: [usize; 2],
    /// The wall of each room the opening is cut into.
    pub sides: [Side; 2],
    /// Opening extent along the wall.
    pub lo: f64,
    pub hi: f64,
    pub height: f64,
    /// The clear opening through both walls, from one room's interior face to the other's.
    pub passage: Aabb,
}

#[derive(Clone, Debug)]
pub enum Shape {
    Cuboid(Aabb),
    /// A wedge filling the box's footprint, rising from `min.y` to `max.y` towards `high`.
    Ramp {
        bounds: Aabb,
        high: Side,
    },
}

impl Shape {
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Cuboid(b) | Shape::Ramp { bounds: b, .. } => *b,
        }
    }
}

#[derive(Clone, Debug)]
pub struct Prop {
    pub name: &'static str,
    pub material: Material,
    pub shape: Shape,
}

/// An empty node carrying gameplay data in its glTF `extras`.
#[derive(Clone, Debug)]
pub struct Marker {
    pub name: &'static str,
    pub position: [f64; 3],
    pub yaw_deg: f64,
    pub extras: Value,
}

#[derive(Clone, Debug)]
pub enum LightKind {
    Point,
    /// Cone angles in radians from the axis.
    Spot {
        inner: f64,
        outer: f64,
    },
}

/// A `KHR_lights_punctual` light. Spots point along their node's -Z, rotated by `pitch_deg`
/// about +X (−90 points straight down).
#[derive(Clone, Debug)]
pub struct Light {
    pub name: &'static str,
    pub kind: LightKind,
    pub position: [f64; 3],
    pub pitch_deg: f64,
    pub color: [f64; 3],
    /// candela (W/sr for the renderer).
    pub intensity: f64,
    pub range: f64,
}

#[derive(Clone, Debug)]
pub struct Camera {
    pub name: &'static str,
    pub position: [f64; 3],
    pub yaw_deg: f64,
    pub pitch_deg: f64,
    pub yfov: f64,
    pub znear: f64,
    pub zfar: f64,
}

#[derive(Clone, Debug)]
pub struct Spawn {
    /// Feet position.
    pub position: [f64; 3],
    /// 0 looks down -Z, positive turns left (counter-clockwise seen from above).
    pub yaw_deg: f64,
    pub pitch_deg: f64,
}

#[derive(Clone, Debug)]
pub struct Headlamp {
    pub power: f64,
    pub fov_deg: f64,
    pub profile: &'static str,
    pub inner_deg: f64,
    pub outer_deg: f64,
    pub color: [f64; 3],
}

/// `[game]` in level.toml.
#[derive(Clone, Debug)]
pub struct GameRules {
    /// A full battery lasts this long lit, seconds.
    pub battery_seconds: f64,
    pub objective: &'static str,
}

#[derive(Clone, Debug)]
pub struct Level {
    pub name: &'static str,
    /// One line for the game's level menu.
    pub description: &'static str,
    pub exposure: f64,
    pub rooms: Vec<Room>,
    pub doorways: Vec<Doorway>,
    pub props: Vec<Prop>,
    pub markers: Vec<Marker>,
    pub lights: Vec<Light>,
    pub camera: Camera,
    pub spawn: Spawn,
    pub headlamp: Headlamp,
    pub game: GameRules,
}

/// What a solid box is part of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SolidKind {
    Floor,
    Ceiling,
    Wall,
    Lintel,
    Prop,
}

/// A box of the level's static geometry.
#[derive(Clone, Debug)]
pub struct Solid {
    pub name: String,
    pub kind: SolidKind,
    pub material: Material,
    pub bounds: Aabb,
}

fn cuboid(min: [f64; 3], max: [f64; 3]) -> Shape {
    Shape::Cuboid(Aabb::new(min, max))
}

fn prop(name: &'static str, material: Material, shape: Shape) -> Prop {
    Prop { name, material, shape }
}

/// A ramp over the box `min..max` whose top rises towards `high`.
fn ramp(min: [f64; 3], max: [f64; 3], high: Side) -> Shape {
    Shape::Ramp { bounds: Aabb::new(min, max), high }
}

/// A crate of `size` metres standing on `y` centred at (x, z).
fn crate_at(x: f64, y: f64, z: f64, size: f64) -> Shape {
    let h = 0.5 * size;
    cuboid([x - h, y, z - h], [x + h, y + size, z + h])
}

/// The Cellar. See the crate README / `--map` for a top-down view.
pub fn cellar() -> Level {
    use Material::*;
    // Walls are listed north, east, south, west.
    let rooms = vec![
        Room {
            name: "start",
            min: [-3.0, 0.0],
            max: [3.0, 5.0],
            height: 3.0,
            walls: [White, White, White, White],
            floor: Concrete,
            ceiling: White,
        },
        Room {
            name: "corridor",
            min: [-1.0, -12.4],
            max: [1.0, -0.4],
            height: 3.0,
            walls: [White, White, White, White],
            floor: Concrete,
            ceiling: White,
        },
        // Entered from the east: red on the left (south), green on the right (north).
        Room {
            name: "cornell",
            min: [-7.4, -10.0],
            max: [-1.4, -4.0],
            height: 3.0,
            walls: [Green, White, Red, White],
            floor: White,
            ceiling: White,
        },
        // Entered from the west: a blue back wall meeting a yellow wall on the right.
        Room {
            name: "blue_yellow",
            min: [1.4, -12.4],
            max: [6.4, -4.0],
            height: 3.0,
            walls: [White, Blue, Yellow, White],
            floor: Concrete,
            ceiling: White,
        },
        Room {
            name: "hall",
            min: [-8.0, -26.8],
            max: [8.0, -12.8],
            height: 6.0,
            walls: [White, White, White, White],
            floor: Concrete,
            ceiling: Concrete,
        },
        Room {
            name: "storeroom",
            min: [8.4, -22.0],
            max: [12.4, -18.0],
            height: 2.8,
            walls: [Concrete, Concrete, Concrete, Concrete],
            floor: Concrete,
            ceiling: White,
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
        prop("start_crate_ne", Wood, crate_at(2.4, 0.0, 0.6, 0.8)),
        prop("start_crate_sw", Wood, crate_at(-2.4, 0.0, 4.4, 0.8)),
        // Cornell room: the classic tall block (back left) and short block (front right).
        prop("cornell_tall_block", White, cuboid([-6.6, 0.0, -6.2], [-5.4, 2.0, -5.0])),
        prop("cornell_short_block", White, cuboid([-4.0, 0.0, -9.0], [-2.8, 1.0, -7.8])),
        // Blue/yellow room: a stack of crates in the blue/yellow corner, one more by the west wall.
        prop("blue_crate", Wood, crate_at(5.7, 0.0, -4.7, 1.0)),
        prop("blue_crate_top", Wood, crate_at(5.7, 1.0, -4.7, 0.6)),
        prop("blue_crate_west", Wood, crate_at(2.4, 0.0, -11.4, 0.8)),
        // Hall: four full-height pillars, crates for cover, a dais with a step and a ramp.
        prop("hall_pillar_sw", Concrete, cuboid([-4.3, 0.0, -16.8], [-3.7, 6.0, -16.2])),
        prop("hall_pillar_se", Concrete, cuboid([3.7, 0.0, -16.8], [4.3, 6.0, -16.2])),
        prop("hall_pillar_nw", Concrete, cuboid([-4.3, 0.0, -22.8], [-3.7, 6.0, -22.2])),
        prop("hall_pillar_ne", Concrete, cuboid([3.7, 0.0, -22.8], [4.3, 6.0, -22.2])),
        prop("hall_crate_stack", Wood, crate_at(-7.1, 0.0, -13.7, 1.0)),
        prop("hall_crate_stack_top", Wood, crate_at(-7.0, 1.0, -13.6, 0.6)),
        prop("hall_crate_mid", Wood, crate_at(-1.0, 0.0, -20.0, 1.0)),
        prop("hall_crate_long", Wood, cuboid([1.0, 0.0, -18.2], [2.6, 0.8, -17.4])),
        prop("hall_dais", Concrete, cuboid([-4.0, 0.0, -26.8], [4.0, 0.4, -25.0])),
        prop("hall_dais_step", Concrete, cuboid([-4.0, 0.0, -25.0], [4.0, 0.2, -24.6])),
        prop("hall_dais_ramp", Concrete, ramp([4.0, 0.0, -26.8], [6.4, 0.4, -25.0], Side::West)),
        // Storeroom: crates along the east wall.
        prop("store_crate_big", Wood, crate_at(11.7, 0.0, -21.3, 1.0)),
        prop("store_crate_small", Wood, crate_at(11.8, 0.0, -18.6, 0.8)),
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
            pitch_deg: 0.0,
            color: [1.0, 0.75, 0.45],
            intensity: 0.3,
            range: 6.0,
        },
        Light {
            name: "storeroom_bulb",
            kind: LightKind::Spot { inner: 0.35, outer: 0.7 },
            position: [10.4, 2.7, -20.0],
            pitch_deg: -90.0,
            color: [0.65, 0.8, 1.0],
            intensity: 0.15,
            range: 4.0,
        },
    ];

    let camera = Camera {
        name: "overview",
        position: [spawn.position[0], spawn.position[1] + EYE_HEIGHT, spawn.position[2]],
        yaw_deg: spawn.yaw_deg,
        pitch_deg: 0.0,
        yfov: 1.05,
        znear: 0.05,
        zfar: 100.0,
    };

    Level {
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

fn same(a: f64, b: f64) -> bool {
    (a - b).abs() < EPS
}

impl Level {
    pub fn room_index(&self, name: &str) -> Option<usize> {
        self.rooms.iter().position(|r| r.name == name)
    }

    /// Finds the shared wall of a doorway's rooms and the clear passage through it.
    pub fn resolve_doorway(&self, d: &Doorway) -> Result<ResolvedDoorway, String> {
        let ia = self.room_index(d.rooms[0]).ok_or_else(|| format!("unknown room {}", d.rooms[0]))?;
        let ib = self.room_index(d.rooms[1]).ok_or_else(|| format!("unknown room {}", d.rooms[1]))?;
        let (a, b) = (&self.rooms[ia], &self.rooms[ib]);
        let name = format!("{}-{}", a.name, b.name);
        if d.width < MIN_DOOR_WIDTH || d.height < DOOR_HEIGHT {
            return Err(format!(
                "doorway {name}: {} x {} m is smaller than {MIN_DOOR_WIDTH} x {DOOR_HEIGHT} m",
                d.width, d.height
            ));
        }
        let (lo, hi) = (d.center - 0.5 * d.width, d.center + 0.5 * d.width);
        // (side of a, along-wall axis (0 = x, 1 = z), across-wall coordinates of the two faces)
        let (side_a, along, across) = if same(a.max[0] + 2.0 * WALL, b.min[0]) {
            (Side::East, 1, (a.max[0], b.min[0]))
        } else if same(b.max[0] + 2.0 * WALL, a.min[0]) {
            (Side::West, 1, (b.max[0], a.min[0]))
        } else if same(a.max[1] + 2.0 * WALL, b.min[1]) {
            (Side::South, 0, (a.max[1], b.min[1]))
        } else if same(b.max[1] + 2.0 * WALL, a.min[1]) {
            (Side::North, 0, (b.max[1], a.min[1]))
        } else {
            return Err(format!("doorway {name}: rooms are not back to back ({} apart walls)", 2.0 * WALL));
        };
        for r in [a, b] {
            if lo < r.min[along] - EPS || hi > r.max[along] + EPS {
                return Err(format!("doorway {name}: opening {lo}..{hi} is outside room {}'s wall", r.name));
            }
            if d.height > r.height + EPS {
                return Err(format!("doorway {name}: taller than room {}", r.name));
            }
        }
        let passage = if along == 0 {
            Aabb::new([lo, 0.0, across.0], [hi, d.height, across.1])
        } else {
            Aabb::new([across.0, 0.0, lo], [across.1, d.height, hi])
        };
        let side_b = match side_a {
            Side::North => Side::South,
            Side::South => Side::North,
            Side::East => Side::West,
            Side::West => Side::East,
        };
        Ok(ResolvedDoorway { name, rooms: [ia, ib], sides: [side_a, side_b], lo, hi, height: d.height, passage })
    }

    pub fn resolved_doorways(&self) -> Vec<ResolvedDoorway> {
        self.doorways.iter().map(|d| self.resolve_doorway(d).unwrap_or_else(|e| panic!("{e}"))).collect()
    }

    /// All static boxes: for each room its floor, ceiling and walls (split around doorways), then
    /// the box-shaped props, in a fixed order.
    pub fn solids(&self) -> Vec<Solid> {
        let doors = self.resolved_doorways();
        let mut out = Vec::new();
        for (ri, room) in self.rooms.iter().enumerate() {
            let shell = room.shell();
            let mut floor = shell;
            floor.max[1] = 0.0;
            let mut ceiling = shell;
            ceiling.min[1] = room.height;
            out.push(Solid {
                name: format!("{}.floor", room.name),
                kind: SolidKind::Floor,
                material: room.floor,
                bounds: floor,
            });
            out.push(Solid {
                name: format!("{}.ceiling", room.name),
                kind: SolidKind::Ceiling,
                material: room.ceiling,
                bounds: ceiling,
            });
            for side in Side::ALL {
                let mut openings: Vec<(f64, f64, f64)> = doors
                    .iter()
                    .flat_map(|d| {
                        (0..2)
                            .filter(move |&k| d.rooms[k] == ri && d.sides[k] == side)
                            .map(move |_| (d.lo, d.hi, d.height))
                    })
                    .collect();
                openings.sort_by(|a, b| a.0.total_cmp(&b.0));
                wall_solids(room, side, &openings, &mut out);
            }
        }
        for p in &self.props {
            if let Shape::Cuboid(b) = &p.shape {
                out.push(Solid { name: p.name.to_string(), kind: SolidKind::Prop, material: p.material, bounds: *b });
            }
        }
        out
    }
}

/// The boxes of one wall of `room`, split around `openings` (along-wall lo, hi, height; sorted).
/// North/south walls run over the corners; east/west walls fit between them.
fn wall_solids(room: &Room, side: Side, openings: &[(f64, f64, f64)], out: &mut Vec<Solid>) {
    let ([x0, z0], [x1, z1], h) = (room.min, room.max, room.height);
    let (span, across) = match side {
        Side::North => ((x0 - WALL, x1 + WALL), (z0 - WALL, z0)),
        Side::South => ((x0 - WALL, x1 + WALL), (z1, z1 + WALL)),
        Side::West => ((z0, z1), (x0 - WALL, x0)),
        Side::East => ((z0, z1), (x1, x1 + WALL)),
    };
    let along_x = matches!(side, Side::North | Side::South);
    let make = |a0: f64, a1: f64, y0: f64, y1: f64| {
        if along_x {
            Aabb::new([a0, y0, across.0], [a1, y1, across.1])
        } else {
            Aabb::new([across.0, y0, a0], [across.1, y1, a1])
        }
    };
    let material = room.walls[side.index()];
    let prefix = format!("{}.{}", room.name, side.name());
    let mut cursor = span.0;
    let mut push = |name: String, kind, bounds| out.push(Solid { name, kind, material, bounds });
    for (i, &(lo, hi, door_h)) in openings.iter().enumerate() {
        assert!(lo >= cursor - EPS, "{prefix}: overlapping doorways");
        if lo > cursor + EPS {
            push(format!("{prefix}.wall{i}"), SolidKind::Wall, make(cursor, lo, 0.0, h));
        }
        if door_h < h - EPS {
            push(format!("{prefix}.lintel{i}"), SolidKind::Lintel, make(lo, hi, door_h, h));
        }
        cursor = hi;
    }
    if span.1 > cursor + EPS {
        push(format!("{prefix}.wall{}", openings.len()), SolidKind::Wall, make(cursor, span.1, 0.0, h));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{dot, normalize};

    /// Minimal deterministic PRNG (64-bit LCG, Knuth's constants), uniform in [0, 1).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn range(&mut self, a: f64, b: f64) -> f64 {
            a + (b - a) * self.next()
        }
        fn unit_vector(&mut self) -> [f64; 3] {
            loop {
                let v = [0, 1, 2].map(|_| self.range(-1.0, 1.0));
                let l2 = dot(v, v);
                if l2 > 1e-4 && l2 <= 1.0 {
                    return normalize(v);
                }
            }
        }
    }

    fn level() -> (Level, Vec<Solid>) {
        let l = cellar();
        let s = l.solids();
        (l, s)
    }

    #[test]
    fn doorways_are_at_least_1_2_wide_and_2_2_high_and_clear() {
        let (level, solids) = level();
        let doors = level.resolved_doorways();
        assert_eq!(doors.len(), level.doorways.len());
        for d in &doors {
            let size = d.passage.size();
            // Axis along the wall and axis through it.
            let (along, axis) = if matches!(d.sides[0], Side::North | Side::South) { (0, 2) } else { (2, 0) };
            let width = size[along];
            assert!(width >= MIN_DOOR_WIDTH - 1e-9, "{}: {width} m wide", d.name);
            assert!(size[1] >= DOOR_HEIGHT - 1e-9, "{}: {} m high", d.name, size[1]);
            // Nothing stands in the opening or within 0.6 m of it on either side.
            let mut approach = d.passage;
            approach.min[axis] -= 0.6;
            approach.max[axis] += 0.6;
            for s in &solids {
                if s.kind != SolidKind::Floor {
                    assert!(!s.bounds.overlaps(&approach, 1e-9), "{} blocks doorway {}", s.name, d.name);
                }
            }
            for p in &level.props {
                assert!(!p.shape.bounds().overlaps(&approach, 1e-9), "{} blocks {}", p.name, d.name);
            }
            // The walls on both sides really have a gap of exactly this size: the boxes just
            // outside the opening (along the wall, and above it) are solid.
            let probe = |dx: f64, y: f64| {
                let mut p = d.passage.center();
                p[1] = y;
                p[along] += dx;
                solids.iter().any(|s| s.kind != SolidKind::Floor && s.bounds.contains(p))
            };
            let half = 0.5 * width;
            assert!(probe(half + 0.05, 1.0) && probe(-half - 0.05, 1.0), "{}: jambs", d.name);
            assert!(probe(0.0, DOOR_HEIGHT + 0.05), "{}: lintel", d.name);
            assert!(!probe(half - 0.05, 1.0) && !probe(0.0, DOOR_HEIGHT - 0.05));
        }
    }

    #[test]
    fn rooms_do_not_overlap_and_everything_sits_inside_a_room() {
        let (level, solids) = level();
        for (i, a) in level.rooms.iter().enumerate() {
            for b in &level.rooms[i + 1..] {
                assert!(!a.shell().overlaps(&b.shell(), 1e-9), "{} overlaps {}", a.name, b.name);
            }
            assert!(a.height >= 2.5, "{} too low for a 1.8 m player", a.name);
        }
        let inside_some_room = |b: &Aabb| {
            level.rooms.iter().any(|r| {
                let i = r.interior();
                (0..3).all(|k| b.min[k] >= i.min[k] - 1e-9 && b.max[k] <= i.max[k] + 1e-9)
            })
        };
        for p in &level.props {
            assert!(inside_some_room(&p.shape.bounds()), "prop {} outside the rooms", p.name);
            for s in solids.iter().filter(|s| s.kind != SolidKind::Prop) {
                assert!(!s.bounds.overlaps(&p.shape.bounds(), 1e-9), "{} intersects {}", p.name, s.name);
            }
        }
        for m in &level.markers {
            let p = m.position;
            assert!(level.rooms.iter().any(|r| r.interior().contains(p)), "{} outside", m.name);
            let above = [p[0], p[1] + 0.05, p[2]];
            assert!(!solids.iter().any(|s| s.bounds.contains(above)), "{} buried", m.name);
        }
        for l in &level.lights {
            assert!(level.rooms.iter().any(|r| r.interior().contains(l.position)), "{}", l.name);
        }
        let cam = level.camera.position;
        assert!(level.rooms[0].interior().contains(cam));
    }

    #[test]
    fn spawn_capsule_is_free_and_on_the_floor() {
        let (level, solids) = level();
        let p = level.spawn.position;
        assert_eq!(p[1], 0.0);
        assert!(level.rooms[0].interior().contains(p), "spawn must be in the start room");
        // The 1.8 m tall, 0.3 m radius capsule's bounding box, with a hand's width to spare.
        let capsule = Aabb::new([p[0] - 0.4, 0.01, p[2] - 0.4], [p[0] + 0.4, 1.8, p[2] + 0.4]);
        for s in &solids {
            assert!(!s.bounds.overlaps(&capsule, 0.0), "spawn intersects {}", s.name);
        }
        // Something solid right below the feet.
        assert!(solids.iter().any(|s| s.kind == SolidKind::Floor && s.bounds.contains([p[0], -0.05, p[2]])));
    }

    /// No holes to the void: rays from random points in every room all hit geometry within 100 m.
    #[test]
    fn random_rays_never_escape() {
        let (level, solids) = level();
        let mut rng = Lcg(0x5eed_ce11a7);
        let mut rays = 0;
        for room in &level.rooms {
            let i = room.interior();
            for _ in 0..64 {
                let o = [0, 1, 2].map(|k| rng.range(i.min[k] + 0.02, i.max[k] - 0.02));
                for _ in 0..256 {
                    let d = rng.unit_vector();
                    let hit = solids.iter().filter_map(|s| s.bounds.ray_hit(o, d)).fold(f64::INFINITY, f64::min);
                    assert!(hit <= 100.0, "ray from {o:?} in {} along {d:?} escapes", room.name);
                    rays += 1;
                }
            }
        }
        assert_eq!(rays, level.rooms.len() * 64 * 256);
    }

    /// Voxelises the solids at 10 cm and flood-fills the air from the spawn point: the fill must
    /// never reach the edge of the grid (sealed level) and must reach every room (connected).
    #[test]
    fn flood_fill_from_spawn_is_sealed_and_reaches_every_room() {
        let (level, solids) = level();
        const H: f64 = 0.1;
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for s in &solids {
            for k in 0..3 {
                lo[k] = lo[k].min(s.bounds.min[k] - 1.0);
                hi[k] = hi[k].max(s.bounds.max[k] + 1.0);
            }
        }
        let dims = [0, 1, 2].map(|k| ((hi[k] - lo[k]) / H).ceil() as usize);
        let idx = |c: [usize; 3]| (c[2] * dims[1] + c[1]) * dims[0] + c[0];
        let cell_of = |p: [f64; 3]| [0, 1, 2].map(|k| ((p[k] - lo[k]) / H).floor() as usize);
        let mut solid = vec![false; dims[0] * dims[1] * dims[2]];
        for s in &solids {
            // Cells whose centre lies inside the box.
            let r = [0, 1, 2].map(|k| {
                let a = ((s.bounds.min[k] - lo[k]) / H - 0.5).ceil() as usize;
                let b = ((s.bounds.max[k] - lo[k]) / H - 0.5).floor() as usize;
                a..=b
            });
            for z in r[2].clone() {
                for y in r[1].clone() {
                    for x in r[0].clone() {
                        solid[idx([x, y, z])] = true;
                    }
                }
            }
        }
        let mut seen = vec![false; solid.len()];
        let start = cell_of([level.spawn.position[0], 1.0, level.spawn.position[2]]);
        assert!(!solid[idx(start)]);
        let mut stack = vec![start];
        seen[idx(start)] = true;
        while let Some(c) = stack.pop() {
            for k in 0..3 {
                assert!(c[k] > 0 && c[k] + 1 < dims[k], "air leaks out of the level at {c:?}");
                for n in [c[k] - 1, c[k] + 1] {
                    let mut nc = c;
                    nc[k] = n;
                    let i = idx(nc);
                    if !solid[i] && !seen[i] {
                        seen[i] = true;
                        stack.push(nc);
                    }
                }
            }
        }
        for room in &level.rooms {
            let c = room.interior().center();
            let probe = [c[0] + 0.03, 1.53, c[2] + 0.03];
            assert!(seen[idx(cell_of(probe))], "room {} not reachable from spawn", room.name);
        }
    }
}
