use std::ffi::OsString;
use std::fs;
use std::path::{Path, PathBuf};

use engine::gamepad::PadButton;
use engine::input::{KeyCode, MouseButton};
use plugin_gi::GiSettings;

use super::format::{section_names, with_range};
use super::{config_path_from, Config, ConfigError, KEYS, OWNERS, PLAIN_SECTIONS};
use crate::bindings::{Action, Binding, KeyBindings};
use crate::pad_bindings::{GamepadSettings, PadBindings};

/// A fresh, empty folder of the test's own.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("headlamp-ui-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn parse_err(text: &str) -> ConfigError {
    Config::from_toml(text, Path::new("/home/me/.config/headlamp/config.toml")).unwrap_err()
}

/// Every field different from its default.
fn changed() -> Config {
    let mut bindings = KeyBindings::default();
    bindings.set(Action::Jump, 1, Binding::Mouse(MouseButton::Right));
    bindings.set(Action::Fire, 1, Binding::Key(KeyCode::Tab));
    bindings.set(Action::MoveForward, 0, Binding::Key(KeyCode::ArrowUp));
    bindings.clear(Action::Crouch, 1);
    let mut pad = PadBindings::default();
    pad.set(Action::Fire, PadButton::LeftTrigger).unwrap();
    pad.set(Action::MoveForward, PadButton::DPadUp).unwrap();
    pad.set(Action::Jump, PadButton::RightBumper).unwrap();
    pad.clear(Action::Crouch);
    let gamepad = GamepadSettings { look_sensitivity: 2.25, dead_zone: 0.3, bindings: pad };
    let gi = GiSettings {
        enabled: false,
        merge_normal_deg: 12.5,
        merge_distance: 0.3,
        split_ratio: 0.3,
        bounces: 3,
        resolution_scale: 0.3,
        interleave: 1,
        min_rows: 60,
        history: 0.25,
        visibility: 0,
        method: plugin_gi::Method::Article,
        light_budget: 2048,
        article_interleave: 2,
        volume_reach: 4.0,
        world_sight: 0,
    };
    Config {
        mouse_sensitivity: 1.37,
        invert_y: true,
        fov_deg: 93.3,
        render_scale: 0.6,
        dynamic_resolution: true,
        target_fps: 24.5,
        vsync: false,
        show_fps: true,
        cpu_note_shown: true,
        bindings,
        gamepad,
        gi,
        brightness: 0.7,
        calibrated: true,
        reduce_flashing: true,
        captions: false,
        hud_scale: 1.25,
        crosshair_scale: 2.5,
        master_volume: 55.5,
        effects_volume: 0.0,
        ambience_volume: 35.0,
    }
}

#[test]
fn every_setting_survives_save_and_load() {
    let c = changed();
    let d = Config::default();
    // The test is only as good as this: every field is off its default.
    for key in KEYS {
        assert_ne!((key.write)(&c), (key.write)(&d), "{}.{}", key.section, key.name);
    }
    for action in [Action::Jump, Action::Fire, Action::MoveForward, Action::Crouch] {
        assert_ne!(c.bindings.get(action), d.bindings.get(action), "{action:?}");
    }
    for field in GiSettings::FIELDS {
        assert_ne!(c.gi.get(field.name), d.gi.get(field.name), "gi.{}", field.name);
    }
    assert_ne!(c.gi.enabled, d.gi.enabled);
    let (p, q) = (&c.gamepad, &d.gamepad);
    assert!(p.look_sensitivity != q.look_sensitivity && p.dead_zone != q.dead_zone);
    for action in [Action::Fire, Action::MoveForward, Action::Jump, Action::Crouch, Action::LampThrow] {
        assert_ne!(p.bindings.get(action), q.bindings.get(action), "{action:?}");
    }

    let dir = scratch("round-trip");
    let path = dir.join("nested/headlamp/config.toml");
    c.save(&path).unwrap();
    assert_eq!(Config::load(&path).unwrap(), c);
    // Saving again replaces the file; no temporary file is left behind.
    d.save(&path).unwrap();
    assert_eq!(Config::load(&path).unwrap(), d);
    let left: Vec<_> = fs::read_dir(path.parent().unwrap()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left, vec![OsString::from("config.toml")]);
    let _ = fs::remove_dir_all(dir);
}

/// Each key the list in `config.rs` declares is written in its section under its comment, and
/// read back alone into its own field.
#[test]
fn every_declared_key_is_written_with_its_comment_and_read_back() {
    let (c, d) = (changed(), Config::default());
    let text = c.to_toml();
    for key in KEYS {
        let value = (key.write)(&c);
        let header = format!("\n[{}]\n", key.section);
        let start = text.find(&header).unwrap_or_else(|| panic!("{header:?} in\n{text}")) + header.len();
        let section = &text[start..text[start..].find("\n[").map_or(text.len(), |end| start + end)];
        let line = format!("{} = {value}\n", key.name);
        let expected = match key.comment {
            Some(comment) => format!("# {}\n{line}", with_range(comment, key)),
            None => line,
        };
        let at_line_start = section.starts_with(&expected) || section.contains(&format!("\n{expected}"));
        assert!(at_line_start, "{expected:?} in [{}]:\n{section}", key.section);

        let alone = format!("[{}]\n{} = {value}\n", key.section, key.name);
        let read = Config::from_toml(&alone, Path::new("c.toml")).unwrap_or_else(|e| panic!("{alone:?}: {e}"));
        for other in KEYS {
            let wanted = if std::ptr::eq(other, key) { &c } else { &d };
            assert_eq!((other.write)(&read), (other.write)(wanted), "{alone:?}: {}", other.name);
        }
        assert_eq!(read.bindings, d.bindings);
        assert_eq!((&read.gamepad, &read.gi), (&d.gamepad, &d.gi));
    }
    assert!(!text.contains("{range}"), "every {{range}} is replaced:\n{text}");
    // The one comment that quotes a constant rather than the key's range.
    let sensitivity = KEYS.iter().find(|k| k.name == "sensitivity").and_then(|k| k.comment).unwrap();
    assert!(sensitivity.contains(&format!("1.0 = {} radians", Config::BASE_RADIANS_PER_PIXEL)), "{sensitivity}");
}

#[test]
fn every_section_is_written_in_order_and_named_in_errors() {
    let text = Config::default().to_toml();
    let headers: Vec<&str> = text.lines().filter(|l| l.starts_with('[')).collect();
    let sections = section_names(PLAIN_SECTIONS, OWNERS);
    let expected: Vec<String> = sections.iter().map(|s| format!("[{s}]")).collect();
    assert_eq!(headers, expected);
    let e = parse_err("[sound]\n");
    assert!(e.problem.ends_with(&format!("(the sections are {})", sections.join(", "))), "{e}");
}

#[test]
fn the_file_is_readable_toml() {
    let text = Config::default().to_toml();
    for expected in ["[controls]\n", "sensitivity = 1.0\n", "[video]\n", "render_scale = 1.0\n", "[bindings]\n"] {
        assert!(text.contains(expected), "{expected:?} in\n{text}");
    }
    for expected in ["MoveForward = [\"KeyW\"]\n", "Crouch = [\"KeyC\", \"ControlLeft\"]\n", "Fire = [\"MouseLeft\"]\n"]
    {
        assert!(text.contains(expected), "{expected:?} in\n{text}");
    }
    for expected in ["[gi]\n", "enabled = true\n", "split_ratio = 0.45\n", "resolution_scale = 0.125\n"] {
        assert!(text.contains(expected), "{expected:?} in\n{text}");
    }
    assert!(text.parse::<toml::Table>().is_ok());
}

#[test]
fn a_missing_file_gives_the_defaults() {
    let dir = scratch("missing");
    assert_eq!(Config::load(&dir.join("config.toml")).unwrap(), Config::default());
    let (c, warning) = Config::load_or_default(&dir.join("config.toml"));
    assert_eq!((c, warning), (Config::default(), None));
    assert!(!dir.join("config.toml.bad").exists());
    let _ = fs::remove_dir_all(dir);
}

#[test]
fn missing_keys_take_defaults() {
    let c =
        Config::from_toml("[controls]\nfov_deg = 80\n\n[bindings]\nJump = [\"KeyG\"]\n", Path::new("c.toml")).unwrap();
    assert_eq!(c.fov_deg, 80.0);
    assert_eq!(c.mouse_sensitivity, 1.0);
    assert_eq!(c.gi, GiSettings::default());
    assert_eq!(c.bindings.get(Action::Jump), [Some(Binding::Key(KeyCode::KeyG)), None]);
    assert_eq!(c.bindings.get(Action::LampDetach), [None, None], "G went to Jump, so the default G is dropped");
    assert_eq!(c.bindings.get(Action::MoveForward), KeyBindings::default().get(Action::MoveForward));
    assert_eq!(Config::from_toml("", Path::new("c.toml")).unwrap(), Config::default());
    // A single name is accepted for one binding, an empty list for none.
    let c = Config::from_toml("[bindings]\nReload = \"KeyE\"\nSprint = []\n", Path::new("c.toml")).unwrap();
    assert_eq!(c.bindings.get(Action::Reload), [Some(Binding::Key(KeyCode::KeyE)), None]);
    assert_eq!(c.bindings.get(Action::Sprint), [None, None]);
}

#[test]
fn bad_toml_names_the_file_and_line() {
    let e = parse_err("[controls]\nsensitivity = 1.0\nfov_deg = = 70\n");
    assert_eq!(e.line, Some(3), "{e}");
    let text = e.to_string();
    assert!(text.starts_with("/home/me/.config/headlamp/config.toml: line 3: "), "{text}");
    assert!(text.contains("not valid TOML"), "{text}");
    assert!(!text.contains('\n'), "one line: {text}");
}

#[test]
fn unknown_keys_are_named() {
    let e = parse_err("[controls]\nsensitivity = 1.0\nsensitivty = 2.0\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(3), Some("controls.sensitivty")), "{e}");
    let text = e.to_string();
    assert!(text.contains("config.toml: line 3: controls.sensitivty: unknown key"), "{text}");
    assert!(text.contains("sensitivity, invert_y, fov_deg"), "lists the known keys: {text}");

    let e = parse_err("[controls]\nfov_deg = 70\n\n[sound]\nvolume = 1\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(4), Some("sound")), "{e}");
    let e = parse_err("[video]\nvsync = true\nhdr = true\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(3), Some("video.hdr")), "{e}");
    let e = parse_err("[gi]\nlite_budget = 3\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(2), Some("gi.lite_budget")), "{e}");
    assert!(e.problem.contains("unknown setting"), "{e}");
    let e = parse_err("[bindings]\nShoot = [\"MouseLeft\"]\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(2), Some("bindings.Shoot")), "{e}");
    assert!(e.problem.contains("MoveForward"), "lists the actions: {e}");
    let e = parse_err("controls = 3\n");
    assert_eq!(e.key.as_deref(), Some("controls"), "{e}");
}

#[test]
fn out_of_range_and_mistyped_values_are_named() {
    let e = parse_err("[controls]\n\nfov_deg = 140\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(3), Some("controls.fov_deg")), "{e}");
    assert!(e.to_string().ends_with("controls.fov_deg: 140 is out of range (50.0 to 110.0)"), "{e}");
    let e = parse_err("[video]\nrender_scale = 0.1\n");
    assert_eq!(e.key.as_deref(), Some("video.render_scale"), "{e}");
    let e = parse_err("[controls]\ninvert_y = \"yes\"\n");
    assert!(e.to_string().contains("controls.invert_y: expected true or false, found string"), "{e}");
    let e = parse_err("[gi]\nbounces = 7\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(2), Some("gi.bounces")), "{e}");
    assert!(e.problem.contains("out of range") && !e.problem.starts_with("gi."), "{e}");
    let e = parse_err("[gi]\nsplit_ratio = \"many\"\n");
    assert!(e.to_string().contains("gi.split_ratio: expected a number, found string"), "{e}");
}

#[test]
fn unknown_key_names_are_named() {
    let e = parse_err("[bindings]\nMoveForward = [\"KeyW\"]\nJump = [\"Spacebar\"]\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(3), Some("bindings.Jump")), "{e}");
    assert!(e.to_string().contains("config.toml: line 3: bindings.Jump: unknown key or button name 'Spacebar'"), "{e}");
    let e = parse_err("[bindings]\nJump = [\"Space\", \"KeyJ\", \"KeyK\"]\n");
    assert!(e.problem.contains("at most 2"), "{e}");
    let e = parse_err("[bindings]\nJump = [\"KeyW\"]\nMoveForward = [\"KeyW\"]\n");
    assert_eq!(e.key.as_deref(), Some("bindings.MoveForward"), "{e}");
    assert!(e.problem.contains("also bound to Jump"), "{e}");
    let e = parse_err("[bindings]\nJump = [3]\n");
    assert!(e.problem.contains("found integer"), "{e}");
}

#[test]
fn a_bad_file_is_kept_before_defaults_are_used() {
    let dir = scratch("bad");
    let path = dir.join("config.toml");
    let bad = "[controls]\nfov_deg = 140 # my precious setting\n";
    fs::write(&path, bad).unwrap();
    let (c, warning) = Config::load_or_default(&path);
    assert_eq!(c, Config::default());
    let warning = warning.expect("a warning to show");
    let kept = dir.join("config.toml.bad");
    assert!(warning.contains("controls.fov_deg") && warning.contains(&kept.display().to_string()), "{warning}");
    assert_eq!(fs::read_to_string(&kept).unwrap(), bad);
    assert_eq!(fs::read_to_string(&path).unwrap(), bad, "the file itself is untouched");
    // Loading again reuses the identical copy.
    let (_, again) = Config::load_or_default(&path);
    assert!(again.unwrap().contains("config.toml.bad"));
    assert!(!dir.join("config.toml.bad2").exists());
    // The game then saves over the file: the copy stays.
    c.save(&path).unwrap();
    assert_eq!(Config::load(&path).unwrap(), c);
    assert_eq!(fs::read_to_string(&kept).unwrap(), bad);
    // A later, different bad file does not replace the first copy.
    fs::write(&path, "not toml [").unwrap();
    let (_, warning) = Config::load_or_default(&path);
    assert!(warning.unwrap().contains("config.toml.bad2"));
    assert_eq!(fs::read_to_string(dir.join("config.toml.bad2")).unwrap(), "not toml [");
    assert_eq!(fs::read_to_string(&kept).unwrap(), bad);
    let _ = fs::remove_dir_all(dir);
}

#[test]
fn the_config_path_follows_the_environment() {
    let env = |vars: &'static [(&'static str, &'static str)]| {
        move |name: &str| vars.iter().find(|(k, _)| *k == name).map(|(_, v)| OsString::from(v))
    };
    assert_eq!(
        config_path_from(env(&[("HEADLAMP_CONFIG", "/tmp/h.toml"), ("HOME", "/home/me")])),
        Some(PathBuf::from("/tmp/h.toml"))
    );
    assert_eq!(config_path_from(env(&[])), None);
    if cfg!(all(unix, not(target_os = "macos"))) {
        assert_eq!(
            config_path_from(env(&[("XDG_CONFIG_HOME", "/xdg"), ("HOME", "/home/me")])),
            Some(PathBuf::from("/xdg/headlamp/config.toml"))
        );
        assert_eq!(
            config_path_from(env(&[("HEADLAMP_CONFIG", ""), ("XDG_CONFIG_HOME", "rel"), ("HOME", "/home/me")])),
            Some(PathBuf::from("/home/me/.config/headlamp/config.toml")),
            "an empty HEADLAMP_CONFIG and a relative XDG_CONFIG_HOME are ignored"
        );
    }
}

#[test]
fn sensitivity_is_a_multiplier_of_the_old_constant() {
    let c = Config { mouse_sensitivity: 2.0, ..Config::default() };
    assert_eq!(Config::default().radians_per_pixel(), 0.0025);
    assert_eq!(c.radians_per_pixel(), 0.005);
}

/// A device or FIFO named as the config file is refused at once, neither read without end nor
/// replaced by a save.
#[cfg(unix)]
#[test]
fn a_device_as_the_config_is_neither_read_nor_replaced() {
    let zero = Path::new("/dev/zero");
    let e = Config::load(zero).unwrap_err();
    assert!(e.to_string().contains("not a regular file"), "{e}");
    let (config, warning) = Config::load_or_default(zero);
    assert_eq!(config, Config::default());
    assert!(warning.is_some_and(|w| w.contains("/dev/zero")));
    let e = Config::default().save(zero).unwrap_err();
    assert!(e.to_string().contains("will not write it"), "{e}");
    assert!(std::fs::metadata(zero).is_ok_and(|m| !m.is_file()), "still the device");
}

#[test]
fn comfort_settings_are_checked_and_placed() {
    let e = parse_err("[comfort]\nbrightness = 0.5\ncrosshair_scale = 9.0\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(3), Some("comfort.crosshair_scale")), "{e}");
    let e = parse_err("[comfort]\nflashy = true\n");
    assert!(e.to_string().contains("reduce_flashing"), "the known keys are listed: {e}");
    let c = Config::from_toml("[comfort]\nbrightness = -1.5\n", Path::new("c.toml")).unwrap();
    assert_eq!((c.brightness, c.calibrated), (-1.5, false));
    assert!((c.exposure_scale() - 0.3536).abs() < 1e-3, "-1.5 stops: {}", c.exposure_scale());
}

#[test]
fn gamepad_settings_are_written_read_and_checked() {
    let text = Config::default().to_toml();
    for expected in ["[gamepad]\n", "dead_zone = 0.15\n", "[gamepad_bindings]\n", "Fire = [\"RightTrigger\"]\n"] {
        assert!(text.contains(expected), "{expected:?} in\n{text}");
    }
    assert!(text.contains("MoveForward = []\n"), "walking has no button: {text}");
    // Like key bindings: a listed action takes what is listed; the others keep their defaults,
    // less a button a listed one took.
    let c = Config::from_toml("[gamepad_bindings]\nReload = \"North\"\nJump = []\n", Path::new("c.toml")).unwrap();
    assert_eq!(c.gamepad.bindings.get(Action::Reload), Some(PadButton::North));
    assert_eq!(c.gamepad.bindings.get(Action::LampToggle), None, "North went to Reload");
    assert_eq!(c.gamepad.bindings.get(Action::Jump), None);
    assert_eq!(c.gamepad.bindings.get(Action::Fire), Some(PadButton::RightTrigger));

    let e = parse_err("[gamepad]\ndead_zone = 0.9\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(2), Some("gamepad.dead_zone")), "{e}");
    assert!(e.problem.contains("out of range (0.0 to 0.5)"), "{e}");
    let e = parse_err("[gamepad]\nlook_sensitivity = 1.0\ninvert = true\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(3), Some("gamepad.invert")), "{e}");
    assert!(e.problem.contains("look_sensitivity, dead_zone"), "{e}");
    let e = parse_err("[gamepad_bindings]\nFire = [\"Start\"]\n");
    assert_eq!(e.key.as_deref(), Some("gamepad_bindings.Fire"), "{e}");
    assert!(e.problem.contains("unknown gamepad button 'Start'"), "Start pauses: {e}");
    let e = parse_err("[gamepad_bindings]\nFire = [\"South\", \"East\"]\n");
    assert!(e.problem.contains("one gamepad button per action"), "{e}");
    let e = parse_err("[gamepad_bindings]\nFire = [\"South\"]\n\nJump = \"South\"\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(4), Some("gamepad_bindings.Jump")), "{e}");
    assert!(e.problem.contains("also bound to Fire"), "{e}");
    let e = parse_err("[gamepad_bindings]\nShoot = [\"South\"]\n");
    assert!(e.problem.contains("MoveForward"), "lists the actions: {e}");
    let e = parse_err("[gamepad_bindings]\nFire = 7\n");
    assert!(e.problem.contains("found integer"), "{e}");
}

#[test]
fn volumes_are_percentages_checked_and_placed() {
    let c = Config::from_toml("[audio]\nmaster = 40\neffects = 12.5\n", Path::new("c.toml")).unwrap();
    assert_eq!((c.master_volume, c.effects_volume), (40.0, 12.5));
    assert_eq!(c.ambience_volume, Config::default().ambience_volume, "a missing key takes its default");
    let e = parse_err("[audio]\nmaster = 50\n\nambience = 120\n");
    assert_eq!((e.line, e.key.as_deref()), (Some(4), Some("audio.ambience")), "{e}");
    assert!(e.problem.contains("out of range (0.0 to 100.0)"), "{e}");
    let e = parse_err("[audio]\nmusic = 50\n");
    assert_eq!(e.key.as_deref(), Some("audio.music"), "{e}");
    assert!(e.problem.contains("master, effects, ambience"), "the known keys are listed: {e}");
    let e = parse_err("[audio]\neffects = \"loud\"\n");
    assert!(e.to_string().contains("audio.effects: expected a number, found string"), "{e}");
    let text = Config::default().to_toml();
    assert!(text.contains("[audio]\n") && text.contains("master = 80.0\n"), "{text}");
}
