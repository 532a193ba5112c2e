//! `headlamp play`: the level in a window with a free-fly camera (the game proper comes later).
//! F1 toggles the GI settings panel; opening it releases the mouse so its sliders can be used
//! at once, and a click on the 3D view captures the mouse again (the panel stays open).

use std::path::Path;

use engine::camera::yaw_pitch_rotation;
use engine::egui;
use engine::frame::ViewState;
use engine::gpu::Gpu;
use engine::input::{Input, KeyCode};
use engine::renderer::Renderer;
use engine::scene::Level;
use engine::start_view::{initial_view, ViewOverrides};
use engine::window::WindowApp;
use glam::Vec3;
use plugin_gi::{GiHandle, GiSettings};

use crate::settings_panel;

/// Radians of view rotation per pixel of mouse motion.
const MOUSE_SENSITIVITY: f32 = 0.0025;
const FLY_SPEED: f32 = 4.0;

pub fn run(level_path: &Path) -> anyhow::Result<()> {
    let level = engine::scene::load_level(level_path)?;
    let view = initial_view(&level, &ViewOverrides::default());
    let (yaw, pitch) = yaw_pitch_of(view.camera.forward());
    let app = FreeFly {
        level,
        view,
        yaw,
        pitch,
        renderer: None,
        gi_settings: GiSettings::default(),
        gi: None,
        panel_open: false,
        release_mouse: false,
    };
    engine::window::run("Headlamp", app)
}

pub struct FreeFly {
    level: Level,
    view: ViewState,
    yaw: f32,
    pitch: f32,
    renderer: Option<Renderer>,
    /// The GI settings as the panel (F1) leaves them, pushed to the plugin on every change.
    pub gi_settings: GiSettings,
    gi: Option<GiHandle>,
    panel_open: bool,
    release_mouse: bool,
}

fn yaw_pitch_of(forward: Vec3) -> (f32, f32) {
    let f = forward.normalize();
    ((-f.x).atan2(-f.z), f.y.clamp(-1.0, 1.0).asin())
}

impl WindowApp for FreeFly {
    fn init(&mut self, gpu: &Gpu, _format: engine::wgpu::TextureFormat) -> anyhow::Result<()> {
        let (plugins, gi) = crate::plugins(self.gi_settings.clone());
        self.renderer = Some(Renderer::new(gpu, &self.level.scene, plugins)?);
        self.gi = Some(gi);
        Ok(())
    }

    fn update(&mut self, input: &Input, dt: f32) {
        if input.captured {
            self.yaw -= input.mouse_delta.x * MOUSE_SENSITIVITY;
            self.pitch = (self.pitch - input.mouse_delta.y * MOUSE_SENSITIVITY).clamp(-1.55, 1.55);
        }
        let camera = &mut self.view.camera;
        camera.rotation = yaw_pitch_rotation(self.yaw, self.pitch);
        let (forward, right) = (camera.forward(), camera.rotation * Vec3::X);
        let mut motion = Vec3::ZERO;
        for (key, dir) in [
            (KeyCode::KeyW, forward),
            (KeyCode::KeyS, -forward),
            (KeyCode::KeyD, right),
            (KeyCode::KeyA, -right),
            (KeyCode::Space, Vec3::Y),
            (KeyCode::KeyC, -Vec3::Y),
        ] {
            if input.held(key) {
                motion += dir;
            }
        }
        let speed = if input.held(KeyCode::ShiftLeft) { FLY_SPEED * 3.0 } else { FLY_SPEED };
        camera.position += motion.normalize_or_zero() * speed * dt;
        if input.pressed(KeyCode::KeyF) {
            self.view.headlamp.on = !self.view.headlamp.on;
        }
        // G puts the lamp down where the camera is, looking where it looks, or picks it up.
        if input.pressed(KeyCode::KeyG) {
            if self.view.headlamp.attached {
                self.view.headlamp.detach_at(&self.view.camera);
            } else {
                self.view.headlamp.attached = true;
            }
        }
        if input.pressed(KeyCode::F1) {
            self.panel_open = !self.panel_open;
            self.release_mouse = self.panel_open;
        }
    }

    fn release_mouse_requested(&mut self) -> bool {
        std::mem::take(&mut self.release_mouse)
    }

    fn ui(&mut self, ctx: &egui::Context) {
        settings_panel::hint(ctx);
        if settings_panel::window(ctx, &mut self.panel_open, &mut self.gi_settings) {
            // The GI reads its settings every frame: the change shows on the next one.
            if let Some(gi) = &self.gi {
                gi.set_settings(self.gi_settings.clone());
            }
        }
    }

    fn render(
        &mut self,
        gpu: &Gpu,
        target: &engine::wgpu::Texture,
        view: &engine::wgpu::TextureView,
    ) -> anyhow::Result<()> {
        let renderer = self.renderer.as_mut().expect("init runs before render");
        renderer.render(gpu, &self.view, target, view)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings_panel::egui_harness::{click, input, texts};

    /// A change made in the panel reaches the GI plugin that renders the next frame.
    #[test]
    fn the_settings_panel_drives_the_gi_plugin() {
        let level = engine::scene::load_level(&crate::default_level()).unwrap();
        let view = initial_view(&level, &ViewOverrides::default());
        let plugin = plugin_gi::GiPlugin::new(GiSettings::default());
        let gi = plugin.handle();
        let mut app = FreeFly {
            level,
            view,
            yaw: 0.0,
            pitch: 0.0,
            renderer: None,
            gi_settings: GiSettings::default(),
            gi: Some(gi.clone()),
            panel_open: true,
            release_mouse: false,
        };
        let ctx = egui::Context::default();
        let mut output = None;
        for _ in 0..3 {
            output = Some(ctx.run_ui(input(Vec::new()), |ui| app.ui(ui.ctx())));
        }
        let (_, rect) = texts(&output.unwrap()).into_iter().find(|(t, _)| t == "enabled").expect("the panel is shown");
        assert!(gi.settings().enabled);
        for events in click(rect.center()) {
            let _ = ctx.run_ui(input(events), |ui| app.ui(ui.ctx()));
        }
        assert!(!app.gi_settings.enabled, "the click unticks 'enabled'");
        assert!(!gi.settings().enabled, "the plugin sees the change");
    }
}
