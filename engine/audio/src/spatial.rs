//! Where a sound is heard from: the listener's pose, and what distance, direction and walls do
//! to a sound at a point (pure functions, so they are tested without a device).

use glam::Vec3;

/// Where the ears are and which way they face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Listener {
    pub position: Vec3,
    /// Unit vectors: where the face points, and up.
    pub forward: Vec3,
    pub up: Vec3,
}

impl Default for Listener {
    fn default() -> Self {
        Self { position: Vec3::ZERO, forward: Vec3::NEG_Z, up: Vec3::Y }
    }
}

/// The three volume sliders, each a fraction 0..=1 of full.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Volumes {
    pub master: f32,
    pub effects: f32,
    pub ambience: f32,
}

impl Default for Volumes {
    fn default() -> Self {
        Self { master: 1.0, effects: 1.0, ambience: 1.0 }
    }
}

/// Within this distance a sound is at its full level, m.
pub const REFERENCE_DISTANCE: f32 = 1.0;
/// Beyond this a sound is not heard at all, m; it fades out over the last quarter.
pub const MAX_DISTANCE: f32 = 40.0;
/// The level a wall leaves of a fully muffled sound (about −8 dB).
pub const WALL_LOSS: f32 = 0.4;
/// The low-pass cutoff of a slightly and of a fully muffled sound, Hz.
pub const MUFFLE_CUTOFF: (f32, f32) = (6000.0, 400.0);
/// Panning never goes fully to one ear: heads let some of every sound round to the other.
pub const MAX_PAN: f32 = 0.8;

/// What a sound at a point sounds like to a listener.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spatial {
    /// Amplitude factor, 0..=1.
    pub gain: f32,
    /// −1 left … 1 right.
    pub pan: f32,
    /// The low-pass cutoff, Hz; None when heard directly.
    pub cutoff_hz: Option<f32>,
}

/// A sound at `position`, muffled by `muffle` (0..=1), heard by `listener`: the inverse-distance
/// law beyond [`REFERENCE_DISTANCE`] (−6 dB each doubling, as sound pressure from a point falls),
/// faded to nothing at [`MAX_DISTANCE`]; panned by how far to the side it is; through a wall
/// quieter and duller.
pub fn spatialize(listener: &Listener, position: Vec3, muffle: f32) -> Spatial {
    let muffle = muffle.clamp(0.0, 1.0);
    let to = position - listener.position;
    let distance = to.length();
    let fade_from = MAX_DISTANCE * 0.75;
    let fade = ((MAX_DISTANCE - distance) / (MAX_DISTANCE - fade_from)).clamp(0.0, 1.0);
    let gain = REFERENCE_DISTANCE / distance.max(REFERENCE_DISTANCE) * fade * (1.0 - (1.0 - WALL_LOSS) * muffle);
    let right = listener.forward.cross(listener.up).normalize_or_zero();
    // Close to the head a direction means little: the pan fades in over the first metre.
    let pan = if distance > 1e-3 { to.dot(right) / distance * (distance / REFERENCE_DISTANCE).min(1.0) } else { 0.0 };
    let cutoff_hz = (muffle > 0.0).then(|| MUFFLE_CUTOFF.0 * (MUFFLE_CUTOFF.1 / MUFFLE_CUTOFF.0).powf(muffle));
    Spatial { gain, pan: pan * MAX_PAN, cutoff_hz }
}

/// A slider's fraction as decibels: squared first, so the slider's travel sounds even (half
/// way is −12 dB, not −6), and 0 is silence.
pub fn slider_decibels(fraction: f32) -> f32 {
    amplitude_decibels(fraction.clamp(0.0, 1.0).powi(2))
}

/// An amplitude factor as decibels, no lower than kira's silence (−60 dB).
pub fn amplitude_decibels(gain: f32) -> f32 {
    if gain <= 0.001 {
        kira::Decibels::SILENCE.0
    } else {
        (20.0 * gain.log10()).max(kira::Decibels::SILENCE.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gain_halves_with_each_doubling_of_distance_and_fades_out_far_away() {
        let l = Listener::default();
        let at = |d: f32| spatialize(&l, Vec3::new(0.0, 0.0, -d), 0.0).gain;
        assert_eq!(at(0.5), 1.0, "full level within the reference distance");
        assert!((at(4.0) / at(2.0) - 0.5).abs() < 1e-6);
        assert!((at(16.0) / at(8.0) - 0.5).abs() < 1e-6);
        assert!((at(35.0) * 35.0 - 0.5).abs() < 1e-5, "half way through fading over the last quarter");
        assert_eq!(at(MAX_DISTANCE), 0.0);
        assert_eq!(at(100.0), 0.0);
    }

    #[test]
    fn sounds_to_the_right_pan_right_and_ahead_stay_centred() {
        let l = Listener::default();
        let pan = |p: Vec3| spatialize(&l, p, 0.0).pan;
        assert_eq!(pan(Vec3::new(0.0, 0.0, -5.0)), 0.0);
        assert!((pan(Vec3::new(5.0, 0.0, 0.0)) - MAX_PAN).abs() < 1e-6, "facing −Z, +X is on the right");
        assert!((pan(Vec3::new(-5.0, 0.0, 0.0)) + MAX_PAN).abs() < 1e-6);
        // Turned to face +X, the same point is ahead.
        let turned = Listener { forward: Vec3::X, ..l };
        assert!(spatialize(&turned, Vec3::new(5.0, 0.0, 0.0), 0.0).pan.abs() < 1e-6);
        assert!(pan(Vec3::new(0.1, 0.0, 0.0)).abs() < 0.1 * MAX_PAN + 1e-6, "at the head, nearly centred");
    }

    #[test]
    fn a_muffled_sound_is_quieter_and_duller() {
        let l = Listener::default();
        let p = Vec3::new(0.0, 0.0, -4.0);
        let (clear, half, full) = (spatialize(&l, p, 0.0), spatialize(&l, p, 0.5), spatialize(&l, p, 1.0));
        assert_eq!(clear.cutoff_hz, None);
        assert!(half.cutoff_hz.unwrap() < MUFFLE_CUTOFF.0 && half.cutoff_hz.unwrap() > MUFFLE_CUTOFF.1);
        assert!((full.cutoff_hz.unwrap() - MUFFLE_CUTOFF.1).abs() < 1e-2);
        assert!(clear.gain > half.gain && half.gain > full.gain);
        assert!((full.gain / clear.gain - WALL_LOSS).abs() < 1e-6);
    }

    #[test]
    fn sliders_map_to_decibels_evenly_with_zero_silent() {
        assert_eq!(slider_decibels(1.0), 0.0);
        assert!((slider_decibels(0.5) + 12.04).abs() < 0.01);
        assert_eq!(slider_decibels(0.0), kira::Decibels::SILENCE.0);
        assert_eq!(slider_decibels(2.0), 0.0, "clamped");
    }
}
