//! The building blocks the sound bank is made of: seeded noise, oscillators with gliding pitch,
//! envelopes and filters. Every sound is a sum of these, computed sample by sample.

use std::f32::consts::TAU;

use crate::sim::Rng;

/// Samples per second of every made sound.
pub const RATE: u32 = 44_100;

/// Seconds of sample `i`.
pub fn time(i: usize) -> f32 {
    i as f32 / RATE as f32
}

/// `seconds` of silence to add into.
pub fn blank(seconds: f32) -> Vec<f32> {
    vec![0.0; (seconds * RATE as f32).round() as usize]
}

/// White noise in −1..1 from a seed: the same seed, the same noise (the simulation's
/// SplitMix64 generator, [`Rng`]).
pub struct Noise(Rng);

impl Noise {
    pub fn new(seed: u64) -> Self {
        Self(Rng::new(seed))
    }

    pub fn sample(&mut self) -> f32 {
        self.0.next_f32() * 2.0 - 1.0
    }

    /// Uniform in `lo..hi`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * (self.sample() * 0.5 + 0.5)
    }
}

/// A sine whose frequency may change every sample (a glide) without clicks: the phase is summed.
#[derive(Default)]
pub struct Osc {
    phase: f32,
}

impl Osc {
    pub fn sine(&mut self, hz: f32) -> f32 {
        let v = (self.phase * TAU).sin();
        self.phase = (self.phase + hz / RATE as f32).fract();
        v
    }

    /// A band-limited-enough sawtooth for growls (a few harmonics of a sine series).
    pub fn buzz(&mut self, hz: f32) -> f32 {
        let p = self.phase * TAU;
        let v = p.sin() + (2.0 * p).sin() / 2.0 + (3.0 * p).sin() / 3.0 + (4.0 * p).sin() / 4.0;
        self.phase = (self.phase + hz / RATE as f32).fract();
        v * 0.6
    }
}

/// Rises over `attack` s, then decays by e every `decay` s.
pub fn hit(t: f32, attack: f32, decay: f32) -> f32 {
    if t < 0.0 {
        0.0
    } else if t < attack {
        t / attack
    } else {
        (-(t - attack) / decay).exp()
    }
}

/// Rises over `attack`, holds, falls over `release` to end at `length` (smooth, raised-cosine edges).
pub fn swell(t: f32, attack: f32, release: f32, length: f32) -> f32 {
    let edge = |x: f32| 0.5 - 0.5 * (x.clamp(0.0, 1.0) * std::f32::consts::PI).cos();
    if t < 0.0 || t > length {
        0.0
    } else {
        edge(t / attack) * edge((length - t) / release)
    }
}

/// A two-pole resonant filter (the RBJ cookbook's biquads).
pub struct Biquad {
    b: [f32; 3],
    a: [f32; 2],
    x: [f32; 2],
    y: [f32; 2],
}

impl Biquad {
    fn new(b: [f32; 3], a0: f32, a: [f32; 2]) -> Self {
        Self { b: b.map(|v| v / a0), a: a.map(|v| v / a0), x: [0.0; 2], y: [0.0; 2] }
    }

    pub fn lowpass(hz: f32, q: f32) -> Self {
        let (cos, alpha) = Self::shape(hz, q);
        Self::new([(1.0 - cos) / 2.0, 1.0 - cos, (1.0 - cos) / 2.0], 1.0 + alpha, [-2.0 * cos, 1.0 - alpha])
    }

    pub fn highpass(hz: f32, q: f32) -> Self {
        let (cos, alpha) = Self::shape(hz, q);
        Self::new([(1.0 + cos) / 2.0, -(1.0 + cos), (1.0 + cos) / 2.0], 1.0 + alpha, [-2.0 * cos, 1.0 - alpha])
    }

    /// Unity gain at the centre.
    pub fn bandpass(hz: f32, q: f32) -> Self {
        let (cos, alpha) = Self::shape(hz, q);
        Self::new([alpha, 0.0, -alpha], 1.0 + alpha, [-2.0 * cos, 1.0 - alpha])
    }

    fn shape(hz: f32, q: f32) -> (f32, f32) {
        let w = TAU * hz.clamp(10.0, RATE as f32 * 0.45) / RATE as f32;
        (w.cos(), w.sin() / (2.0 * q))
    }

    pub fn run(&mut self, x: f32) -> f32 {
        let y = self.b[0] * x + self.b[1] * self.x[0] + self.b[2] * self.x[1]
            - self.a[0] * self.y[0]
            - self.a[1] * self.y[1];
        self.x = [x, self.x[0]];
        self.y = [y, self.y[0]];
        y
    }
}

/// Adds `sound` into `into` starting at `at` seconds (cut at the end of `into`).
pub fn mix_in(into: &mut [f32], sound: &[f32], at: f32, gain: f32) {
    let start = (at * RATE as f32).round() as usize;
    for (o, s) in into.iter_mut().skip(start).zip(sound) {
        *o += s * gain;
    }
}

/// Scales to the given peak (nothing to scale in silence).
pub fn normalize(samples: &mut [f32], peak: f32) {
    let max = samples.iter().fold(0.0f32, |m, s| m.max(s.abs()));
    if max > 0.0 {
        samples.iter_mut().for_each(|s| *s *= peak / max);
    }
}

/// Makes the end flow into the start, for a seamless loop: the last `overlap` s are faded out
/// over the first ones, which are then dropped.
pub fn make_loop(mut samples: Vec<f32>, overlap: f32) -> Vec<f32> {
    let n = ((overlap * RATE as f32) as usize).min(samples.len() / 2);
    let len = samples.len() - n;
    for i in 0..n {
        let w = i as f32 / n as f32;
        samples[i] = samples[i] * w + samples[len + i] * (1.0 - w);
    }
    samples.truncate(len);
    samples
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_is_seeded_and_spans_minus_one_to_one() {
        let a: Vec<f32> = (0..1000).scan(Noise::new(3), |n, _| Some(n.sample())).collect();
        let b: Vec<f32> = (0..1000).scan(Noise::new(3), |n, _| Some(n.sample())).collect();
        let c: Vec<f32> = (0..1000).scan(Noise::new(4), |n, _| Some(n.sample())).collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert!(a.iter().all(|v| (-1.0..1.0).contains(v)));
        let mean = a.iter().sum::<f32>() / a.len() as f32;
        assert!(mean.abs() < 0.1, "{mean}");
    }

    #[test]
    fn a_lowpass_keeps_low_tones_and_removes_high_ones() {
        let level = |hz: f32| {
            let mut f = Biquad::lowpass(500.0, 0.707);
            let mut osc = Osc::default();
            let out: Vec<f32> = (0..RATE as usize / 4).map(|_| f.run(osc.sine(hz))).collect();
            out[out.len() / 2..].iter().fold(0.0f32, |m, v| m.max(v.abs()))
        };
        assert!(level(100.0) > 0.9, "{}", level(100.0));
        assert!(level(5000.0) < 0.02, "{}", level(5000.0));
    }

    #[test]
    fn a_loop_joins_without_a_jump() {
        let mut n = Noise::new(1);
        let mut f = Biquad::lowpass(200.0, 0.7);
        let s: Vec<f32> = (0..RATE as usize).map(|_| f.run(n.sample())).collect();
        let looped = make_loop(s, 0.25);
        let jump = (looped[0] - looped[looped.len() - 1]).abs();
        let typical = looped.windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0f32, f32::max);
        assert!(jump <= typical, "the seam ({jump}) is no bigger than any step inside ({typical})");
    }
}
