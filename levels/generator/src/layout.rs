//! A level as data — rooms with their wall materials, the doorways between them, props, marker
//! nodes and lights — and the expansion of that data into solid boxes. The shipped levels' own
//! layouts are in `cellar.rs`, `gallery.rs` and `hall.rs`.
//!
//! Conventions: metres, +Y up, the main floor at y = 0, north = -Z (where yaw 0 looks), east = +X.
//! A room is described by its *interior* rectangle. Each room owns its four walls, which sit just
//! outside the interior and are `WALL` thick; its floor and ceiling slabs cover the interior plus
//! the walls. Two connected rooms therefore lie exactly `2 * WALL` apart, back to back, and a
//! doorway is cut through both walls (each wall split into segments plus a lintel).

use crate::geometry::{Aabb, Side};
use crate::materials::Material;
use serde_json::Value;

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
    pub name: String,
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

/// A `KHR_lights_punctual` light (in the scene file, or a `[[lights]]` entry of level.toml).
/// Spots point along their node's -Z turned by `yaw_deg` about +Y (positive turns left), then
/// by `pitch_deg` about the node's +X (−90 points straight down).
#[derive(Clone, Debug)]
pub struct Light {
    pub name: &'static str,
    pub kind: LightKind,
    pub position: [f64; 3],
    pub yaw_deg: f64,
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

impl Camera {
    /// The file's own view: from the spawn's eyes, level, the way the spawn faces.
    pub fn overview(spawn: &Spawn) -> Self {
        Camera {
            name: "overview",
            position: [spawn.position[0], spawn.position[1] + EYE_HEIGHT, spawn.position[2]],
            yaw_deg: spawn.yaw_deg,
            pitch_deg: 0.0,
            yfov: 1.05,
            znear: 0.05,
            zfar: 100.0,
        }
    }
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
    /// The level's folder name under `levels/` (a replay names its level by it).
    pub id: &'static str,
    pub name: &'static str,
    /// One line for the game's level menu.
    pub description: &'static str,
    pub exposure: f64,
    pub rooms: Vec<Room>,
    pub doorways: Vec<Doorway>,
    pub props: Vec<Prop>,
    pub markers: Vec<Marker>,
    /// Lights written into the scene file.
    pub lights: Vec<Light>,
    /// Lights written into level.toml as `[[lights]]`: a modder moves them without Blender.
    pub toml_lights: Vec<Light>,
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

pub fn cuboid(min: [f64; 3], max: [f64; 3]) -> Shape {
    Shape::Cuboid(Aabb::new(min, max))
}

pub fn prop(name: &str, material: Material, shape: Shape) -> Prop {
    Prop { name: name.to_string(), material, shape }
}

/// A ramp over the box `min..max` whose top rises towards `high`.
pub fn ramp(min: [f64; 3], max: [f64; 3], high: Side) -> Shape {
    Shape::Ramp { bounds: Aabb::new(min, max), high }
}

/// A crate of `size` metres standing on `y` centred at (x, z).
pub fn crate_at(x: f64, y: f64, z: f64, size: f64) -> Shape {
    let h = 0.5 * size;
    cuboid([x - h, y, z - h], [x + h, y + size, z + h])
}

/// A block of `size` (x, y, z) metres standing on `y` centred at (x, z).
pub fn block_at(x: f64, y: f64, z: f64, size: [f64; 3]) -> Shape {
    let (hx, hz) = (0.5 * size[0], 0.5 * size[2]);
    cuboid([x - hx, y, z - hz], [x + hx, y + size[1], z + hz])
}

/// A straight flight of `steps` solid steps (each a box down to the floor at y = 0) over the
/// footprint `min..max` (x, z), climbing towards `up` to `top` metres: every riser is
/// `top / steps`, every tread the footprint's length along `up` over `steps`.
pub fn stairs(
    name: &str,
    material: Material,
    min: [f64; 2],
    max: [f64; 2],
    up: Side,
    top: f64,
    steps: usize,
) -> Vec<Prop> {
    let rise = top / steps as f64;
    (0..steps)
        .map(|k| {
            let (t0, t1) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
            let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
            // The step's extent along the climb, from its low edge to its high edge.
            let ([x0, z0], [x1, z1]) = match up {
                Side::North => ([min[0], lerp(max[1], min[1], t1)], [max[0], lerp(max[1], min[1], t0)]),
                Side::South => ([min[0], lerp(min[1], max[1], t0)], [max[0], lerp(min[1], max[1], t1)]),
                Side::West => ([lerp(max[0], min[0], t1), min[1]], [lerp(max[0], min[0], t0), max[1]]),
                Side::East => ([lerp(min[0], max[0], t0), min[1]], [lerp(min[0], max[0], t1), max[1]]),
            };
            prop(&format!("{name}_{:02}", k + 1), material, cuboid([x0, 0.0, z0], [x1, (k + 1) as f64 * rise, z1]))
        })
        .collect()
}

fn same(a: f64, b: f64) -> bool {
    (a - b).abs() < EPS
}

impl Level {
    /// The scene file's lights, then level.toml's.
    pub fn all_lights(&self) -> impl Iterator<Item = &Light> {
        self.lights.iter().chain(&self.toml_lights)
    }

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
