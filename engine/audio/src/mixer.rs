//! The mix on a device: kira's main track is the master bus, with an effects bus and an
//! ambience bus under it. Sounds placed in the world play on a small pool of voices under the
//! effects bus, each with its own low-pass filter, so one sound can be muffled while another
//! is not; their level, pan and filter follow the listener and their source every frame.

use std::time::Duration;

use glam::Vec3;
use kira::backend::Backend;
use kira::effect::filter::{FilterBuilder, FilterHandle, FilterMode};
use kira::sound::static_sound::StaticSoundHandle;
use kira::sound::PlaybackState;
use kira::track::{TrackBuilder, TrackHandle};
use kira::{AudioManager, AudioManagerSettings, Decibels, Easing, Mix, Panning, StartTime, Tween};

use crate::spatial::{amplitude_decibels, slider_decibels, spatialize, Listener, Volumes};
use crate::{Emitter, Sound};

/// Sounds placed in the world at once; a new one beyond this replaces the oldest.
pub const VOICES: usize = 24;
/// Changes of level, pan and filter glide over this long, so a moving sound does not click.
const GLIDE: Tween = glide(40);
/// How fast a replaced voice or ambience fades out.
const CUT: Tween = glide(15);

const fn glide(ms: u64) -> Tween {
    Tween { start_time: StartTime::Immediate, duration: Duration::from_millis(ms), easing: Easing::Linear }
}

struct Voice {
    track: TrackHandle,
    filter: FilterHandle,
    sound: Option<StaticSoundHandle>,
    emitter: Emitter,
    gain: f32,
    /// When it started, counted in plays, to find the oldest.
    started: u64,
}

impl Voice {
    fn busy(&self) -> bool {
        self.sound.as_ref().is_some_and(|s| s.state() != PlaybackState::Stopped)
    }

    /// Sets level, pan and filter for where the sound is now.
    fn place(&mut self, listener: &Listener, tween: Tween) {
        let Some(sound) = &mut self.sound else { return };
        let s = spatialize(listener, self.emitter.position, self.emitter.muffle);
        sound.set_volume(Decibels(amplitude_decibels(s.gain * self.gain)), tween);
        sound.set_panning(Panning(s.pan), tween);
        match s.cutoff_hz {
            Some(hz) => {
                self.filter.set_cutoff(hz as f64, tween);
                self.filter.set_mix(Mix::WET, tween);
            }
            None => self.filter.set_mix(Mix::DRY, tween),
        }
    }
}

/// What [`crate::AudioOutput`] asks of a mix, whatever its backend.
pub(crate) trait Mixing {
    fn set_volumes(&mut self, volumes: Volumes);
    fn set_listener(&mut self, listener: Listener);
    fn play(&mut self, sound: &Sound, gain: f32);
    fn play_at(&mut self, sound: &Sound, gain: f32, emitter: Emitter);
    fn move_source(&mut self, source: u32, position: Vec3, muffle: f32);
    fn loop_ambience(&mut self, sound: Option<&Sound>, gain: f32);
    fn voices_playing(&self) -> usize;
    fn set_paused(&mut self, paused: bool);
    fn paused(&self) -> bool;
}

/// Why a mix could not be built: the backend's error (no device), or kira out of tracks.
pub(crate) enum OpenError<E> {
    Backend(E),
    Tracks(kira::ResourceLimitReached),
}

impl<E: std::fmt::Display> std::fmt::Display for OpenError<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OpenError::Backend(e) => e.fmt(f),
            OpenError::Tracks(e) => e.fmt(f),
        }
    }
}

pub(crate) struct Mixer<B: Backend> {
    manager: AudioManager<B>,
    effects: TrackHandle,
    ambience: TrackHandle,
    ambience_sound: Option<StaticSoundHandle>,
    voices: Vec<Voice>,
    listener: Listener,
    plays: u64,
    /// The effects bus (every voice) is held, as while the game is paused.
    paused: bool,
}

impl<B: Backend> Mixer<B> {
    /// Opens the backend and builds the buses.
    pub fn new(backend: B::Settings, volumes: Volumes) -> Result<Self, OpenError<B::Error>> {
        let settings = AudioManagerSettings::<B> {
            capacities: Default::default(),
            main_track_builder: Default::default(),
            internal_buffer_size: 128,
            backend_settings: backend,
        };
        let mut manager = AudioManager::<B>::new(settings).map_err(OpenError::Backend)?;
        let limit = OpenError::Tracks;
        let mut effects = manager.add_sub_track(TrackBuilder::new().sub_track_capacity(VOICES)).map_err(limit)?;
        let ambience = manager.add_sub_track(TrackBuilder::new()).map_err(limit)?;
        let mut voices = Vec::with_capacity(VOICES);
        for _ in 0..VOICES {
            let mut builder = TrackBuilder::new();
            let filter = builder.add_effect(FilterBuilder::new().mode(FilterMode::LowPass).mix(Mix::DRY));
            let track = effects.add_sub_track(builder).map_err(limit)?;
            let emitter = Emitter { position: Vec3::ZERO, muffle: 0.0, source: None };
            voices.push(Voice { track, filter, sound: None, emitter, gain: 0.0, started: 0 });
        }
        let mut mixer = Self {
            manager,
            effects,
            ambience,
            ambience_sound: None,
            voices,
            listener: Listener::default(),
            plays: 0,
            paused: false,
        };
        mixer.set_volumes(volumes);
        Ok(mixer)
    }

    #[cfg(test)]
    pub fn backend_mut(&mut self) -> &mut B {
        self.manager.backend_mut()
    }
}

impl<B: Backend> Mixing for Mixer<B> {
    fn set_volumes(&mut self, v: Volumes) {
        let now = Tween::default();
        self.manager.main_track().set_volume(Decibels(slider_decibels(v.master)), now);
        self.effects.set_volume(Decibels(slider_decibels(v.effects)), now);
        self.ambience.set_volume(Decibels(slider_decibels(v.ambience)), now);
    }

    fn set_listener(&mut self, listener: Listener) {
        self.listener = listener;
        for voice in self.voices.iter_mut().filter(|v| v.busy()) {
            voice.place(&listener, GLIDE);
        }
    }

    fn play(&mut self, sound: &Sound, gain: f32) {
        let data = sound.data.volume(Decibels(amplitude_decibels(gain)));
        if let Err(e) = self.effects.play(data) {
            log::debug!("sound not played: {e}");
        }
    }

    fn play_at(&mut self, sound: &Sound, gain: f32, emitter: Emitter) {
        self.plays += 1;
        // A free voice, else the one that started longest ago.
        let index = match self.voices.iter().position(|v| !v.busy()) {
            Some(i) => i,
            None => (0..self.voices.len()).min_by_key(|&i| self.voices[i].started).unwrap_or(0),
        };
        let voice = &mut self.voices[index];
        if let Some(mut old) = voice.sound.take() {
            old.stop(CUT);
        }
        let s = spatialize(&self.listener, emitter.position, emitter.muffle);
        // Start at the right level and pan at once; only later changes glide.
        let data = sound.data.volume(Decibels(amplitude_decibels(s.gain * gain))).panning(Panning(s.pan));
        voice.emitter = emitter;
        voice.gain = gain;
        voice.started = self.plays;
        match s.cutoff_hz {
            Some(hz) => {
                voice.filter.set_cutoff(hz as f64, Tween::default());
                voice.filter.set_mix(Mix::WET, Tween::default());
            }
            None => voice.filter.set_mix(Mix::DRY, Tween::default()),
        }
        match voice.track.play(data) {
            Ok(handle) => voice.sound = Some(handle),
            Err(e) => log::debug!("sound not played: {e}"),
        }
    }

    fn move_source(&mut self, source: u32, position: Vec3, muffle: f32) {
        let listener = self.listener;
        for voice in self.voices.iter_mut().filter(|v| v.emitter.source == Some(source) && v.busy()) {
            voice.emitter.position = position;
            voice.emitter.muffle = muffle;
            voice.place(&listener, GLIDE);
        }
    }

    fn set_paused(&mut self, paused: bool) {
        if paused == self.paused {
            return;
        }
        self.paused = paused;
        // Pausing a track fades out and holds every sound and sub-track (the voices) on it.
        if paused {
            self.effects.pause(CUT);
        } else {
            self.effects.resume(CUT);
        }
    }

    fn paused(&self) -> bool {
        self.paused
    }

    fn loop_ambience(&mut self, sound: Option<&Sound>, gain: f32) {
        if let Some(mut old) = self.ambience_sound.take() {
            old.stop(CUT);
        }
        let Some(sound) = sound else { return };
        let data = sound.data.volume(Decibels(amplitude_decibels(gain))).loop_region(..);
        match self.ambience.play(data) {
            Ok(handle) => self.ambience_sound = Some(handle),
            Err(e) => log::debug!("ambience not played: {e}"),
        }
    }

    fn voices_playing(&self) -> usize {
        self.voices.iter().filter(|v| v.busy()).count()
    }
}

#[cfg(test)]
mod tests {
    use kira::backend::mock::{MockBackend, MockBackendSettings};

    use super::*;
    use crate::output::tests::beep;

    #[test]
    fn placed_sounds_share_a_pool_of_voices_and_follow_their_source() {
        let settings = MockBackendSettings { sample_rate: 48_000 };
        let Ok(mut mixer) = Mixer::<MockBackend>::new(settings, Volumes::default()) else { panic!("a mock mix") };
        let s = beep();
        mixer.loop_ambience(Some(&s), 0.5);
        for i in 0..VOICES as u32 + 5 {
            let emitter = Emitter { position: Vec3::new(i as f32, 0.0, -3.0), muffle: 0.5, source: Some(i % 3) };
            mixer.play_at(&s, 1.0, emitter);
            mixer.play(&s, 0.8);
        }
        // The renderer picks the sounds up and mixes a few blocks.
        for _ in 0..4 {
            mixer.backend_mut().on_start_processing();
            mixer.backend_mut().process();
        }
        assert_eq!(mixer.voices_playing(), VOICES, "more sounds than voices: the oldest were replaced");
        mixer.move_source(1, Vec3::new(0.0, 0.0, 2.0), 0.0);
        mixer.set_listener(Listener { position: Vec3::ONE, ..Listener::default() });
        mixer.set_volumes(Volumes { master: 0.3, effects: 0.0, ambience: 1.0 });
        let moved: Vec<_> = mixer.voices.iter().filter(|v| v.emitter.source == Some(1)).collect();
        assert!(!moved.is_empty() && moved.iter().all(|v| v.emitter.position == Vec3::new(0.0, 0.0, 2.0)));
        assert!(mixer.voices.iter().filter(|v| v.emitter.source == Some(2)).all(|v| v.emitter.position.z == -3.0));
        mixer.loop_ambience(None, 0.0);
        assert!(mixer.ambience_sound.is_none());
    }

    /// The game's pause holds the effects where they are and lets them finish after.
    #[test]
    fn pausing_holds_the_effects_and_resuming_lets_them_finish() {
        let settings = MockBackendSettings { sample_rate: 48_000 };
        let Ok(mut mixer) = Mixer::<MockBackend>::new(settings, Volumes::default()) else { panic!("a mock mix") };
        let blocks = |mixer: &mut Mixer<MockBackend>, n: usize| {
            for _ in 0..n {
                mixer.backend_mut().on_start_processing();
                mixer.backend_mut().process();
            }
        };
        // A 0.1 s beep; 400 blocks of 128 frames are over a second.
        mixer.play_at(&beep(), 1.0, Emitter { position: -Vec3::Z, muffle: 0.0, source: None });
        blocks(&mut mixer, 2);
        assert_eq!(mixer.voices_playing(), 1);
        mixer.set_paused(true);
        blocks(&mut mixer, 400);
        assert!(mixer.paused());
        assert_eq!(mixer.effects.state(), kira::track::TrackPlaybackState::Paused);
        assert_eq!(mixer.voices_playing(), 1, "held, not finished");
        mixer.set_paused(false);
        blocks(&mut mixer, 400);
        assert!(!mixer.paused());
        assert_eq!(mixer.voices_playing(), 0, "resumed, it played out");
    }
}
