//! The simulation is deterministic: the same commands give the same state hash on every tick,
//! run after run, whether they come from a script, a replay file or live input.

use std::path::Path;

use engine::input::{Input, KeyCode};
use engine::window::WindowApp;
use game::play::{GameWindow, TickSource};
use game::recording::{self, LoadedReplay, Recorder};
use game::sim::{Rng, Simulation, TickCommand};
use headlamp_tests::{cellar, cellar_path, engine, replay_files};

/// Per-tick state hashes of `commands` from a fresh start (fresh collision geometry too).
fn hashes(level: &engine::scene::Level, commands: &[TickCommand], seed: u64) -> Vec<u64> {
    let mut sim = Simulation::new(level, game::sim::level_world(level).unwrap(), 60, seed);
    commands
        .iter()
        .map(|c| {
            sim.step(c);
            sim.state.hash()
        })
        .collect()
}

/// A long random walk through the level as a script: every action, turning, jumping,
/// crouching, sprinting and the lamp, in steps of 1–90 ticks.
fn random_script(ticks: u32, seed: u64) -> String {
    let mut rng = Rng::new(seed);
    let mut text = String::new();
    let mut total = 0;
    let actions = ["forward", "back", "left", "right", "forward sprint", "forward jump", "crouch forward", "wait"];
    while total < ticks {
        let n = 1 + (rng.next_u64() % 90) as u32;
        let action = actions[(rng.next_u64() % actions.len() as u64) as usize];
        let turn = rng.next_f32() * 240.0 - 120.0;
        let look = rng.next_f32() * 40.0 - 20.0;
        let lamp = match rng.next_u64() % 12 {
            0 => " lamp toggle",
            1 => " lamp detach",
            _ => "",
        };
        text.push_str(&format!("{n} {action} turn {turn:.2} look {look:.2}{lamp}\n"));
        total += n;
    }
    text
}

#[test]
fn ten_thousand_scripted_ticks_hash_identically_in_three_runs() {
    let level = cellar();
    let commands = game::script::parse(&random_script(10_000, 7), Path::new("random.txt")).unwrap();
    assert!(commands.len() >= 10_000);
    let runs: Vec<Vec<u64>> = (0..3).map(|_| hashes(&level, &commands, 99)).collect();
    for (tick, ((a, b), c)) in runs[0].iter().zip(&runs[1]).zip(&runs[2]).enumerate() {
        assert!(a == b && a == c, "runs differ at tick {}: {a:016x} {b:016x} {c:016x}", tick + 1);
    }
    // The walk really went places: hashes are not stuck on a standing player.
    let distinct: std::collections::BTreeSet<u64> = runs[0].iter().copied().collect();
    assert!(distinct.len() > commands.len() / 2, "only {} distinct states", distinct.len());
    // And a different seed is a different world (the RNG is part of the state).
    assert_ne!(hashes(&level, &commands[..10], 100), runs[0][..10]);
}

#[test]
fn the_same_replay_twice_gives_identical_hashes_on_every_tick() {
    for name in replay_files::script_names() {
        let replay = replay_files::open(&name);
        let runs: Vec<Vec<u64>> =
            (0..2).map(|_| hashes(&replay.level, &replay.commands, replay.replay.header.seed)).collect();
        for (i, (a, b)) in runs[0].iter().zip(&runs[1]).enumerate() {
            assert_eq!(a, b, "{name}: tick {} differs between two runs", i + 1);
            assert_eq!(*a, replay.replay.state_hash(i), "{name}: tick {} differs from the recording", i + 1);
        }
    }
}

#[test]
fn shipped_replays_are_their_scripts() {
    for name in replay_files::script_names() {
        let stored = std::fs::read(replay_files::path(&name)).unwrap();
        assert!(
            stored == replay_files::record_script(&name),
            "tests/replays/{name}.replay is not what its script records now (the simulation or the level \
             changed): re-make it with {}",
            headlamp_tests::UPDATE_COMMAND
        );
    }
}

/// Plays the level "live" through the game window's own loop — frames of uneven length, mouse
/// motion, held and pressed keys — records it, then verifies the file: what was recorded is
/// what was simulated.
#[test]
fn recording_live_then_verifying_agrees() {
    let level = cellar();
    let level_path = cellar_path();
    let gi = plugin_gi::GiSettings::default();
    let out = std::env::temp_dir().join(format!("headlamp-live-{}.replay", std::process::id()));
    let header = recording::header(&level, &level_path, 60, 5, &gi);
    let sim = Simulation::new(&level, game::sim::level_world(&level).unwrap(), 60, 5);
    let config = game_ui::Config { gi, ..Default::default() };
    let source = TickSource::live(&config, Some(Recorder::new(header, out.clone())));
    let mut app = GameWindow::new(level, sim, source, config);
    let mut input = Input::default();
    input.captured = true;
    let mut rng = Rng::new(3);
    let script: [(u32, KeyCode); 6] = [
        (30, KeyCode::KeyW),
        (50, KeyCode::KeyG),
        (80, KeyCode::Space),
        (120, KeyCode::KeyD),
        (200, KeyCode::KeyF),
        (260, KeyCode::ShiftLeft),
    ];
    for frame in 0..400u32 {
        for (at, key) in script {
            if frame == at {
                input.key_event(key, true, false);
            }
            if frame == at + 40 && key != KeyCode::KeyW {
                input.key_event(key, false, false);
            }
        }
        input.mouse_delta = engine::glam::Vec2::new(rng.next_f32() * 30.0 - 10.0, rng.next_f32() * 6.0 - 3.0);
        let dt = 0.004 + rng.next_f32() * 0.03;
        app.update(&input, dt);
        input.end_frame();
    }
    let TickSource::Live { recorder: Some(recorder), .. } = &app.source else { unreachable!() };
    recorder.save().unwrap();
    let replay = LoadedReplay::open(&out, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(replay.commands.len() as u32, app.sim.state.tick);
    assert!(replay.commands.iter().any(|c| c.turn != 0) && replay.commands.iter().any(|c| c.forward != 0));
    assert!(!app.sim.state.lamp.attached && !app.sim.state.lamp.on, "G and F reached the simulation");
    let end = replay.verify().unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(end.hash(), app.sim.state.hash(), "the replay ends where the live game did");
    let _ = std::fs::remove_file(&out);
}

/// The states of a replay after each tick (index 0 = the start).
fn states(replay: &LoadedReplay) -> Vec<game::sim::WorldState> {
    let mut sim = replay.simulation().unwrap();
    let mut out = vec![sim.state.clone()];
    for c in &replay.commands {
        sim.step(c);
        out.push(sim.state.clone());
    }
    out
}

/// The test replays do what their scripts say, so their frames show what their names promise.
#[test]
fn replays_do_what_their_scripts_say() {
    // Walls: backing into the start room's south wall (z = 5) and sideways into its east
    // wall (x = 3) stops the 0.3 m capsule at the wall.
    let s = states(&replay_files::open("walls"));
    let p = s[60].player.body.position;
    assert!((4.6..=4.71).contains(&p.z), "south wall: {p}");
    let p = s[120].player.body.position;
    assert!((2.6..=2.71).contains(&p.x) && (4.6..=4.71).contains(&p.z), "east wall: {p}");
    assert!(s[165].player.body.position.distance(p) < 1e-3, "turning on the spot does not move");
    let back = s[190].player.body.position;
    assert!(back.x < p.x - 0.5 && back.z < p.z - 0.5, "backing away from the corner: {back}");

    // Jumping: the eye rises well above standing height, lands, and crouching lowers it.
    let s = states(&replay_files::open("jumping"));
    let standing = s[60].player.eye().y;
    let top = s[61..122].iter().map(|s| s.player.eye().y).fold(f32::MIN, f32::max);
    assert!(top > standing + 0.8, "jump apex {top} from {standing}");
    assert!(s[121].player.body.grounded && s[121].player.body.position.y.abs() < 0.02, "landed");
    assert!(s[161].player.body.crouching && s[161].player.eye().y < standing - 0.4);
    assert!(!s[201].player.body.crouching && (s[201].player.eye().y - standing).abs() < 1e-3, "{:?}", s[201].player);

    // Turning: two quarter turns left, then up 45° and down 90°.
    let s = states(&replay_files::open("turning"));
    assert_eq!((s[30].player.yaw, s[60].player.yaw), (16384, 32768));
    assert_eq!((s[90].player.pitch, s[120].player.pitch), (8192, -8192));

    // The lamp: off on tick 31, on again on tick 61.
    let s = states(&replay_files::open("lamp_toggle"));
    assert!(s[30].lamp.on && !s[31].lamp.on && !s[60].lamp.on && s[61].lamp.on);

    // Detached: set down on the floor inside the red/green room (x < -1.4) looking west, while
    // the player walks back out to the corridor.
    let s = states(&replay_files::open("lamp_detach"));
    let lamp = s[285].lamp;
    assert!(!lamp.attached && lamp.position.x < -1.8 && (lamp.position.z + 7.0).abs() < 0.1, "{lamp:?}");
    assert!(lamp.resting && lamp.position.y < 0.1, "it lies on the floor: {lamp:?}");
    assert_eq!(lamp.yaw, 16384, "the lamp looks west, where the view did");
    assert!(s[285].player.body.position.x > -1.0, "the player is back in the corridor");

    // The win: every crawler put down by the gun, the player unhurt enough to live, the lamp
    // still on.
    let s = states(&replay_files::open("win"));
    let end = s.last().unwrap();
    assert_eq!(end.outcome, game::sim::Outcome::Won);
    assert_eq!(end.enemies_left(), 0);
    assert!(end.player.alive() && end.lamp.on && end.lamp.attached);
    let shots = s.windows(2).filter(|w| w[1].weapon.flash == game::sim::weapon::FLASH_TICKS).count();
    assert!(shots >= 12, "the crawlers went down to gunfire: {shots} shots");
    // The last one down ended the game; its body still finished falling.
    assert!(end.enemies.iter().all(|e| e.timer >= 20), "{:?}", end.enemies);

    // The Gallery: won at the way out at the back of the vault, two of its four crawlers shot
    // on the way there, the player unhurt.
    let s = states(&replay_files::open("gallery_win"));
    let end = s.last().unwrap();
    assert_eq!(end.outcome, game::sim::Outcome::Won);
    assert_eq!(end.enemies_left(), 2, "won by the exit, not by putting every crawler down");
    let p = end.player.body.position;
    assert!(p.x > 5.4 && p.z < -10.8, "in the vault: {p}");
    assert_eq!(end.player.health, game::sim::player::MAX_HEALTH);

    // The Hall: up the stairs onto a balcony (the storey above the crawlers' walk grid) and
    // back down, every crawler put down, all of them still on the ground floor.
    let s = states(&replay_files::open("hall_win"));
    assert!(s.iter().any(|s| s.player.body.position.y > 3.7), "the player went up to a balcony");
    let end = s.last().unwrap();
    assert_eq!(end.outcome, game::sim::Outcome::Won);
    assert_eq!(end.enemies_left(), 0);
    assert!(end.player.body.position.y < 0.1, "back on the floor");
    assert!(end.enemies.iter().all(|e| e.body.position.y.abs() < 0.1), "the crawlers kept to the ground floor");

    // The strike: the guard walks up (its walk cycle advancing), its attack starts on tick 256 and
    // its blow comes at the end of the windup on tick 280, its frame.
    let s = states(&replay_files::open("crawler_strike"));
    let guard = |tick: usize| s[tick].enemies[0];
    assert_ne!(guard(230).walked, guard(220).walked, "walking up");
    assert_eq!((guard(256).mind, guard(256).timer), (game::sim::enemy::Mind::Attack, 0));
    assert_eq!((guard(280).mind, guard(280).timer), (game::sim::enemy::Mind::Attack, game::sim::enemy::WINDUP));
    assert_eq!(guard(280).walked, guard(256).walked, "it stands to strike");
}
