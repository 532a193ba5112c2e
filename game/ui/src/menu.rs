//! The front-end screens as a small state machine: main menu, pause menu, settings, game
//! over, and "playing" (no menu). The game asks [`Menus::show`] every frame and acts on the
//! [`MenuAction`] it returns; it switches screens itself with [`Menus::pause`],
//! [`Menus::game_over`] and [`Menus::playing`].

mod calibration_screen;
mod levels_screen;
mod settings_screen;
#[cfg(test)]
mod tests;
mod widgets;

use engine::egui::{self, Color32, RichText};
use engine::input::{Input, KeyCode};

use crate::config::Config;
use levels_screen::LevelsScreen;
pub use levels_screen::{LevelCard, THUMBNAIL};
use settings_screen::SettingsScreen;
use widgets::{big_button, heading, panel};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Screen {
    MainMenu,
    /// No menu: the game has the screen (and the mouse).
    Playing,
    Paused,
    Settings,
    /// The level menu, from the main menu.
    Levels,
    /// Brightness calibration, on a first start; then the main menu.
    Calibration,
    GameOver {
        won: bool,
    },
}

/// What the player asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MenuAction {
    /// Start a game from the main menu.
    Play,
    /// Start the level of this card (see [`Menus::set_levels`]) from the level menu.
    PlayLevel(usize),
    /// Leave the pause menu.
    Resume,
    /// Start the level again.
    Restart,
    /// Back to the main menu (the game ends the current one).
    MainMenu,
    Quit,
    /// A setting changed: save the config and apply it.
    ConfigChanged,
}

pub struct Menus {
    screen: Screen,
    /// Where Settings' Back returns: the main menu or the pause menu.
    settings_from: Screen,
    settings: SettingsScreen,
    levels: LevelsScreen,
    /// Shown on every menu until dismissed, e.g. the config file's problem.
    warning: Option<String>,
    /// Set when the game switches screens: the Esc that made it pause must not also resume
    /// on the new screen in the same frame.
    ignore_esc: bool,
}

impl Default for Menus {
    fn default() -> Self {
        Self::new()
    }
}

/// The title of the main menu.
pub const TITLE: &str = "Headlamp";
/// The headlamp's warm white, for titles.
const LAMP_YELLOW: Color32 = Color32::from_rgb(250, 225, 140);

impl Menus {
    /// Starts on the main menu.
    pub fn new() -> Self {
        Self {
            screen: Screen::MainMenu,
            settings_from: Screen::MainMenu,
            settings: SettingsScreen::default(),
            levels: LevelsScreen::default(),
            warning: None,
            ignore_esc: false,
        }
    }

    pub fn screen(&self) -> Screen {
        self.screen
    }

    /// A menu is up: the game should release the mouse and, except in a paused or finished
    /// game, may stop its simulation.
    /// Whether a game is under way behind the menus (its HUD belongs on screen): not on the
    /// main menu, nor in Settings opened from it.
    pub fn in_game(&self) -> bool {
        match self.screen {
            Screen::MainMenu | Screen::Levels | Screen::Calibration => false,
            Screen::Settings => self.settings_from != Screen::MainMenu,
            _ => true,
        }
    }

    pub fn is_open(&self) -> bool {
        self.screen != Screen::Playing
    }

    /// Opens the pause menu, while playing only (so e.g. losing focus in Settings stays there).
    pub fn pause(&mut self) {
        if self.screen == Screen::Playing {
            self.screen = Screen::Paused;
            self.ignore_esc = true;
        }
    }

    /// The game ended: won (reached the exit or cleared the level) or died.
    pub fn game_over(&mut self, won: bool) {
        self.screen = Screen::GameOver { won };
        self.ignore_esc = true;
    }

    /// The brightness screen (a first start opens it before the main menu).
    pub fn calibrate(&mut self) {
        self.screen = Screen::Calibration;
    }

    /// Back to the main menu (e.g. a level picked from the level menu failed to load).
    pub fn to_main_menu(&mut self) {
        self.screen = Screen::MainMenu;
    }

    /// Closes any menu.
    pub fn playing(&mut self) {
        self.screen = Screen::Playing;
    }

    /// The levels the level menu lists, in order ([`MenuAction::PlayLevel`] names them by
    /// index); until this is called it says it is still looking.
    pub fn set_levels(&mut self, cards: Vec<LevelCard>) {
        self.levels.set_cards(cards);
    }

    pub fn levels(&self) -> Option<&[LevelCard]> {
        self.levels.cards()
    }

    /// The level whose thumbnail the game should render next: only while the level menu is
    /// open (thumbnails are made on first sight).
    pub fn wants_thumbnail(&self) -> Option<usize> {
        (self.screen == Screen::Levels).then(|| self.levels.wants_thumbnail()).flatten()
    }

    /// A level's thumbnail, RGBA8 rows from the top.
    pub fn set_thumbnail(&mut self, index: usize, width: usize, height: usize, rgba: &[u8]) {
        self.levels.set_thumbnail(index, width, height, rgba);
    }

    /// Shows `text` (e.g. from `Config::load_or_default`) on the menus until dismissed.
    pub fn show_warning(&mut self, text: impl Into<String>) {
        self.warning = Some(text.into());
    }

    /// The warning the menus show, until dismissed.
    pub fn warning(&self) -> Option<&str> {
        self.warning.as_deref()
    }

    /// What Settings > Video says of the device first (e.g. that it renders on the CPU, and
    /// with which settings): shown there on every visit, where a warning is shown once.
    pub fn set_device_note(&mut self, text: impl Into<String>) {
        self.settings.device_note = Some(text.into());
    }

    pub fn device_note(&self) -> Option<&str> {
        self.settings.device_note.as_deref()
    }

    /// Draws the current screen and handles its clicks and keys. `input` is the frame's input
    /// as `WindowApp::update` saw it (its presses are cleared before `WindowApp::ui` runs, so
    /// the game keeps a copy); Esc resumes from Paused and goes back from Settings.
    pub fn show(&mut self, ctx: &egui::Context, config: &mut Config, input: &Input) -> Option<MenuAction> {
        let ignore_esc = std::mem::take(&mut self.ignore_esc);
        // egui also sees Esc when it keeps a key from the game (a widget has keyboard focus).
        let esc = !ignore_esc && (input.pressed(KeyCode::Escape) || ctx.input(|i| i.key_pressed(egui::Key::Escape)));
        if self.screen == Screen::Playing {
            return None;
        }
        backdrop(ctx);
        self.warning_banner(ctx);
        let action = match self.screen {
            Screen::Playing => None,
            Screen::MainMenu => self.main_menu(ctx),
            Screen::Paused if esc => Some(MenuAction::Resume),
            Screen::Paused => self.pause_menu(ctx),
            Screen::Settings => {
                let before = config.clone();
                if self.settings.show(ctx, config, input, esc) {
                    self.screen = self.settings_from;
                }
                (*config != before).then_some(MenuAction::ConfigChanged)
            }
            Screen::Levels => match self.levels.show(ctx, esc) {
                Some(Some(index)) => Some(MenuAction::PlayLevel(index)),
                Some(None) => {
                    self.screen = Screen::MainMenu;
                    None
                }
                None => None,
            },
            Screen::Calibration => {
                let before = config.clone();
                if calibration_screen::show(ctx, config) {
                    self.screen = Screen::MainMenu;
                }
                (*config != before).then_some(MenuAction::ConfigChanged)
            }
            Screen::GameOver { won } => self.game_over_menu(ctx, won),
        };
        match action {
            Some(MenuAction::Play | MenuAction::Resume | MenuAction::Restart | MenuAction::PlayLevel(_)) => {
                self.screen = Screen::Playing
            }
            Some(MenuAction::MainMenu) => self.screen = Screen::MainMenu,
            _ => {}
        }
        action
    }

    fn open_settings(&mut self) {
        self.settings_from = self.screen;
        self.screen = Screen::Settings;
        self.settings.open();
    }

    fn main_menu(&mut self, ctx: &egui::Context) -> Option<MenuAction> {
        let mut action = None;
        panel(ctx, "main menu", |ui| {
            ui.label(RichText::new(TITLE).size(48.0).strong().color(LAMP_YELLOW));
            ui.add_space(24.0);
            if big_button(ui, "Play") {
                action = Some(MenuAction::Play);
            }
            if big_button(ui, "Levels") {
                self.screen = Screen::Levels;
            }
            if big_button(ui, "Settings") {
                self.open_settings();
            }
            if big_button(ui, "Quit") {
                action = Some(MenuAction::Quit);
            }
        });
        action
    }

    fn pause_menu(&mut self, ctx: &egui::Context) -> Option<MenuAction> {
        let mut action = None;
        panel(ctx, "pause menu", |ui| {
            heading(ui, "Paused");
            for (text, chosen) in [("Resume", MenuAction::Resume), ("Restart", MenuAction::Restart)] {
                if big_button(ui, text) {
                    action = Some(chosen);
                }
            }
            if big_button(ui, "Settings") {
                self.open_settings();
            }
            for (text, chosen) in [("Main menu", MenuAction::MainMenu), ("Quit", MenuAction::Quit)] {
                if big_button(ui, text) {
                    action = Some(chosen);
                }
            }
        });
        action
    }

    fn game_over_menu(&mut self, ctx: &egui::Context, won: bool) -> Option<MenuAction> {
        let mut action = None;
        panel(ctx, "game over", |ui| {
            let (title, color) =
                if won { ("You made it out", LAMP_YELLOW) } else { ("You died", Color32::from_rgb(230, 70, 60)) };
            ui.label(RichText::new(title).size(32.0).strong().color(color));
            ui.add_space(16.0);
            for (text, chosen) in
                [("Restart", MenuAction::Restart), ("Main menu", MenuAction::MainMenu), ("Quit", MenuAction::Quit)]
            {
                if big_button(ui, text) {
                    action = Some(chosen);
                }
            }
        });
        action
    }

    fn warning_banner(&mut self, ctx: &egui::Context) {
        let Some(text) = &self.warning else { return };
        let mut dismissed = false;
        egui::Area::new(egui::Id::unique("menu warning"))
            .order(egui::Order::Foreground)
            .anchor(egui::Align2::CENTER_TOP, egui::vec2(0.0, 12.0))
            .show(ctx, |ui| {
                egui::Frame::NONE
                    .fill(Color32::from_rgba_unmultiplied(90, 20, 15, 235))
                    .corner_radius(6.0)
                    .inner_margin(egui::Margin::symmetric(12, 8))
                    .show(ui, |ui| {
                        ui.set_max_width(ctx.content_rect().width() * 0.8);
                        ui.horizontal_wrapped(|ui| {
                            ui.label(RichText::new(text).color(Color32::from_gray(240)));
                            dismissed = ui.button("OK").clicked();
                        });
                    });
            });
        if dismissed {
            self.warning = None;
        }
    }
}

/// Dims the game behind a menu and takes the clicks that miss the menu, so they neither
/// reach the game nor capture the mouse.
fn backdrop(ctx: &egui::Context) {
    let screen = ctx.content_rect();
    egui::Area::new(egui::Id::unique("menu backdrop")).order(egui::Order::Middle).fixed_pos(screen.min).show(
        ctx,
        |ui| {
            let (rect, _) = ui.allocate_exact_size(screen.size(), egui::Sense::click());
            ui.painter().rect_filled(rect, 0.0, Color32::from_black_alpha(170));
        },
    );
}
