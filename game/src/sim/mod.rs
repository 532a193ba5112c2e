//! The deterministic game simulation: a fixed tick consumes one [`TickCommand`] and advances
//! the world. It reads no clock (the tick length is fixed), draws randomness only from its
//! seeded [`Rng`], and iterates only in fixed orders, so the same commands from the same start
//! give the same [`WorldState`] bit for bit; [`WorldState::hash`] proves it tick by tick.

pub mod command;
pub mod lamp;
pub mod player;
pub mod rng;

use std::sync::Arc;

use glam::Vec3;
use physics::{CharacterConfig, CharacterController, LevelCollision};
use scene::Level;

pub use command::TickCommand;
pub use lamp::Lamp;
pub use player::Player;
pub use rng::Rng;

/// Everything that changes from tick to tick. The level's geometry is not here: it is fixed,
/// and the replay header pins it by content hash.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldState {
    /// Ticks simulated so far.
    pub tick: u32,
    pub player: Player,
    pub lamp: Lamp,
    pub rng: Rng,
}

impl WorldState {
    /// 64-bit FNV-1a over every field's exact bits, in declaration order.
    pub fn hash(&self) -> u64 {
        let mut h = scene::Fnv1a::default();
        let f32s = |h: &mut scene::Fnv1a, vs: &[f32]| vs.iter().for_each(|v| h.write(&v.to_bits().to_le_bytes()));
        h.write(&self.tick.to_le_bytes());
        let p = &self.player;
        f32s(&mut h, &p.body.position.to_array());
        f32s(&mut h, &p.body.velocity.to_array());
        h.write(&[p.body.grounded as u8, p.body.crouching as u8]);
        h.write(&p.yaw.to_le_bytes());
        h.write(&p.pitch.to_le_bytes());
        f32s(&mut h, &[p.eye_height]);
        let l = &self.lamp;
        h.write(&[l.on as u8, l.attached as u8]);
        f32s(&mut h, &l.position.to_array());
        h.write(&l.yaw.to_le_bytes());
        h.write(&l.pitch.to_le_bytes());
        h.write(&self.rng.state().to_le_bytes());
        h.finish()
    }
}

/// The world and the fixed things it is simulated against.
pub struct Simulation {
    pub state: WorldState,
    collision: Arc<LevelCollision>,
    controller: CharacterController,
    tick_rate: u32,
}

impl Simulation {
    /// The level as it starts: the player at the spawn (or, for a bare scene file, below the
    /// first view's eye), lamp on and attached.
    pub fn new(level: &Level, collision: Arc<LevelCollision>, tick_rate: u32, seed: u64) -> Self {
        let config = CharacterConfig::default();
        let (feet, yaw, pitch) = match &level.spawn {
            Some(s) => (s.position, s.yaw, s.pitch),
            None => {
                let camera = engine::start_view::initial_camera(level, &Default::default());
                let f = camera.forward();
                (camera.position - Vec3::Y * scene::DEFAULT_EYE_HEIGHT, (-f.x).atan2(-f.z), f.y.clamp(-1.0, 1.0).asin())
            }
        };
        let units = |radians: f32| command::angle_units(radians).round() as i64;
        let yaw = units(yaw).rem_euclid(65536) as u16;
        let pitch = units(pitch).clamp(-(player::MAX_PITCH as i64), player::MAX_PITCH as i64) as i16;
        let state = WorldState {
            tick: 0,
            player: Player::spawn(feet, yaw, pitch, &config),
            lamp: Lamp::new(),
            rng: Rng::new(seed),
        };
        Self { state, collision, controller: CharacterController::new(config), tick_rate }
    }

    pub fn tick_rate(&self) -> u32 {
        self.tick_rate
    }

    /// Advances one tick.
    pub fn step(&mut self, cmd: &TickCommand) {
        let dt = 1.0 / self.tick_rate as f32;
        let s = &mut self.state;
        let mv = s.player.steer(cmd);
        self.controller.step(&self.collision, &mut s.player.body, &mv, dt);
        s.player.settle_eye(&self.controller.config, dt);
        s.lamp.apply(cmd, &s.player);
        s.tick += 1;
    }
}

/// The collision geometry of a level, built once and shared by every simulation of it.
pub fn level_collision(level: &Level) -> anyhow::Result<Arc<LevelCollision>> {
    LevelCollision::from_scene(&level.scene)
        .map(Arc::new)
        .map_err(|e| anyhow::anyhow!("{}: cannot build collision geometry: {e}", level.scene_path.display()))
}
