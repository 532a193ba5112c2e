//! The sound of a replay is decided inside the deterministic tick: the simulation emits sound
//! events, the audio output only listens. So a replay yields the same event list every time,
//! and plays to its end without any audio device.

use engine::input::Input;
use engine::window::WindowApp;
use game::play::{GameWindow, TickSource};
use game::sim::player::Gait;
use game::sim::{Event, Outcome, PickupKind};
use headlamp_tests::{engine, replay_files};

/// Every event of the replay, with the tick it happened on.
fn events(name: &str) -> Vec<(u32, Event)> {
    let replay = replay_files::open(name);
    let mut sim = replay.simulation().unwrap();
    let mut all = Vec::new();
    for i in 0..replay.commands.len() {
        replay.step_checked(&mut sim, i).unwrap_or_else(|e| panic!("{name}: {e}"));
        all.extend(sim.events.iter().map(|e| (sim.state.tick, *e)));
    }
    all
}

fn has(events: &[(u32, Event)], what: &str, f: fn(&Event) -> bool) {
    assert!(events.iter().any(|(_, e)| f(e)), "no {what} among {events:?}");
}

#[test]
fn a_replays_sound_events_are_the_same_every_time_and_the_expected_ones_occur() {
    // The Hall played to a win: shots, a battery picked up on the stairs, four crawlers down.
    let hall = events("hall_win");
    assert_eq!(hall, events("hall_win"), "the same replay, the same events on the same ticks");
    has(&hall, "shot", |e| *e == Event::Fired);
    has(&hall, "pickup", |e| *e == Event::Picked(PickupKind::Battery));
    has(&hall, "crawler's death", |e| matches!(e, Event::EnemyDown { .. }));
    has(&hall, "win", |e| matches!(e, Event::Won { exit: false }));

    // The Cellar's win: the same again, and every crawler sound and the gun's reload.
    let win = events("win");
    assert_eq!(win, events("win"));
    for (what, f) in [
        ("shot", (|e| *e == Event::Fired) as fn(&Event) -> bool),
        ("shot striking a crawler", |e| matches!(e, Event::Hit { enemy: Some(_), .. })),
        ("footstep", |e| matches!(e, Event::Footstep(Gait::Walk))),
        ("crawler breathing", |e| matches!(e, Event::Breath { .. })),
        ("crawler noticing", |e| matches!(e, Event::Noticed { .. })),
        ("reload", |e| *e == Event::ReloadStarted),
        ("reload's end", |e| *e == Event::Reloaded),
        ("win", |e| matches!(e, Event::Won { exit: false })),
    ] {
        has(&win, what, f);
    }
    let deaths: Vec<Event> =
        win.iter().filter(|(_, e)| matches!(e, Event::EnemyDown { .. })).map(|(_, e)| *e).collect();
    let each = (0..4).map(|enemy| Event::EnemyDown { enemy }).collect::<Vec<_>>();
    assert_eq!(deaths, each, "the Cellar's four crawlers, in the order they were shot");
    let (won_at, _) = win.iter().find(|(_, e)| matches!(e, Event::Won { .. })).unwrap();
    assert!(win.iter().all(|(t, _)| t <= won_at), "nothing is heard after the win");

    // The lamp's and the feet's sounds, in the replays that do those things.
    let lamp = events("lamp_detach");
    assert_eq!(lamp, events("lamp_detach"));
    has(&lamp, "lamp set down", |e| *e == Event::LampLetGo { thrown: false });
    has(&lamp, "lamp landing", |e| matches!(e, Event::LampLanded { .. }));
    let toggled = events("lamp_toggle");
    has(&toggled, "lamp off", |e| *e == Event::LampSwitched { on: false });
    has(&toggled, "lamp on", |e| *e == Event::LampSwitched { on: true });
    let jumping = events("jumping");
    has(&jumping, "jump", |e| *e == Event::Jumped);
    has(&jumping, "landing", |e| matches!(e, Event::Landed { .. }));
}

/// The game as the window runs it, but with no window and no audio device: a replay driven
/// frame by frame plays to its end and wins.
#[test]
fn the_game_plays_a_replay_with_no_audio_device() {
    let replay = replay_files::open("win");
    let ticks = replay.commands.len() as u32;
    let sim = replay.simulation().unwrap();
    let level = replay.level.clone();
    let source = TickSource::Replay { replay: Box::new(replay), next: 0, diverged: None };
    let mut app = GameWindow::new(level, sim, source, game_ui::Config::default());
    let input = Input::default();
    for _ in 0..ticks + 10 {
        app.update(&input, 1.0 / 60.0);
    }
    let TickSource::Replay { next, diverged, .. } = &app.source else { unreachable!() };
    assert_eq!((*next as u32, *diverged), (ticks, None));
    assert_eq!(app.sim.state.outcome, Outcome::Won);
}
