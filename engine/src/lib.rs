//! Headlamp's engine: GPU context, render graph, scene assets, deferred renderer, headless
//! output, the window loop and its egui UI layer, gamepads, the fixed-tick clock and the replay
//! container.
//! It knows nothing of any game.

pub mod bindings;
pub mod camera;
pub mod clock;
pub mod dynamic_resolution;
pub mod frame;
pub mod gamepad;
pub mod globals;
pub mod gpu;
pub mod gpu_instances;
pub mod gpu_layout;
pub mod gpu_scene;
pub mod gpu_timer;
pub mod graph;
pub mod headlamp;
pub mod headless;
pub mod input;
pub mod output;
pub mod passes;
pub mod plugin;
pub mod primitives;
pub mod renderer;
pub mod replay;
pub mod shader;
pub mod shared_constants;
pub mod start_view;
pub mod ui;
pub mod view_state;
pub mod window;

pub use egui;
pub use glam;
pub use scene;
pub use wgpu;
