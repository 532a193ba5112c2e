use engine::egui::{self, Rect};
use engine::gamepad::{menu_key, PadButton, PadEvent};
use engine::input::{Input, KeyCode, MouseButton};

use super::settings_screen::{pads_connected, SLIDER_WIDTH, UNBOUND, WAITING, WAITING_PAD};
use super::{MenuAction, Menus, Screen};
use crate::bindings::{Action, Binding, KeyBindings};
use crate::config::Config;
use crate::egui_harness::{click_with, find, input, key_down, texts};

/// The menus in a headless egui, as the game drives them each frame.
struct Harness {
    ctx: egui::Context,
    menus: Menus,
    config: Config,
    /// The texts the last pass drew.
    shown: Vec<(String, Rect)>,
}

impl Harness {
    fn new() -> Self {
        let mut h =
            Self { ctx: egui::Context::default(), menus: Menus::new(), config: Config::default(), shown: Vec::new() };
        h.settle();
        h
    }

    fn pass_with(&mut self, events: Vec<egui::Event>, game_input: &Input) -> Option<MenuAction> {
        let mut action = None;
        let output =
            self.ctx.run_ui(input(events), |ui| action = self.menus.show(ui.ctx(), &mut self.config, game_input));
        self.shown = texts(&output);
        action
    }

    fn pass(&mut self, events: Vec<egui::Event>) -> Option<MenuAction> {
        self.pass_with(events, &Input::default())
    }

    /// Idle passes until nothing moves: a new screen's panel sizes itself over its first passes.
    fn settle(&mut self) {
        for n in 0..12 {
            let before = std::mem::take(&mut self.shown);
            assert_eq!(self.pass(Vec::new()), None, "an idle frame does nothing");
            // The first pass of a new panel only measures it and draws nothing.
            if n >= 2 && self.shown == before {
                return;
            }
        }
        panic!("the menu keeps moving: {:?}", self.shown);
    }

    fn rect(&self, text: &str) -> Rect {
        let shown: Vec<&str> = self.shown.iter().map(|(t, _)| t.as_str()).collect();
        find(&self.shown, text).unwrap_or_else(|| panic!("'{text}' is not shown; shown: {shown:?}"))
    }

    fn shows(&self, text: &str) -> bool {
        find(&self.shown, text).is_some()
    }

    /// Clicks at `at`; returns what the menus returned on the way (at most one action).
    fn click_at(&mut self, at: egui::Pos2, button: egui::PointerButton) -> Option<MenuAction> {
        let actions: Vec<MenuAction> = click_with(button, at).into_iter().filter_map(|e| self.pass(e)).collect();
        assert!(actions.len() <= 1, "one click, one action: {actions:?}");
        actions.first().copied()
    }

    /// Clicks the text, then lets the next screen settle.
    fn click(&mut self, text: &str) -> Option<MenuAction> {
        let action = self.click_at(self.rect(text).center(), egui::PointerButton::Primary);
        self.settle();
        action
    }

    /// The binding cell of `action` (its label on the settings screen) in `slot`.
    fn cell(&self, action: Action, slot: usize) -> Rect {
        let row = self.rect(action.label());
        let mut cells: Vec<Rect> = self
            .shown
            .iter()
            .filter(|(_, r)| (r.center().y - row.center().y).abs() < 6.0 && r.left() > row.right())
            .map(|(_, r)| *r)
            .collect();
        cells.sort_by(|a, b| a.left().total_cmp(&b.left()));
        assert_eq!(cells.len(), 2, "two cells beside '{}'", action.label());
        cells[slot]
    }

    /// The point `fraction` of the way along the slider on the row that ends in `label`.
    /// The row is: the rail ([`SLIDER_WIDTH`] wide), the value box (at least 40 points wide,
    /// its text centred with 4 points of padding), then the label, 8 points apart.
    fn slider_point(&self, label: &str, fraction: f32) -> egui::Pos2 {
        let label = self.rect(label);
        let value = self
            .shown
            .iter()
            .filter(|(_, r)| (r.center().y - label.center().y).abs() < 6.0 && r.right() < label.left())
            .map(|(_, r)| *r)
            .reduce(|a, b| a.union(b))
            .expect("a value beside the slider's label");
        let box_left = value.center().x - (value.width() / 2.0 + 4.0).max(20.0);
        let rail_right = box_left - 8.0;
        egui::pos2(rail_right - SLIDER_WIDTH * (1.0 - fraction), label.center().y)
    }

    fn open_settings_tab(&mut self, tab: &str) {
        assert_eq!(self.click("Settings"), None);
        assert_eq!(self.menus.screen(), Screen::Settings);
        assert_eq!(self.click(tab), None, "changing tabs changes no setting");
    }
}

/// A fake pad's button going down this frame, as the game's input has it.
fn pad_press(button: PadButton) -> Input {
    let mut input = Input::default();
    input.pad.apply(PadEvent::Button(0, button, 1.0));
    input
}

/// The egui keys the window loop taps for a pad button while a menu is up, and the game's
/// input with the press: what one pass sees of it.
fn pad_tap(button: PadButton) -> (Vec<egui::Event>, Input) {
    let events = menu_key(button)
        .map(|(key, modifiers)| {
            [true, false]
                .map(|pressed| egui::Event::Key { key, physical_key: None, pressed, repeat: false, modifiers })
                .to_vec()
        })
        .unwrap_or_default();
    (events, pad_press(button))
}

fn key(code: KeyCode) -> Input {
    let mut input = Input::default();
    input.key_event(code, true, false);
    input
}

#[test]
fn clicking_play_on_the_main_menu_returns_play() {
    let mut h = Harness::new();
    assert_eq!(h.menus.screen(), Screen::MainMenu);
    assert!(h.shows(super::TITLE) && h.shows("Settings") && h.shows("Quit"));
    assert_eq!(h.click("Play"), Some(MenuAction::Play));
    assert_eq!(h.menus.screen(), Screen::Playing);
    assert!(!h.menus.is_open());
    assert!(h.shown.is_empty(), "playing shows no menu: {:?}", h.shown);
}

#[test]
fn quit_returns_quit() {
    let mut h = Harness::new();
    assert_eq!(h.click("Quit"), Some(MenuAction::Quit));
}

#[test]
fn esc_in_paused_resumes() {
    let mut h = Harness::new();
    h.menus.playing();
    // The game pauses on the frame's Esc; the same Esc must not resume at once.
    h.menus.pause();
    assert_eq!(h.pass_with(Vec::new(), &key(KeyCode::Escape)), None);
    assert_eq!(h.menus.screen(), Screen::Paused);
    h.settle();
    for text in ["Paused", "Resume", "Restart", "Settings", "Main menu", "Quit"] {
        assert!(h.shows(text), "'{text}' on the pause menu");
    }
    assert_eq!(h.pass_with(Vec::new(), &key(KeyCode::Escape)), Some(MenuAction::Resume));
    assert_eq!(h.menus.screen(), Screen::Playing);
    // Esc through egui alone (a widget had keyboard focus) works too.
    h.menus.pause();
    h.settle();
    assert_eq!(h.pass(vec![key_down(egui::Key::Escape)]), Some(MenuAction::Resume));
}

#[test]
fn pause_menu_buttons() {
    let mut h = Harness::new();
    for (text, action, screen) in [
        ("Resume", MenuAction::Resume, Screen::Playing),
        ("Restart", MenuAction::Restart, Screen::Playing),
        ("Main menu", MenuAction::MainMenu, Screen::MainMenu),
    ] {
        h.menus.playing();
        h.menus.pause();
        h.settle();
        assert_eq!(h.click(text), Some(action), "{text}");
        assert_eq!(h.menus.screen(), screen, "{text}");
    }
}

#[test]
fn game_over_says_how_it_ended() {
    let mut h = Harness::new();
    h.menus.game_over(false);
    h.settle();
    assert!(h.shows("You died"));
    assert_eq!(h.click("Restart"), Some(MenuAction::Restart));
    h.menus.game_over(true);
    h.settle();
    assert!(h.shows("You made it out") && !h.shows("You died"));
    assert_eq!(h.click("Main menu"), Some(MenuAction::MainMenu));
    assert_eq!(h.menus.screen(), Screen::MainMenu);
}

#[test]
fn settings_go_back_where_they_came_from() {
    let mut h = Harness::new();
    h.click("Settings");
    assert_eq!(h.menus.screen(), Screen::Settings);
    assert_eq!(h.click("Back"), None);
    assert_eq!(h.menus.screen(), Screen::MainMenu);
    h.menus.playing();
    h.menus.pause();
    h.settle();
    h.click("Settings");
    assert_eq!(h.menus.screen(), Screen::Settings);
    assert_eq!(h.pass_with(Vec::new(), &key(KeyCode::Escape)), None);
    assert_eq!(h.menus.screen(), Screen::Paused, "Esc goes back to the pause menu, not into the game");
}

#[test]
fn menus_keep_clicks_from_the_game() {
    let mut h = Harness::new();
    let corner = egui::pos2(5.0, 595.0);
    h.pass(vec![egui::Event::PointerMoved(corner)]);
    assert!(h.ctx.egui_wants_pointer_input(), "a click beside the menu must not capture the mouse");
    h.menus.playing();
    h.pass(vec![egui::Event::PointerMoved(corner)]);
    assert!(!h.ctx.egui_wants_pointer_input(), "while playing the clicks are the game's");
}

#[test]
fn clicking_a_binding_then_pressing_a_key_rebinds() {
    let mut h = Harness::new();
    h.open_settings_tab("Key bindings");
    assert!(h.shows("W") && h.shows("Left mouse"));
    let cell = h.cell(Action::MoveForward, 0);
    assert_eq!(h.click_at(cell.center(), egui::PointerButton::Primary), None);
    h.settle();
    assert!(h.shows(WAITING), "the cell asks for a key");
    assert_eq!(h.pass_with(Vec::new(), &key(KeyCode::KeyK)), Some(MenuAction::ConfigChanged));
    assert_eq!(h.config.bindings.get(Action::MoveForward), [Some(Binding::Key(KeyCode::KeyK)), None]);
    assert_eq!(h.config.bindings.action_of(Binding::Key(KeyCode::KeyW)), None);
    h.settle();
    assert!(!h.shows(WAITING) && h.shows("K"));
    assert_eq!(h.menus.screen(), Screen::Settings);
}

#[test]
fn rebinding_a_key_used_elsewhere_moves_it_and_says_so() {
    let mut h = Harness::new();
    h.open_settings_tab("Key bindings");
    let cell = h.cell(Action::Jump, 1);
    assert!(find(&h.shown, UNBOUND).is_some());
    h.click_at(cell.center(), egui::PointerButton::Primary);
    assert_eq!(h.pass_with(Vec::new(), &key(KeyCode::KeyW)), Some(MenuAction::ConfigChanged));
    assert_eq!(
        h.config.bindings.get(Action::Jump),
        [Some(Binding::Key(KeyCode::Space)), Some(Binding::Key(KeyCode::KeyW))]
    );
    assert_eq!(h.config.bindings.get(Action::MoveForward), [None, None]);
    h.settle();
    let notice = "W now does Jump; it was taken from Move forward, which has no key left.";
    assert!(h.shows(notice), "{:?}", h.shown);
    // Reset to defaults brings it back.
    assert_eq!(h.click("Reset to defaults"), Some(MenuAction::ConfigChanged));
    assert_eq!(h.config.bindings, KeyBindings::default());
}

#[test]
fn esc_cancels_a_rebinding_then_leaves() {
    let mut h = Harness::new();
    h.open_settings_tab("Key bindings");
    h.click_at(h.cell(Action::Reload, 0).center(), egui::PointerButton::Primary);
    h.settle();
    assert!(h.shows(WAITING));
    assert_eq!(h.pass_with(Vec::new(), &key(KeyCode::Escape)), None);
    assert_eq!(h.menus.screen(), Screen::Settings, "the first Esc only cancels");
    assert_eq!(h.config, Config::default());
    assert!(!h.shows(WAITING));
    assert_eq!(h.pass_with(Vec::new(), &key(KeyCode::Escape)), None);
    assert_eq!(h.menus.screen(), Screen::MainMenu);
}

#[test]
fn mouse_buttons_and_egui_only_keys_bind_too() {
    let mut h = Harness::new();
    h.open_settings_tab("Key bindings");
    // A right click over the menu reaches egui only (the window loop keeps it from `Input`).
    let cell = h.cell(Action::Fire, 1);
    h.click_at(cell.center(), egui::PointerButton::Primary);
    let actions: Vec<_> =
        click_with(egui::PointerButton::Secondary, cell.center()).into_iter().filter_map(|e| h.pass(e)).collect();
    assert_eq!(actions, [MenuAction::ConfigChanged]);
    assert_eq!(h.config.bindings.get(Action::Fire)[1], Some(Binding::Mouse(MouseButton::Right)));
    h.settle();
    assert!(!h.shows(WAITING), "the release of that click does not start waiting again");
    // Tab: egui always consumes it, so it arrives as an egui event only.
    h.click_at(h.cell(Action::Reload, 1).center(), egui::PointerButton::Primary);
    assert_eq!(h.pass(vec![key_down(egui::Key::Tab)]), Some(MenuAction::ConfigChanged));
    assert_eq!(h.config.bindings.get(Action::Reload)[1], Some(Binding::Key(KeyCode::Tab)));
    // A mouse button through the game's input, and left/right modifiers told apart.
    h.settle();
    h.click_at(h.cell(Action::Sprint, 1).center(), egui::PointerButton::Primary);
    let mut input = Input::default();
    input.key_event(KeyCode::ShiftRight, true, false);
    assert_eq!(h.pass_with(Vec::new(), &input), Some(MenuAction::ConfigChanged));
    assert_eq!(h.config.bindings.get(Action::Sprint)[1], Some(Binding::Key(KeyCode::ShiftRight)));
    // A right-click on a cell that is not waiting clears it.
    h.settle();
    assert_eq!(
        h.click_at(h.cell(Action::Sprint, 1).center(), egui::PointerButton::Secondary),
        Some(MenuAction::ConfigChanged)
    );
    assert_eq!(h.config.bindings.get(Action::Sprint)[1], None);
}

#[test]
fn controls_sliders_change_the_config() {
    let mut h = Harness::new();
    h.open_settings_tab("Controls");
    assert!(h.shows("1.00") && h.shows("60") && h.shows("°"), "{:?}", h.shown);
    let at = h.slider_point("Mouse sensitivity", 0.15);
    assert_eq!(h.click_at(at, egui::PointerButton::Primary), Some(MenuAction::ConfigChanged));
    assert!(h.config.mouse_sensitivity < 0.5, "{}", h.config.mouse_sensitivity);
    h.settle();
    let at = h.slider_point("Field of view", 0.85);
    assert_eq!(h.click_at(at, egui::PointerButton::Primary), Some(MenuAction::ConfigChanged));
    assert!(h.config.fov_deg > 90.0 && h.config.fov_deg <= 110.0, "{}", h.config.fov_deg);
    h.settle();
    assert_eq!(h.click("Invert mouse Y"), Some(MenuAction::ConfigChanged));
    assert!(h.config.invert_y);
}

/// The device's note (e.g. that it renders on the CPU) heads the Video tab on every visit,
/// after its warning on the menus has been dismissed.
#[test]
fn the_video_tab_says_what_the_device_note_says() {
    let mut h = Harness::new();
    let note = "llvmpipe renders on the CPU";
    h.menus.show_warning(note);
    h.menus.set_device_note(note);
    h.settle();
    assert_eq!(h.click("OK"), None, "dismissing the warning changes no setting");
    h.settle();
    assert!(!h.shows(note), "the warning is gone: {:?}", h.shown);
    h.open_settings_tab("Video");
    h.settle();
    assert!(h.shows(note), "{:?}", h.shown);
}

#[test]
fn video_and_gi_settings_change_the_config() {
    let mut h = Harness::new();
    h.open_settings_tab("Video");
    assert!(h.shows("100%"), "{:?}", h.shown);
    let at = h.slider_point("Render scale", 0.02);
    assert_eq!(h.click_at(at, egui::PointerButton::Primary), Some(MenuAction::ConfigChanged));
    assert!(h.config.render_scale < 0.4, "{}", h.config.render_scale);
    h.settle();
    assert_eq!(h.click("Show FPS"), Some(MenuAction::ConfigChanged));
    assert!(h.config.show_fps);
    assert_eq!(h.click("Dynamic resolution"), Some(MenuAction::ConfigChanged));
    assert!(h.config.dynamic_resolution);
    h.settle();
    let at = h.slider_point("Target FPS", 0.02);
    assert_eq!(h.click_at(at, egui::PointerButton::Primary), Some(MenuAction::ConfigChanged));
    assert!(h.config.target_fps < 15.0, "{}", h.config.target_fps);
    assert_eq!(h.click("Global illumination"), None);
    assert_eq!(h.click("enabled"), Some(MenuAction::ConfigChanged));
    assert!(!h.config.gi.enabled);
    let at = h.slider_point("bounces", 0.95);
    assert_eq!(h.click_at(at, egui::PointerButton::Primary), Some(MenuAction::ConfigChanged));
    assert_eq!(h.config.gi.bounces, 3);
}

#[test]
fn audio_sliders_change_the_volumes() {
    let mut h = Harness::new();
    h.open_settings_tab("Audio");
    assert!(h.shows("80") && h.shows("Master volume") && h.shows("Ambience"), "{:?}", h.shown);
    let at = h.slider_point("Master volume", 0.0);
    assert_eq!(h.click_at(at, egui::PointerButton::Primary), Some(MenuAction::ConfigChanged));
    assert_eq!(h.config.master_volume, 0.0);
    h.settle();
    let at = h.slider_point("Ambience", 0.5);
    assert_eq!(h.click_at(at, egui::PointerButton::Primary), Some(MenuAction::ConfigChanged));
    assert!((h.config.ambience_volume - 50.0).abs() <= 2.0, "{}", h.config.ambience_volume);
    assert_eq!(h.config.ambience_volume.fract(), 0.0, "whole percents");
    assert_eq!(h.config.effects_volume, 100.0, "the others stay");
}

#[test]
fn a_warning_shows_until_dismissed() {
    let mut h = Harness::new();
    h.menus.show_warning("config.toml: line 2: controls.fov_deg: 140 is out of range");
    h.settle();
    assert!(h.shows("config.toml: line 2: controls.fov_deg: 140 is out of range"));
    assert_eq!(h.click("OK"), None);
    assert!(!h.shows("config.toml: line 2: controls.fov_deg: 140 is out of range"));
    assert_eq!(h.menus.screen(), Screen::MainMenu);
}

#[test]
fn a_game_is_under_way_except_on_the_main_menu_and_its_settings() {
    let mut h = Harness::new();
    assert!(!h.menus.in_game());
    h.click("Settings");
    assert!(!h.menus.in_game(), "settings from the main menu");
    h.menus.playing();
    assert!(h.menus.in_game());
    h.menus.pause();
    h.settle();
    h.click("Settings");
    assert!(h.menus.in_game(), "settings from the pause menu");
}

/// The settings panel keeps its place from its first drawn frame on (a panel that grew, and
/// moved, over its first frames would make a click aimed at what was shown miss).
#[test]
fn the_settings_panel_does_not_move_once_shown() {
    let mut h = Harness::new();
    h.click_at(h.rect("Settings").center(), egui::PointerButton::Primary);
    let mut places = Vec::new();
    for _ in 0..15 {
        h.pass(Vec::new());
        if h.shows("Back") {
            places.push(h.rect("Back"));
        }
    }
    assert!(places.len() >= 12, "shown from the first frames: {}", places.len());
    assert!(places.windows(2).all(|w| w[0] == w[1]), "{places:?}");
}

#[test]
fn the_level_menu_lists_levels_and_plays_the_one_clicked() {
    use super::LevelCard;
    let mut h = Harness::new();
    assert_eq!(h.click("Levels"), None);
    assert_eq!(h.menus.screen(), Screen::Levels);
    assert!(!h.menus.in_game());
    assert!(h.shows("Looking for levels…"), "{:?}", h.shown);
    assert_eq!(h.menus.wants_thumbnail(), None, "nothing listed yet");

    let card = |name: &str, error: Option<&str>| LevelCard {
        name: name.into(),
        description: format!("{name}, described"),
        location: "shipped".into(),
        error: error.map(str::to_owned),
    };
    h.menus
        .set_levels(vec![card("Broken", Some("scene.gltf: error: node 'p': unknown pickup")), card("Gallery", None)]);
    h.settle();
    for text in
        ["Gallery", "Gallery, described", "Broken", "scene.gltf: error: node 'p': unknown pickup", "Play Gallery"]
    {
        assert!(h.shows(text), "'{text}' not shown: {:?}", h.shown);
    }
    assert!(!h.shows("Play Broken"), "a level that fails check cannot be started");
    assert_eq!(h.menus.wants_thumbnail(), Some(1), "thumbnails for playable levels only");
    h.menus.set_thumbnail(1, 2, 1, &[255, 0, 0, 255, 0, 255, 0, 255]);
    assert_eq!(h.menus.wants_thumbnail(), None);

    assert_eq!(h.click("Play Gallery"), Some(MenuAction::PlayLevel(1)));
    assert_eq!(h.menus.screen(), Screen::Playing);
    assert_eq!(h.menus.wants_thumbnail(), None, "only while the level menu is open");
}

#[test]
fn back_and_esc_leave_the_level_menu() {
    let mut h = Harness::new();
    h.click("Levels");
    assert_eq!(h.click("Back"), None);
    assert_eq!(h.menus.screen(), Screen::MainMenu);
    h.click("Levels");
    assert_eq!(h.pass_with(Vec::new(), &key(KeyCode::Escape)), None);
    assert_eq!(h.menus.screen(), Screen::MainMenu);
}

#[test]
fn the_brightness_screen_sets_brightness_then_goes_to_the_main_menu() {
    let mut h = Harness::new();
    h.menus.calibrate();
    h.settle();
    assert_eq!(h.menus.screen(), Screen::Calibration);
    assert!(h.shows("Set the brightness") && h.shows("Done"), "{:?}", h.shown);
    assert!(!h.menus.in_game());
    let at = h.slider_point("Brightness", 0.95);
    assert_eq!(h.click_at(at, egui::PointerButton::Primary), Some(MenuAction::ConfigChanged));
    assert!(h.config.brightness > 1.5, "{}", h.config.brightness);
    assert!(!h.config.calibrated);
    h.settle();
    assert_eq!(h.click("Done"), Some(MenuAction::ConfigChanged));
    assert!(h.config.calibrated);
    assert_eq!(h.menus.screen(), Screen::MainMenu);
}

#[test]
fn the_pad_moves_through_a_menu_presses_and_goes_back() {
    let mut h = Harness::new();
    h.menus.playing();
    h.menus.pause();
    h.settle();
    // D-pad down: the first tap wakes egui's keyboard focus, the next put it on Resume, then
    // on Restart; A presses it.
    for button in [PadButton::DPadDown, PadButton::DPadDown, PadButton::DPadDown, PadButton::South] {
        let (events, input) = pad_tap(button);
        let action = h.pass_with(events, &input);
        if button == PadButton::South {
            assert_eq!(action, Some(MenuAction::Restart));
        } else {
            assert_eq!(action, None);
        }
    }
    // B (as Esc) resumes from the pause menu, and goes back from Settings.
    h.menus.pause();
    h.settle();
    let (events, input) = pad_tap(PadButton::DPadDown);
    h.pass_with(events, &input);
    let (events, input) = pad_tap(PadButton::East);
    assert_eq!(h.pass_with(events, &input), Some(MenuAction::Resume));
    h.menus.pause();
    h.settle();
    h.click("Settings");
    let (events, input) = pad_tap(PadButton::Start);
    assert_eq!(h.pass_with(events, &input), None);
    assert_eq!(h.menus.screen(), Screen::Paused);
}

#[test]
fn a_gamepad_cell_waits_for_a_pad_button() {
    let mut h = Harness::new();
    h.open_settings_tab("Gamepad");
    assert!(h.shows("RT") && h.shows("A (bottom)"), "{:?}", h.shown);
    assert!(h.shows(&pads_connected(0)), "{:?}", h.shown);
    let mut plugged = Input::default();
    plugged.pad.apply(PadEvent::Connected(0));
    h.pass_with(Vec::new(), &plugged);
    h.pass_with(Vec::new(), &plugged);
    assert!(h.shows(&pads_connected(1)), "the tab says a pad is plugged in: {:?}", h.shown);
    let fire = h.rect(Action::Fire.label());
    let cell = |h: &Harness| {
        h.shown
            .iter()
            .find(|(_, r)| (r.center().y - fire.center().y).abs() < 6.0 && r.left() > fire.right())
            .map(|(_, r)| *r)
            .expect("Fire's gamepad cell")
    };
    h.click_at(cell(&h).center(), egui::PointerButton::Primary);
    h.settle();
    assert!(h.shows(WAITING_PAD));
    // A key does not bind here; B does, though it is Esc to the menus, and it leaves Crouch.
    assert_eq!(h.pass_with(Vec::new(), &key(KeyCode::KeyK)), None);
    let (events, input) = pad_tap(PadButton::East);
    assert_eq!(h.pass_with(events, &input), Some(MenuAction::ConfigChanged));
    assert_eq!(h.config.gamepad.bindings.get(Action::Fire), Some(PadButton::East));
    assert_eq!(h.config.gamepad.bindings.get(Action::Crouch), None);
    assert_eq!(h.menus.screen(), Screen::Settings, "the B that bound did not also go back");
    h.settle();
    assert!(h.shows("B (right) now does Fire; it was taken from Crouch."), "{:?}", h.shown);
    // Start cancels a waiting cell and binds nothing.
    h.click_at(cell(&h).center(), egui::PointerButton::Primary);
    h.settle();
    let (events, input) = pad_tap(PadButton::Start);
    assert_eq!(h.pass_with(events, &input), None);
    assert_eq!(h.menus.screen(), Screen::Settings, "the first Start only cancels");
    h.settle();
    assert!(!h.shows(WAITING_PAD));
    // Right-click clears; reset brings the defaults back.
    assert_eq!(h.click_at(cell(&h).center(), egui::PointerButton::Secondary), Some(MenuAction::ConfigChanged));
    assert_eq!(h.config.gamepad.bindings.get(Action::Fire), None);
    h.settle();
    assert_eq!(h.click("Reset gamepad to defaults"), Some(MenuAction::ConfigChanged));
    assert_eq!(h.config.gamepad, crate::GamepadSettings::default());
}
