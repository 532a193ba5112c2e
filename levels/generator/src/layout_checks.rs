//! Checks every shipped level's layout must pass: doorways open and clear, rooms apart,
//! everything inside a room, a free spawn on the floor, no hole to the void, every room
//! reachable from the spawn. (Compiled for tests only.)

use crate::geometry::{dot, normalize, Aabb, Side};
use crate::layout::{Level, Solid, SolidKind, DOOR_HEIGHT, MIN_DOOR_WIDTH};

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

/// Every shipped level with its solids.
fn levels() -> Vec<(Level, Vec<Solid>)> {
    crate::all_levels()
        .into_iter()
        .map(|l| {
            let s = l.solids();
            (l, s)
        })
        .collect()
}

#[test]
fn doorways_are_at_least_1_2_wide_and_2_2_high_and_clear() {
    for (level, solids) in levels() {
        let doors = level.resolved_doorways();
        assert_eq!(doors.len(), level.doorways.len());
        for d in &doors {
            let name = format!("{}: {}", level.id, d.name);
            let size = d.passage.size();
            // Axis along the wall and axis through it.
            let (along, axis) = if matches!(d.sides[0], Side::North | Side::South) { (0, 2) } else { (2, 0) };
            let width = size[along];
            assert!(width >= MIN_DOOR_WIDTH - 1e-9, "{name}: {width} m wide");
            assert!(size[1] >= DOOR_HEIGHT - 1e-9, "{name}: {} m high", size[1]);
            // Nothing stands in the opening or within 0.6 m of it on either side.
            let mut approach = d.passage;
            approach.min[axis] -= 0.6;
            approach.max[axis] += 0.6;
            for s in &solids {
                if s.kind != SolidKind::Floor {
                    assert!(!s.bounds.overlaps(&approach, 1e-9), "{} blocks doorway {name}", s.name);
                }
            }
            for p in &level.props {
                assert!(!p.shape.bounds().overlaps(&approach, 1e-9), "{} blocks {name}", p.name);
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
            let top = d.height;
            assert!(probe(half + 0.05, 1.0) && probe(-half - 0.05, 1.0), "{name}: jambs");
            let lintel = level.rooms[d.rooms[0]].height.min(level.rooms[d.rooms[1]].height) > top + 1e-9;
            assert!(!lintel || probe(0.0, top + 0.05), "{name}: lintel");
            assert!(!probe(half - 0.05, 1.0) && !probe(0.0, top - 0.05), "{name}: open");
        }
    }
}

#[test]
fn rooms_do_not_overlap_and_everything_sits_inside_a_room() {
    for (level, solids) in levels() {
        let id = level.id;
        for (i, a) in level.rooms.iter().enumerate() {
            for b in &level.rooms[i + 1..] {
                assert!(!a.shell().overlaps(&b.shell(), 1e-9), "{id}: {} overlaps {}", a.name, b.name);
            }
            assert!(a.height >= 2.5, "{id}: {} too low for a 1.8 m player", a.name);
        }
        let inside_some_room = |b: &Aabb| {
            level.rooms.iter().any(|r| {
                let i = r.interior();
                (0..3).all(|k| b.min[k] >= i.min[k] - 1e-9 && b.max[k] <= i.max[k] + 1e-9)
            })
        };
        for p in &level.props {
            assert!(inside_some_room(&p.shape.bounds()), "{id}: prop {} outside the rooms", p.name);
            for s in solids.iter().filter(|s| s.kind != SolidKind::Prop) {
                assert!(!s.bounds.overlaps(&p.shape.bounds(), 1e-9), "{id}: {} intersects {}", p.name, s.name);
            }
        }
        for m in &level.markers {
            let p = m.position;
            assert!(level.rooms.iter().any(|r| r.interior().contains(p)), "{id}: {} outside", m.name);
            let above = [p[0], p[1] + 0.05, p[2]];
            assert!(!solids.iter().any(|s| s.bounds.contains(above)), "{id}: {} buried", m.name);
        }
        // A crawler's body (0.35 m radius, 1.5 m tall) starts clear of everything.
        for m in level.markers.iter().filter(|m| m.extras.get("enemy").is_some()) {
            let [x, y, z] = m.position;
            let body = Aabb::new([x - 0.35, y + 0.01, z - 0.35], [x + 0.35, y + 1.5, z + 0.35]);
            for s in &solids {
                assert!(!s.bounds.overlaps(&body, 0.0), "{id}: {} starts inside {}", m.name, s.name);
            }
        }
        for l in level.all_lights() {
            assert!(level.rooms.iter().any(|r| r.interior().contains(l.position)), "{id}: {}", l.name);
        }
        let cam = level.camera.position;
        assert!(level.rooms[0].interior().contains(cam), "{id}: the camera is in the first room");
    }
}

#[test]
fn spawn_capsule_is_free_and_on_the_floor() {
    for (level, solids) in levels() {
        let id = level.id;
        let p = level.spawn.position;
        assert_eq!(p[1], 0.0);
        assert!(level.rooms[0].interior().contains(p), "{id}: spawn must be in the first room");
        // The 1.8 m tall, 0.3 m radius capsule's bounding box, with a hand's width to spare.
        let capsule = Aabb::new([p[0] - 0.4, 0.01, p[2] - 0.4], [p[0] + 0.4, 1.8, p[2] + 0.4]);
        for s in &solids {
            assert!(!s.bounds.overlaps(&capsule, 0.0), "{id}: spawn intersects {}", s.name);
        }
        // Something solid right below the feet.
        assert!(solids.iter().any(|s| s.kind == SolidKind::Floor && s.bounds.contains([p[0], -0.05, p[2]])));
    }
}

/// No holes to the void: rays from random points in every room all hit geometry within 100 m.
#[test]
fn random_rays_never_escape() {
    for (level, solids) in levels() {
        let mut rng = Lcg(0x5eed_ce11a7);
        let mut rays = 0;
        for room in &level.rooms {
            let i = room.interior();
            for _ in 0..64 {
                let o = [0, 1, 2].map(|k| rng.range(i.min[k] + 0.02, i.max[k] - 0.02));
                for _ in 0..256 {
                    let d = rng.unit_vector();
                    let hit = solids.iter().filter_map(|s| s.bounds.ray_hit(o, d)).fold(f64::INFINITY, f64::min);
                    assert!(hit <= 100.0, "{}: ray from {o:?} in {} along {d:?} escapes", level.id, room.name);
                    rays += 1;
                }
            }
        }
        assert_eq!(rays, level.rooms.len() * 64 * 256);
    }
}

/// Voxelises the solids at 10 cm and flood-fills the air from the spawn point: the fill must
/// never reach the edge of the grid (sealed level) and must reach every room (connected).
#[test]
fn flood_fill_from_spawn_is_sealed_and_reaches_every_room() {
    for (level, solids) in levels() {
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
                assert!(c[k] > 0 && c[k] + 1 < dims[k], "{}: air leaks out of the level at {c:?}", level.id);
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
            assert!(seen[idx(cell_of(probe))], "{}: room {} not reachable from spawn", level.id, room.name);
        }
    }
}
