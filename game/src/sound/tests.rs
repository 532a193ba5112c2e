//! What the game plays, checked without a device: which cues events make and where, muffling
//! behind walls, and a whole replay heard through a silent output and through an offline mix.

use std::sync::Arc;

use glam::Vec3;
use physics::LevelCollision;

use super::bank::SoundId;
use super::cues::{cues, muffle};
use super::*;
use crate::sim::level_entities::{EnemySpawn, LevelEntities, Rules};
use crate::sim::{Event, PickupKind, Simulation};

/// A 60 m floor with a 4 m wall across x at z = −6, and one crawler at `crawler_z` on −Z.
fn walled(crawler_z: f32) -> (Simulation, Arc<LevelWorld>) {
    let positions = [
        Vec3::new(-30.0, 0.0, -30.0),
        Vec3::new(30.0, 0.0, -30.0),
        Vec3::new(30.0, 0.0, 30.0),
        Vec3::new(-30.0, 0.0, 30.0),
        Vec3::new(-30.0, 0.0, -6.0),
        Vec3::new(30.0, 0.0, -6.0),
        Vec3::new(30.0, 4.0, -6.0),
        Vec3::new(-30.0, 4.0, -6.0),
    ];
    let collision = LevelCollision::from_triangles(&positions, &[[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7]]).unwrap();
    let enemy = EnemySpawn { name: "c".into(), position: Vec3::new(0.0, 0.0, crawler_z), yaw: 0.0, route: vec![] };
    let rules = Rules { battery_seconds: 150.0, objective: String::new() };
    let entities = LevelEntities { pickups: vec![], enemies: vec![enemy], exit: None, rules };
    let world = Arc::new(LevelWorld::new(collision, entities));
    (Simulation::at(Vec3::ZERO, 0, 0, world.clone(), 60, 1), world)
}

#[test]
fn the_players_own_sounds_are_at_the_head_and_a_crawlers_at_the_crawler() {
    let (sim, world) = walled(-4.0);
    let ear = sim.state.player.eye();
    let events = [
        Event::Fired,
        Event::Footstep(crate::sim::player::Gait::Sprint),
        Event::Picked(PickupKind::Ammo),
        Event::Noticed { enemy: 0, in_sight: true },
    ];
    let heard = cues(&events, &sim.state, &world.collision, ear);
    let sounds: Vec<SoundId> = heard.iter().map(|c| c.sound).collect();
    assert_eq!(sounds[0], SoundId::Gunshot);
    assert!(matches!(sounds[1], SoundId::Step(_)));
    assert_eq!(sounds[2..], [SoundId::PickAmmo, SoundId::Notice]);
    assert!(heard[..3].iter().all(|c| c.at.is_none()), "the player's own sounds are at the head");
    let at = heard[3].at.expect("a crawler's cry is placed");
    assert!((at.position - Vec3::new(0.0, 0.8, -4.0)).length() < 1e-5, "{at:?}");
    assert_eq!((at.muffle, at.source), (0.0, Some(0)), "in the open, unmuffled, following crawler 0");
}

#[test]
fn a_crawler_behind_a_wall_is_muffled_and_one_round_its_end_partly() {
    let (sim, world) = walled(-9.0);
    let ear = sim.state.player.eye();
    let heard = cues(&[Event::Breath { enemy: 0 }], &sim.state, &world.collision, ear);
    assert_eq!(heard[0].at.unwrap().muffle, 1.0, "the wall stands between");
    assert!(matches!(heard[0].sound, SoundId::Breath(_)));
    // Seen from past the wall's end (x = 30): some of the lines pass it.
    let corner = muffle(&world.collision, Vec3::new(30.2, 1.6, 0.0), Vec3::new(29.5, 0.8, -9.0));
    assert!(corner > 0.0 && corner < 1.0, "{corner}");
    assert_eq!(muffle(&world.collision, ear, Vec3::new(0.0, 1.0, -3.0)), 0.0);
}

#[test]
fn a_killing_shot_is_heard_as_a_death_not_a_cry_and_stings_end_the_level() {
    let (mut sim, world) = walled(-4.0);
    let ear = sim.state.player.eye();
    sim.state.enemies[0].health = 0.0;
    sim.state.enemies[0].mind = crate::sim::enemy::Mind::Dead;
    let events = [
        Event::Hit { enemy: Some(0), at: Vec3::new(0.0, 1.0, -3.7) },
        Event::EnemyDown { enemy: 0 },
        Event::Won { exit: true },
    ];
    let sounds: Vec<SoundId> = cues(&events, &sim.state, &world.collision, ear).iter().map(|c| c.sound).collect();
    assert_eq!(sounds, [SoundId::CrawlerDeath, SoundId::ExitSting, SoundId::WinSting]);
    let lost = cues(&[Event::Died], &sim.state, &world.collision, ear);
    assert_eq!(lost[0].sound, SoundId::DeathSting);
}

/// The win replay's ticks, each heard by `sound` as the game hears them (the ears at the eye).
fn hear_the_win_replay(sound: &mut Soundscape) -> (crate::sim::Outcome, usize) {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/replays/win.replay"));
    let replay = crate::recording::LoadedReplay::open(path, None).unwrap_or_else(|e| panic!("{e:#}"));
    let mut sim = replay.simulation().unwrap();
    let world = sim.world();
    let mut most_voices = 0;
    for i in 0..replay.commands.len() {
        replay.step_checked(&mut sim, i).unwrap();
        sound.hear(&sim.events, &sim.state, &world);
        sound.listen(sim.state.player.eye(), sim.state.player.aim(), &sim.state, &world);
        most_voices = most_voices.max(sound.output.voices_playing());
    }
    (sim.state.outcome, most_voices)
}

#[test]
fn without_a_device_a_replay_plays_through_silently() {
    let mut sound = Soundscape::silent();
    assert!(sound.is_silent());
    let (outcome, voices) = hear_the_win_replay(&mut sound);
    assert_eq!((outcome, voices), (crate::sim::Outcome::Won, 0));
}

#[test]
fn through_an_offline_mix_a_replay_starts_placed_sounds() {
    let mut sound = Soundscape::on(audio::AudioOutput::offline());
    assert!(!sound.is_silent() && sound.bank.is_some(), "the bank is made when there is a mix");
    let (outcome, voices) = hear_the_win_replay(&mut sound);
    assert_eq!(outcome, crate::sim::Outcome::Won);
    assert!(voices > 0, "the crawlers' cries and the shots' ricochets were placed in the level");
}
