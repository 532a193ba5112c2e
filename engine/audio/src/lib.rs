//! Sound output for a game, knowing nothing of any game: sounds made in memory ([`Sound`]),
//! played at the listener's head or at a point in the world with distance attenuation, left/
//! right panning and a muffle (a low-pass and a loss, for sound heard through a wall), a looping
//! ambience, and three volume buses (master, effects, ambience).
//!
//! [`AudioOutput::open`] plays on the system's default device; where there is none (CI, a
//! server, a headless run) it logs one line and stays silent, accepting every call. Nothing
//! here ever fails the caller.

mod mixer;
mod output;
mod quiet_alsa;
mod sound;
mod spatial;

pub use output::AudioOutput;
pub use sound::Sound;
pub use spatial::{spatialize, Listener, Spatial, Volumes};

/// A sound placed in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emitter {
    pub position: glam::Vec3,
    /// 0 = heard directly; 1 = fully muffled (through a wall).
    pub muffle: f32,
    /// Sounds given the same source move together with [`AudioOutput::move_source`] (a
    /// creature's cries follow it); `None` stays where it started.
    pub source: Option<u32>,
}
