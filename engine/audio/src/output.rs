//! The one thing a game holds: a mix on a device, or silence.

use glam::Vec3;
use kira::backend::Backend;

use crate::mixer::{Mixer, Mixing};
use crate::spatial::{Listener, Volumes};
use crate::{Emitter, Sound};

/// Plays sounds on the default output device, or — where there is none — accepts every call
/// and plays nothing. It never returns an error: a game without sound is still a game.
pub struct AudioOutput {
    mix: Option<Box<dyn Mixing>>,
}

impl AudioOutput {
    /// The system's default output device at `volumes`. Without one, logs one line saying so
    /// and returns a silent output.
    pub fn open(volumes: Volumes) -> Self {
        crate::quiet_alsa::while_opening(|| Self::open_with::<kira::DefaultBackend>(Default::default(), volumes))
    }

    /// [`AudioOutput::open`] on any kira backend (tests use kira's mock backend, or one that
    /// fails as a machine without a sound card does).
    pub fn open_with<B: Backend + 'static>(settings: B::Settings, volumes: Volumes) -> Self
    where
        B::Error: std::fmt::Display,
    {
        match Mixer::<B>::new(settings, volumes) {
            Ok(mixer) => {
                log::info!("sound: output open");
                Self { mix: Some(Box::new(mixer)) }
            }
            Err(e) => {
                log::warn!("sound: no audio output ({e}); the game runs silently");
                Self::silent()
            }
        }
    }

    /// Mixes as on a device, into nothing (kira's mock backend, never run): every call takes
    /// the path it takes with a device, for tests of what a game plays.
    pub fn offline() -> Self {
        let settings = kira::backend::mock::MockBackendSettings { sample_rate: 48_000 };
        match Mixer::<kira::backend::mock::MockBackend>::new(settings, Volumes::default()) {
            Ok(mixer) => Self { mix: Some(Box::new(mixer)) },
            Err(_) => {
                log::warn!("sound: the offline mix could not be built");
                Self::silent()
            }
        }
    }

    /// Plays nothing (headless runs, tests, a server).
    pub fn silent() -> Self {
        Self { mix: None }
    }

    pub fn is_silent(&self) -> bool {
        self.mix.is_none()
    }

    /// The master, effects and ambience sliders, applied at once.
    pub fn set_volumes(&mut self, volumes: Volumes) {
        if let Some(m) = &mut self.mix {
            m.set_volumes(volumes);
        }
    }

    /// Where the ears are; sounds playing in the world follow.
    pub fn set_listener(&mut self, listener: Listener) {
        if let Some(m) = &mut self.mix {
            m.set_listener(listener);
        }
    }

    /// A sound at the listener's own head (their steps, their gun), at `gain` (amplitude, 1 = as made).
    pub fn play(&mut self, sound: &Sound, gain: f32) {
        if let Some(m) = &mut self.mix {
            m.play(sound, gain);
        }
    }

    /// A sound at a point in the world.
    pub fn play_at(&mut self, sound: &Sound, gain: f32, emitter: Emitter) {
        if let Some(m) = &mut self.mix {
            m.play_at(sound, gain, emitter);
        }
    }

    /// Moves the sounds still playing from `source` (see [`Emitter::source`]).
    pub fn move_source(&mut self, source: u32, position: Vec3, muffle: f32) {
        if let Some(m) = &mut self.mix {
            m.move_source(source, position, muffle);
        }
    }

    /// Loops `sound` on the ambience bus in place of any loop before; None stops it.
    pub fn loop_ambience(&mut self, sound: Option<&Sound>, gain: f32) {
        if let Some(m) = &mut self.mix {
            m.loop_ambience(sound, gain);
        }
    }

    /// Holds (true) or resumes (false) every effect — shots, steps, crawlers — where they are,
    /// as the game's pause does; the ambience plays on.
    pub fn set_paused(&mut self, paused: bool) {
        if let Some(m) = &mut self.mix {
            m.set_paused(paused);
        }
    }

    /// Whether the effects are held (false when silent).
    pub fn is_paused(&self) -> bool {
        self.mix.as_ref().is_some_and(|m| m.paused())
    }

    /// Sounds placed in the world still playing (0 when silent).
    pub fn voices_playing(&self) -> usize {
        self.mix.as_ref().map_or(0, |m| m.voices_playing())
    }
}

impl Default for AudioOutput {
    fn default() -> Self {
        Self::silent()
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use kira::backend::Renderer;

    use super::*;

    /// A machine with no sound card: the backend cannot start.
    struct NoDevice;

    impl Backend for NoDevice {
        type Settings = ();
        type Error = &'static str;
        fn setup(_: (), _: usize) -> Result<(Self, u32), Self::Error> {
            Err("no default output device")
        }
        fn start(&mut self, _: Renderer) -> Result<(), Self::Error> {
            Err("no default output device")
        }
    }

    pub(crate) fn beep() -> Sound {
        let samples: Vec<f32> = (0..4800).map(|i| (i as f32 * 0.1).sin() * 0.5).collect();
        Sound::from_mono(48_000, &samples)
    }

    /// The real device path: on a machine with sound it opens, without (CI) it is silent;
    /// either way no error and no panic. Nothing is played.
    #[test]
    fn opening_the_default_device_never_fails() {
        let mut out = AudioOutput::open(Volumes { master: 0.0, ..Volumes::default() });
        out.set_listener(Listener::default());
        assert_eq!(out.voices_playing(), 0);
    }

    #[test]
    fn without_a_device_the_output_is_silent_and_takes_every_call() {
        let mut out = AudioOutput::open_with::<NoDevice>((), Volumes::default());
        assert!(out.is_silent());
        let s = beep();
        out.set_volumes(Volumes { master: 0.5, effects: 0.2, ambience: 0.0 });
        out.set_listener(Listener::default());
        out.play(&s, 1.0);
        out.play_at(&s, 1.0, Emitter { position: Vec3::X, muffle: 1.0, source: Some(3) });
        out.move_source(3, Vec3::Z, 0.0);
        out.loop_ambience(Some(&s), 0.3);
        assert_eq!(out.voices_playing(), 0);
    }
}
