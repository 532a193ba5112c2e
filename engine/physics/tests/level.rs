//! Building collision geometry (from triangles, from scenes, from the shipped level), ray casts,
//! and walking around the shipped level.

mod common;

use std::path::Path;

use common::{controller, run, settled, walk, Geometry, DT};
use glam::{Vec3, Vec3Swizzles};
use physics::{CharacterBody, CharacterMove, CollisionError, LevelCollision};
use scene::{Mesh, Scene, Vertex};

fn mesh(name: &str, positions: &[[f32; 3]], indices: &[u32]) -> Mesh {
    Mesh {
        name: name.into(),
        vertices: positions.iter().map(|&position| Vertex { position, ..Vertex::default() }).collect(),
        indices: indices.to_vec(),
        material: 0,
    }
}

#[test]
fn rays_hit_the_nearest_surface_with_a_normal_facing_back() {
    let mut g = Geometry::with_floor();
    g.cuboid(Vec3::new(3.0, 0.0, -1.0), Vec3::new(4.0, 2.0, 1.0));
    let level = g.build();
    assert_eq!(level.triangle_count(), 24);

    let hit = level.cast_ray(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, -2.0, 0.0), 10.0).expect("floor");
    assert!((hit.distance - 1.0).abs() < 1e-5 && hit.point.abs_diff_eq(Vec3::ZERO, 1e-5), "{hit:?}");
    assert!(hit.normal.abs_diff_eq(Vec3::Y, 1e-5), "{hit:?}");

    let hit = level.cast_ray(Vec3::new(0.0, 1.0, 0.0), Vec3::X, 10.0).expect("block");
    assert!((hit.distance - 3.0).abs() < 1e-5 && hit.normal.abs_diff_eq(Vec3::NEG_X, 1e-5), "{hit:?}");
    // From inside the block the far face is hit, its normal still facing the ray.
    let hit = level.cast_ray(Vec3::new(3.5, 1.0, 0.0), Vec3::X, 10.0).expect("far face");
    assert!((hit.distance - 0.5).abs() < 1e-5 && hit.normal.abs_diff_eq(Vec3::NEG_X, 1e-5), "{hit:?}");

    assert_eq!(level.cast_ray(Vec3::new(0.0, 1.0, 0.0), Vec3::X, 2.5), None, "beyond max_distance");
    assert_eq!(level.cast_ray(Vec3::new(0.0, 1.0, 0.0), Vec3::Y, 100.0), None, "open sky");
    assert_eq!(level.cast_ray(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, 10.0), None, "no direction");
    assert_eq!(level.cast_ray(Vec3::new(0.0, 1.0, 0.0), Vec3::NAN, 10.0), None);
    assert_eq!(level.cast_ray(Vec3::NAN, Vec3::NEG_Y, 10.0), None);
    assert_eq!(level.cast_ray(Vec3::new(0.0, 1.0, 0.0), Vec3::NEG_Y, f32::NAN), None);
    assert!(level.cast_ray(Vec3::new(0.0, 1.0, 0.0), Vec3::NEG_Y, f32::INFINITY).is_some());
}

#[test]
fn bad_triangles_are_errors_not_panics() {
    let tri = [Vec3::ZERO, Vec3::X, Vec3::Z];
    assert_eq!(LevelCollision::from_triangles(&tri, &[]).err(), Some(CollisionError::NoTriangles));
    assert_eq!(LevelCollision::from_triangles(&[], &[]).err(), Some(CollisionError::NoTriangles));
    assert_eq!(
        LevelCollision::from_triangles(&tri, &[[0, 1, 3]]).err(),
        Some(CollisionError::IndexOutOfRange { mesh: None, triangle: 0, index: 3, vertex_count: 3 })
    );
    assert_eq!(
        LevelCollision::from_triangles(&[Vec3::ZERO, Vec3::new(1.0, f32::NAN, 0.0), Vec3::Z], &[[0, 1, 2]]).err(),
        Some(CollisionError::NonFinitePosition { mesh: None, vertex: 1 })
    );
    assert_eq!(
        LevelCollision::from_triangles(&[Vec3::ZERO, Vec3::INFINITY, Vec3::Z], &[[0, 1, 2]]).err(),
        Some(CollisionError::NonFinitePosition { mesh: None, vertex: 1 })
    );
    // Only degenerate triangles (a repeated vertex, collinear points) leave nothing to collide with.
    let line = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
    assert_eq!(LevelCollision::from_triangles(&line, &[[0, 1, 2], [0, 0, 1]]).err(), Some(CollisionError::NoTriangles));
    // Mixed in with good ones they are dropped.
    let level = LevelCollision::from_triangles(&[tri[0], tri[1], tri[2], Vec3::X * 2.0], &[[0, 1, 2], [0, 1, 3]])
        .expect("one good triangle");
    assert_eq!(level.triangle_count(), 1);

    for err in [
        CollisionError::NoTriangles,
        CollisionError::IndexOutOfRange { mesh: Some("m".into()), triangle: 0, index: 3, vertex_count: 3 },
        CollisionError::NonFinitePosition { mesh: None, vertex: 1 },
        CollisionError::PartialTriangle { mesh: "m".into(), index_count: 4 },
        CollisionError::TooManyVertices { count: 1 << 33 },
    ] {
        let message = err.to_string();
        assert!(!message.is_empty() && !message.contains('\n'), "{message:?}");
    }
}

#[test]
fn scenes_are_merged_mesh_by_mesh_and_checked_by_name() {
    let floor =
        mesh("floor", &[[-5.0, 0.0, -5.0], [-5.0, 0.0, 5.0], [5.0, 0.0, 5.0], [5.0, 0.0, -5.0]], &[0, 1, 2, 0, 2, 3]);
    let wall =
        mesh("wall", &[[2.0, 0.0, -5.0], [2.0, 3.0, -5.0], [2.0, 3.0, 5.0], [2.0, 0.0, 5.0]], &[0, 1, 2, 0, 2, 3]);
    let scene = Scene { meshes: vec![floor.clone(), wall.clone()], ..Scene::default() };
    let level = LevelCollision::from_scene(&scene).expect("valid scene");
    assert_eq!(level.triangle_count(), 4);
    // The second mesh's indices were offset onto its own vertices.
    let hit = level.cast_ray(Vec3::new(0.0, 1.0, 0.0), Vec3::X, 10.0).expect("wall");
    assert!((hit.distance - 2.0).abs() < 1e-5, "{hit:?}");

    assert_eq!(LevelCollision::from_scene(&Scene::default()).err(), Some(CollisionError::NoTriangles));
    let mut bad = wall.clone();
    bad.indices[4] = 9;
    assert_eq!(
        LevelCollision::from_scene(&Scene { meshes: vec![floor.clone(), bad], ..Scene::default() }).err(),
        Some(CollisionError::IndexOutOfRange { mesh: Some("wall".into()), triangle: 1, index: 9, vertex_count: 4 })
    );
    let mut bad = wall.clone();
    bad.indices.pop();
    assert_eq!(
        LevelCollision::from_scene(&Scene { meshes: vec![floor.clone(), bad], ..Scene::default() }).err(),
        Some(CollisionError::PartialTriangle { mesh: "wall".into(), index_count: 5 })
    );
    let mut bad = wall;
    bad.vertices[2].position[0] = f32::NAN;
    let err = LevelCollision::from_scene(&Scene { meshes: vec![floor, bad], ..Scene::default() }).err();
    assert_eq!(err, Some(CollisionError::NonFinitePosition { mesh: Some("wall".into()), vertex: 2 }));
    assert!(err.unwrap().to_string().contains("\"wall\""));
}

fn cellar() -> (LevelCollision, Vec3) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../levels/cellar/level.toml");
    let level = scene::load_level(&path).expect("the cellar loads");
    let spawn = level.spawn.expect("the cellar has a spawn").position;
    (LevelCollision::from_scene(&level.scene).expect("the cellar has collision"), spawn)
}

#[test]
fn the_cellar_can_be_walked_from_its_spawn() {
    let (level, spawn) = cellar();
    assert!(level.triangle_count() > 100, "{} triangles", level.triangle_count());
    let ctrl = controller();

    let mut body = settled(&ctrl, &level, spawn);
    assert!(body.position.y.abs() < 0.02 && body.position.xz().abs_diff_eq(spawn.xz(), 1e-4), "{body:?}");

    // North (-Z), through the start room's doorway into the corridor.
    run(&ctrl, &level, &mut body, walk(Vec3::NEG_Z, 4.0), 60, |tick, b| {
        assert!(b.grounded && b.position.y.abs() < 0.02, "tick {tick}: off the floor: {b:?}");
    });
    let walked = spawn.z - body.position.z;
    assert!((walked - 4.0).abs() < 0.1, "walked {walked} m in 1 s: {body:?}");
    assert!(body.position.x.abs() < 1e-3, "veered: {body:?}");

    // South (+Z) from the spawn: the start room's back wall (inner face z = 5) stops it.
    let mut body = settled(&ctrl, &level, spawn);
    run(&ctrl, &level, &mut body, walk(Vec3::Z, 4.0), (3.0 / DT) as usize, |_, _| {});
    let r = ctrl.config.radius;
    assert!((body.position.z - (5.0 - r)).abs() < 0.03 && body.grounded, "not at the back wall: {body:?}");

    // A ray down the corridor from the spawn's eye height ends at a wall, not in the void.
    let hit = level.cast_ray(spawn + Vec3::Y * 1.6, Vec3::NEG_Z, 100.0).expect("the cellar is closed");
    assert!(hit.distance > 4.0 && hit.normal.z > 0.99, "{hit:?}");
}

#[test]
fn a_random_walk_around_the_cellar_stays_inside_it() {
    let (level, spawn) = cellar();
    let ctrl = controller();
    let mut body = CharacterBody::standing_at(spawn);
    // A scripted, pseudo-random walk (an LCG): new direction, speed and crouch every half second.
    let mut state = 0x9e37_79b9_u32;
    let mut next = move || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        state >> 8
    };
    let mut mv = CharacterMove::default();
    for tick in 0..3600 {
        if tick % 30 == 0 {
            let angle = (next() % 360) as f32 * std::f32::consts::PI / 180.0;
            let speed = [1.0, 2.0, 4.0, 6.0][(next() % 4) as usize];
            mv.wish_velocity = Vec3::new(angle.cos(), 0.0, angle.sin()) * speed;
            mv.crouch = next() % 6 == 0;
        }
        mv.jump = next() % 100 == 0;
        ctrl.step(&level, &mut body, &mv, DT);
        // Every floor of the cellar is at y >= 0, and its walls enclose x -8..12.4, z -26.8..5.
        let p = body.position;
        assert!(p.y > -0.02, "tick {tick}: through the floor: {body:?}");
        assert!((-8.0..12.4).contains(&p.x) && (-26.8..5.0).contains(&p.z), "tick {tick}: outside the walls: {body:?}");
    }
}

#[test]
fn bounds_hold_every_triangle_and_capsules_fit_only_clear_of_them() {
    let mut g = Geometry::with_floor();
    g.cuboid(Vec3::new(2.0, 0.0, -1.0), Vec3::new(3.0, 2.0, 1.0));
    let level = g.build();
    assert_eq!(level.bounds(), (Vec3::new(-50.0, -0.2, -50.0), Vec3::new(50.0, 2.0, 50.0)));
    let fits = |x: f32, y: f32| level.capsule_fits(Vec3::new(x, y, 0.0), 0.3, 1.8);
    assert!(fits(0.0, 0.05), "clear of the floor and the box");
    assert!(!fits(0.0, -0.05), "sunk into the floor");
    assert!(!fits(1.8, 0.05), "overlapping the box's side");
    assert!(fits(1.65, 0.05), "just short of it");
    assert!(fits(2.5, 2.05), "standing on top of it");
}
