//! The game in a window: live play, live play while recording, or watching a replay. All three
//! run the same fixed-tick simulation; they differ only in where each tick's command comes from.
//! F1 toggles the GI settings panel; opening it releases the mouse so its sliders can be used
//! at once, and a click on the 3D view captures the mouse again (the panel stays open).

use std::path::Path;

use engine::clock::FixedClock;
use engine::egui;
use engine::frame::ViewState;
use engine::gpu::Gpu;
use engine::input::{Input, KeyCode};
use engine::renderer::Renderer;
use engine::scene::Level;
use engine::start_view::{initial_view, ViewOverrides};
use engine::window::WindowApp;
use plugin_gi::{GiHandle, GiSettings};

use crate::command_sampler::{CommandSampler, MOUSE_SENSITIVITY};
use crate::recording::{Divergence, LoadedReplay, Recorder};
use crate::settings_panel;
use crate::sim::{Simulation, WorldState};

/// A recording is also written every this many ticks (10 s), so a crash or a killed process
/// loses at most the last few seconds.
pub const AUTOSAVE_TICKS: u32 = 600;

/// `headlamp play`.
pub fn run(level_path: &Path) -> anyhow::Result<()> {
    let level = engine::scene::load_level(level_path)?;
    let collision = crate::sim::level_collision(&level)?;
    let sim = Simulation::new(&level, collision, FixedClock::DEFAULT_TICK_RATE, crate::recording::fresh_seed());
    let mut app = GameWindow::new(level, sim, TickSource::live(None), GiSettings::default());
    engine::window::run("Headlamp", &mut app)
}

/// Where ticks come from.
pub enum TickSource {
    /// The keyboard and mouse, optionally recorded.
    Live { sampler: CommandSampler, recorder: Option<Recorder> },
    /// A replay's commands, checked against its hashes as they run.
    Replay { replay: Box<LoadedReplay>, next: usize, diverged: Option<Divergence> },
}

impl TickSource {
    pub fn live(recorder: Option<Recorder>) -> Self {
        TickSource::Live { sampler: CommandSampler::new(MOUSE_SENSITIVITY), recorder }
    }
}

pub struct GameWindow {
    level: Level,
    pub sim: Simulation,
    /// The state one tick before `sim.state`: frames are drawn between the two.
    prev: WorldState,
    clock: FixedClock,
    view: ViewState,
    pub source: TickSource,
    renderer: Option<Renderer>,
    /// The GI settings as the panel (F1) leaves them, pushed to the plugin on every change.
    pub gi_settings: GiSettings,
    gi: Option<GiHandle>,
    panel_open: bool,
    release_mouse: bool,
}

impl GameWindow {
    pub fn new(level: Level, sim: Simulation, source: TickSource, gi_settings: GiSettings) -> Self {
        let mut view = initial_view(&level, &ViewOverrides::default());
        crate::view::at(&mut view, &sim.state);
        Self {
            prev: sim.state,
            clock: FixedClock::new(sim.tick_rate()),
            level,
            sim,
            view,
            source,
            renderer: None,
            gi_settings,
            gi: None,
            panel_open: false,
            release_mouse: false,
        }
    }

    /// Runs the ticks this frame's time pays for.
    fn run_ticks(&mut self, input: &Input, dt: f32) {
        if let TickSource::Live { sampler, .. } = &mut self.source {
            sampler.gather(input);
        }
        for _ in 0..self.clock.advance(dt) {
            let before = self.sim.state;
            match &mut self.source {
                TickSource::Live { sampler, recorder } => {
                    let cmd = sampler.next_command(input);
                    self.sim.step(&cmd);
                    if let Some(r) = recorder {
                        r.push(&cmd, &self.sim.state);
                        if r.tick_count() % AUTOSAVE_TICKS == 0 {
                            if let Err(e) = r.save() {
                                log::error!("{e:#}");
                            }
                        }
                    }
                }
                TickSource::Replay { replay, next, diverged } => {
                    if *next >= replay.commands.len() {
                        // Finished: hold the last state instead of drawing between two.
                        self.prev = self.sim.state;
                        break;
                    }
                    if let Err(d) = replay.step_checked(&mut self.sim, *next) {
                        log::error!("{}: {d}", replay.path.display());
                        diverged.get_or_insert(d);
                    }
                    *next += 1;
                }
            }
            self.prev = before;
        }
    }

    fn status(&self) -> String {
        let tick = self.sim.state.tick;
        match &self.source {
            TickSource::Live { recorder: Some(r), .. } => {
                format!("REC {} — tick {tick} (close the window to save)", r.path.display())
            }
            TickSource::Live { recorder: None, .. } => String::new(),
            TickSource::Replay { replay, diverged: Some(d), .. } => format!("{}: {d}", replay.path.display()),
            TickSource::Replay { replay, next, .. } => {
                let end = if *next >= replay.commands.len() { " — finished" } else { "" };
                format!("REPLAY {} — tick {tick} of {}{end}", replay.path.display(), replay.commands.len())
            }
        }
    }
}

impl WindowApp for GameWindow {
    fn init(&mut self, gpu: &Gpu, _format: engine::wgpu::TextureFormat) -> anyhow::Result<()> {
        let (plugins, gi) = crate::plugins(self.gi_settings.clone());
        self.renderer = Some(Renderer::new(gpu, &self.level.scene, plugins)?);
        self.gi = Some(gi);
        Ok(())
    }

    fn update(&mut self, input: &Input, dt: f32) {
        self.run_ticks(input, dt);
        let pending = match &self.source {
            TickSource::Live { sampler, .. } => sampler.pending_look(),
            TickSource::Replay { .. } => (0.0, 0.0),
        };
        crate::view::apply(&mut self.view, &self.prev, &self.sim.state, self.clock.alpha(), pending);
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
        let status = self.status();
        if !status.is_empty() {
            egui::Area::new(egui::Id::unique("headlamp status"))
                .anchor(egui::Align2::RIGHT_TOP, egui::vec2(-8.0, 8.0))
                .interactable(false)
                .show(ctx, |ui| {
                    egui::Frame::NONE
                        .fill(egui::Color32::from_black_alpha(150))
                        .inner_margin(egui::Margin::symmetric(6, 3))
                        .show(ui, |ui| ui.label(egui::RichText::new(status).color(egui::Color32::from_gray(230))));
                });
        }
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

    fn app() -> GameWindow {
        let level = engine::scene::load_level(&crate::default_level()).unwrap();
        let sim = Simulation::new(&level, crate::sim::level_collision(&level).unwrap(), 60, 1);
        GameWindow::new(level, sim, TickSource::live(None), GiSettings::default())
    }

    /// A change made in the panel reaches the GI plugin that renders the next frame.
    #[test]
    fn the_settings_panel_drives_the_gi_plugin() {
        let plugin = plugin_gi::GiPlugin::new(GiSettings::default());
        let gi = plugin.handle();
        let mut app = app();
        app.gi = Some(gi.clone());
        app.panel_open = true;
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

    /// Frames of any length run the ticks their time pays for, and the view sits between the
    /// two latest states.
    #[test]
    fn frames_run_fixed_ticks_and_draw_between_them() {
        let mut app = app();
        let input = Input::default();
        app.update(&input, 1.0 / 144.0);
        assert_eq!(app.sim.state.tick, 0, "less than a tick of time runs no tick");
        for _ in 0..143 {
            app.update(&input, 1.0 / 144.0);
        }
        assert!((59..=60).contains(&app.sim.state.tick), "a second runs 60 ticks, not {}", app.sim.state.tick);
        let (a, b) = (app.prev.player.eye(), app.sim.state.player.eye());
        let eye = app.view.camera.position;
        assert!(eye.distance(a) <= a.distance(b) + 1e-5 && eye.distance(b) <= a.distance(b) + 1e-5);
    }

    /// Watching a replay in the window runs exactly its ticks, ends on its last state, and
    /// notices (and shows) a command that no longer gives the recorded state.
    #[test]
    fn watching_a_replay_runs_its_ticks_and_notices_divergence() {
        let level_path = crate::default_level();
        let level = engine::scene::load_level(&level_path).unwrap();
        let commands = crate::script::parse("30 forward\n10 turn 20\n", Path::new("t.txt")).unwrap();
        let path = std::env::temp_dir().join(format!("headlamp-watch-{}.replay", std::process::id()));
        let gi = GiSettings::default();
        let rec = crate::replay_cmd::record_commands(&level, &level_path, &commands, 1, &gi, path.clone()).unwrap();
        rec.save().unwrap();
        let watch = |tamper: bool| {
            let mut loaded = LoadedReplay::open(&path, Some(&level_path)).unwrap();
            if tamper {
                loaded.commands[5].forward = -127;
            }
            let sim = loaded.simulation().unwrap();
            let source = TickSource::Replay { replay: Box::new(loaded), next: 0, diverged: None };
            let mut app = GameWindow::new(level.clone(), sim, source, gi.clone());
            for _ in 0..60 {
                app.update(&Input::default(), 0.05);
            }
            app
        };
        let app = watch(false);
        assert_eq!(app.sim.state.tick, 40);
        assert_eq!(app.sim.state.hash(), rec.last_hash());
        assert_eq!(app.prev, app.sim.state, "a finished replay holds its last state");
        assert!(matches!(app.source, TickSource::Replay { diverged: None, .. }));
        assert!(app.status().ends_with("finished"), "{}", app.status());
        let app = watch(true);
        assert!(matches!(app.source, TickSource::Replay { diverged: Some(Divergence { tick: 6, .. }), .. }));
        assert!(app.status().contains("diverged at tick 6"), "{}", app.status());
        let _ = std::fs::remove_file(&path);
    }
}
