//! The game in a window: live play (from the main menu), live play while recording, or
//! watching a replay. All three run the same fixed-tick simulation; they differ only in where
//! each tick's command comes from. Menus pause the simulation (no ticks run while one is
//! open), Esc opens the pause menu, F1 the GI panel, F3 the performance overlay.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use engine::camera::CameraProjection;
use engine::clock::FixedClock;
use engine::dynamic_resolution::DynamicResolution;
use engine::egui;
use engine::gamepad::PadButton;
use engine::gpu::Gpu;
use engine::input::{Input, KeyCode};
use engine::renderer::Renderer;
use engine::scene::Level;
use engine::window::WindowApp;
use game_ui::{gi_panel, hud, overlay, Config, FrameRate, HudInfo, MenuAction, Menus, OverlayInfo};
use plugin_gi::GiHandle;

use crate::command_sampler::CommandSampler;
use crate::game_events::Messages;
use crate::level_list::ListedLevel;
use crate::level_watch::FileWatch;
use crate::recording::{Divergence, LoadedReplay, Recorder};
use crate::sim::{lamp, player, weapon, LevelWorld, Outcome, Simulation, WorldState};
use crate::sound::Soundscape;
use crate::view::WorldView;

/// A recording is also written every this many ticks (10 s), so a crash or a killed process
/// loses at most the last few seconds.
pub const AUTOSAVE_TICKS: u32 = 600;
/// After a win or a death the world stays on screen this long before the menu comes up, s.
const GAME_OVER_DELAY: f32 = 1.5;
/// A game starts with the controls shown this long, ticks (8 s).
const CONTROLS_HINT_TICKS: u32 = 480;
/// The F3 overlay reads GPU pass times this often (reading waits for the GPU), frames.
const TIMING_EVERY: u32 = 30;
/// "Reloaded" shows this long after a live reload, s.
const RELOADED_NOTICE: f32 = 2.0;

/// The highest render scale a CPU device starts with; dynamic resolution (holding
/// [`CPU_TARGET_FPS`]) lowers it as far as the machine needs, down to 25 %. Frame costs on
/// lavapipe differ by more than 2× between 2-core VMs (`headlamp bench --size 1280x720
/// --render-scale 0.4 --set gi.min_rows=45`: 25 fps on one, 9.3 on a slower one), so no fixed
/// scale serves both; `bench --target-fps` shows where the controller settles.
pub const CPU_RENDER_SCALE: f32 = 0.5;
/// The frame rate a CPU device's dynamic resolution holds: some margin over 15 fps.
pub const CPU_TARGET_FPS: f32 = 20.0;

/// The rows of indirect light (`gi.min_rows`) dynamic resolution falls back to when even its
/// lowest render scale cannot hold the frame rate: receivers of 8×8 pixels at 640×360 (a
/// slower 2-core VM settles at the floor with these).
pub const STARVED_GI_ROWS: u32 = 45;

/// What the main menu says on a CPU device: the settings that keep it playable, and whether
/// they are the ones in use.
fn cpu_note(adapter: &str, config: &Config) -> String {
    let preset = plugin_gi::GiSettings::cpu_preset();
    let chosen = format!(
        "dynamic resolution holding {CPU_TARGET_FPS:.0} fps (render scale 25 to {:.0} %) and at least {} rows of \
         indirect light (gi.min_rows; {STARVED_GI_ROWS} where even 25 % is too slow)",
        CPU_RENDER_SCALE * 100.0,
        preset.min_rows
    );
    let held = config.dynamic_resolution && config.target_fps >= 15.0 && config.gi.min_rows <= preset.min_rows;
    if !config.gi.enabled || held {
        format!(
            "{adapter} renders on the CPU. For 15 fps or more with global illumination on, Headlamp \
             uses the CPU settings: {chosen}. Settings > Video and F1 change them."
        )
    } else {
        format!(
            "{adapter} renders on the CPU, and these settings are heavier than its defaults \
             ({chosen}), which keep global illumination on at 15 fps or more: set them in \
             Settings > Video and F1."
        )
    }
}

/// Where `headlamp play` begins.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// On the main menu (the brightness screen first, until it has been shown once).
    MainMenu,
    /// In the level at once, as `play --level X` asks (Quake's `+map`); Esc opens the menu.
    InLevel,
}

/// `headlamp play`: the config file loaded (and saved on change), the level's files watched
/// for edits, and the level menu filled from the shipped levels, the user's levels folder and
/// `levels_dirs`.
pub fn run(level_path: &Path, levels_dirs: &[PathBuf], start: Start) -> anyhow::Result<()> {
    let (config, config_path, warning) = user_config();
    let mut app = game_window(level_path, config, config_path, start)?;
    app.open_sound();
    // Loading and checking every level takes a moment: the menu says so meanwhile.
    let dirs = crate::level_list::level_dirs(levels_dirs);
    let (found, listed) = std::sync::mpsc::channel();
    std::thread::spawn(move || found.send(crate::level_list::scan(&dirs)));
    app.listing = Some(listed);
    if let Some(w) = warning {
        app.menus.show_warning(w);
    }
    engine::window::run("Headlamp", &mut app)
}

/// The game's window app for `level_path` with the player's `config` (read from `config_path`,
/// where it is saved), its menus set for `start`, the level's files watched.
pub fn game_window(
    level_path: &Path,
    config: Config,
    config_path: Option<PathBuf>,
    start: Start,
) -> anyhow::Result<GameWindow> {
    let level = engine::scene::load_level(level_path)?;
    let world = crate::sim::level_world(&level)?;
    let sim = Simulation::new(&level, world, FixedClock::DEFAULT_TICK_RATE, crate::recording::fresh_seed());
    let mut app = GameWindow::new(level, sim, TickSource::live(&config, None), config);
    // No file yet: the first run, whose defaults may still follow the device (see `init`).
    app.first_run = config_path.as_ref().is_some_and(|p| !p.exists());
    app.config_path = config_path;
    app.menus = Menus::new();
    match start {
        Start::InLevel => app.menus.playing(),
        // A first start (or the first since the setting came) asks for the brightness first;
        // one that begins in a level leaves it for the next start on the menu.
        Start::MainMenu if !app.config.calibrated => app.menus.calibrate(),
        Start::MainMenu => {}
    }
    app.watch_level(level_path);
    Ok(app)
}

/// The player's settings from their config file, where it is, and a warning to show when the
/// file could not be used (a bad file is kept beside it as `.bad`; the defaults are used).
pub fn user_config() -> (Config, Option<PathBuf>, Option<String>) {
    let path = game_ui::config_path();
    let (config, warning) = match &path {
        Some(path) => Config::load_or_default(path),
        None => (Config::default(), Some("no home directory: settings will not be saved".to_owned())),
    };
    if let Some(w) = &warning {
        log::warn!("{w}");
    }
    (config, path, warning)
}

/// Where ticks come from.
// One per window: the size difference between the variants costs nothing.
#[allow(clippy::large_enum_variant)]
pub enum TickSource {
    /// The keyboard and mouse, optionally recorded.
    Live { sampler: CommandSampler, recorder: Option<Recorder> },
    /// A replay's commands, checked against its hashes as they run.
    Replay { replay: Box<LoadedReplay>, next: usize, diverged: Option<Divergence> },
}

impl TickSource {
    pub fn live(config: &Config, recorder: Option<Recorder>) -> Self {
        let mut sampler = CommandSampler::new(config.radians_per_pixel(), config.invert_y, config.bindings.clone());
        sampler.pad = config.gamepad.clone();
        TickSource::Live { sampler, recorder }
    }
}

pub struct GameWindow {
    level: Level,
    pub sim: Simulation,
    /// The state one tick before `sim.state`: frames are drawn between the two.
    prev: WorldState,
    clock: FixedClock,
    view: WorldView,
    pub source: TickSource,
    renderer: Option<Renderer>,
    gi: Option<GiHandle>,
    pub config: Config,
    /// Where the config is saved when a setting changes (None: not saved, e.g. in tests).
    pub config_path: Option<PathBuf>,
    /// The player has no config file yet: on a CPU device the CPU defaults are chosen for them.
    pub first_run: bool,
    pub menus: Menus,
    /// The input of this frame's `update`, for the menus (the window clears it before `ui`).
    input: Input,
    /// Seconds since the window opened (idle animation only).
    time: f32,
    /// Seconds since the level was won or lost.
    since_outcome: f32,
    messages: Messages,
    /// What the player hears: silent until [`GameWindow::open_sound`] (tests never open it).
    sound: Soundscape,
    frame_rate: FrameRate,
    /// The render scale that holds the target frame rate (`video.dynamic_resolution`).
    resolution: Option<DynamicResolution>,
    ticks_this_frame: u32,
    overlay_open: bool,
    pass_times: Vec<(String, f64)>,
    /// Reflection lights the GI built in the last frame read back (None: not read yet, or GI off).
    reflection_lights: Option<u32>,
    /// Frames drawn since the overlay was opened.
    frames: u32,
    /// A restart or the lamp set down, thrown or picked up since the last frame: the renderer's
    /// history is reset before the next (a new level brings a new renderer).
    light_cut: bool,
    gi_panel_open: bool,
    quit: bool,
    /// The level being played, for live reload (None while watching a replay).
    level_path: Option<PathBuf>,
    /// Its files, polled for edits.
    watch: Option<FileWatch>,
    /// A level loaded and waiting for the next render to swap in.
    next_level: Option<NextLevel>,
    /// The last reload's failure, shown until a reload works.
    reload_error: Option<String>,
    /// When (`time`) the level was last swapped, for a brief notice.
    reloaded_at: Option<f32>,
    /// The level menu's levels, once the scan that finds them is done.
    levels: Vec<ListedLevel>,
    listing: Option<std::sync::mpsc::Receiver<Vec<ListedLevel>>>,
}

/// A level loaded and checked, waiting for the GPU. Defined here, beside the window that holds
/// it, rather than in `level_switch`, which makes and swaps it: this module does not import
/// its own child back.
struct NextLevel {
    path: PathBuf,
    level: Level,
    world: Arc<LevelWorld>,
    /// Live reload keeps the player where they stand and look; a new level starts at its spawn.
    keep_pose: bool,
}

impl GameWindow {
    /// A window on `sim`. Recording and watching a replay start at once; plain play starts on
    /// the screen `menus` shows (`run` sets the main menu).
    pub fn new(level: Level, sim: Simulation, source: TickSource, config: Config) -> Self {
        let mut view = WorldView::new(&level);
        view.view.camera.projection = CameraProjection::Perspective { fov_y: config.fov_deg.to_radians() };
        view.at(sim.entities(), &sim.state);
        let mut menus = Menus::new();
        menus.playing();
        Self {
            prev: sim.state.clone(),
            clock: FixedClock::new(sim.tick_rate()),
            level,
            sim,
            view,
            source,
            renderer: None,
            gi: None,
            config,
            config_path: None,
            first_run: false,
            menus,
            input: Input::default(),
            time: 0.0,
            since_outcome: 0.0,
            messages: Messages::default(),
            sound: Soundscape::silent(),
            frame_rate: FrameRate::new(),
            resolution: None,
            ticks_this_frame: 0,
            overlay_open: false,
            pass_times: Vec::new(),
            reflection_lights: None,
            frames: 0,
            light_cut: false,
            gi_panel_open: false,
            quit: false,
            level_path: None,
            watch: None,
            next_level: None,
            reload_error: None,
            reloaded_at: None,
            levels: Vec::new(),
            listing: None,
        }
    }

    /// Plays sound on the default output device (or, without one, stays silent after one log
    /// line).
    pub fn open_sound(&mut self) {
        self.sound = Soundscape::open(&self.config);
    }

    /// Hands the level menu what the scan found, once it is done.
    fn take_listing(&mut self) {
        let Some(Ok(found)) = self.listing.as_ref().map(|rx| rx.try_recv()) else { return };
        self.listing = None;
        let cards = found
            .iter()
            .map(|l| game_ui::LevelCard {
                name: l.name.clone(),
                description: l.description.clone(),
                location: l.location.clone(),
                error: l.error.clone(),
            })
            .collect();
        self.menus.set_levels(cards);
        self.levels = found;
    }

    /// Runs the ticks this frame's time pays for.
    fn run_ticks(&mut self, input: &Input, dt: f32) {
        if let TickSource::Live { sampler, .. } = &mut self.source {
            sampler.gather(input, dt);
        }
        self.ticks_this_frame = 0;
        for _ in 0..self.clock.advance(dt) {
            let before = self.sim.state.clone();
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
                        self.prev = self.sim.state.clone();
                        break;
                    }
                    if let Err(d) = replay.step_checked(&mut self.sim, *next) {
                        log::error!("{}: {d}", replay.path.display());
                        diverged.get_or_insert(d);
                    }
                    *next += 1;
                }
            }
            self.light_cut |= self.sim.events.iter().any(crate::sim::Event::cuts_the_light);
            self.messages.push_events(&self.sim.events, &self.sim.state, self.config.captions);
            self.sound.hear(&self.sim.events, &self.sim.state, &self.sim.world());
            self.ticks_this_frame += 1;
            self.prev = before;
        }
    }

    /// The level again from the start, with a fresh seed. A recording so far is saved and the
    /// new attempt goes to a new file beside it, so no attempt is lost.
    fn restart(&mut self) {
        let seed = crate::recording::fresh_seed();
        self.sim = Simulation::new(&self.level, self.sim.world(), self.sim.tick_rate(), seed);
        self.prev = self.sim.state.clone();
        self.clock = FixedClock::new(self.sim.tick_rate());
        self.since_outcome = 0.0;
        self.light_cut = true;
        self.messages = Messages::default();
        if let TickSource::Live { sampler, recorder: Some(r) } = &mut self.source {
            sampler.clear();
            if let Err(e) = r.save() {
                log::error!("{e:#}");
            }
            let mut header = r.writer().header().clone();
            header.seed = seed;
            let path = crate::recording::next_attempt_path(&r.path);
            log::info!("recording the new attempt to {}", path.display());
            *r = Recorder::new(header, path);
        }
    }

    /// Dynamic resolution is at its floor and still too slow: fewer rows of indirect light,
    /// once (they do not come back by themselves; F1 sets them).
    fn lighten_gi(&mut self) {
        if self.config.gi.enabled && self.config.gi.min_rows > STARVED_GI_ROWS {
            self.config.gi.min_rows = STARVED_GI_ROWS;
            if let Some(gi) = &self.gi {
                gi.set_settings(self.config.gi.clone());
            }
        }
    }

    fn apply_config(&mut self) {
        if let TickSource::Live { sampler, .. } = &mut self.source {
            sampler.sensitivity = self.config.radians_per_pixel();
            sampler.invert_y = self.config.invert_y;
            sampler.bindings = self.config.bindings.clone();
            sampler.pad = self.config.gamepad.clone();
        }
        self.view.view.camera.projection = CameraProjection::Perspective { fov_y: self.config.fov_deg.to_radians() };
        self.view.comfort = crate::view::Comfort::of(&self.config);
        self.sound.set_volumes(&self.config);
        // Dynamic resolution keeps its scale while its target and ceiling stay (a GI setting
        // changed); a new target or ceiling starts it again from the ceiling.
        let fresh = DynamicResolution::new(self.config.target_fps, self.config.render_scale);
        self.resolution = match self.resolution.take() {
            _ if !self.config.dynamic_resolution => None,
            Some(d) if d.target_fps() == fresh.target_fps() && d.max_scale() == fresh.max_scale() => Some(d),
            _ => Some(fresh),
        };
        if let Some(r) = &mut self.renderer {
            r.set_render_scale(self.resolution.as_ref().map_or(self.config.render_scale, |d| d.scale()));
            r.set_timing(self.overlay_open);
        }
        if let Some(gi) = &self.gi {
            gi.set_settings(self.config.gi.clone());
        }
    }

    fn save_config(&self) {
        if let Some(path) = &self.config_path {
            if let Err(e) = self.config.save(path) {
                log::error!("{e}");
            }
        }
    }

    fn menu_action(&mut self, action: MenuAction) {
        match action {
            MenuAction::Play | MenuAction::Resume => self.menus.playing(),
            MenuAction::PlayLevel(i) => {
                if let Some(listed) = self.levels.get(i).cloned() {
                    self.play_listed(&listed);
                }
            }
            MenuAction::Restart => {
                self.restart();
                self.menus.playing();
            }
            MenuAction::MainMenu => self.restart(),
            MenuAction::Quit => self.quit = true,
            MenuAction::ConfigChanged => {
                self.apply_config();
                self.save_config();
            }
        }
    }

    fn status(&self) -> String {
        let tick = self.sim.state.tick;
        match &self.source {
            TickSource::Live { recorder: Some(r), .. } => {
                format!("REC {} — tick {tick} (quit from the menu to save)", r.path.display())
            }
            TickSource::Live { recorder: None, .. } => String::new(),
            TickSource::Replay { replay, diverged: Some(d), .. } => format!("{}: {d}", replay.path.display()),
            TickSource::Replay { replay, next, .. } => {
                let end = if *next >= replay.commands.len() {
                    format!(" — finished, {}", self.sim.state.outcome.name())
                } else {
                    String::new()
                };
                format!("REPLAY {} — tick {tick} of {}{end}", replay.path.display(), replay.commands.len())
            }
        }
    }

    fn hud(&self) -> HudInfo {
        let s = &self.sim.state;
        let hint = self.lamp_hint();
        HudInfo {
            health: s.player.health,
            max_health: player::MAX_HEALTH,
            ammo_in_magazine: s.weapon.magazine as u32,
            magazine_size: weapon::MAGAZINE as u32,
            ammo_reserve: s.weapon.reserve as u32,
            reloading: s.weapon.reloading > 0,
            battery: s.lamp.battery,
            lamp_on: s.lamp.on,
            lamp_attached: s.lamp.attached,
            enemies_left: s.enemies_left() as u32,
            enemies_total: s.enemies.len() as u32,
            objective: self.sim.entities().rules.objective.clone(),
            hurt: s.player.hurt_ticks as f32 / player::HURT_TICKS as f32,
            hint,
            message: self.messages.current().map(str::to_owned),
            hit: self.messages.hit(),
            crosshair_scale: self.config.crosshair_scale,
        }
    }

    /// What the keys do right now: the controls for the first seconds of a game, then what the
    /// lamp needs.
    fn lamp_hint(&self) -> Option<String> {
        use game_ui::Action;
        let s = &self.sim.state;
        // With a pad connected, its buttons are named.
        let pad = self.input.pad.connected() > 0;
        let key = |a: Action| {
            let label = if pad {
                self.config.gamepad.bindings.get(a).map(|b| game_ui::pad_bindings::button_label(b).to_owned())
            } else {
                self.config.bindings.get(a)[0].map(|b| b.label().into_owned())
            };
            label.unwrap_or_else(|| "(unbound)".into())
        };
        if s.tick < CONTROLS_HINT_TICKS && s.lamp.attached {
            let (moves, menu) = if pad {
                ("Left stick".to_owned(), "Start")
            } else {
                (
                    [Action::MoveForward, Action::StrafeLeft, Action::MoveBack, Action::StrafeRight].map(key).concat(),
                    "Esc",
                )
            };
            return Some(format!(
                "{} move · {} fire · {} reload · {} lamp on/off · {} set lamp down · {} throw lamp · {} menu",
                moves,
                key(Action::Fire),
                key(Action::Reload),
                key(Action::LampToggle),
                key(Action::LampDetach),
                key(Action::LampThrow),
                menu,
            ));
        }
        if !s.lamp.attached {
            return Some(if s.lamp.within_reach(&s.player) {
                format!("{} — pick up the lamp", key(game_ui::Action::LampDetach))
            } else {
                format!("Your lamp lies {:.0} m away", s.lamp.position.distance(s.player.eye()))
            });
        }
        if s.lamp.battery == 0.0 {
            return Some("The battery is flat — find a battery".into());
        }
        if s.lamp.battery < lamp::LOW_BATTERY {
            return Some("Battery low".into());
        }
        None
    }

    fn overlay(&self) -> OverlayInfo {
        OverlayInfo {
            fps: self.frame_rate.fps(),
            frame_ms: self.frame_rate.frame_ms(),
            pass_times_ms: self.pass_times.clone(),
            // Read back with the pass times.
            reflection_lights: self.reflection_lights.unwrap_or(0),
            light_volumes: self.config.gi.method == plugin_gi::Method::Article,
            ticks: self.ticks_this_frame,
            render_scale: self.renderer.as_ref().map_or(self.config.render_scale, |r| r.render_scale()),
            target_fps: self.resolution.as_ref().map(|d| d.target_fps()),
        }
    }

    /// Renders (or fetches from the cache) the picture of level menu card `index`. A level
    /// that cannot be pictured gets a dark one, so it is not tried every frame.
    fn make_thumbnail(&mut self, gpu: &Gpu, index: usize) {
        let Some(listed) = self.levels.get(index) else { return };
        let cache = crate::level_list::thumbnail_cache_dir();
        let img = crate::thumbnail::thumbnail(gpu, listed, &self.config.gi, cache.as_deref()).unwrap_or_else(|e| {
            log::warn!("thumbnail of {}: {e:#}", listed.path.display());
            image::RgbaImage::from_pixel(2, 1, image::Rgba([30, 30, 30, 255]))
        });
        self.menus.set_thumbnail(index, img.width() as usize, img.height() as usize, img.as_raw());
    }

    /// The banner of a failed reload (until one works), or a moment's notice of one that worked.
    fn reload_notice(&self, ctx: &egui::Context) {
        let (text, fill) = match (&self.reload_error, self.reloaded_at) {
            (Some(e), _) => (
                format!(
                    "Reload failed — {e}\nThe last good level keeps running: fix the file and save it, or press F5."
                ),
                egui::Color32::from_rgba_unmultiplied(110, 25, 20, 235),
            ),
            (None, Some(t)) if self.time - t < RELOADED_NOTICE => {
                (format!("Reloaded {}", self.level.name), egui::Color32::from_rgba_unmultiplied(20, 70, 30, 220))
            }
            _ => return,
        };
        egui::Area::new(egui::Id::unique("reload notice"))
            .order(egui::Order::Foreground)
            .anchor(egui::Align2::CENTER_TOP, egui::vec2(0.0, 60.0))
            .interactable(false)
            .show(ctx, |ui| {
                egui::Frame::NONE.fill(fill).corner_radius(6.0).inner_margin(egui::Margin::symmetric(12, 8)).show(
                    ui,
                    |ui| {
                        ui.set_max_width(ctx.content_rect().width() * 0.8);
                        ui.label(egui::RichText::new(text).color(egui::Color32::from_gray(240)));
                    },
                );
            });
    }

    fn corner_label(ctx: &egui::Context, id: &str, offset: egui::Vec2, text: String) {
        egui::Area::new(egui::Id::unique(id)).anchor(egui::Align2::RIGHT_TOP, offset).interactable(false).show(
            ctx,
            |ui| {
                egui::Frame::NONE
                    .fill(egui::Color32::from_black_alpha(150))
                    .inner_margin(egui::Margin::symmetric(6, 3))
                    .show(ui, |ui| ui.label(egui::RichText::new(text).color(egui::Color32::from_gray(230))));
            },
        );
    }
}

impl WindowApp for GameWindow {
    fn init(&mut self, gpu: &Gpu, _format: engine::wgpu::TextureFormat) -> anyhow::Result<()> {
        let (plugins, gi) = crate::plugins(self.config.gi.clone());
        let mut renderer = Renderer::new(gpu, &self.level.scene, plugins)?;
        self.view.add_meshes(&mut renderer, gpu);
        self.renderer = Some(renderer);
        self.gi = Some(gi);
        self.apply_config();
        let adapter = gpu.adapter.get_info();
        if adapter.device_type == engine::wgpu::DeviceType::Cpu {
            if self.first_run {
                self.config.render_scale = CPU_RENDER_SCALE;
                self.config.dynamic_resolution = true;
                self.config.target_fps = CPU_TARGET_FPS;
                self.config.gi = plugin_gi::GiSettings::cpu_preset();
                self.apply_config();
            }
            let note = cpu_note(&adapter.name, &self.config);
            // Once per machine on the menus; Settings > Video says it on every visit.
            let first_note = !self.config.cpu_note_shown;
            if first_note {
                self.menus.show_warning(note.clone());
                self.config.cpu_note_shown = true;
            }
            self.menus.set_device_note(note);
            if self.first_run || first_note {
                self.save_config();
            }
        }
        Ok(())
    }

    fn update(&mut self, input: &Input, dt: f32) {
        self.input = input.clone();
        self.frame_rate.push(dt);
        let mut starved = false;
        if let Some(d) = &mut self.resolution {
            if let (Some(scale), Some(r)) = (d.push(dt), &mut self.renderer) {
                r.set_render_scale(scale);
            }
            starved = d.starved();
        }
        if starved {
            self.lighten_gi();
        }
        self.time += dt;
        if input.pressed(KeyCode::F3) {
            self.overlay_open = !self.overlay_open;
            self.frames = 0;
            if let Some(r) = &mut self.renderer {
                r.set_timing(self.overlay_open);
            }
        }
        if input.pressed(KeyCode::F1) {
            self.gi_panel_open = !self.gi_panel_open;
        }
        self.take_listing();
        self.poll_reload(dt, input.pressed(KeyCode::F5));
        // A finished game's sting plays out behind its menu; a paused one holds every effect.
        self.sound.set_paused(self.menus.is_open() && self.sim.state.outcome == Outcome::Playing);
        if self.menus.is_open() {
            self.ticks_this_frame = 0;
            return; // paused: no time passes in the world
        }
        if input.pressed(KeyCode::Escape) || input.pad.pressed(PadButton::Start) {
            self.menus.pause();
            if let TickSource::Live { sampler, .. } = &mut self.source {
                sampler.clear();
            }
            return;
        }
        self.run_ticks(input, dt);
        self.messages.tick(dt);
        let pending = match &self.source {
            TickSource::Live { sampler, .. } => sampler.pending_look(),
            TickSource::Replay { .. } => (0.0, 0.0),
        };
        let (prev, cur, t) = (&self.prev, &self.sim.state, self.clock.alpha());
        self.view.update(self.sim.entities(), prev, cur, t, pending, self.time);
        let camera = &self.view.view.camera;
        self.sound.listen(camera.position, camera.forward(), &self.sim.state, &self.sim.world());
        if self.sim.state.outcome != Outcome::Playing && matches!(self.source, TickSource::Live { .. }) {
            self.since_outcome += dt;
            if self.since_outcome >= GAME_OVER_DELAY {
                self.menus.game_over(self.sim.state.outcome == Outcome::Won);
            }
        }
    }

    fn capture_wanted(&self) -> Option<bool> {
        Some(!self.menus.is_open() && !self.gi_panel_open)
    }

    fn vsync(&self) -> bool {
        self.config.vsync
    }

    fn wants_exit(&self) -> bool {
        self.quit
    }

    fn ui(&mut self, ctx: &egui::Context) {
        // The HUD's size; menus keep theirs, so any size can be undone from them.
        let zoom = if self.menus.is_open() { 1.0 } else { self.config.hud_scale };
        if ctx.zoom_factor() != zoom {
            ctx.set_zoom_factor(zoom);
        }
        if self.menus.in_game() {
            hud::show(ctx, &self.hud());
        }
        self.reload_notice(ctx);
        let status = self.status();
        if !status.is_empty() {
            Self::corner_label(ctx, "headlamp status", egui::vec2(-8.0, 8.0), status);
        }
        if self.overlay_open {
            overlay::show(ctx, &self.overlay());
        } else if self.config.show_fps {
            Self::corner_label(ctx, "fps", egui::vec2(-8.0, 40.0), format!("{:.0} fps", self.frame_rate.fps()));
        }
        if gi_panel::window(ctx, &mut self.gi_panel_open, &mut self.config.gi) {
            // The GI reads its settings every frame: the change shows on the next one.
            self.apply_config();
            self.save_config();
        }
        let input = std::mem::take(&mut self.input);
        if let Some(action) = self.menus.show(ctx, &mut self.config, &input) {
            self.menu_action(action);
        }
    }

    fn render(
        &mut self,
        gpu: &Gpu,
        target: &engine::wgpu::Texture,
        view: &engine::wgpu::TextureView,
    ) -> anyhow::Result<()> {
        if let Some(next) = self.next_level.take() {
            if let Err(e) = self.switch_level(gpu, next) {
                self.reload_error = Some(format!("{e:#}"));
            }
        }
        if let Some(i) = self.menus.wants_thumbnail() {
            self.make_thumbnail(gpu, i);
        }
        let renderer = self.renderer.as_mut().expect("init runs before render");
        if std::mem::take(&mut self.light_cut) {
            renderer.reset_history();
        }
        renderer.render(gpu, &self.view.view, target, view)?;
        self.frames += 1;
        // The first timed frame is the one after opening; then every TIMING_EVERY.
        if self.overlay_open && (self.frames == 2 || self.frames.is_multiple_of(TIMING_EVERY)) {
            if let Some(times) = renderer.last_pass_times(gpu) {
                self.pass_times = times;
            }
            if self.config.gi.enabled {
                self.reflection_lights = match self.config.gi.method {
                    plugin_gi::Method::Cuts => {
                        plugin_gi::readback::cut_stats(gpu, renderer).map(|s| s.lights_per_tile().round() as u32)
                    }
                    plugin_gi::Method::Article => plugin_gi::readback::volume_stats(gpu, renderer).map(|s| s.drawn),
                };
            } else {
                self.reflection_lights = Some(0);
            }
        }
        Ok(())
    }
}

mod level_switch;
#[cfg(test)]
mod tests;
