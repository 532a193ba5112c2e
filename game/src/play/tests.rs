//! The window app without a window: frames, menus, the GI panel, replays, the HUD.

use super::*;
use game_ui::egui_harness::{click, find, input, texts};
use game_ui::Screen;
use glam::Vec3;
use plugin_gi::GiSettings;

fn app() -> GameWindow {
    let level = engine::scene::load_level(&crate::default_level()).unwrap();
    let sim = Simulation::new(&level, crate::sim::level_world(&level).unwrap(), 60, 1);
    let config = Config::default();
    GameWindow::new(level, sim, TickSource::live(&config, None), config)
}

/// Runs one frame of `ui` and returns what it drew.
fn frame_ui(app: &mut GameWindow, ctx: &egui::Context, events: Vec<egui::Event>) -> egui::FullOutput {
    ctx.run_ui(input(events), |ui| app.ui(ui.ctx()))
}

/// A few frames with no input (egui lays windows out over its first frames), and the last.
fn settled_ui(app: &mut GameWindow, ctx: &egui::Context) -> egui::FullOutput {
    (0..3).map(|_| frame_ui(app, ctx, Vec::new())).last().unwrap()
}

fn press(key: KeyCode) -> Input {
    let mut input = Input::default();
    input.key_event(key, true, false);
    input
}

/// A change made in the F1 panel reaches the GI plugin that renders the next frame.
#[test]
fn the_gi_panel_drives_the_gi_plugin() {
    let plugin = plugin_gi::GiPlugin::new(GiSettings::default());
    let gi = plugin.handle();
    let mut app = app();
    app.gi = Some(gi.clone());
    app.gi_panel_open = true;
    let ctx = egui::Context::default();
    let mut output = None;
    for _ in 0..3 {
        output = Some(frame_ui(&mut app, &ctx, Vec::new()));
    }
    let (_, rect) = texts(&output.unwrap()).into_iter().find(|(t, _)| t == "enabled").expect("the panel is shown");
    assert!(gi.settings().enabled);
    for events in click(rect.center()) {
        frame_ui(&mut app, &ctx, events);
    }
    assert!(!app.config.gi.enabled, "the click unticks 'enabled'");
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
    let eye = app.view.view.camera.position;
    assert!(eye.distance(a) <= a.distance(b) + 1e-5 && eye.distance(b) <= a.distance(b) + 1e-5);
}

/// Where even the lowest render scale cannot hold the frame rate, dynamic resolution lowers
/// the GI's rows once, and the GI plugin renders with them.
#[test]
fn a_machine_too_slow_at_the_lowest_scale_gets_fewer_rows_of_indirect_light() {
    let plugin = plugin_gi::GiPlugin::new(GiSettings::cpu_preset());
    let gi = plugin.handle();
    let mut slow = app();
    slow.gi = Some(gi.clone());
    slow.config.dynamic_resolution = true;
    slow.config.target_fps = CPU_TARGET_FPS;
    slow.config.render_scale = CPU_RENDER_SCALE;
    slow.config.gi = GiSettings::cpu_preset();
    slow.apply_config();
    let input = Input::default();
    // 10 fps whatever the scale.
    for _ in 0..(3 * engine::dynamic_resolution::DynamicResolution::WINDOW) {
        slow.update(&input, 0.1);
    }
    assert_eq!(slow.config.gi.min_rows, GiSettings::cpu_preset().min_rows, "not before the scale is at its floor");
    for _ in 0..(20 * engine::dynamic_resolution::DynamicResolution::WINDOW) {
        slow.update(&input, 0.1);
    }
    let floor = engine::dynamic_resolution::DynamicResolution::MIN_SCALE;
    assert_eq!(slow.resolution.as_ref().map(|d| d.scale()), Some(floor));
    assert_eq!(slow.config.gi.min_rows, STARVED_GI_ROWS);
    assert_eq!(gi.settings().min_rows, STARVED_GI_ROWS, "the plugin sees the change");
    // A machine that holds its frame rate keeps the preset.
    let mut fast = app();
    fast.config.dynamic_resolution = true;
    fast.config.gi = GiSettings::cpu_preset();
    fast.apply_config();
    for _ in 0..(20 * engine::dynamic_resolution::DynamicResolution::WINDOW) {
        fast.update(&input, 0.03);
    }
    assert_eq!(fast.config.gi.min_rows, GiSettings::cpu_preset().min_rows);
}

/// The main menu and the pause menu stop the world; Esc pauses, Play and Resume go on.
#[test]
fn menus_pause_the_world() {
    let mut app = app();
    app.menus = Menus::new();
    let ctx = egui::Context::default();
    for _ in 0..30 {
        app.update(&Input::default(), 0.1);
    }
    assert_eq!(app.sim.state.tick, 0, "no ticks on the main menu");
    assert_eq!(app.capture_wanted(), Some(false), "the mouse is free for the menu");
    let out = settled_ui(&mut app, &ctx);
    let play = find(&texts(&out), "Play").expect("the main menu shows Play");
    for events in click(play.center()) {
        frame_ui(&mut app, &ctx, events);
    }
    assert_eq!(app.menus.screen(), Screen::Playing);
    assert_eq!(app.capture_wanted(), Some(true), "playing grabs the mouse");
    for _ in 0..5 {
        app.update(&Input::default(), 0.1);
    }
    let ticks = app.sim.state.tick;
    assert!(ticks >= 29, "{ticks}");
    app.update(&press(KeyCode::Escape), 0.5);
    assert_eq!(app.menus.screen(), Screen::Paused);
    app.update(&Input::default(), 0.5);
    assert_eq!(app.sim.state.tick, ticks, "paused");
}

/// Losing shows the game-over screen after a moment, and Restart starts the level afresh.
#[test]
fn death_ends_the_game_and_restart_begins_again() {
    let mut app = app();
    app.sim.state.player.hurt(1000.0);
    app.update(&Input::default(), 0.05);
    assert_eq!(app.sim.state.outcome, Outcome::Lost);
    for _ in 0..40 {
        app.update(&Input::default(), 0.05);
    }
    assert_eq!(app.menus.screen(), Screen::GameOver { won: false });
    app.menu_action(MenuAction::Restart);
    assert_eq!(app.sim.state.outcome, Outcome::Playing);
    assert_eq!(app.sim.state.tick, 0);
    assert_eq!(app.sim.state.player.health, player::MAX_HEALTH);
    assert_eq!(app.menus.screen(), Screen::Playing);
}

/// The HUD shows the simulation's numbers, and what the lamp keys do.
#[test]
fn the_hud_follows_the_state() {
    let mut app = app();
    let controls = app.hud().hint.unwrap();
    assert!(controls.starts_with("WASD move · Left mouse fire · R reload"), "the controls first: {controls}");
    app.sim.state.tick = 1000;
    app.sim.state.weapon.magazine = 7;
    app.sim.state.lamp.attached = false;
    app.sim.state.lamp.position = app.sim.state.player.eye() + engine::glam::Vec3::X;
    let hud = app.hud();
    assert_eq!((hud.ammo_in_magazine, hud.enemies_total), (7, 4));
    assert_eq!(hud.hint.as_deref(), Some("G — pick up the lamp"));
    let ctx = egui::Context::default();
    let out = settled_ui(&mut app, &ctx);
    let shown: Vec<String> = texts(&out).into_iter().map(|(t, _)| t).collect();
    assert!(shown.iter().any(|t| t.contains('7') && t.contains("24")), "ammo shown: {shown:?}");
    assert!(shown.iter().any(|t| t.contains("pick up the lamp")), "{shown:?}");
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
        let mut app = GameWindow::new(level.clone(), sim, source, Config::default());
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
    assert!(app.status().contains("finished"), "{}", app.status());
    let app = watch(true);
    assert!(matches!(app.source, TickSource::Replay { diverged: Some(Divergence { tick: 6, .. }), .. }));
    assert!(app.status().contains("diverged at tick 6"), "{}", app.status());
    let _ = std::fs::remove_file(&path);
}

#[test]
fn restarting_a_recording_keeps_the_first_attempt() {
    let dir = std::env::temp_dir().join(format!("headlamp-attempts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let first = dir.join("run.replay");
    assert_eq!(crate::recording::next_attempt_path(&first), dir.join("run-2.replay"));
    std::fs::write(dir.join("run-2.replay"), b"x").unwrap();
    assert_eq!(crate::recording::next_attempt_path(&first), dir.join("run-3.replay"));
    assert_eq!(crate::recording::next_attempt_path(&dir.join("run-3.replay")), dir.join("run-4.replay"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_cpu_note_says_whether_the_cpu_settings_are_in_use() {
    let mut config = Config {
        render_scale: CPU_RENDER_SCALE,
        dynamic_resolution: true,
        target_fps: CPU_TARGET_FPS,
        gi: plugin_gi::GiSettings::cpu_preset(),
        ..Config::default()
    };
    let note = cpu_note("llvmpipe", &config);
    assert!(
        note.contains("uses the CPU settings: dynamic resolution holding 20 fps") && note.contains("gi.min_rows"),
        "{note}"
    );
    config.dynamic_resolution = false;
    let note = cpu_note("llvmpipe", &config);
    assert!(note.contains("heavier than its defaults"), "{note}");
    config.gi.enabled = false;
    assert!(cpu_note("llvmpipe", &config).contains("uses the CPU settings"));
}

/// `play --level X` starts X at once; the menu is one Esc away. Without a level the menus come
/// first: the brightness screen until it has been shown, then the main menu.
#[test]
fn play_with_a_level_starts_in_it_and_the_menu_is_one_esc_away() {
    let cellar = crate::default_level();
    let mut app = game_window(&cellar, Config::default(), None, Start::InLevel).unwrap();
    assert_eq!(app.menus.screen(), Screen::Playing);
    app.update(&Input::default(), 0.1);
    assert!(app.sim.state.tick > 0, "the world runs from the first frame");
    app.update(&press(KeyCode::Escape), 0.1);
    assert_eq!(app.menus.screen(), Screen::Paused);

    let first = game_window(&cellar, Config::default(), None, Start::MainMenu).unwrap();
    assert_eq!(first.menus.screen(), Screen::Calibration);
    let calibrated = Config { calibrated: true, ..Config::default() };
    let later = game_window(&cellar, calibrated, None, Start::MainMenu).unwrap();
    assert_eq!(later.menus.screen(), Screen::MainMenu);
}

/// On a device that renders on the CPU the note on its settings shows on the menus once per
/// machine (the config file remembers it), and Settings > Video says it every time.
#[test]
fn the_cpu_note_shows_once_per_machine_and_settings_keeps_it() {
    let dir = std::env::temp_dir().join(format!("headlamp-cpu-note-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("config.toml");
    let _ = std::fs::remove_file(&path);
    // Lavapipe: a CPU device wherever the test runs.
    let gpu = Gpu::lavapipe().unwrap_or_else(|e| panic!("{e}"));
    let format = engine::wgpu::TextureFormat::Rgba8UnormSrgb;
    let start = |config: Config| {
        let mut app = game_window(&crate::default_level(), config, Some(path.clone()), Start::InLevel).unwrap();
        app.config.gi.enabled = false;
        app.init(&gpu, format).unwrap();
        app
    };
    let first = start(Config::default());
    let warning = first.menus.warning().expect("the first start shows the note");
    assert!(warning.contains("renders on the CPU"), "{warning}");
    assert_eq!(first.menus.device_note(), Some(warning));
    let (saved, problem) = Config::load_or_default(&path);
    assert!(problem.is_none() && saved.cpu_note_shown, "the file remembers the note: {problem:?}");

    let second = start(saved);
    assert_eq!(second.menus.warning(), None, "shown once");
    assert!(second.menus.device_note().is_some_and(|n| n.contains("renders on the CPU")));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A copy of the Cellar, to edit: `cellar` in a folder of its own.
fn cellar_copy(tag: &str) -> PathBuf {
    let parent = std::env::temp_dir().join(format!("headlamp-live-reload-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&parent);
    let dir = parent.join("cellar");
    std::fs::create_dir_all(&dir).unwrap();
    // Every file: the scene's textures are PNGs beside it.
    for entry in std::fs::read_dir(crate::default_level()).unwrap() {
        let path = entry.unwrap().path();
        if path.is_file() {
            std::fs::copy(&path, dir.join(path.file_name().unwrap())).unwrap();
        }
    }
    dir
}

/// Frames of `seconds` of time with no input: enough polls for a saved file to be read.
fn idle(app: &mut GameWindow, gpu: &Gpu, target: &engine::headless::HeadlessTarget, seconds: f32) {
    let dt = 0.1;
    for _ in 0..(seconds / dt).ceil() as usize {
        app.update(&Input::default(), dt);
        app.render(gpu, &target.texture, &target.view).unwrap();
    }
}

/// Saving level.toml reloads the level within a second, keeping where the player stands and
/// looks; a bad edit shows its error (file and line) and the last good level keeps running;
/// F5 reloads by hand.
#[test]
fn a_saved_level_reloads_live_and_a_bad_edit_keeps_the_last_good_level() {
    let dir = cellar_copy("edit");
    let level = engine::scene::load_level(&dir).unwrap();
    let sim = Simulation::new(&level, crate::sim::level_world(&level).unwrap(), 60, 1);
    let config = Config { gi: GiSettings { enabled: false, ..GiSettings::default() }, ..Config::default() };
    let mut app = GameWindow::new(level, sim, TickSource::live(&config, None), config);
    app.watch_level(&dir);
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let target = engine::headless::HeadlessTarget::new(&gpu, 64, 36, engine::headless::ImageKind::Display);
    app.init(&gpu, target.texture.format()).unwrap();
    // The player has walked off the spawn and turned.
    let (feet, yaw, pitch) = (app.sim.state.player.body.position + Vec3::new(0.0, 0.0, -1.5), 9000, -500);
    app.sim = Simulation::at(feet, yaw, pitch, app.sim.world(), 60, 1);
    idle(&mut app, &gpu, &target, 0.6);
    assert_eq!(app.level.headlamp.power, 40.0);

    let toml = dir.join("level.toml");
    let text = std::fs::read_to_string(&toml).unwrap();
    // Another length as well as another time: file systems with coarse clocks see it too.
    std::fs::write(&toml, text.replace("power = 40.0", "power = 25.00")).unwrap();
    idle(&mut app, &gpu, &target, 1.0);
    assert_eq!(app.level.headlamp.power, 25.0, "reloaded within a second");
    let p = &app.sim.state.player;
    assert!(p.body.position.distance(feet) < 0.05 && (p.yaw, p.pitch) == (yaw, pitch), "kept the player: {p:?}");
    assert!(app.reload_error.is_none());

    // A typo: the error names the file and line, the level as it was keeps running.
    std::fs::write(&toml, text.replace("power = 40.0", "powr = 10.0")).unwrap();
    idle(&mut app, &gpu, &target, 1.0);
    let error = app.reload_error.clone().expect("the bad edit is reported");
    assert!(error.contains("level.toml:") && error.contains("unknown field `powr`"), "{error}");
    assert_eq!(app.level.headlamp.power, 25.0, "the last good level keeps running");
    let ctx = egui::Context::default();
    let shown = texts(&settled_ui(&mut app, &ctx));
    assert!(
        shown.iter().any(|(t, _)| t.starts_with("Reload failed") && t.contains("unknown field `powr`")),
        "{shown:?}"
    );

    // The reloader keeps to the level folder like every load: a scene outside it is refused.
    std::fs::write(dir.parent().unwrap().join("outside.gltf"), "{}").unwrap();
    std::fs::write(&toml, text.replace("scene = \"scene.gltf\"", "scene = \"../outside.gltf\"")).unwrap();
    idle(&mut app, &gpu, &target, 1.0);
    let error = app.reload_error.clone().expect("the escape is reported");
    assert!(error.contains("level.toml: path '../outside.gltf' escapes the level folder"), "{error}");
    assert_eq!(app.level.headlamp.power, 25.0);

    // Fixed, and F5: reloaded, banner gone.
    std::fs::write(&toml, text.replace("power = 40.0", "power = 30.000")).unwrap();
    app.update(&press(KeyCode::F5), 0.01);
    app.render(&gpu, &target.texture, &target.view).unwrap();
    assert_eq!((app.level.headlamp.power, app.reload_error.is_none()), (30.0, true));
    std::fs::remove_dir_all(dir.parent().unwrap()).unwrap();
}

/// A level picked from the level menu replaces the one running, from its spawn, and its files
/// are the ones watched from then on.
#[test]
fn a_level_picked_from_the_menu_starts_at_its_spawn_and_is_watched() {
    let dir = cellar_copy("pick");
    let toml = dir.join("level.toml");
    let text = std::fs::read_to_string(&toml).unwrap();
    std::fs::write(&toml, text.replace("name = \"The Cellar\"", "name = \"Another Cellar\"")).unwrap();
    let mut app = app();
    app.config.gi.enabled = false;
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let target = engine::headless::HeadlessTarget::new(&gpu, 64, 36, engine::headless::ImageKind::Display);
    app.init(&gpu, target.texture.format()).unwrap();
    idle(&mut app, &gpu, &target, 0.5);
    assert!(app.sim.state.tick > 0);
    let listed = crate::level_list::scan(&[(dir.parent().unwrap().to_path_buf(), "tmp".into())])
        .into_iter()
        .find(|l| l.path == dir)
        .expect("the copy is found");
    app.levels = vec![listed];
    app.menu_action(MenuAction::PlayLevel(0));
    app.render(&gpu, &target.texture, &target.view).unwrap();
    assert_eq!((app.level.name.as_str(), app.sim.state.tick), ("Another Cellar", 0));
    assert_eq!(app.level_path.as_deref(), Some(dir.as_path()));
    assert!(app.watch.as_ref().unwrap().files().contains(&toml));
    std::fs::remove_dir_all(dir.parent().unwrap()).unwrap();
}
