//! The fixed-tick clock: wall time enters the game here and nowhere else. Frames of any length
//! are turned into a whole number of fixed simulation ticks plus an interpolation fraction, so
//! the simulation itself only ever sees "one more tick".

/// Accumulates frame time and hands out fixed ticks.
#[derive(Clone, Debug)]
pub struct FixedClock {
    tick_rate: u32,
    /// Unspent time, in ticks (fractional); kept in f64 so hours of play do not drift.
    accumulated: f64,
    /// At most this many ticks per frame: after a long stall (a breakpoint, a slow GI frame on
    /// a software rasteriser) the game slows down instead of spiralling into ever longer frames.
    max_ticks_per_frame: u32,
}

impl FixedClock {
    pub const DEFAULT_TICK_RATE: u32 = 60;

    pub fn new(tick_rate: u32) -> Self {
        assert!(tick_rate > 0, "a tick rate of 0 Hz never advances");
        Self { tick_rate, accumulated: 0.0, max_ticks_per_frame: (tick_rate / 4).max(1) }
    }

    pub fn tick_rate(&self) -> u32 {
        self.tick_rate
    }

    /// Seconds per tick.
    pub fn tick_seconds(&self) -> f32 {
        1.0 / self.tick_rate as f32
    }

    /// Adds a frame of `seconds` and returns how many ticks to simulate now.
    pub fn advance(&mut self, seconds: f32) -> u32 {
        let seconds = if seconds.is_finite() { seconds.max(0.0) } else { 0.0 };
        self.accumulated += seconds as f64 * self.tick_rate as f64;
        let ticks = self.accumulated.floor();
        let run = ticks.min(self.max_ticks_per_frame as f64);
        // Time beyond the cap is dropped, not owed: the next frame starts fresh.
        self.accumulated = if ticks > run { 0.0 } else { self.accumulated - run };
        run as u32
    }

    /// How far the present lies between the last simulated tick (0) and the next one (1): the
    /// renderer interpolates the two latest states by this much.
    pub fn alpha(&self) -> f32 {
        self.accumulated.clamp(0.0, 1.0) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_ticks_and_a_remainder() {
        let mut c = FixedClock::new(60);
        assert_eq!(c.advance(1.0 / 120.0), 0);
        assert!((c.alpha() - 0.5).abs() < 1e-6);
        assert_eq!(c.advance(1.0 / 120.0), 1);
        assert!(c.alpha() < 1e-6);
        // A second of 144 Hz frames runs exactly 60 ticks.
        let mut c = FixedClock::new(60);
        let ticks: u32 = (0..144).map(|_| c.advance(1.0 / 144.0)).sum();
        assert!((59..=60).contains(&ticks), "{ticks}");
    }

    #[test]
    fn a_stall_is_capped_and_forgotten() {
        let mut c = FixedClock::new(60);
        assert_eq!(c.advance(5.0), 15);
        assert_eq!(c.advance(0.0), 0);
        assert_eq!(c.advance(f32::NAN), 0);
        assert_eq!(c.advance(-1.0), 0);
    }
}
