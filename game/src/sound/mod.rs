//! The game's sound: a bank of sounds made at start ([`bank`]), what each tick's events sound
//! like and where ([`cues`]), and the [`Soundscape`] that plays them on an
//! [`audio::AudioOutput`]. The simulation only emits events; this only listens, so sound can
//! never change what happens, and a replay without a device plays the same game.

pub mod bank;
pub mod cues;
pub mod synth;

use std::collections::HashMap;

use glam::Vec3;

use crate::sim::{Event, LevelWorld, WorldState};
use bank::SoundId;

/// The bank's seed: fixed, so the game sounds the same every start.
const SEED: u64 = 0x5eed_500d;
/// The room tone's level under everything else.
const ROOM_TONE_GAIN: f32 = 0.5;
/// Every effect's level: sounds made to full scale overlap (a shot, its ricochet, a crawler's
/// cry), so the mix keeps 6 dB in hand and a fight does not clip.
const HEADROOM: f32 = 0.5;

/// The sliders as the output takes them.
pub fn volumes(config: &game_ui::Config) -> audio::Volumes {
    audio::Volumes {
        master: config.master_volume / 100.0,
        effects: config.effects_volume / 100.0,
        ambience: config.ambience_volume / 100.0,
    }
}

/// Every sound, made.
pub struct SoundBank {
    sounds: HashMap<SoundId, audio::Sound>,
}

impl SoundBank {
    pub fn make() -> Self {
        let started = std::time::Instant::now();
        let sounds = SoundId::all()
            .into_iter()
            .map(|id| (id, audio::Sound::from_mono(synth::RATE, &id.synthesize(SEED))))
            .collect();
        log::debug!("sound: bank made in {:.0} ms", started.elapsed().as_secs_f64() * 1e3);
        Self { sounds }
    }

    pub fn get(&self, id: SoundId) -> Option<&audio::Sound> {
        self.sounds.get(&id)
    }
}

/// Plays the game's sound: events as they happen, crawlers' cries following them, the room's
/// tone under it all, heard from the camera.
pub struct Soundscape {
    output: audio::AudioOutput,
    /// Made only when there is an output to play it.
    bank: Option<SoundBank>,
    /// Where the ears are (the camera), for the muffling of new sounds.
    ear: Vec3,
}

impl Soundscape {
    /// No sound at all (tests, headless runs); accepts everything.
    pub fn silent() -> Self {
        Self { output: audio::AudioOutput::silent(), bank: None, ear: Vec3::ZERO }
    }

    /// The default output device at the config's volumes, the bank made and the room tone
    /// started; without a device, silent (the output logs why, once).
    pub fn open(config: &game_ui::Config) -> Self {
        Self::on(audio::AudioOutput::open(volumes(config)))
    }

    /// Plays on `output`.
    pub fn on(output: audio::AudioOutput) -> Self {
        let bank = (!output.is_silent()).then(SoundBank::make);
        let mut s = Self { output, bank, ear: Vec3::ZERO };
        if let Some(tone) = s.bank.as_ref().and_then(|b| b.get(SoundId::RoomTone)) {
            s.output.loop_ambience(Some(tone), ROOM_TONE_GAIN);
        }
        s
    }

    pub fn is_silent(&self) -> bool {
        self.output.is_silent()
    }

    pub fn set_volumes(&mut self, config: &game_ui::Config) {
        self.output.set_volumes(volumes(config));
    }

    /// While the game is paused the effects hold where they are (a crawler's shriek does not
    /// run on behind the pause menu); the room tone plays on.
    pub fn set_paused(&mut self, paused: bool) {
        self.output.set_paused(paused);
    }

    /// After a tick: its events, with the world they left.
    pub fn hear(&mut self, events: &[Event], state: &WorldState, world: &LevelWorld) {
        let Some(bank) = &self.bank else { return };
        for cue in cues::cues(events, state, &world.collision, self.ear) {
            let Some(sound) = bank.get(cue.sound) else { continue };
            match cue.at {
                None => self.output.play(sound, cue.gain * HEADROOM),
                Some(emitter) => self.output.play_at(sound, cue.gain * HEADROOM, emitter),
            }
        }
    }

    /// Each frame: the ears at the camera (`forward` its view), and the crawlers' sounds
    /// still playing moved to where they now are, muffled as the walls between now are.
    pub fn listen(&mut self, ear: Vec3, forward: Vec3, state: &WorldState, world: &LevelWorld) {
        self.ear = ear;
        if self.bank.is_none() {
            return;
        }
        self.output.set_listener(audio::Listener { position: ear, forward, up: Vec3::Y });
        for (i, e) in state.enemies.iter().enumerate() {
            let at = cues::crawler_voice(e);
            self.output.move_source(cues::crawler_source(i as u16), at, cues::muffle(&world.collision, ear, at));
        }
    }
}

#[cfg(test)]
mod tests;
