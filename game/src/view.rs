//! What the renderer sees of the simulation: the two latest tick states blended by the clock's
//! fraction, so motion is smooth at any frame rate while the simulation stays at its fixed tick.

use engine::camera::yaw_pitch_rotation;
use engine::frame::ViewState;
use engine::gpu::Gpu;
use engine::renderer::Renderer;
use engine::scene::Level;
use engine::start_view::{initial_view, ViewOverrides};

use crate::actors::ActorMeshes;
use crate::sim::command::radians;
use crate::sim::{weapon, LevelEntities, WorldState};

/// The muzzle flash at its brightest: radiant intensity, W/sr (warm white). For comparison the
/// cellar's headlamp peaks at 40 W/sr; the flash lights the whole room about as brightly for
/// its 50 ms.
pub const FLASH_INTENSITY: [f32; 3] = [36.0, 26.0, 13.0];

/// The frame's [`ViewState`] built from world states.
pub struct WorldView {
    pub view: ViewState,
    /// The level's headlamp power; the lamp's battery flicker scales it.
    lamp_power: f32,
    /// Added once the renderer exists; without them only the camera and lights follow the state.
    meshes: Option<ActorMeshes>,
}

impl WorldView {
    pub fn new(level: &Level) -> Self {
        let view = initial_view(level, &ViewOverrides::default());
        Self { lamp_power: view.headlamp.profile.power, view, meshes: None }
    }

    /// Adds the actors' meshes to the renderer that will draw this view.
    pub fn add_meshes(&mut self, renderer: &mut Renderer, gpu: &Gpu) {
        self.meshes = Some(ActorMeshes::add_to(renderer, gpu));
    }

    /// The view between `prev` (t = 0) and `cur` (t = 1). `extra_turn` (angle units) is mouse
    /// motion not yet in any tick: adding it keeps mouse look immediate in a live game (0 when
    /// replaying). `time` animates idle things only.
    pub fn update(
        &mut self,
        entities: &LevelEntities,
        prev: &WorldState,
        cur: &WorldState,
        t: f32,
        extra_turn: (f32, f32),
        time: f32,
    ) {
        let view = &mut self.view;
        let (p, c) = (&prev.player, &cur.player);
        view.camera.position = p.eye().lerp(c.eye(), t);
        let yaw = yaw_between(p.yaw, c.yaw, t) + extra_turn.0;
        let pitch = (p.pitch as f32 + (c.pitch - p.pitch) as f32 * t + extra_turn.1)
            .clamp(-(crate::sim::player::MAX_PITCH as f32), crate::sim::player::MAX_PITCH as f32);
        view.camera.rotation = yaw_pitch_rotation(radians(yaw), radians(pitch));
        let lamp = &cur.lamp;
        view.headlamp.on = lamp.brightness() > 0.0;
        view.headlamp.profile.power = self.lamp_power * lamp.brightness();
        view.headlamp.attached = lamp.attached;
        if !lamp.attached {
            view.headlamp.position = lamp.drawn_position(&prev.lamp, t);
            view.headlamp.rotation = yaw_pitch_rotation(radians(lamp.yaw as f32), radians(lamp.pitch as f32));
        }
        let flash = cur.weapon.flash as f32 / weapon::FLASH_TICKS as f32;
        view.camera_flash = FLASH_INTENSITY.map(|i| i * flash);
        view.instances = match &self.meshes {
            Some(m) => m.instances(entities, prev, cur, t, time),
            None => Vec::new(),
        };
    }

    /// The view exactly at one tick (snapshots, tests).
    pub fn at(&mut self, entities: &LevelEntities, state: &WorldState) {
        self.update(entities, state, state, 1.0, (0.0, 0.0), state.tick as f32 / 60.0);
    }
}

/// Blends yaw the short way round.
fn yaw_between(a: u16, b: u16, t: f32) -> f32 {
    a as f32 + (b.wrapping_sub(a) as i16) as f32 * t
}
