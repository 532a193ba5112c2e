//! What the renderer sees of the simulation: the two latest tick states blended by the clock's
//! fraction, so motion is smooth at any frame rate while the simulation stays at its fixed tick.

use engine::camera::yaw_pitch_rotation;
use engine::frame::ViewState;
use engine::gpu::Gpu;
use engine::renderer::Renderer;
use engine::scene::Level;
use engine::start_view::{initial_view, ViewOverrides};

use crate::actors::ActorMeshes;
use crate::crawler_body::LampLight;
use crate::gun_model::{GunModel, GunPose};
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
    /// The level's exposure, before the player's brightness.
    level_exposure: f32,
    /// The player's brightness (a multiplier of the exposure) and "reduce flashing".
    pub comfort: Comfort,
    /// Added once the renderer exists; without them only the camera and lights follow the state.
    meshes: Option<ActorMeshes>,
    /// The gun in hand, added with the meshes.
    gun: Option<GunModel>,
}

impl WorldView {
    pub fn new(level: &Level) -> Self {
        let view = initial_view(level, &ViewOverrides::default());
        Self {
            lamp_power: view.headlamp.profile.power,
            level_exposure: view.exposure,
            comfort: Comfort::default(),
            view,
            meshes: None,
            gun: None,
        }
    }

    /// Adds the actors' meshes to the renderer that will draw this view.
    pub fn add_meshes(&mut self, renderer: &mut Renderer, gpu: &Gpu) {
        self.meshes = Some(ActorMeshes::add_to(renderer, gpu));
        self.gun = Some(GunModel::add_to(renderer, gpu));
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
        view.exposure = self.level_exposure * self.comfort.exposure_scale;
        let lamp = &cur.lamp;
        view.headlamp.on = lamp.brightness() > 0.0;
        view.headlamp.profile.power = self.lamp_power * self.comfort.flicker(lamp.brightness());
        view.headlamp.attached = lamp.attached;
        if !lamp.attached {
            view.headlamp.position = lamp.drawn_position(&prev.lamp, t);
            view.headlamp.rotation = yaw_pitch_rotation(radians(lamp.yaw as f32), radians(lamp.pitch as f32));
        }
        let flash = cur.weapon.flash as f32 / weapon::FLASH_TICKS as f32;
        view.camera_flash = FLASH_INTENSITY.map(|i| i * self.comfort.flash(flash));
        view.instances = match &self.meshes {
            Some(m) => m.instances(entities, prev, cur, t, time, &LampLight::of(view)),
            None => Vec::new(),
        };
        view.view_models = match &self.gun {
            Some(gun) if c.alive() => {
                let pose = GunPose::lerp(GunPose::of(&prev.weapon), GunPose::of(&cur.weapon), t);
                gun.instances(&view.camera, pose, self.comfort.flashing)
            }
            _ => Vec::new(),
        };
    }

    /// The view exactly at one tick (snapshots, tests).
    pub fn at(&mut self, entities: &LevelEntities, state: &WorldState) {
        self.update(entities, state, state, 1.0, (0.0, 0.0), state.tick as f32 / 60.0);
    }
}

/// What the player chose to see differently: how the picture looks only, never the simulation
/// (replays play the same whatever these are).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comfort {
    /// Multiplies the level's exposure.
    pub exposure_scale: f32,
    /// Keep this fraction of flashes (1: as they are): the low-battery flicker's dips and the
    /// muzzle flash's light.
    pub flashing: f32,
}

impl Default for Comfort {
    fn default() -> Self {
        Self { exposure_scale: 1.0, flashing: 1.0 }
    }
}

impl Comfort {
    /// The player's settings.
    pub fn of(config: &game_ui::Config) -> Self {
        let flashing = if config.reduce_flashing { game_ui::Config::REDUCED_FLASH } else { 1.0 };
        Self { exposure_scale: config.exposure_scale(), flashing }
    }

    /// A lamp brightness (1, dipping in a flicker, 0 when off) with its dips kept to `flashing`.
    fn flicker(self, brightness: f32) -> f32 {
        // Untouched by default: the picture is exactly the simulation's.
        if self.flashing >= 1.0 {
            brightness
        } else if brightness > 0.0 {
            1.0 - (1.0 - brightness) * self.flashing
        } else {
            0.0
        }
    }

    fn flash(self, flash: f32) -> f32 {
        flash * self.flashing
    }
}

/// Blends yaw the short way round.
fn yaw_between(a: u16, b: u16, t: f32) -> f32 {
    a as f32 + (b.wrapping_sub(a) as i16) as f32 * t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config(brightness: f32, reduce_flashing: bool) -> game_ui::Config {
        game_ui::Config { brightness, reduce_flashing, ..game_ui::Config::default() }
    }

    #[test]
    fn brightness_scales_the_exposure_and_reduce_flashing_tames_flicker_and_flash() {
        let level = engine::scene::load_level(&crate::default_level()).unwrap();
        let world = crate::sim::level_world(&level).unwrap();
        let sim = crate::sim::Simulation::new(&level, world, 60, 1);
        let mut state = sim.state.clone();
        state.weapon.flash = weapon::FLASH_TICKS;
        state.lamp.flicker = 0.2;
        let mut view = WorldView::new(&level);
        let exposure = view.view.exposure;
        view.at(sim.entities(), &state);
        let (power, flash) = (view.view.headlamp.profile.power, view.view.camera_flash[0]);
        assert_eq!((power, flash), (view.lamp_power * 0.2, FLASH_INTENSITY[0]), "as the simulation says");

        view.comfort = Comfort::of(&config(1.0, true));
        view.at(sim.entities(), &state);
        assert_eq!(view.view.exposure, exposure * 2.0, "one stop up");
        let dip = 1.0 - view.view.headlamp.profile.power / view.lamp_power;
        assert!(
            (dip - 0.8 * game_ui::Config::REDUCED_FLASH).abs() < 1e-6,
            "the flicker's dip kept to a quarter: {dip}"
        );
        assert!((view.view.camera_flash[0] - FLASH_INTENSITY[0] * game_ui::Config::REDUCED_FLASH).abs() < 1e-4);
        state.lamp.on = false;
        view.at(sim.entities(), &state);
        assert!(!view.view.headlamp.on && view.view.headlamp.profile.power == 0.0, "off stays off");
    }
}
