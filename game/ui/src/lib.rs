//! Headlamp's front end: the menus and the Settings screen, key and gamepad bindings, the
//! config file they edit, the in-game HUD and the F3 performance overlay. All of it is egui
//! drawn by the engine's UI layer; none of it touches the simulation, which only ever sees what the game
//! makes of it (a `Config`, a `MenuAction`).

pub mod bindings;
pub mod config;
pub mod egui_harness;
pub mod gi_panel;
pub mod hud;
pub mod menu;
pub mod overlay;
pub mod pad_bindings;

pub use bindings::{Action, Binding, KeyBindings};
pub use config::{config_path, Config, ConfigError};
pub use hud::HudInfo;
pub use menu::{LevelCard, MenuAction, Menus, Screen, THUMBNAIL};
pub use overlay::{FrameRate, OverlayInfo};
pub use pad_bindings::{GamepadSettings, PadBindings};
