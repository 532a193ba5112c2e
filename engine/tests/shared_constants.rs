//! Numbers the engine's Rust and WGSL share cannot drift: each WGSL constant of
//! `engine::shared_constants::CONSTANTS`, in every module as the engine assembles it, has its
//! Rust constant's value, as naga evaluates it; and the buffers the engine sizes for a WGSL
//! binding have that binding's size. No GPU needed.

mod constant_check;

use constant_check::{check_constants, global_size};
use engine::shared_constants::CONSTANTS;

fn engine_files() -> Vec<(&'static str, String)> {
    engine::passes::SHADERS.iter().map(|(name, source)| (*name, engine::shader::compose(source, &[]))).collect()
}

#[test]
fn every_shared_constant_has_its_rust_value_in_wgsl() {
    let raw: Vec<(&str, &str)> =
        engine::passes::SHADERS.iter().chain(engine::shader::ENGINE_INCLUDES).copied().collect();
    let compared = check_constants(&engine_files(), &raw, CONSTANTS)
        .unwrap_or_else(|e| panic!("WGSL constants drifted from Rust:\n{e}"));
    assert!(compared >= CONSTANTS.len(), "compared {compared} of {} constants", CONSTANTS.len());
}

/// The ambient cube the view-model pass reads is the buffer the engine makes.
#[test]
fn the_ambient_cube_has_the_size_the_engine_makes_it() {
    let files = engine_files();
    let (file, source) = files.iter().find(|(f, _)| *f == "view_model.wgsl").expect("the view model's file");
    assert_eq!(global_size(file, source, "ambient_cube") as u64, engine::passes::VIEW_MODEL_IRRADIANCE_SIZE);
}
