//! The camera's fixed, deterministic path through a level, the same on every run.

use std::f32::consts::TAU;

use engine::camera::Camera;
use engine::glam::{Quat, Vec3};
use engine::scene::Level;
use engine::start_view::{framing_camera, DEFAULT_FOV_Y};

/// How far the walk goes from the spawn over the whole run, metres.
const WALK_M: f32 = 3.0;
/// Amplitude of the yaw sweep, degrees.
const SWEEP_DEG: f32 = 60.0;

/// Where the camera is on frame `i` of `n`.
#[derive(Clone, Debug)]
pub enum CameraPath {
    /// From a level's spawn: walk `WALK_M` forward while the yaw sweeps ±`SWEEP_DEG` (one sine
    /// period over the run).
    Walk { eye: Vec3, yaw: f32, pitch: f32, fov_y: f32 },
    /// Without a spawn: one full orbit about the vertical axis through the scene's centre,
    /// starting from the view that frames the whole scene.
    Orbit { centre: Vec3, offset: Vec3, fov_y: f32 },
}

impl CameraPath {
    pub fn for_level(level: &Level) -> Self {
        let fov_y = DEFAULT_FOV_Y;
        if let Some(spawn) = &level.spawn {
            return CameraPath::Walk { eye: spawn.eye(), yaw: spawn.yaw, pitch: spawn.pitch, fov_y };
        }
        let framing = framing_camera(&level.scene, fov_y);
        let bounds = level.scene.bounds();
        let centre = if bounds.is_empty() { Vec3::ZERO } else { bounds.center() };
        CameraPath::Orbit { centre, offset: framing.position - centre, fov_y }
    }

    pub fn camera(&self, i: usize, n: usize) -> Camera {
        let t = i as f32 / n.max(1) as f32;
        match *self {
            CameraPath::Walk { eye, yaw, pitch, fov_y } => {
                let ahead = Vec3::new(-yaw.sin(), 0.0, -yaw.cos());
                let swept = yaw + SWEEP_DEG.to_radians() * (TAU * t).sin();
                Camera::from_yaw_pitch(eye + ahead * (WALK_M * t), swept, pitch, fov_y)
            }
            CameraPath::Orbit { centre, offset, fov_y } => {
                Camera::look_at(centre + Quat::from_rotation_y(TAU * t) * offset, centre, fov_y)
            }
        }
    }

    pub fn describe(&self) -> String {
        match self {
            CameraPath::Walk { .. } => {
                format!("from the spawn, walk {WALK_M} m forward while the yaw sweeps ±{SWEEP_DEG}° (lamp attached)")
            }
            CameraPath::Orbit { .. } => {
                "one orbit about the scene's centre from the framing view (lamp attached)".to_owned()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_walk_starts_at_the_spawn_and_sweeps_sixty_degrees() {
        let path = CameraPath::Walk { eye: Vec3::new(0.0, 1.6, 3.8), yaw: 0.0, pitch: 0.0, fov_y: 1.0 };
        let first = path.camera(0, 60);
        assert!((first.position - Vec3::new(0.0, 1.6, 3.8)).length() < 1e-6);
        assert!((first.forward() - Vec3::NEG_Z).length() < 1e-5);
        // A quarter of the way: yaw +60° (turned left), 0.75 m walked down -Z.
        let quarter = path.camera(15, 60);
        assert!((quarter.position - Vec3::new(0.0, 1.6, 3.05)).length() < 1e-5);
        let f = quarter.forward();
        assert!((f.x + 60f32.to_radians().sin()).abs() < 1e-5 && (f.z + 0.5).abs() < 1e-5, "{f}");
        // The same inputs give the same path.
        assert_eq!(path.camera(7, 60), path.camera(7, 60));
    }

    #[test]
    fn the_orbit_keeps_its_distance_and_looks_at_the_centre() {
        let centre = Vec3::new(1.0, 2.0, 3.0);
        let path = CameraPath::Orbit { centre, offset: Vec3::new(0.0, 1.0, 5.0), fov_y: 1.0 };
        for i in 0..8 {
            let c = path.camera(i, 8);
            assert!(((c.position - centre).length() - 26f32.sqrt()).abs() < 1e-4);
            assert!((c.forward() - (centre - c.position).normalize()).length() < 1e-5);
        }
    }
}
