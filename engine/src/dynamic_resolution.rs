//! Dynamic resolution: the render scale that holds a frame rate, chosen from the frame times
//! as they come. A CPU adapter (lavapipe) renders the view at a cost nearly proportional to its
//! pixels, and machines differ by several times; a fixed scale is either too slow on one or
//! needlessly blurry on another.
//!
//! Each window of [`DynamicResolution::WINDOW`] frames gives a median frame time. Above the
//! target, the scale shrinks as if the whole frame cost were in the view's pixels (time ∝
//! scale²), which under-corrects while part of the frame is fixed, so it approaches the target
//! from above in a few windows. Well under the target it grows one step, but only if that same
//! model (pessimistic for growth) says the target still holds: no oscillation.

/// The render scale that holds a target frame time.
#[derive(Clone, Debug)]
pub struct DynamicResolution {
    target_s: f32,
    min: f32,
    max: f32,
    scale: f32,
    window: Vec<f32>,
    /// Frames still ignored after a change (the change's own frame reallocates the targets).
    settling: u32,
    /// Windows in a row that were too slow at the floor: the scale alone cannot hold the target.
    starved_windows: u32,
}

impl DynamicResolution {
    /// Frames per decision.
    pub const WINDOW: usize = 12;
    /// The render scale never drops below this (the renderer's own floor).
    pub const MIN_SCALE: f32 = 0.25;
    /// A frame slower than this is a hitch (a level loading, the window moved), not a load.
    const HITCH_S: f32 = 0.5;
    /// The scale grows by this much at a time.
    const STEP_UP: f32 = 0.05;
    /// Frames ignored after a change.
    const SETTLE_FRAMES: u32 = 3;
    /// Shrink when the median frame exceeds the target by this factor…
    const SLOW: f32 = 1.05;
    /// …and grow only while the predicted frame stays under the target by this one.
    const ROOM: f32 = 0.95;
    /// Slow windows in a row at the floor before [`Self::starved`].
    pub const STARVED_WINDOWS: u32 = 3;

    /// Holds `target_fps` with a render scale between [`Self::MIN_SCALE`] and `max_scale`,
    /// starting at `max_scale`.
    pub fn new(target_fps: f32, max_scale: f32) -> Self {
        let max = if max_scale.is_finite() { max_scale.clamp(Self::MIN_SCALE, 1.0) } else { 1.0 };
        let fps = if target_fps.is_finite() && target_fps > 0.0 { target_fps } else { 30.0 };
        Self {
            target_s: 1.0 / fps,
            min: Self::MIN_SCALE,
            max,
            scale: max,
            window: Vec::with_capacity(Self::WINDOW),
            settling: 0,
            starved_windows: 0,
        }
    }

    /// Whether the target has not held for [`Self::STARVED_WINDOWS`] windows in a row with the
    /// scale at its floor: what else the frame costs must give (the caller's to choose).
    pub fn starved(&self) -> bool {
        self.starved_windows >= Self::STARVED_WINDOWS
    }

    /// The scale to render at now.
    pub fn scale(&self) -> f32 {
        self.scale
    }

    /// The highest scale it uses.
    pub fn max_scale(&self) -> f32 {
        self.max
    }

    /// The frame rate it holds.
    pub fn target_fps(&self) -> f32 {
        1.0 / self.target_s
    }

    /// One frame took `dt` seconds; returns the new scale when it changes.
    pub fn push(&mut self, dt: f32) -> Option<f32> {
        if !(dt.is_finite() && dt > 0.0 && dt < Self::HITCH_S) {
            return None;
        }
        if self.settling > 0 {
            self.settling -= 1;
            return None;
        }
        self.window.push(dt);
        if self.window.len() < Self::WINDOW {
            return None;
        }
        self.window.sort_by(f32::total_cmp);
        let median = self.window[Self::WINDOW / 2];
        self.window.clear();
        let slow_at_floor = self.scale <= self.min && median > self.target_s * Self::SLOW;
        self.starved_windows = if slow_at_floor { self.starved_windows + 1 } else { 0 };
        let wanted = if median > self.target_s * Self::SLOW {
            self.scale * (self.target_s / median).sqrt()
        } else {
            let up = (self.scale + Self::STEP_UP).min(self.max);
            let predicted = median * (up / self.scale).powi(2);
            if predicted < self.target_s * Self::ROOM {
                up
            } else {
                self.scale
            }
        };
        // Hundredths: a change of less than that is not worth reallocating the targets for.
        let next = ((wanted * 100.0).floor() / 100.0).clamp(self.min, self.max);
        if (next - self.scale).abs() < 0.01 {
            return None;
        }
        self.scale = next;
        self.settling = Self::SETTLE_FRAMES;
        Some(next)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame costing `fixed` seconds plus `per_area` × scale².
    fn frame(fixed: f32, per_area: f32, scale: f32) -> f32 {
        fixed + per_area * scale * scale
    }

    fn run(d: &mut DynamicResolution, frames: usize, cost: impl Fn(f32) -> f32) -> Vec<f32> {
        let mut changes = Vec::new();
        for _ in 0..frames {
            let dt = cost(d.scale());
            if let Some(s) = d.push(dt) {
                changes.push(s);
            }
        }
        changes
    }

    #[test]
    fn a_slow_frame_settles_at_the_target_from_above_and_stays() {
        // 30 ms fixed, 200 ms for a full-scale view: 20 fps needs scale ≈ 0.35.
        let cost = |s| frame(0.030, 0.200, s);
        let mut d = DynamicResolution::new(20.0, 1.0);
        let changes = run(&mut d, 300, cost);
        let settled = d.scale();
        assert!(cost(settled) <= 0.05 * 1.05, "settled at {settled}: {} s a frame", cost(settled));
        assert!(cost(settled + 0.05) > 0.05 * 0.95, "{settled} leaves room: it should have grown");
        assert!(changes.len() <= 8, "too many changes: {changes:?}");
        // Once settled, no change for as long again.
        assert!(run(&mut d, 300, cost).is_empty());
    }

    #[test]
    fn room_to_spare_grows_back_to_the_maximum_but_not_beyond() {
        let mut d = DynamicResolution::new(20.0, 0.6);
        run(&mut d, 200, |s| frame(0.030, 0.400, s));
        assert!(d.scale() < 0.4, "{}", d.scale());
        // The scene got cheaper (a small room): back up to the player's maximum.
        run(&mut d, 400, |s| frame(0.010, 0.050, s));
        assert_eq!(d.scale(), 0.6);
    }

    #[test]
    fn the_scale_stays_within_its_floor_and_hitches_are_ignored() {
        let mut d = DynamicResolution::new(60.0, 1.0);
        run(&mut d, 400, |s| frame(0.100, 0.100, s));
        assert_eq!(d.scale(), DynamicResolution::MIN_SCALE, "the floor holds however slow");

        let mut d = DynamicResolution::new(20.0, 0.8);
        let fast = 0.030;
        for i in 0..120 {
            // A hitch every fourth frame (loading) and garbage times are not a slow machine.
            let dt = if i % 4 == 0 {
                2.0
            } else if i % 7 == 0 {
                f32::NAN
            } else {
                fast
            };
            assert_eq!(d.push(dt), None);
        }
        assert_eq!(d.scale(), 0.8);
    }

    #[test]
    fn too_slow_at_the_floor_is_starved_and_a_lighter_frame_is_not() {
        let mut d = DynamicResolution::new(20.0, 0.5);
        run(&mut d, 60, |s| frame(0.040, 0.100, s));
        assert!(!d.starved(), "20 fps holds at some scale above the floor: {}", d.scale());
        // 70 ms even at the floor: the scale cannot hold 20 fps.
        let mut d = DynamicResolution::new(20.0, 0.5);
        run(&mut d, 36, |s| frame(0.070, 0.100, s));
        assert!(!d.starved(), "not yet at the floor long enough: {}", d.scale());
        run(&mut d, 200, |s| frame(0.070, 0.100, s));
        assert_eq!(d.scale(), DynamicResolution::MIN_SCALE);
        assert!(d.starved());
        // The caller lightened the frame: no longer starved once a window of lighter frames is in.
        run(&mut d, 2 * DynamicResolution::WINDOW, |s| frame(0.030, 0.100, s));
        assert!(!d.starved());
    }

    #[test]
    fn bad_arguments_give_a_usable_controller() {
        let d = DynamicResolution::new(f32::NAN, f32::INFINITY);
        assert_eq!(d.scale(), 1.0);
        assert!((d.target_fps() - 30.0).abs() < 1e-3);
        let d = DynamicResolution::new(-5.0, 0.1);
        assert_eq!(d.scale(), 0.25);
        assert!((d.target_fps() - 30.0).abs() < 1e-3);
    }
}
