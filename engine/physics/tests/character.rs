//! The walking controller against hand-built levels: walls, gravity, jumps, slopes, steps,
//! crouching, ceilings and bit-exact determinism.

mod common;

use common::{controller, run, settled, walk, Geometry, DT};
use glam::Vec3;
use physics::{CharacterBody, CharacterConfig, CharacterMove};

const WALK: f32 = 4.0;

#[test]
fn a_wall_stops_the_capsule_at_its_radius() {
    let mut g = Geometry::with_floor();
    g.cuboid(Vec3::new(3.0, 0.0, -10.0), Vec3::new(3.5, 3.0, 10.0));
    let level = g.build();
    let ctrl = controller();
    let r = ctrl.config.radius;
    let mut body = settled(&ctrl, &level, Vec3::ZERO);

    run(&ctrl, &level, &mut body, walk(Vec3::X, WALK), 120, |tick, b| {
        assert!(b.position.x <= 3.0 - r + 1e-3, "tick {tick}: inside the wall at {}", b.position);
        assert!(b.grounded, "tick {tick}: left the ground: {b:?}");
    });
    assert!((body.position.x - (3.0 - r)).abs() < 0.03, "stopped at {}", body.position);
    // Contact normals are only nearly exact: sliding along the wall may creep a few mm.
    assert!(body.position.y.abs() < 0.02 && body.position.z.abs() < 0.01, "drifted: {}", body.position);
    assert!(body.velocity.x.abs() < 1e-3, "still pushing into the wall: {}", body.velocity);
}

#[test]
fn walking_diagonally_into_a_wall_slides_along_it() {
    let mut g = Geometry::with_floor();
    g.cuboid(Vec3::new(3.0, 0.0, -20.0), Vec3::new(3.5, 3.0, 20.0));
    let level = g.build();
    let ctrl = controller();
    let r = ctrl.config.radius;
    let mut body = settled(&ctrl, &level, Vec3::ZERO);

    run(&ctrl, &level, &mut body, walk(Vec3::new(1.0, 0.0, -1.0), WALK), 120, |tick, b| {
        assert!(b.position.x <= 3.0 - r + 1e-3, "tick {tick}: inside the wall at {}", b.position);
    });
    // 0.95 s to reach the wall at 2.83 m/s per axis, then 1.05 s sliding at 2.83 m/s along it.
    assert!((body.position.x - (3.0 - r)).abs() < 0.03, "not against the wall: {}", body.position);
    assert!(body.position.z < -5.3, "did not slide along the wall: {}", body.position);
    assert!(body.velocity.z < -2.7, "lost the speed along the wall: {}", body.velocity);
}

#[test]
fn a_dropped_body_falls_for_sqrt_2h_over_g_and_lands_on_the_floor() {
    let level = Geometry::with_floor().build();
    let ctrl = controller();
    let g = ctrl.config.gravity;
    let h = 2.0;
    let mut body = CharacterBody::standing_at(Vec3::new(0.0, h, 0.0));
    let mut landed_at = None;
    run(&ctrl, &level, &mut body, CharacterMove::default(), 90, |tick, b| {
        assert!(b.position.y > -0.01, "tick {tick}: through the floor at {}", b.position);
        if b.grounded && landed_at.is_none() {
            landed_at = Some((tick + 1) as f32 * DT);
        }
    });
    let expected = (2.0 * h / g).sqrt();
    let landed_at = landed_at.expect("never landed");
    assert!((landed_at - expected).abs() <= 2.0 * DT, "landed after {landed_at} s, expected {expected} s");
    assert!(body.grounded && body.position.y.abs() < 0.02, "not resting on the floor: {body:?}");
    assert_eq!(body.velocity.y, 0.0);
}

#[test]
fn a_jump_reaches_v2_over_2g_and_cannot_be_repeated_in_the_air() {
    let level = Geometry::with_floor().build();
    let ctrl = controller();
    let cfg = ctrl.config;
    let mut body = settled(&ctrl, &level, Vec3::ZERO);
    let jump = CharacterMove { jump: true, ..CharacterMove::default() };

    ctrl.step(&level, &mut body, &jump, DT);
    assert!(!body.grounded && body.velocity.y > 0.0, "did not take off: {body:?}");
    // Keep asking to jump: nothing may happen until the feet are back on the ground.
    let (mut apex, mut last_vy, mut airborne_ticks) = (body.position.y, body.velocity.y, 1);
    while !body.grounded {
        ctrl.step(&level, &mut body, &jump, DT);
        assert!(body.grounded || body.velocity.y < last_vy, "jumped again in mid-air: {body:?}");
        last_vy = body.velocity.y;
        apex = apex.max(body.position.y);
        airborne_ticks += 1;
        assert!(airborne_ticks < 120, "never landed: {body:?}");
    }
    let expected = cfg.jump_speed * cfg.jump_speed / (2.0 * cfg.gravity);
    assert!((apex - expected).abs() < 0.05 * expected, "apex {apex} m, expected {expected} m");
    let flight = airborne_ticks as f32 * DT;
    let expected_flight = 2.0 * cfg.jump_speed / cfg.gravity;
    assert!((flight - expected_flight).abs() <= 2.0 * DT, "flew {flight} s, expected {expected_flight} s");

    // Back on the ground, held jump jumps again.
    ctrl.step(&level, &mut body, &jump, DT);
    assert!(body.velocity.y > 0.0, "could not jump again after landing: {body:?}");
}

#[test]
fn air_control_is_a_bounded_acceleration() {
    let level = Geometry::with_floor().build();
    let ctrl = controller();
    let mut body = settled(&ctrl, &level, Vec3::ZERO);
    // Take off standing still, then ask for full speed sideways.
    ctrl.step(&level, &mut body, &CharacterMove { jump: true, ..CharacterMove::default() }, DT);
    run(&ctrl, &level, &mut body, walk(Vec3::X, WALK), 30, |tick, b| {
        let expected = (ctrl.config.air_control * DT * (tick + 1) as f32).min(WALK);
        assert!((b.velocity.x - expected).abs() < 1e-4, "tick {tick}: vx {} expected {expected}", b.velocity.x);
        assert!(!b.grounded);
    });
}

/// Floor, a ramp rising 1 m towards +X from x = 1 at `slope_deg`, a platform on top.
fn ramp_level(slope_deg: f32) -> (physics::LevelCollision, f32) {
    let run_length = 1.0 / slope_deg.to_radians().tan();
    let top_start = 1.0 + run_length;
    let mut g = Geometry::with_floor();
    g.ramp_up_x(Vec3::new(1.0, 0.0, -3.0), Vec3::new(top_start, 1.0, 3.0));
    g.cuboid(Vec3::new(top_start, 0.0, -3.0), Vec3::new(top_start + 4.0, 1.0, 3.0));
    (g.build(), top_start)
}

#[test]
fn a_30_degree_ramp_is_walked_up_and_down_at_full_speed() {
    let (level, top_start) = ramp_level(30.0);
    let ctrl = controller();
    let mut body = settled(&ctrl, &level, Vec3::ZERO);
    run(&ctrl, &level, &mut body, walk(Vec3::X, WALK), 90, |tick, b| {
        assert!(b.grounded, "tick {tick}: left the ramp: {b:?}");
    });
    // 1.5 s at 4 m/s: the ramp does not slow the walk down.
    assert!((body.position.x - 6.0).abs() < 0.05, "lost speed on the ramp: {body:?}");
    assert!(body.position.x > top_start + 0.5, "did not reach the top: {body:?}");
    assert!((body.position.y - 1.0).abs() < 0.02, "not standing on the top: {body:?}");

    run(&ctrl, &level, &mut body, walk(Vec3::NEG_X, WALK), 90, |tick, b| {
        assert!(b.grounded, "tick {tick}: took off going down the ramp: {b:?}");
    });
    assert!(body.position.x.abs() < 0.05 && body.position.y.abs() < 0.02, "not back at the start: {body:?}");
}

#[test]
fn a_60_degree_slope_cannot_be_climbed() {
    let (level, _) = ramp_level(60.0);
    let ctrl = controller();
    let mut body = settled(&ctrl, &level, Vec3::ZERO);
    let mut highest = 0.0f32;
    run(&ctrl, &level, &mut body, walk(Vec3::X, WALK), 180, |_, b| highest = highest.max(b.position.y));
    assert!(body.position.x < 1.0, "went up the slope: {body:?}");
    assert!(highest < 0.25, "climbed to {highest} m");
    assert!(body.position.y < 0.02, "ended above the floor: {body:?}");
}

#[test]
fn a_body_on_a_60_degree_slope_slides_down_it() {
    let (level, top_start) = ramp_level(60.0);
    let ctrl = controller();
    // Dropped onto the middle of the slope.
    let mut body = CharacterBody::standing_at(Vec3::new(0.5 * (1.0 + top_start), 1.0, 0.0));
    run(&ctrl, &level, &mut body, CharacterMove::default(), 120, |_, _| {});
    assert!(body.position.x < 1.0 && body.position.y.abs() < 0.02, "did not slide to the floor: {body:?}");
    assert!(body.grounded);
}

/// Floor and a block of `height` from x = 1 on.
fn step_level(height: f32) -> physics::LevelCollision {
    let mut g = Geometry::with_floor();
    g.cuboid(Vec3::new(1.0, 0.0, -3.0), Vec3::new(6.0, height, 3.0));
    g.build()
}

#[test]
fn a_30_cm_step_is_climbed_while_walking() {
    let level = step_level(0.3);
    let ctrl = controller();
    let mut body = settled(&ctrl, &level, Vec3::ZERO);
    run(&ctrl, &level, &mut body, walk(Vec3::X, WALK), 60, |_, _| {});
    assert!(body.position.x > 2.5, "stuck at the step: {body:?}");
    assert!((body.position.y - 0.3).abs() < 0.02 && body.grounded, "not standing on the step: {body:?}");
}

#[test]
fn steps_taller_than_step_height_block() {
    let ctrl = controller();
    let r = ctrl.config.radius;
    // 0.4 m: just over step_height (0.35), but low enough for the rounded bottom to reach it.
    for height in [0.6, 0.4] {
        let level = step_level(height);
        let mut body = settled(&ctrl, &level, Vec3::ZERO);
        run(&ctrl, &level, &mut body, walk(Vec3::X, WALK), 60, |_, _| {});
        assert!((body.position.x - (1.0 - r)).abs() < 0.03, "{height} m: not stopped at the step: {body:?}");
        assert!(body.position.y.abs() < 0.02 && body.grounded, "{height} m: climbed: {body:?}");
    }
}

#[test]
fn steps_are_climbed_at_any_walking_speed() {
    let level = step_level(0.35);
    let ctrl = controller();
    for (speed, crouch) in [(0.5, false), (1.0, true), (2.0, false), (8.0, false)] {
        let mut body = settled(&ctrl, &level, Vec3::ZERO);
        let mv = CharacterMove { crouch, ..walk(Vec3::X, speed) };
        run(&ctrl, &level, &mut body, mv, (2.0 / speed / DT) as usize, |tick, b| {
            assert!(b.grounded, "{speed} m/s: tick {tick}: left the ground: {b:?}");
        });
        assert!((body.position.y - 0.35).abs() < 0.02, "{speed} m/s: not on the step: {body:?}");
    }
}

#[test]
fn stairs_are_walked_up_and_down_without_leaving_the_ground() {
    // Ten 17 cm risers with 28 cm treads from x = 1, then a landing at 1.7 m.
    let mut g = Geometry::with_floor();
    for i in 0..10 {
        let x = 1.0 + 0.28 * i as f32;
        g.cuboid(Vec3::new(x, 0.0, -1.0), Vec3::new(x + 0.28, 0.17 * (i + 1) as f32, 1.0));
    }
    g.cuboid(Vec3::new(3.8, 0.0, -1.0), Vec3::new(8.0, 1.7, 1.0));
    let level = g.build();
    let ctrl = controller();
    for speed in [2.0, WALK] {
        let mut body = settled(&ctrl, &level, Vec3::ZERO);
        let ticks = (5.0 / speed / DT) as usize;
        run(&ctrl, &level, &mut body, walk(Vec3::X, speed), ticks, |tick, b| {
            assert!(b.grounded, "{speed} m/s up: tick {tick}: airborne: {b:?}");
        });
        assert!(body.position.x > 4.5 && (body.position.y - 1.7).abs() < 0.02, "{speed} m/s: not upstairs: {body:?}");
        run(&ctrl, &level, &mut body, walk(Vec3::NEG_X, speed), ticks, |tick, b| {
            assert!(b.grounded, "{speed} m/s down: tick {tick}: airborne: {b:?}");
        });
        assert!(body.position.x < 0.5 && body.position.y.abs() < 0.02, "{speed} m/s: not downstairs: {body:?}");
        assert!(body.position.z.abs() < 0.05, "{speed} m/s: drifted sideways: {body:?}");
    }
}

#[test]
fn walking_off_a_step_follows_the_ground_down_but_off_a_ledge_falls() {
    let level = step_level(0.3);
    let ctrl = controller();
    let mut body = settled(&ctrl, &level, Vec3::new(3.0, 0.3, 0.0));
    run(&ctrl, &level, &mut body, walk(Vec3::NEG_X, WALK), 45, |tick, b| {
        assert!(b.grounded, "tick {tick}: airborne going down a step: {b:?}");
    });
    assert!(body.position.x < 0.5 && body.position.y.abs() < 0.02, "{body:?}");

    let level = step_level(1.0);
    let mut body = settled(&ctrl, &level, Vec3::new(3.0, 1.0, 0.0));
    let mut airborne_ticks = 0;
    run(&ctrl, &level, &mut body, walk(Vec3::NEG_X, WALK), 90, |_, b| airborne_ticks += usize::from(!b.grounded));
    // A 1 m fall takes 0.45 s (27 ticks), give or take rolling off the edge.
    assert!((20..35).contains(&airborne_ticks), "airborne for {airborne_ticks} ticks");
    assert!(body.position.y.abs() < 0.02 && body.grounded, "{body:?}");
}

#[test]
fn crouching_lowers_the_head_and_standing_up_needs_headroom() {
    // A 1.5 m high crawl space from x = 2 to x = 6 (its roof is a slab at 1.5..1.8 m).
    let mut g = Geometry::with_floor();
    g.cuboid(Vec3::new(2.0, 1.5, -3.0), Vec3::new(6.0, 1.8, 3.0));
    let level = g.build();
    let ctrl = controller();
    let cfg = ctrl.config;
    let mut body = settled(&ctrl, &level, Vec3::ZERO);

    let crouch = CharacterMove { crouch: true, ..CharacterMove::default() };
    ctrl.step(&level, &mut body, &crouch, DT);
    assert!(body.crouching && body.height(&cfg) == cfg.crouch_height, "{body:?}");
    assert!(body.position.y.abs() < 0.02 && body.grounded, "the feet moved: {body:?}");

    // Standing, the roof's edge is a wall at head height.
    let mut standing = settled(&ctrl, &level, Vec3::ZERO);
    run(&ctrl, &level, &mut standing, walk(Vec3::X, WALK), 60, |_, _| {});
    assert!(standing.position.x < 2.0 - cfg.radius + 0.03, "walked under a 1.5 m roof standing: {standing:?}");

    // Crouched, the body fits under it; let go of crouch there and it stays down.
    run(&ctrl, &level, &mut body, CharacterMove { crouch: true, ..walk(Vec3::X, WALK) }, 60, |_, _| {});
    assert!((3.5..5.0).contains(&body.position.x), "did not crawl in: {body:?}");
    run(&ctrl, &level, &mut body, CharacterMove::default(), 10, |tick, b| {
        assert!(b.crouching, "tick {tick}: stood up under the roof: {b:?}");
    });
    assert!(body.position.y.abs() < 0.02 && body.grounded, "pushed out of place: {body:?}");

    // Still not holding crouch, walk out: it stands up once the head is clear of the roof.
    run(&ctrl, &level, &mut body, walk(Vec3::X, WALK), 40, |tick, b| {
        if b.position.x < 6.0 + cfg.radius - 0.02 {
            assert!(b.crouching, "tick {tick}: stood up under the roof's edge: {b:?}");
        }
    });
    assert!(!body.crouching && body.height(&cfg) == cfg.height, "did not stand up in the open: {body:?}");
}

#[test]
fn jumping_under_a_low_ceiling_does_not_pass_through_it() {
    // The ceiling's underside is 2.2 m up: 0.4 m of room above a standing head.
    let mut g = Geometry::with_floor();
    g.cuboid(Vec3::new(-5.0, 2.2, -5.0), Vec3::new(5.0, 2.5, 5.0));
    let level = g.build();
    let ctrl = controller();
    let height = ctrl.config.height;
    let mut body = settled(&ctrl, &level, Vec3::ZERO);
    let jump = CharacterMove { jump: true, ..CharacterMove::default() };

    let mut apex = 0.0f32;
    let mut bumped = false;
    run(&ctrl, &level, &mut body, jump, 40, |tick, b| {
        assert!(b.position.y + height <= 2.2 + 1e-3, "tick {tick}: head in the ceiling: {b:?}");
        apex = apex.max(b.position.y);
        bumped |= b.velocity.y == 0.0 && !b.grounded;
    });
    assert!(apex > 0.35, "did not reach the ceiling: apex {apex}");
    assert!(bumped, "upward speed was not cut by the ceiling");
    // Jumps, bumps and lands again and again, always below the ceiling.
    assert!(body.position.y < 0.4 && body.position.y > -0.01);
}

#[test]
fn same_inputs_give_bit_identical_states() {
    // A course with walls, a ramp, a step, a low roof and a pillar to run into.
    let geometry = || {
        let mut g = Geometry::with_floor();
        g.cuboid(Vec3::new(-8.0, 0.0, -8.0), Vec3::new(8.0, 3.0, -7.5));
        g.cuboid(Vec3::new(-8.0, 0.0, 7.5), Vec3::new(8.0, 3.0, 8.0));
        g.cuboid(Vec3::new(-8.0, 0.0, -8.0), Vec3::new(-7.5, 3.0, 8.0));
        g.cuboid(Vec3::new(7.5, 0.0, -8.0), Vec3::new(8.0, 3.0, 8.0));
        g.ramp_up_x(Vec3::new(1.0, 0.0, -6.0), Vec3::new(3.0, 0.8, -3.0));
        g.cuboid(Vec3::new(3.0, 0.0, -6.0), Vec3::new(6.0, 0.8, -3.0));
        g.cuboid(Vec3::new(-4.0, 0.0, 2.0), Vec3::new(-1.0, 0.3, 5.0));
        g.cuboid(Vec3::new(1.0, 1.5, 2.0), Vec3::new(5.0, 1.8, 6.0));
        g.cuboid(Vec3::new(-0.5, 0.0, -0.5), Vec3::new(0.5, 3.0, 0.5));
        g
    };
    // A scripted, pseudo-random 600-tick input sequence (an LCG: no RNG crate, no seeds from the clock).
    let inputs: Vec<CharacterMove> = {
        let mut state = 0x2545_f491_u32;
        let mut next = move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            state >> 8
        };
        let mut mv = CharacterMove::default();
        (0..600)
            .map(|tick| {
                if tick % 20 == 0 {
                    let angle = (next() % 360) as f32 * std::f32::consts::PI / 180.0;
                    mv.wish_velocity = Vec3::new(angle.cos(), 0.0, angle.sin()) * WALK;
                    mv.crouch = next() % 5 == 0;
                }
                mv.jump = next() % 25 == 0;
                mv
            })
            .collect()
    };
    let simulate = || {
        let level = geometry().build();
        let ctrl = controller();
        let mut body = CharacterBody::standing_at(Vec3::new(-3.0, 0.5, -3.0));
        inputs
            .iter()
            .map(|mv| {
                ctrl.step(&level, &mut body, mv, DT);
                body
            })
            .collect::<Vec<_>>()
    };
    let bits = |b: &CharacterBody| {
        let [px, py, pz, vx, vy, vz] =
            [b.position.x, b.position.y, b.position.z, b.velocity.x, b.velocity.y, b.velocity.z].map(f32::to_bits);
        (px, py, pz, vx, vy, vz, b.grounded, b.crouching)
    };
    let (first, second) = (simulate(), simulate());
    for (tick, (a, b)) in first.iter().zip(&second).enumerate() {
        assert_eq!(bits(a), bits(b), "tick {tick} differs: {a:?} vs {b:?}");
    }
    // The script must have exercised the controller, not stood still.
    let travelled: f32 = first.windows(2).map(|w| (w[1].position - w[0].position).length()).sum();
    assert!(travelled > 20.0, "travelled only {travelled} m");
    assert!(first.iter().any(|b| b.velocity.y > 0.0), "never jumped");
    assert!(first.iter().any(|b| b.crouching), "never crouched");
    assert!(first.iter().all(|b| b.position.is_finite() && b.position.y > -0.05), "fell out of the level");
}

#[test]
fn a_bad_tick_or_move_does_not_poison_the_state() {
    let level = Geometry::with_floor().build();
    let ctrl = controller();
    let mut body = settled(&ctrl, &level, Vec3::ZERO);
    let before = body;
    for dt in [0.0, -DT, f32::NAN, f32::INFINITY] {
        ctrl.step(&level, &mut body, &walk(Vec3::X, WALK), dt);
        assert_eq!(body, before, "dt {dt} changed the body");
    }
    let nan_wish = CharacterMove { wish_velocity: Vec3::new(f32::NAN, 0.0, f32::INFINITY), ..CharacterMove::default() };
    ctrl.step(&level, &mut body, &nan_wish, DT);
    assert!(body.position.is_finite() && body.velocity.is_finite() && body.grounded, "{body:?}");
    // A body somewhere absurd gives nonsense, but no panic.
    let mut lost = CharacterBody::standing_at(Vec3::splat(f32::NAN));
    ctrl.step(&level, &mut lost, &walk(Vec3::X, WALK), DT);
}

#[test]
fn config_validation() {
    assert_eq!(CharacterConfig::default().validate(), Ok(()));
    let bad = [
        CharacterConfig { radius: 0.0, ..CharacterConfig::default() },
        CharacterConfig { crouch_height: 0.5, ..CharacterConfig::default() },
        CharacterConfig { height: 1.0, ..CharacterConfig::default() },
        CharacterConfig { max_slope_deg: 90.0, ..CharacterConfig::default() },
        CharacterConfig { gravity: f32::NAN, ..CharacterConfig::default() },
        CharacterConfig { air_control: -1.0, ..CharacterConfig::default() },
    ];
    for cfg in bad {
        let err = cfg.validate().expect_err("bad config accepted");
        assert!(!err.to_string().is_empty());
    }
}
