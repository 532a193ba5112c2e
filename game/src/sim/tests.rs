//! Gameplay rules on small made-up levels: pickups, the gun, the crawler's senses and moves,
//! the lamp's battery, throw and pick-up, winning and losing.

use std::sync::Arc;

use glam::Vec3;
use physics::LevelCollision;

use super::command::{angle_units, buttons, TickCommand};
use super::enemy::Mind;
use super::level_entities::{EnemySpawn, Exit, LevelEntities, PickupKind, PickupSpawn, Rules};
use super::*;

/// A 60 m square floor at y = 0, plus a 4 m high wall across x (at z = `wall_z`) if given.
fn world(
    enemies: Vec<EnemySpawn>,
    pickups: Vec<PickupSpawn>,
    exit: Option<Exit>,
    wall_z: Option<f32>,
) -> Arc<LevelWorld> {
    let mut positions = vec![
        Vec3::new(-30.0, 0.0, -30.0),
        Vec3::new(30.0, 0.0, -30.0),
        Vec3::new(30.0, 0.0, 30.0),
        Vec3::new(-30.0, 0.0, 30.0),
    ];
    let mut triangles = vec![[0, 2, 1], [0, 3, 2]];
    if let Some(z) = wall_z {
        positions.extend([
            Vec3::new(-30.0, 0.0, z),
            Vec3::new(30.0, 0.0, z),
            Vec3::new(30.0, 4.0, z),
            Vec3::new(-30.0, 4.0, z),
        ]);
        triangles.extend([[4, 5, 6], [4, 6, 7]]);
    }
    let collision = LevelCollision::from_triangles(&positions, &triangles).unwrap();
    let rules = Rules { battery_seconds: 150.0, objective: String::new() };
    Arc::new(LevelWorld::new(collision, LevelEntities { pickups, enemies, exit, rules }))
}

fn crawler(x: f32, z: f32, yaw_deg: f32, route: Vec<Vec3>) -> EnemySpawn {
    EnemySpawn { name: "c".into(), position: Vec3::new(x, 0.0, z), yaw: yaw_deg.to_radians(), route }
}

/// The player at the origin facing −Z.
fn sim(world: Arc<LevelWorld>) -> Simulation {
    Simulation::at(Vec3::ZERO, 0, 0, world, 60, 7)
}

fn run(sim: &mut Simulation, ticks: u32, cmd: TickCommand) {
    for _ in 0..ticks {
        sim.step(&cmd);
    }
}

fn press(b: u8) -> TickCommand {
    TickCommand { buttons: b, ..Default::default() }
}

fn idle() -> TickCommand {
    TickCommand::default()
}

#[test]
fn pickups_are_taken_when_of_use() {
    let pick = |kind, x| PickupSpawn { name: "p".into(), kind, position: Vec3::new(x, 0.0, -2.0), amount: 0.5 };
    let w = world(vec![], vec![pick(PickupKind::Battery, 0.0), pick(PickupKind::Health, 0.3)], None, None);
    let mut s = sim(w.clone());
    run(&mut s, 40, TickCommand { forward: 127, ..Default::default() });
    assert!(s.state.pickups.iter().all(|p| !p.taken), "a full battery and full health leave both lying");

    let mut s = sim(w);
    s.state.lamp.battery = 0.0;
    s.state.lamp.on = false;
    s.state.player.health = 50.0;
    s.state.pickups[1].amount = 30.0;
    run(&mut s, 40, TickCommand { forward: 127, ..Default::default() });
    assert!(s.state.pickups.iter().all(|p| p.taken));
    assert!(s.state.lamp.battery > 0.49 && s.state.lamp.on, "refilled and back on: {:?}", s.state.lamp);
    assert_eq!(s.state.player.health, 80.0);

    let ammo =
        PickupSpawn { name: "a".into(), kind: PickupKind::Ammo, position: Vec3::new(0.0, 0.0, -2.0), amount: 24.0 };
    let mut s = sim(world(vec![], vec![ammo], None, None));
    let before = s.state.weapon.reserve;
    run(&mut s, 40, TickCommand { forward: 127, ..Default::default() });
    assert_eq!(s.state.weapon.reserve, before + 24);
}

#[test]
fn shots_hit_the_nearest_thing_and_three_put_a_crawler_down() {
    // A crawler 8 m ahead, facing away so it does not come at us first.
    let mut s = sim(world(vec![crawler(0.0, -8.0, 0.0, vec![])], vec![], None, None));
    s.state.player.pitch = angle_units((-2.0f32).to_radians()).round() as i16;
    s.step(&press(buttons::FIRE));
    assert!(s.events.iter().any(|e| matches!(e, Event::Hit { enemy: Some(0), .. })), "{:?}", s.events);
    assert_eq!(s.state.enemies[0].health, enemy::MAX_HEALTH - weapon::DAMAGE);
    let impact = s.state.impacts[0];
    assert!(impact.on_enemy && (impact.position.z - (-8.0 + 0.35)).abs() < 0.1, "{impact:?}");
    assert_eq!(s.state.weapon.flash, weapon::FLASH_TICKS, "the shot lights the muzzle flash");
    // Hold the trigger: two more hits drop it, and with no enemy left the level is won.
    run(&mut s, 2 * weapon::FIRE_INTERVAL as u32, press(buttons::FIRE));
    assert_eq!(s.state.enemies[0].mind, Mind::Dead);
    assert_eq!(s.state.outcome, Outcome::Won);
    assert_eq!(s.state.weapon.magazine, weapon::MAGAZINE - 3);

    // A wall between: the shot marks the wall, the crawler is untouched.
    let mut s = sim(world(vec![crawler(0.0, -8.0, 180.0, vec![])], vec![], None, Some(-4.0)));
    s.step(&press(buttons::FIRE));
    assert_eq!(s.state.enemies[0].health, enemy::MAX_HEALTH);
    let impact = s.state.impacts[0];
    assert!(!impact.on_enemy && (impact.position.z + 4.0).abs() < 1e-3 && impact.normal.z > 0.99, "{impact:?}");
}

#[test]
fn a_crawler_notices_a_lit_player_far_off_but_a_dark_one_only_close() {
    // A crawler 12 m or 4 m down −Z; yaw 180° faces +Z (towards the player at the origin).
    let notices = |lamp_on: bool, z: f32, enemy_yaw: f32, player_yaw: f32| {
        let mut s = sim(world(vec![crawler(0.0, z, enemy_yaw, vec![])], vec![], None, None));
        s.state.lamp.on = lamp_on;
        s.state.player.yaw = angle_units(player_yaw.to_radians()).round().rem_euclid(65536.0) as u16;
        run(&mut s, 3, idle());
        s.state.enemies[0].mind != Mind::Patrol
    };
    assert!(notices(true, -12.0, 180.0, 180.0), "the headlamp gives the player away at 12 m");
    assert!(!notices(false, -12.0, 180.0, 180.0), "in the dark at 12 m it sees nothing");
    assert!(notices(false, -4.0, 180.0, 180.0), "in the dark at 4 m it does");
    assert!(!notices(true, -12.0, 0.0, 180.0), "looking the other way, out of our beam, it does not");
    assert!(notices(true, -12.0, 0.0, 0.0), "but it feels our beam on its back");
}

#[test]
fn noticing_the_player_is_an_event_once_saying_whether_it_is_in_sight() {
    // Lit from behind at 12 m (our beam on its back); then 8 m away behind a wall, close
    // enough to hear a shot through it.
    for (z, wall, in_sight) in [(-12.0, None, true), (-8.0, Some(-6.0), false)] {
        let mut s = sim(world(vec![crawler(0.0, z, 0.0, vec![])], vec![], None, wall));
        s.state.lamp.on = true;
        let mut noticed = Vec::new();
        for _ in 0..60 {
            s.step(&idle());
            noticed.extend(s.events.iter().filter(|e| matches!(e, Event::Noticed { .. })).copied());
        }
        if wall.is_none() {
            assert_eq!(noticed, vec![Event::Noticed { enemy: 0, in_sight }], "once, when it turns alert");
        } else {
            // Behind a wall it neither sees us nor feels the beam: a gunshot it hears does it.
            assert!(noticed.is_empty(), "{noticed:?}");
            run(&mut s, 1, press(buttons::FIRE));
            let events: Vec<Event> = s.events.clone();
            assert!(events.contains(&Event::Noticed { enemy: 0, in_sight }), "{events:?}");
        }
    }
}

#[test]
fn a_crawler_turns_approaches_strikes_and_can_kill() {
    let mut s = sim(world(vec![crawler(0.0, -10.0, 90.0, vec![])], vec![], None, None));
    let start = s.state.enemies[0].body.position.distance(Vec3::ZERO);
    run(&mut s, 5, idle());
    assert_eq!(s.state.enemies[0].mind, Mind::Alert, "our beam falls on it");
    run(&mut s, 120, idle());
    let d = s.state.enemies[0].body.position.distance(s.state.player.body.position);
    assert!(d < start - 3.0, "it comes for us: {start} → {d}");
    let mut hurt_at = None;
    for _ in 0..1200 {
        s.step(&idle());
        if hurt_at.is_none() && s.events.contains(&Event::PlayerHurt) {
            hurt_at = Some(s.state.tick);
        }
    }
    assert!(hurt_at.is_some(), "it strikes");
    assert_eq!(s.state.player.health, 0.0);
    assert_eq!(s.state.outcome, Outcome::Lost);
    let frozen = s.state.clone();
    run(&mut s, 10, TickCommand { forward: 127, ..Default::default() });
    assert_eq!(s.state.player, frozen.player, "nothing moves once the level is lost");
}

#[test]
fn a_crawler_walks_its_route_and_a_gunshot_turns_it() {
    let route = vec![Vec3::new(10.0, 0.0, -10.0), Vec3::new(14.0, 0.0, -10.0)];
    let mut s = sim(world(vec![crawler(10.0, -10.0, -90.0, route)], vec![], None, None));
    s.state.lamp.on = false;
    let mut xs = Vec::new();
    for _ in 0..600 {
        s.step(&idle());
        xs.push(s.state.enemies[0].body.position.x);
    }
    let (lo, hi) = xs.iter().fold((f32::MAX, f32::MIN), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    assert!(lo < 10.6 && hi > 13.4, "walks between its waypoints: x in {lo}..{hi}");
    assert_eq!(s.state.enemies[0].mind, Mind::Patrol, "it never saw us in the dark");
    s.step(&press(buttons::FIRE));
    run(&mut s, 2, idle());
    assert_ne!(s.state.enemies[0].mind, Mind::Patrol, "it heard the shot");
}

#[test]
fn a_lamp_lying_in_the_dark_draws_a_crawler_to_it() {
    // Throw the lamp ahead, towards a crawler that faces away from us.
    let mut s = sim(world(vec![crawler(6.0, -12.0, 0.0, vec![])], vec![], None, None));
    s.state.player.yaw = angle_units((-20.0f32).to_radians()).round().rem_euclid(65536.0) as u16;
    s.step(&press(buttons::LAMP_THROW));
    assert!(!s.state.lamp.attached);
    run(&mut s, 120, idle());
    assert!(s.state.lamp.resting && s.state.lamp.position.y < 0.2, "the lamp lands on the floor: {:?}", s.state.lamp);
    // Point the lying lamp at the crawler: it goes to look.
    let to = s.state.enemies[0].body.position - s.state.lamp.position;
    s.state.lamp.yaw = angle_units(libm::atan2f(-to.x, -to.z)).round().rem_euclid(65536.0) as u16;
    s.state.lamp.pitch = 0;
    let before = s.state.enemies[0].body.position.distance(s.state.lamp.position);
    run(&mut s, 240, idle());
    let e = &s.state.enemies[0];
    assert!(e.body.position.distance(s.state.lamp.position) < before - 2.0, "{:?}", e);
}

#[test]
fn the_lamp_drains_flickers_when_low_and_dies() {
    let mut s = sim(world(vec![], vec![], None, None));
    s.state.lamp.battery = lamp::LOW_BATTERY;
    let mut flickered = false;
    let mut ticks = 0;
    while s.state.lamp.on {
        s.step(&idle());
        flickered |= s.state.lamp.flicker < 1.0;
        ticks += 1;
        assert!(ticks < 100_000);
    }
    let expected = lamp::LOW_BATTERY * 150.0 * 60.0;
    assert!((ticks as f32 - expected).abs() < 3.0, "{ticks} ticks of light, expected {expected}");
    assert!(flickered, "a low lamp flickers");
    s.step(&press(buttons::LAMP_TOGGLE));
    assert!(!s.state.lamp.on, "an empty lamp will not switch on");
    let off = s.state.lamp.battery;
    run(&mut s, 60, idle());
    assert_eq!(s.state.lamp.battery, off, "an off lamp does not drain");
}

#[test]
fn the_lamp_is_set_down_or_thrown_and_picked_up_only_within_reach() {
    let mut s = sim(world(vec![], vec![], None, None));
    s.step(&press(buttons::LAMP_DETACH));
    run(&mut s, 60, idle());
    let l = s.state.lamp;
    assert!(!l.attached && l.resting && l.position.y < 0.2, "set down, it falls to the floor: {l:?}");
    assert!(l.position.z < 0.0 && l.position.z > -1.0, "just ahead: {l:?}");
    s.step(&press(buttons::LAMP_DETACH));
    assert!(s.state.lamp.attached, "within reach it is picked up");

    s.step(&press(buttons::LAMP_THROW));
    run(&mut s, 120, idle());
    let l = s.state.lamp;
    assert!(l.resting && l.position.z < -5.0, "thrown, it flies metres: {l:?}");
    s.step(&press(buttons::LAMP_DETACH));
    assert!(!s.state.lamp.attached, "out of reach it stays where it lies");
    assert!(!s.events.contains(&Event::LampPickedUp));
}

#[test]
fn the_lamp_leaving_the_head_or_coming_back_cuts_the_light_and_nothing_else_does() {
    let mut s = sim(world(vec![], vec![], None, None));
    let cut = |s: &Simulation| s.events.iter().any(Event::cuts_the_light);
    run(&mut s, 10, TickCommand { forward: 127, ..Default::default() });
    assert!(!cut(&s), "walking keeps the renderer's history: {:?}", s.events);
    s.step(&press(buttons::LAMP_TOGGLE));
    assert!(!cut(&s), "the lamp switched off is light the history can follow");
    s.step(&press(buttons::LAMP_TOGGLE));
    s.step(&press(buttons::LAMP_DETACH));
    assert!(cut(&s), "set down: {:?}", s.events);
    run(&mut s, 60, idle());
    s.step(&press(buttons::LAMP_DETACH));
    assert!(cut(&s), "picked up: {:?}", s.events);
    s.step(&press(buttons::LAMP_THROW));
    assert!(cut(&s), "thrown: {:?}", s.events);
}

#[test]
fn a_thrown_lamp_bounces_off_walls() {
    let mut s = sim(world(vec![], vec![], None, Some(-3.0)));
    s.step(&press(buttons::LAMP_THROW));
    run(&mut s, 180, idle());
    let l = s.state.lamp;
    assert!(l.resting && l.position.z > -3.0 && l.position.y < 0.2, "it stays on our side of the wall: {l:?}");
}

#[test]
fn reaching_the_exit_wins() {
    let exit = Exit { position: Vec3::new(0.0, 0.0, -5.0), radius: 1.0, yaw: 0.0 };
    let mut s = sim(world(vec![crawler(20.0, 20.0, 0.0, vec![])], vec![], Some(exit), None));
    s.state.lamp.on = false;
    run(&mut s, 40, TickCommand { forward: 127, ..Default::default() });
    assert_eq!(s.state.outcome, Outcome::Playing, "not yet");
    run(&mut s, 40, TickCommand { forward: 127, ..Default::default() });
    assert_eq!(s.state.outcome, Outcome::Won);
}

#[test]
fn crawlers_do_not_melt_into_one() {
    // Two crawlers on the same spot, nothing to chase (lamp off, player far away): they part.
    let mut s = Simulation::at(
        Vec3::new(25.0, 0.0, 25.0),
        0,
        0,
        world(vec![crawler(0.0, 0.0, 0.0, vec![]), crawler(0.1, 0.0, 0.0, vec![])], vec![], None, None),
        60,
        7,
    );
    s.state.lamp.on = false;
    run(&mut s, 120, idle());
    let (a, b) = (s.state.enemies[0].body.position, s.state.enemies[1].body.position);
    assert!(a.distance(b) >= enemy::CROWD_RADIUS - 0.05, "{a} {b}");
    assert_eq!(enemy::crowd_push(Vec3::ZERO, [Vec3::new(1.0, 0.0, 0.0)].into_iter()), Vec3::ZERO, "far enough apart");
}

#[test]
fn footsteps_come_with_the_ground_walked_at_each_gaits_pace() {
    let w = world(vec![], vec![], None, None);
    // Two seconds of holding forward with these buttons: the footsteps' gaits.
    let steps = |buttons: u8| {
        let mut s = sim(w.clone());
        run(&mut s, 10, idle());
        let mut gaits = Vec::new();
        for _ in 0..120 {
            s.step(&TickCommand { forward: 127, buttons, ..Default::default() });
            gaits.extend(s.events.iter().filter_map(|e| match e {
                Event::Footstep(g) => Some(*g),
                _ => None,
            }));
        }
        gaits
    };
    // 8 m walked: the first step after 0.5 m, then one every 1.8 m.
    assert_eq!(steps(0), vec![player::Gait::Walk; 5]);
    // 13 m sprinted, a step every 2.3 m; 4 m crouched, every 1.1 m.
    assert_eq!(steps(buttons::SPRINT), vec![player::Gait::Sprint; 6]);
    assert_eq!(steps(buttons::CROUCH), vec![player::Gait::Crouch; 4]);
    let mut still = sim(w.clone());
    run(&mut still, 120, idle());
    assert!(still.events.is_empty());

    // A jump: off the ground, then the landing; no footstep in the air.
    let mut s = sim(w);
    run(&mut s, 10, idle());
    let mut heard = Vec::new();
    s.step(&press(buttons::JUMP));
    heard.extend(s.events.iter().copied());
    for _ in 0..90 {
        s.step(&idle());
        heard.extend(s.events.iter().copied());
    }
    assert_eq!(heard.len(), 2, "{heard:?}");
    assert_eq!(heard[0], Event::Jumped);
    assert!(matches!(heard[1], Event::Landed { speed } if speed > 3.0), "{heard:?}");
}

#[test]
fn a_low_battery_ticks_once_a_second_and_the_lamp_switch_is_heard() {
    let mut s = sim(world(vec![], vec![], None, None));
    s.state.lamp.battery = lamp::LOW_BATTERY * 0.5;
    let mut ticks = 0;
    for _ in 0..180 {
        s.step(&idle());
        ticks += s.events.iter().filter(|e| **e == Event::LowBattery).count();
    }
    assert_eq!(ticks, 3);
    s.step(&press(buttons::LAMP_TOGGLE));
    assert!(s.events.contains(&Event::LampSwitched { on: false }), "{:?}", s.events);
    run(&mut s, 120, idle());
    assert!(s.events.is_empty(), "an unlit lamp does not tick");
    s.step(&press(buttons::LAMP_TOGGLE));
    assert!(s.events.contains(&Event::LampSwitched { on: true }), "{:?}", s.events);
}
