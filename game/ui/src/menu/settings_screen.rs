//! The Settings screen: tabs for controls, key bindings, the gamepad, video, audio and global
//! illumination. It edits the [`Config`] in place; the menu reports any change to the game.
//!
//! Rebinding: clicking a binding cell makes it wait ("press a key…"); the next key or mouse
//! button sets it, Esc cancels. While a cell waits everything else is disabled, so the click
//! that sets a mouse button cannot also press another widget. A gamepad cell waits for a pad
//! button ("press a button…"); Start or Esc cancels.

use engine::egui::{self, Color32, RichText};
use engine::input::Input;

use super::widgets::panel;
use crate::bindings::{Action, Binding, SLOTS};
use crate::config::Config;
use crate::gi_panel;
use crate::pad_bindings::{self, GamepadSettings};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum Tab {
    #[default]
    Controls,
    Bindings,
    Gamepad,
    Video,
    Audio,
    Gi,
}

impl Tab {
    const ALL: [Tab; 6] = [Tab::Controls, Tab::Bindings, Tab::Gamepad, Tab::Video, Tab::Audio, Tab::Gi];

    fn label(self) -> &'static str {
        match self {
            Tab::Controls => "Controls",
            Tab::Bindings => "Key bindings",
            Tab::Gamepad => "Gamepad",
            Tab::Video => "Video",
            Tab::Audio => "Audio",
            Tab::Gi => "Global illumination",
        }
    }
}

/// The text of a cell waiting for a key.
pub const WAITING: &str = "press a key…";
/// The text of a gamepad cell waiting for a button.
pub const WAITING_PAD: &str = "press a button…";
/// The text of an empty binding cell.
pub const UNBOUND: &str = "—";
/// Sliders are this wide, so tests know where a slider's rail is.
pub const SLIDER_WIDTH: f32 = 220.0;
const CELL_WIDTH: f32 = 130.0;
const NOTICE: Color32 = Color32::from_rgb(235, 190, 90);

#[derive(Default)]
pub(super) struct SettingsScreen {
    tab: Tab,
    /// The binding cell waiting for a key: action and slot.
    waiting: Option<(Action, usize)>,
    /// The gamepad cell waiting for a pad button.
    waiting_pad: Option<Action>,
    /// What the last rebinding did, above all when it took the key from another action.
    notice: Option<String>,
    /// Gamepads connected as of this frame, said on the Gamepad tab.
    pads: usize,
    /// What the Video tab says of the device first, e.g. that it renders on the CPU.
    pub device_note: Option<String>,
}

impl SettingsScreen {
    /// Entering the screen: nothing half-done from last time.
    pub fn open(&mut self) {
        self.waiting = None;
        self.waiting_pad = None;
        self.notice = None;
    }

    /// Draws the screen and applies what the player does to `config`. Returns true to leave
    /// (Back, or Esc while no cell waits).
    pub fn show(&mut self, ctx: &egui::Context, config: &mut Config, input: &Input, esc: bool) -> bool {
        self.pads = input.pad.connected();
        if let Some((action, slot)) = self.waiting {
            if esc {
                self.waiting = None;
            } else if let Some(binding) = pressed_binding(ctx, input) {
                self.waiting = None;
                let taken_from = config.bindings.set(action, slot, binding);
                self.notice = Some(rebind_notice(config, action, binding, taken_from));
            }
        } else if let Some(action) = self.waiting_pad {
            // The pad's buttons first: East also reaches the menus as Esc (it goes back), yet
            // may be bound; Start may not, and cancels.
            let button = input.pad.pressed_buttons().iter().copied().find(|b| pad_bindings::is_bindable(*b));
            if let Some(button) = button {
                self.waiting_pad = None;
                let taken_from = config.gamepad.bindings.set(action, button).ok().flatten();
                self.notice = Some(pad_rebind_notice(action, pad_bindings::button_label(button), taken_from));
            } else if esc || input.pad.pressed(engine::gamepad::PadButton::Start) {
                self.waiting_pad = None;
            }
        } else if esc {
            return true;
        }
        let idle = self.waiting.is_none() && self.waiting_pad.is_none();
        let mut back = false;
        panel(ctx, "settings", |ui| {
            // Wide enough for the six tabs in one row: a row wider than the panel grows it over its
            // first frames, and the centred panel moves.
            ui.set_width(640.0);
            // Larger than egui's tool-sized defaults: a game menu is read from further away.
            for (style, font) in ui.style_mut().text_styles.iter_mut() {
                if matches!(style, egui::TextStyle::Body | egui::TextStyle::Button) {
                    font.size = 15.0;
                }
            }
            ui.label(RichText::new("Settings").size(26.0).strong().color(Color32::from_gray(240)));
            ui.add_space(8.0);
            ui.add_enabled_ui(idle, |ui| {
                ui.horizontal(|ui| {
                    for tab in Tab::ALL {
                        ui.selectable_value(&mut self.tab, tab, RichText::new(tab.label()).size(16.0));
                    }
                });
            });
            ui.separator();
            ui.spacing_mut().slider_width = SLIDER_WIDTH;
            ui.spacing_mut().item_spacing.y = 8.0;
            // One fixed size for every tab, so the panel does not jump when the tab changes.
            let height = (ctx.content_rect().height() - 210.0).clamp(120.0, 420.0);
            // A region of exactly that size from the first frame: a scroll area left to size
            // itself grows over its first frames, and the centred panel moves with it.
            let size = egui::vec2(ui.available_width(), height);
            ui.allocate_ui_with_layout(size, egui::Layout::top_down(egui::Align::Min), |ui| {
                ui.set_min_size(size);
                egui::ScrollArea::vertical().auto_shrink([false, false]).max_height(height).show(ui, |ui| {
                    match self.tab {
                        Tab::Controls => controls(ui, config),
                        Tab::Bindings => self.bindings(ui, config),
                        Tab::Gamepad => self.gamepad(ui, config),
                        Tab::Video => {
                            if let Some(note) = &self.device_note {
                                ui.label(RichText::new(note).color(NOTICE));
                                ui.separator();
                            }
                            video(ui, config)
                        }
                        Tab::Audio => audio(ui, config),
                        Tab::Gi => {
                            gi_panel::sliders(ui, &mut config.gi);
                            ui.label(RichText::new("Changes show on the next frame.").weak());
                        }
                    }
                });
            });
            ui.separator();
            back = ui.add_enabled(idle, egui::Button::new(RichText::new("Back").size(18.0))).clicked();
        });
        back
    }

    fn gamepad(&mut self, ui: &mut egui::Ui, config: &mut Config) {
        let idle = self.waiting_pad.is_none();
        let pad = &mut config.gamepad;
        ui.add_enabled_ui(idle, |ui| {
            let look = egui::Slider::new(&mut pad.look_sensitivity, GamepadSettings::SENSITIVITY_RANGE)
                .logarithmic(true)
                .fixed_decimals(2)
                .text("Look sensitivity");
            ui.add(look).on_hover_text(format!(
                "1.00 turns the view {:.2} radians a second with the right stick pushed all the way",
                GamepadSettings::BASE_RADIANS_PER_SECOND
            ));
            let dead = egui::Slider::new(&mut pad.dead_zone, GamepadSettings::DEAD_ZONE_RANGE)
                .custom_formatter(|v, _| format!("{:.0}%", v * 100.0))
                .custom_parser(|s| s.trim().trim_end_matches('%').trim().parse::<f64>().ok().map(|p| p / 100.0))
                .text("Stick dead zone");
            ui.add(dead).on_hover_text("how far a stick moves before it counts: raise it if the view drifts");
        });
        let help = if idle {
            "The left stick walks, the right stick looks (Invert mouse Y in Controls turns it over too), \
             Start pauses. Click a button's cell, then press a pad button. Right-click clears it."
        } else {
            "Press a button on the gamepad for it; Start or Esc cancels."
        };
        ui.label(RichText::new(help).weak());
        ui.label(pads_connected(self.pads));
        if let Some(notice) = &self.notice {
            ui.label(RichText::new(notice).color(NOTICE));
        }
        if ui.add_enabled(idle, egui::Button::new("Reset gamepad to defaults")).clicked() {
            *pad = GamepadSettings::default();
            self.notice = Some("The gamepad's buttons and sticks are back to their defaults.".into());
        }
        ui.add_space(6.0);
        egui::Grid::new("pad bindings").num_columns(2).spacing([12.0, 4.0]).striped(true).show(ui, |ui| {
            ui.label(RichText::new("Action").strong());
            ui.label(RichText::new("Gamepad").strong());
            ui.end_row();
            for action in Action::ALL {
                ui.label(action.label());
                if self.waiting_pad == Some(action) {
                    let cell = egui::Button::new(RichText::new(WAITING_PAD).color(Color32::BLACK))
                        .fill(NOTICE)
                        .sense(egui::Sense::hover())
                        .min_size(egui::vec2(CELL_WIDTH, 0.0));
                    ui.add(cell);
                    ui.end_row();
                    continue;
                }
                let bound = pad.bindings.get(action);
                let text = bound.map_or(UNBOUND, pad_bindings::button_label);
                let cell = egui::Button::new(text).min_size(egui::vec2(CELL_WIDTH, 0.0));
                let response =
                    ui.add_enabled(idle, cell).on_hover_text("click, then press a pad button; right-click clears");
                if response.clicked() {
                    self.waiting_pad = Some(action);
                    self.notice = None;
                }
                if response.secondary_clicked() && bound.is_some() {
                    pad.bindings.clear(action);
                    self.notice = Some(format!("{text} no longer does {}.", action.label()));
                }
                ui.end_row();
            }
        });
    }

    fn bindings(&mut self, ui: &mut egui::Ui, config: &mut Config) {
        let idle = self.waiting.is_none();
        // Help, notice and reset first: the grid below may scroll on a small window.
        let help = if idle {
            "Click a binding, then press a key or mouse button. Right-click clears it. A key does one \
             thing: giving it to an action takes it from any other."
        } else {
            "Press a key or mouse button for it; Esc cancels."
        };
        ui.label(RichText::new(help).weak());
        if let Some(notice) = &self.notice {
            ui.label(RichText::new(notice).color(NOTICE));
        }
        if ui.add_enabled(idle, egui::Button::new("Reset to defaults")).clicked() {
            config.bindings.reset_defaults();
            self.notice = Some("All bindings are back to their defaults.".into());
        }
        ui.add_space(6.0);
        egui::Grid::new("key bindings").num_columns(1 + SLOTS).spacing([12.0, 4.0]).striped(true).show(ui, |ui| {
            ui.label(RichText::new("Action").strong());
            for slot in 0..SLOTS {
                ui.label(RichText::new(format!("Binding {}", slot + 1)).strong());
            }
            ui.end_row();
            for action in Action::ALL {
                ui.label(action.label());
                for slot in 0..SLOTS {
                    if self.waiting == Some((action, slot)) {
                        // Looks like a cell but takes no clicks: the click that sets a mouse
                        // button must not start waiting again.
                        let cell = egui::Button::new(RichText::new(WAITING).color(Color32::BLACK))
                            .fill(NOTICE)
                            .sense(egui::Sense::hover())
                            .min_size(egui::vec2(CELL_WIDTH, 0.0));
                        ui.add(cell);
                        continue;
                    }
                    let bound = config.bindings.get(action)[slot];
                    let text = bound.map_or(UNBOUND.into(), |b| b.label());
                    let cell = egui::Button::new(text.as_ref()).min_size(egui::vec2(CELL_WIDTH, 0.0));
                    let response = ui
                        .add_enabled(idle, cell)
                        .on_hover_text("click, then press a key or mouse button; right-click clears");
                    if response.clicked() {
                        self.waiting = Some((action, slot));
                        self.notice = None;
                    }
                    if response.secondary_clicked() && bound.is_some() {
                        config.bindings.clear(action, slot);
                        self.notice = Some(format!("{} no longer does {}.", text, action.label()));
                    }
                }
                ui.end_row();
            }
        });
    }
}

fn controls(ui: &mut egui::Ui, config: &mut Config) {
    let sensitivity = egui::Slider::new(&mut config.mouse_sensitivity, Config::SENSITIVITY_RANGE)
        .logarithmic(true)
        .fixed_decimals(2)
        .text("Mouse sensitivity");
    ui.add(sensitivity)
        .on_hover_text(format!("1.00 turns the view {} radians per pixel", Config::BASE_RADIANS_PER_PIXEL));
    ui.checkbox(&mut config.invert_y, "Invert mouse Y");
    let fov =
        egui::Slider::new(&mut config.fov_deg, Config::FOV_RANGE).fixed_decimals(0).suffix("°").text("Field of view");
    ui.add(fov).on_hover_text("vertical, in degrees");
}

fn video(ui: &mut egui::Ui, config: &mut Config) {
    let scale = egui::Slider::new(&mut config.render_scale, Config::RENDER_SCALE_RANGE)
        .custom_formatter(|v, _| format!("{:.0}%", v * 100.0))
        .custom_parser(|s| s.trim().trim_end_matches('%').trim().parse::<f64>().ok().map(|p| p / 100.0))
        .text("Render scale");
    ui.add(scale).on_hover_text(if config.dynamic_resolution {
        "the highest resolution of the 3D view relative to the window: dynamic resolution goes no higher"
    } else {
        "the 3D view's resolution relative to the window: lower is faster"
    });
    ui.checkbox(&mut config.dynamic_resolution, "Dynamic resolution")
        .on_hover_text("lower the render scale, down to 25 %, while frames are slower than the target frame rate");
    let fps = egui::Slider::new(&mut config.target_fps, Config::TARGET_FPS_RANGE).fixed_decimals(0).text("Target FPS");
    ui.add_enabled(config.dynamic_resolution, fps).on_hover_text("the frame rate dynamic resolution holds");
    ui.checkbox(&mut config.vsync, "VSync").on_hover_text("wait for the display: no tearing, a little more latency");
    ui.checkbox(&mut config.show_fps, "Show FPS");
    ui.separator();
    let brightness = egui::Slider::new(&mut config.brightness, Config::BRIGHTNESS_RANGE)
        .step_by(0.1)
        .fixed_decimals(1)
        .suffix(" stops")
        .text("Brightness");
    ui.add(brightness).on_hover_text("each stop doubles the picture's light; 0 shows the level as it is lit");
    ui.checkbox(&mut config.reduce_flashing, "Reduce flashing")
        .on_hover_text("a steady lamp when the battery runs low, and a dimmer muzzle flash");
    ui.checkbox(&mut config.captions, "Captions")
        .on_hover_text("write what is heard and matters: a crawler noticing you, where, and whether you can see it");
    let hud = egui::Slider::new(&mut config.hud_scale, Config::HUD_SCALE_RANGE)
        .step_by(0.05)
        .custom_formatter(|v, _| format!("{:.0}%", v * 100.0))
        .custom_parser(|s| s.trim().trim_end_matches('%').trim().parse::<f64>().ok().map(|p| p / 100.0))
        .text("HUD size");
    ui.add(hud).on_hover_text("the HUD while playing; the menus keep their size");
    let crosshair = egui::Slider::new(&mut config.crosshair_scale, Config::CROSSHAIR_SCALE_RANGE)
        .fixed_decimals(1)
        .text("Crosshair size");
    ui.add(crosshair);
}

fn audio(ui: &mut egui::Ui, config: &mut Config) {
    fn volume<'a>(value: &'a mut f32, label: &str) -> egui::Slider<'a> {
        egui::Slider::new(value, Config::VOLUME_RANGE).step_by(1.0).fixed_decimals(0).suffix(" %").text(label)
    }
    ui.add(volume(&mut config.master_volume, "Master volume")).on_hover_text("everything the game plays");
    ui.add(volume(&mut config.effects_volume, "Effects"))
        .on_hover_text("shots, steps, the lamp, pickups, the crawlers, the stings at the end");
    ui.add(volume(&mut config.ambience_volume, "Ambience"))
        .on_hover_text("the quiet of the room: air, a hum, dripping");
    ui.label(RichText::new("Changes are heard at once. Without a sound device the game plays silently.").weak());
}

/// The first key or mouse button pressed this frame that can be bound. The game's `Input`
/// comes first (it tells left from right Shift and the keypad from the digits); egui's
/// events add what the window loop gives to the UI alone: clicks over the menu, and keys
/// egui consumes (Tab, or any key while a widget has keyboard focus).
/// The Gamepad tab's line on what is plugged in.
pub fn pads_connected(n: usize) -> String {
    match n {
        0 => "No gamepad connected: plug one in at any time.".to_owned(),
        1 => "A gamepad is connected.".to_owned(),
        n => format!("{n} gamepads are connected; they play together."),
    }
}

fn pressed_binding(ctx: &egui::Context, input: &Input) -> Option<Binding> {
    let from_game = input
        .pressed_keys()
        .iter()
        .map(|&k| Binding::Key(k))
        .chain(input.pressed_buttons().iter().map(|&b| Binding::Mouse(b)));
    let from_egui: Vec<Binding> = ctx.input(|i| {
        i.events
            .iter()
            .filter_map(|event| match event {
                egui::Event::Key { key, physical_key, pressed: true, repeat: false, .. } => {
                    Binding::from_egui_key(physical_key.unwrap_or(*key))
                }
                egui::Event::PointerButton { button, pressed: true, .. } => Some(Binding::from_egui_button(*button)),
                _ => None,
            })
            .collect()
    });
    from_game.chain(from_egui).find(|b| b.is_supported())
}

fn rebind_notice(config: &Config, action: Action, binding: Binding, taken_from: Option<Action>) -> String {
    let key = binding.label();
    match taken_from {
        Some(other) if config.bindings.bindings(other).next().is_none() => {
            format!("{key} now does {}; it was taken from {}, which has no key left.", action.label(), other.label())
        }
        Some(other) => format!("{key} now does {}; it was taken from {}.", action.label(), other.label()),
        None => format!("{key} now does {}.", action.label()),
    }
}

fn pad_rebind_notice(action: Action, button: &str, taken_from: Option<Action>) -> String {
    match taken_from {
        Some(other) => format!("{button} now does {}; it was taken from {}.", action.label(), other.label()),
        None => format!("{button} now does {}.", action.label()),
    }
}
