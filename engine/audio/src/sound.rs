//! A sound as the output plays it: frames in memory, shared (cloning is cheap).

use std::sync::Arc;

use kira::sound::static_sound::{StaticSoundData, StaticSoundSettings};
use kira::Frame;

#[derive(Clone)]
pub struct Sound {
    pub(crate) data: StaticSoundData,
}

impl Sound {
    /// A mono sound from its samples (−1..=1) at `sample_rate` Hz.
    pub fn from_mono(sample_rate: u32, samples: &[f32]) -> Self {
        let frames: Arc<[Frame]> = samples.iter().map(|&s| Frame::from_mono(s)).collect();
        Self { data: StaticSoundData { sample_rate, frames, settings: StaticSoundSettings::default(), slice: None } }
    }

    /// Seconds.
    pub fn duration(&self) -> f32 {
        self.data.duration().as_secs_f32()
    }
}

impl std::fmt::Debug for Sound {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Sound({} frames at {} Hz)", self.data.frames.len(), self.data.sample_rate)
    }
}
