//! Where the player starts: `level.toml`'s `[spawn]`.

use glam::Vec3;

/// Height of the eyes above the feet, metres (the spawn position is the feet).
pub const DEFAULT_EYE_HEIGHT: f32 = 1.6;

/// Where the player starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spawn {
    /// Feet position, metres.
    pub position: Vec3,
    /// Radians; 0 looks down -Z, positive turns left (counter-clockwise seen from above).
    pub yaw: f32,
    /// Radians; positive looks up.
    pub pitch: f32,
}

impl Spawn {
    /// The eye position: feet raised by [`DEFAULT_EYE_HEIGHT`].
    pub fn eye(&self) -> Vec3 {
        self.position + Vec3::Y * DEFAULT_EYE_HEIGHT
    }

    /// Unit view direction for `yaw` and `pitch`.
    pub fn forward(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        Vec3::new(-sy * cp, sp, -cy * cp)
    }
}
