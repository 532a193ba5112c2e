//! Every sound the game plays, made by code at start from a seed: no recordings, nothing
//! downloaded. Each recipe is a few layers of noise and tone shaped by envelopes and filters.

use super::synth::{blank, hit, make_loop, mix_in, normalize, swell, time, Biquad, Noise, Osc};

/// The sounds, by what they are for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SoundId {
    Gunshot,
    DryClick,
    MagazineOut,
    MagazineIn,
    /// A footfall on stone; a few variants so a walk is not one sample over and over.
    Step(u8),
    Jump,
    Land,
    LampOn,
    LampOff,
    BatteryTick,
    LampLetGo,
    LampLand,
    PickBattery,
    PickAmmo,
    PickHealth,
    /// A shot striking stone.
    Ricochet,
    PlayerHurt,
    /// A crawler breathing; variants as for steps.
    Breath(u8),
    Notice,
    Strike,
    CrawlerHurt,
    CrawlerDeath,
    ExitSting,
    WinSting,
    DeathSting,
    /// The cellar's quiet: a seamless loop.
    RoomTone,
}

pub const STEP_VARIANTS: u8 = 4;
pub const BREATH_VARIANTS: u8 = 2;

impl SoundId {
    pub fn all() -> Vec<SoundId> {
        use SoundId::*;
        let mut all = vec![
            Gunshot,
            DryClick,
            MagazineOut,
            MagazineIn,
            Jump,
            Land,
            LampOn,
            LampOff,
            BatteryTick,
            LampLetGo,
            LampLand,
            PickBattery,
            PickAmmo,
            PickHealth,
            Ricochet,
            PlayerHurt,
            Notice,
            Strike,
            CrawlerHurt,
            CrawlerDeath,
            ExitSting,
            WinSting,
            DeathSting,
            RoomTone,
        ];
        all.extend((0..STEP_VARIANTS).map(Step));
        all.extend((0..BREATH_VARIANTS).map(Breath));
        all
    }

    /// The samples (at [`super::synth::RATE`]), peak ≤ 1. `seed` varies the noise of the
    /// whole bank; the same seed makes the same samples.
    pub fn synthesize(self, seed: u64) -> Vec<f32> {
        // Each sound its own noise stream, so adding a sound changes no other.
        let mut noise = Noise::new(seed ^ (self.key() << 32));
        let n = &mut noise;
        let (mut s, peak) = match self {
            SoundId::Gunshot => (gunshot(n), 1.0),
            SoundId::DryClick => (clicks(n, &[0.0, 0.025], 2600.0, 0.08), 0.5),
            SoundId::MagazineOut => (clicks(n, &[0.0, 0.11], 1800.0, 0.3), 0.6),
            SoundId::MagazineIn => (magazine_in(n), 0.7),
            SoundId::Step(v) => (step(n, v), 0.8),
            SoundId::Jump => (scuff(n, 0.18), 0.5),
            SoundId::Land => (land(n), 0.9),
            SoundId::LampOn => (clicks(n, &[0.0, 0.045], 3200.0, 0.1), 0.45),
            SoundId::LampOff => (clicks(n, &[0.0, 0.05], 2300.0, 0.1), 0.45),
            SoundId::BatteryTick => (battery_tick(n), 0.35),
            SoundId::LampLetGo => (whoosh(n, 0.35), 0.4),
            SoundId::LampLand => (clatter(n), 0.8),
            SoundId::PickBattery => (chime(&[659.3, 987.8], 0.09, 0.5), 0.5),
            SoundId::PickAmmo => (clicks(n, &[0.0, 0.05, 0.085, 0.14], 1500.0, 0.3), 0.6),
            SoundId::PickHealth => (chime(&[523.3, 659.3, 784.0], 0.06, 0.7), 0.5),
            SoundId::Ricochet => (ricochet(n), 0.6),
            SoundId::PlayerHurt => (player_hurt(n), 0.8),
            SoundId::Breath(v) => (breath(n, v), 0.5),
            SoundId::Notice => (shriek(n), 0.9),
            SoundId::Strike => (snarl(n), 0.8),
            SoundId::CrawlerHurt => (squeal(n), 0.8),
            SoundId::CrawlerDeath => (death_groan(n), 0.9),
            SoundId::ExitSting => (door(n), 0.7),
            SoundId::WinSting => (win_sting(), 0.7),
            SoundId::DeathSting => (death_sting(n), 0.7),
            SoundId::RoomTone => (room_tone(n), 0.25),
        };
        normalize(&mut s, peak);
        if self != SoundId::RoomTone {
            // A last few milliseconds faded, so no sound stops on a click.
            let n = s.len().min(256);
            let len = s.len();
            for (k, v) in s[len - n..].iter_mut().enumerate() {
                *v *= 1.0 - (k + 1) as f32 / n as f32;
            }
        }
        s
    }

    fn key(self) -> u64 {
        match self {
            SoundId::Step(v) => 100 + v as u64,
            SoundId::Breath(v) => 200 + v as u64,
            other => SoundId::all().iter().position(|&s| s == other).unwrap_or(0) as u64,
        }
    }
}

/// Noise through a filter, shaped by an envelope, over `seconds`.
fn shaped(n: &mut Noise, seconds: f32, mut filter: Biquad, env: impl Fn(f32) -> f32) -> Vec<f32> {
    let mut s = blank(seconds);
    for (i, v) in s.iter_mut().enumerate() {
        *v = filter.run(n.sample()) * env(time(i));
    }
    s
}

/// A tone gliding along `hz(t)`, shaped by `env`.
fn tone(seconds: f32, hz: impl Fn(f32) -> f32, env: impl Fn(f32) -> f32) -> Vec<f32> {
    let mut osc = Osc::default();
    (0..blank(seconds).len()).map(|i| osc.sine(hz(time(i))) * env(time(i))).collect()
}

/// A crack of noise, a low thump under it and a room's tail after it.
fn gunshot(n: &mut Noise) -> Vec<f32> {
    let mut s = shaped(n, 0.9, Biquad::lowpass(5000.0, 0.7), |t| hit(t, 0.0005, 0.035));
    let thump = tone(0.3, |t| 45.0 + 90.0 * (-t / 0.03).exp(), |t| hit(t, 0.001, 0.07));
    mix_in(&mut s, &thump, 0.0, 0.6);
    let tail = shaped(n, 0.9, Biquad::bandpass(700.0, 0.6), |t| hit(t, 0.02, 0.22));
    mix_in(&mut s, &tail, 0.0, 0.5);
    s
}

/// Short metallic clicks at the given times: a ringing tone over a snap of noise.
fn clicks(n: &mut Noise, at: &[f32], hz: f32, seconds: f32) -> Vec<f32> {
    let mut s = blank(seconds);
    for (k, &t0) in at.iter().enumerate() {
        let pitch = hz * (1.0 + 0.13 * k as f32);
        let mut click = shaped(n, 0.05, Biquad::bandpass(pitch * 1.6, 1.5), |t| hit(t, 0.0002, 0.004));
        let ring = tone(0.05, |_| pitch, |t| hit(t, 0.0003, 0.008));
        mix_in(&mut click, &ring, 0.0, 0.6);
        mix_in(&mut s, &click, t0, 1.0 - 0.15 * k as f32);
    }
    s
}

/// The magazine slid home and the slide racked.
fn magazine_in(n: &mut Noise) -> Vec<f32> {
    let mut s = shaped(n, 0.45, Biquad::bandpass(1200.0, 0.8), |t| swell(t, 0.03, 0.04, 0.12) * 0.25);
    let home = clicks(n, &[0.0], 1400.0, 0.06);
    mix_in(&mut s, &home, 0.12, 1.0);
    let rack = clicks(n, &[0.0, 0.07], 2100.0, 0.15);
    mix_in(&mut s, &rack, 0.27, 0.9);
    s
}

/// A footfall on stone: a soft heel thud and a gritty scuff, each variant its own.
fn step(n: &mut Noise, variant: u8) -> Vec<f32> {
    let v = variant as f32;
    let mut s = shaped(n, 0.2, Biquad::lowpass(300.0 + 40.0 * v, 0.8), |t| hit(t, 0.002, 0.025));
    let grit = shaped(n, 0.2, Biquad::bandpass(2500.0 + 350.0 * v, 1.2), |t| hit(t - 0.01, 0.004, 0.03));
    mix_in(&mut s, &grit, 0.0, 0.35);
    let thud = tone(0.1, |_| 90.0 + 12.0 * v, |t| hit(t, 0.002, 0.02));
    mix_in(&mut s, &thud, 0.0, 0.5);
    s
}

fn scuff(n: &mut Noise, seconds: f32) -> Vec<f32> {
    shaped(n, seconds, Biquad::bandpass(1400.0, 0.7), |t| swell(t, 0.01, 0.12, seconds))
}

/// Both feet coming down hard.
fn land(n: &mut Noise) -> Vec<f32> {
    let mut s = shaped(n, 0.35, Biquad::lowpass(250.0, 0.9), |t| hit(t, 0.002, 0.05));
    let second = shaped(n, 0.3, Biquad::lowpass(320.0, 0.9), |t| hit(t, 0.002, 0.04));
    mix_in(&mut s, &second, 0.03, 0.8);
    let thud = tone(0.25, |t| 55.0 + 40.0 * (-t / 0.04).exp(), |t| hit(t, 0.002, 0.06));
    mix_in(&mut s, &thud, 0.0, 1.2);
    s
}

/// The dying battery: a faint electric tick with a buzz.
fn battery_tick(n: &mut Noise) -> Vec<f32> {
    let mut s = tone(0.09, |_| 1250.0, |t| hit(t, 0.001, 0.02));
    let buzz = shaped(n, 0.09, Biquad::bandpass(4000.0, 2.0), |t| hit(t, 0.0005, 0.006));
    mix_in(&mut s, &buzz, 0.0, 0.8);
    let hum = tone(0.09, |_| 100.0, |t| swell(t, 0.005, 0.05, 0.09));
    mix_in(&mut s, &hum, 0.0, 0.3);
    s
}

fn whoosh(n: &mut Noise, seconds: f32) -> Vec<f32> {
    let mut f = Biquad::bandpass(600.0, 1.0);
    let mut s = blank(seconds);
    for (i, v) in s.iter_mut().enumerate() {
        let t = time(i);
        // The band sweeps up and back as it passes.
        let hz = 500.0 + 1200.0 * (std::f32::consts::PI * t / seconds).sin();
        if i % 64 == 0 {
            f = Biquad::bandpass(hz, 1.0);
        }
        *v = f.run(n.sample()) * swell(t, seconds * 0.5, seconds * 0.5, seconds);
    }
    s
}

/// The lamp hitting the floor: a plastic-and-metal knock, then two smaller bounces.
fn clatter(n: &mut Noise) -> Vec<f32> {
    let mut s = blank(0.6);
    for (k, (t0, g)) in [(0.0, 1.0), (0.13, 0.45), (0.22, 0.2)].into_iter().enumerate() {
        let mut knock = shaped(n, 0.2, Biquad::bandpass(1800.0 + 300.0 * k as f32, 1.0), |t| hit(t, 0.0005, 0.01));
        for (hz, a) in [(930.0, 0.5), (2370.0, 0.35), (3810.0, 0.2)] {
            let ring = tone(0.2, |_| hz, |t| hit(t, 0.0005, 0.03));
            mix_in(&mut knock, &ring, 0.0, a);
        }
        mix_in(&mut s, &knock, t0, g);
    }
    s
}

/// Soft bell tones one after another, each ringing on.
fn chime(notes: &[f32], gap: f32, ring: f32) -> Vec<f32> {
    let mut s = blank(gap * notes.len() as f32 + ring);
    for (k, &hz) in notes.iter().enumerate() {
        let mut bell = tone(ring, |_| hz, |t| hit(t, 0.004, ring * 0.3));
        let over = tone(ring, |_| hz * 2.76, |t| hit(t, 0.002, ring * 0.08));
        mix_in(&mut bell, &over, 0.0, 0.25);
        mix_in(&mut s, &bell, gap * k as f32, 1.0);
    }
    s
}

fn ricochet(n: &mut Noise) -> Vec<f32> {
    let mut s = shaped(n, 0.25, Biquad::bandpass(3000.0, 0.9), |t| hit(t, 0.0005, 0.02));
    let whine = tone(0.25, |t| 2600.0 - 1400.0 * t / 0.25, |t| hit(t - 0.01, 0.01, 0.05));
    mix_in(&mut s, &whine, 0.0, 0.25);
    s
}

/// A blow taken: a dull hit and a short grunt (a voice-like buzz through a vowel's band).
fn player_hurt(n: &mut Noise) -> Vec<f32> {
    let mut s = shaped(n, 0.4, Biquad::lowpass(400.0, 0.8), |t| hit(t, 0.002, 0.04));
    let mut voice = Osc::default();
    let mut vowel = Biquad::bandpass(650.0, 2.0);
    let grunt: Vec<f32> = (0..blank(0.35).len())
        .map(|i| {
            let t = time(i);
            vowel.run(voice.buzz(140.0 - 40.0 * t)) * swell(t, 0.02, 0.2, 0.3)
        })
        .collect();
    mix_in(&mut s, &grunt, 0.03, 2.0);
    s
}

/// A crawler breathing: a wet, low inhale and a longer rasping exhale.
fn breath(n: &mut Noise, variant: u8) -> Vec<f32> {
    let v = variant as f32;
    let length = 1.3 + 0.2 * v;
    let mut s = shaped(n, length, Biquad::bandpass(450.0 + 80.0 * v, 1.6), |t| swell(t, 0.25, 0.15, 0.5));
    let exhale = shaped(n, length, Biquad::bandpass(320.0, 1.2), |t| swell(t - 0.55, 0.08, 0.5, 0.7 + 0.2 * v));
    mix_in(&mut s, &exhale, 0.0, 1.3);
    let mut voice = Osc::default();
    let rasp: Vec<f32> =
        (0..s.len()).map(|i| voice.buzz(62.0 + 6.0 * v) * swell(time(i) - 0.6, 0.1, 0.4, 0.6) * 0.08).collect();
    mix_in(&mut s, &rasp, 0.0, 1.0);
    s
}

/// The crawler has seen you: a rasping shriek rising, with a tremble.
fn shriek(n: &mut Noise) -> Vec<f32> {
    let length = 0.8;
    let mut voice = Osc::default();
    let mut wobble = Osc::default();
    let mut band = Biquad::bandpass(1100.0, 1.5);
    let mut s: Vec<f32> = (0..blank(length).len())
        .map(|i| {
            let t = time(i);
            let hz = 260.0 + 520.0 * (t / 0.35).min(1.0) + 25.0 * wobble.sine(13.0);
            band.run(voice.buzz(hz)) * swell(t, 0.05, 0.35, length)
        })
        .collect();
    let hiss = shaped(n, length, Biquad::highpass(2500.0, 0.7), |t| swell(t, 0.03, 0.4, length));
    mix_in(&mut s, &hiss, 0.0, 0.35);
    s
}

/// Rearing up to strike: a hiss over a throaty growl.
fn snarl(n: &mut Noise) -> Vec<f32> {
    let length = 0.55;
    let mut s = shaped(n, length, Biquad::bandpass(2200.0, 0.9), |t| swell(t, 0.08, 0.2, length));
    let mut voice = Osc::default();
    let mut flutter = Osc::default();
    let mut vowel = Biquad::bandpass(500.0, 1.5);
    let growl: Vec<f32> = (0..s.len())
        .map(|i| {
            let t = time(i);
            let am = 0.6 + 0.4 * flutter.sine(28.0);
            vowel.run(voice.buzz(85.0 + 30.0 * t)) * am * swell(t, 0.05, 0.2, length)
        })
        .collect();
    mix_in(&mut s, &growl, 0.0, 1.6);
    s
}

/// Hit: a short squeal falling.
fn squeal(n: &mut Noise) -> Vec<f32> {
    let length = 0.3;
    let mut voice = Osc::default();
    let mut vowel = Biquad::bandpass(900.0, 1.4);
    let mut s: Vec<f32> = (0..blank(length).len())
        .map(|i| {
            let t = time(i);
            vowel.run(voice.buzz(620.0 - 700.0 * t)) * swell(t, 0.01, 0.2, length)
        })
        .collect();
    let splat = shaped(n, 0.1, Biquad::lowpass(900.0, 0.8), |t| hit(t, 0.001, 0.015));
    mix_in(&mut s, &splat, 0.0, 0.6);
    s
}

/// A long groan sinking away, and the body falling at its end.
fn death_groan(n: &mut Noise) -> Vec<f32> {
    let length = 1.5;
    let mut voice = Osc::default();
    let mut vowel = Biquad::bandpass(450.0, 1.5);
    let mut s: Vec<f32> = (0..blank(length).len())
        .map(|i| {
            let t = time(i);
            vowel.run(voice.buzz(240.0 * (-t / 0.7).exp() + 55.0)) * swell(t, 0.04, 0.5, 1.0)
        })
        .collect();
    let fall = land(n);
    mix_in(&mut s, &fall, 0.95, 0.9);
    s
}

/// The exit's door: the latch, then old hinges creaking open.
fn door(n: &mut Noise) -> Vec<f32> {
    let length = 1.3;
    let mut s = clicks(n, &[0.0, 0.06], 900.0, length);
    let mut hinge = Osc::default();
    let mut wander = Osc::default();
    let mut band = Biquad::bandpass(1300.0, 3.0);
    let creak: Vec<f32> = (0..s.len())
        .map(|i| {
            let t = time(i);
            // Stick-slip: a slow buzz whose rate wanders, through the door's ringing band.
            let rate = 38.0 + 14.0 * wander.sine(1.7);
            band.run(hinge.buzz(rate)) * swell(t - 0.15, 0.1, 0.4, 1.1)
        })
        .collect();
    mix_in(&mut s, &creak, 0.0, 8.0);
    s
}

/// Out: a major arpeggio rising into a held chord.
fn win_sting() -> Vec<f32> {
    let mut s = chime(&[261.6, 329.6, 392.0, 523.3], 0.16, 1.8);
    let pad = tone(2.5, |_| 130.8, |t| swell(t, 0.3, 1.2, 2.4));
    mix_in(&mut s, &pad, 0.0, 0.25);
    s
}

/// Dead: a low minor chord sinking, trembling, with a rumble.
fn death_sting(n: &mut Noise) -> Vec<f32> {
    let length = 2.6;
    let mut s = blank(length);
    for hz in [110.0, 130.8, 164.8] {
        let mut tremble = Osc::default();
        let mut osc = Osc::default();
        for (i, v) in s.iter_mut().enumerate() {
            let t = time(i);
            *v += osc.buzz(hz * (1.0 - 0.12 * t / length))
                * swell(t, 0.05, 1.5, length)
                * (0.7 + 0.3 * tremble.sine(6.0));
        }
    }
    let mut f = Biquad::lowpass(900.0, 0.7);
    s.iter_mut().for_each(|v| *v = f.run(*v));
    let rumble = shaped(n, length, Biquad::lowpass(90.0, 0.8), |t| swell(t, 0.02, 1.8, length));
    mix_in(&mut s, &rumble, 0.0, 3.0);
    s
}

/// The cellar's quiet: a low rumble of air, a faint mains hum, and water dripping now and then.
fn room_tone(n: &mut Noise) -> Vec<f32> {
    let length = 8.0;
    let mut s = shaped(n, length + 1.0, Biquad::lowpass(160.0, 0.6), |_| 1.0);
    let air = shaped(n, length + 1.0, Biquad::bandpass(900.0, 0.5), |_| 0.08);
    mix_in(&mut s, &air, 0.0, 1.0);
    let hum = tone(length + 1.0, |_| 50.0, |_| 0.06);
    mix_in(&mut s, &hum, 0.0, 1.0);
    for k in 0..3 {
        let at = n.range(0.5, length - 0.5);
        let pitch = n.range(1400.0, 2200.0);
        let drip = tone(0.12, |t| pitch * (1.0 + 2.0 * t), |t| hit(t, 0.001, 0.02));
        mix_in(&mut s, &drip, at, 0.25 + 0.1 * k as f32);
    }
    make_loop(s, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_sound_is_made_the_same_each_time_audible_and_in_range() {
        for id in SoundId::all() {
            let a = id.synthesize(7);
            assert_eq!(a, id.synthesize(7), "{id:?} differs between two makings");
            assert!(!a.is_empty() && a.iter().all(|v| v.is_finite() && v.abs() <= 1.0), "{id:?}");
            let peak = a.iter().fold(0.0f32, |m, v| m.max(v.abs()));
            assert!(peak > 0.2, "{id:?} is nearly silent: peak {peak}");
            // Ends quietly (no click as it stops); a loop ends where it began instead.
            if id != SoundId::RoomTone {
                let tail = a[a.len() - 64..].iter().fold(0.0f32, |m, v| m.max(v.abs()));
                assert!(tail < 0.05 * peak.max(1e-6) + 0.01, "{id:?} ends abruptly: {tail}");
            }
        }
        assert_ne!(SoundId::Step(0).synthesize(7), SoundId::Step(1).synthesize(7), "variants differ");
        assert_ne!(SoundId::Gunshot.synthesize(7), SoundId::Gunshot.synthesize(8), "the seed matters");
    }

    #[test]
    fn every_sound_has_its_own_key() {
        let mut keys: Vec<u64> = SoundId::all().iter().map(|s| s.key()).collect();
        keys.sort();
        let n = keys.len();
        keys.dedup();
        assert_eq!(keys.len(), n);
    }
}
