//! Hand-built test levels and a loop to run the controller.
#![allow(dead_code)] // each test binary uses part of this

use glam::Vec3;
use physics::{CharacterBody, CharacterConfig, CharacterController, CharacterMove, LevelCollision};

pub const DT: f32 = 1.0 / 60.0;

/// Triangles for a level, built like the shipped one: every box has its own 24 vertices.
#[derive(Default)]
pub struct Geometry {
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
}

impl Geometry {
    /// A 100 m × 100 m floor slab whose top is y = 0.
    pub fn with_floor() -> Self {
        let mut g = Self::default();
        g.cuboid(Vec3::new(-50.0, -0.2, -50.0), Vec3::new(50.0, 0.0, 50.0));
        g
    }

    /// A convex planar polygon, corners in order.
    pub fn face(&mut self, corners: &[Vec3]) -> &mut Self {
        let base = self.positions.len() as u32;
        self.positions.extend_from_slice(corners);
        for i in 1..corners.len() as u32 - 1 {
            self.triangles.push([base, base + i, base + i + 1]);
        }
        self
    }

    /// An axis-aligned box: six faces of four vertices each, outward winding.
    pub fn cuboid(&mut self, min: Vec3, max: Vec3) -> &mut Self {
        let p = |x: bool, y: bool, z: bool| {
            Vec3::new(if x { max.x } else { min.x }, if y { max.y } else { min.y }, if z { max.z } else { min.z })
        };
        let (f, t) = (false, true);
        self.face(&[p(f, f, f), p(f, f, t), p(f, t, t), p(f, t, f)]); // -X
        self.face(&[p(t, f, f), p(t, t, f), p(t, t, t), p(t, f, t)]); // +X
        self.face(&[p(f, f, f), p(t, f, f), p(t, f, t), p(f, f, t)]); // -Y
        self.face(&[p(f, t, f), p(f, t, t), p(t, t, t), p(t, t, f)]); // +Y
        self.face(&[p(f, f, f), p(f, t, f), p(t, t, f), p(t, f, f)]); // -Z
        self.face(&[p(f, f, t), p(t, f, t), p(t, t, t), p(f, t, t)]) // +Z
    }

    /// A wedge over `min..max` whose top rises from `min.y` at `min.x` to `max.y` at `max.x`.
    pub fn ramp_up_x(&mut self, min: Vec3, max: Vec3) -> &mut Self {
        let (x0, x1, y0, y1, z0, z1) = (min.x, max.x, min.y, max.y, min.z, max.z);
        self.face(&[Vec3::new(x0, y0, z0), Vec3::new(x0, y0, z1), Vec3::new(x1, y1, z1), Vec3::new(x1, y1, z0)]);
        self.face(&[Vec3::new(x0, y0, z0), Vec3::new(x1, y0, z0), Vec3::new(x1, y0, z1), Vec3::new(x0, y0, z1)]);
        self.face(&[Vec3::new(x1, y0, z0), Vec3::new(x1, y1, z0), Vec3::new(x1, y1, z1), Vec3::new(x1, y0, z1)]);
        self.face(&[Vec3::new(x0, y0, z0), Vec3::new(x1, y1, z0), Vec3::new(x1, y0, z0)]);
        self.face(&[Vec3::new(x0, y0, z1), Vec3::new(x1, y0, z1), Vec3::new(x1, y1, z1)])
    }

    pub fn build(&self) -> LevelCollision {
        LevelCollision::from_triangles(&self.positions, &self.triangles).expect("valid test geometry")
    }
}

/// A controller with the default config.
pub fn controller() -> CharacterController {
    CharacterController::new(CharacterConfig::default())
}

/// Walking at `speed` m/s along `dir` (normalised here).
pub fn walk(dir: Vec3, speed: f32) -> CharacterMove {
    CharacterMove { wish_velocity: dir.normalize() * speed, ..CharacterMove::default() }
}

/// Steps `ticks` times with the same move, calling `each` after every tick.
pub fn run(
    ctrl: &CharacterController,
    level: &LevelCollision,
    body: &mut CharacterBody,
    mv: CharacterMove,
    ticks: usize,
    mut each: impl FnMut(usize, &CharacterBody),
) {
    for tick in 0..ticks {
        ctrl.step(level, body, &mv, DT);
        each(tick, body);
    }
}

/// A body standing still on the floor at `feet` (after settling for a few ticks).
pub fn settled(ctrl: &CharacterController, level: &LevelCollision, feet: Vec3) -> CharacterBody {
    let mut body = CharacterBody::standing_at(feet);
    run(ctrl, level, &mut body, CharacterMove::default(), 5, |_, _| {});
    assert!(body.grounded, "should stand on the floor at {feet}: {body:?}");
    body
}
