//! Headlamp, the game: the deterministic simulation, the command line, the play loop, replays,
//! and how the engine and the GI plugin are wired.

pub mod actors;
pub mod bench;
pub mod check;
pub mod cli;
pub mod command_sampler;
pub mod crawler_body;
pub mod game_events;
pub mod golden;
pub mod gun_model;
pub mod level_list;
pub mod level_watch;
pub mod play;
pub mod recording;
pub mod render_cmd;
pub mod replay_cmd;
pub mod replay_frames;
pub mod replay_goldens;
pub mod script;
pub mod script_trace;
pub mod sim;
pub mod sound;
pub mod thumbnail;
pub mod view;
pub mod world_reference;

use std::path::PathBuf;

/// The render plugins the game runs with, and the handle that tunes the GI live.
pub fn plugins(gi: plugin_gi::GiSettings) -> (Vec<Box<dyn engine::plugin::Plugin>>, plugin_gi::GiHandle) {
    let plugin = plugin_gi::GiPlugin::new(gi);
    let handle = plugin.handle();
    (vec![Box::new(plugin)], handle)
}

/// The level `headlamp` plays when none is named: the shipped one beside the executable's
/// source tree, or `levels/cellar` under the working directory.
pub fn default_level() -> PathBuf {
    let beside_source = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../levels/cellar"));
    if beside_source.join("level.toml").exists() {
        beside_source
    } else {
        PathBuf::from("levels/cellar")
    }
}
