//! What the player hears of a tick: each sim [`Event`] becomes a [`Cue`] — which sound, how
//! loud, and where: at the player's own head, or at a point in the level, muffled when the
//! level's geometry stands between it and the ears. Pure, so it is tested without a device.

use glam::Vec3;
use physics::LevelCollision;

use super::bank::{SoundId, BREATH_VARIANTS, STEP_VARIANTS};
use crate::sim::player::Gait;
use crate::sim::{Enemy, Event, PickupKind, WorldState};

/// A sound to start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cue {
    pub sound: SoundId,
    /// Amplitude, 1 = as made.
    pub gain: f32,
    /// Where it is heard from; None: at the player's head (their own steps, gun, pickups).
    pub at: Option<audio::Emitter>,
}

/// The id that crawler `index`'s sounds follow it by.
pub fn crawler_source(index: u16) -> u32 {
    index as u32
}

/// Where a crawler's sounds come from: its chest.
pub fn crawler_voice(crawler: &Enemy) -> Vec3 {
    crawler.body.position + Vec3::Y * 0.8
}

/// How much of the way from `ear` to `source` the level blocks: three lines, to the point and
/// to points beside and above it, so a sound round a corner is half muffled rather than
/// switching at once. 0 = in the open, 1 = behind a wall.
pub fn muffle(level: &LevelCollision, ear: Vec3, source: Vec3) -> f32 {
    let to = source - ear;
    let side = Vec3::new(-to.z, 0.0, to.x).normalize_or_zero() * 0.5;
    let targets = [source, source + side, source + Vec3::Y * 0.5];
    let blocked = targets.iter().filter(|&&p| !crate::sim::enemy::clear_line(level, ear, p)).count();
    blocked as f32 / targets.len() as f32
}

/// The cues of one tick's events, heard from `ear`; `state` is the world after the tick.
pub fn cues(events: &[Event], state: &WorldState, level: &LevelCollision, ear: Vec3) -> Vec<Cue> {
    let head = |sound, gain| Cue { sound, gain, at: None };
    let placed = |sound, gain, position: Vec3, source: Option<u32>| Cue {
        sound,
        gain,
        at: Some(audio::Emitter { position, muffle: muffle(level, ear, position), source }),
    };
    let crawler = |sound, gain, enemy: u16| {
        let position = state.enemies.get(enemy as usize).map_or(ear, crawler_voice);
        placed(sound, gain, position, Some(crawler_source(enemy)))
    };
    // Variants take turns by tick: the same replay picks the same ones.
    let tick = state.tick;
    let mut out = Vec::new();
    for e in events {
        let cue = match *e {
            Event::Fired => head(SoundId::Gunshot, 1.0),
            Event::DryFire => head(SoundId::DryClick, 0.8),
            Event::ReloadStarted => head(SoundId::MagazineOut, 0.7),
            Event::Reloaded => head(SoundId::MagazineIn, 0.7),
            Event::Hit { enemy: None, at } => placed(SoundId::Ricochet, 0.6, at, None),
            Event::Hit { enemy: Some(i), .. } => match state.enemies.get(i as usize) {
                // A killing shot is heard as the death below.
                Some(c) if c.alive() => crawler(SoundId::CrawlerHurt, 0.9, i),
                _ => continue,
            },
            Event::EnemyDown { enemy } => crawler(SoundId::CrawlerDeath, 1.0, enemy),
            Event::Picked(kind) => head(
                match kind {
                    PickupKind::Battery => SoundId::PickBattery,
                    PickupKind::Ammo => SoundId::PickAmmo,
                    PickupKind::Health => SoundId::PickHealth,
                },
                0.7,
            ),
            Event::PlayerHurt => head(SoundId::PlayerHurt, 0.9),
            Event::Footstep(gait) => {
                let gain = match gait {
                    Gait::Walk => 0.45,
                    Gait::Sprint => 0.7,
                    Gait::Crouch => 0.2,
                };
                head(SoundId::Step((tick % STEP_VARIANTS as u32) as u8), gain)
            }
            Event::Jumped => head(SoundId::Jump, 0.5),
            Event::Landed { speed } => head(SoundId::Land, (speed / 6.0).clamp(0.3, 1.0)),
            Event::LampPickedUp => head(SoundId::LampOn, 0.5),
            Event::LampLetGo { thrown } => head(SoundId::LampLetGo, if thrown { 0.8 } else { 0.3 }),
            Event::LampLanded { at, speed } => placed(SoundId::LampLand, (speed / 8.0).clamp(0.25, 1.0), at, None),
            Event::LampSwitched { on } => {
                let gain = 0.6;
                // A lamp lying elsewhere clicks where it lies.
                let sound = if on { SoundId::LampOn } else { SoundId::LampOff };
                if state.lamp.attached {
                    head(sound, gain)
                } else {
                    placed(sound, gain, state.lamp.position, None)
                }
            }
            Event::LowBattery => {
                if state.lamp.attached {
                    head(SoundId::BatteryTick, 0.4)
                } else {
                    placed(SoundId::BatteryTick, 0.4, state.lamp.position, None)
                }
            }
            Event::Noticed { enemy, .. } => crawler(SoundId::Notice, 1.0, enemy),
            Event::Breath { enemy } => {
                crawler(SoundId::Breath(((tick / 60 + enemy as u32) % BREATH_VARIANTS as u32) as u8), 0.7, enemy)
            }
            Event::Strike { enemy } => crawler(SoundId::Strike, 1.0, enemy),
            Event::Won { exit } => {
                if exit {
                    out.push(head(SoundId::ExitSting, 0.8));
                }
                head(SoundId::WinSting, 0.8)
            }
            Event::Died => head(SoundId::DeathSting, 0.9),
        };
        out.push(cue);
    }
    out
}
