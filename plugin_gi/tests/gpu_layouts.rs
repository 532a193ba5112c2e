//! GPU layouts that cannot drift: every struct of the GI's WGSL, assembled as the plugin
//! assembles it, is laid out by naga and compared with its Rust twin (`plugin_gi::gpu_types`),
//! or is one of the GPU-only structs listed there. The engine's shaders are checked alongside,
//! as the GI's include the engine's: a struct of the same name must agree across both. The byte
//! sizes the CPU keeps of GPU-only structs are checked against WGSL too. No GPU needed.

#[path = "../../engine/tests/layout_check/mod.rs"]
mod layout_check;

use engine::gpu_layout::GpuLayout;
use engine::wgpu;
use layout_check::{check, compare, Checked};
use plugin_gi::gpu_types::{self, GiParams, GATHER_STATS_SIZE, NODE_SIZE, RETRY_HEADER, VOLUME_LIGHT_SIZE};

fn compose(files: &[(&'static str, &str)], includes: &[(&str, &str)]) -> Vec<(&'static str, String)> {
    files.iter().map(|(name, source)| (*name, engine::shader::compose(source, includes))).collect()
}

/// The GI's files and the engine's, with the twins and GPU-only lists of both; and how many
/// structs the GI's files declare.
fn check_all() -> (Checked, usize) {
    let gi_files = compose(plugin_gi::SHADERS, plugin_gi::SHADER_INCLUDES);
    let gi_structs = gi_files.iter().map(|(name, source)| layout_check::wgsl_structs(name, source).len()).sum();
    let files = [compose(engine::passes::SHADERS, &[]), gi_files].concat();
    let twins = [engine::gpu_layout::twins(), gpu_types::twins()].concat();
    let gpu_only = [engine::gpu_layout::GPU_ONLY, gpu_types::GPU_ONLY].concat();
    let checked = check(&files, &twins, &gpu_only).unwrap_or_else(|e| panic!("GPU layouts drifted:\n{e}"));
    (checked, gi_structs)
}

#[test]
fn every_wgsl_struct_has_its_twins_layout_or_is_gpu_only() {
    let (checked, gi_structs) = check_all();
    // Not vacuous: the GI's files declare structs, and each GI twin found its WGSL struct.
    assert_ne!(gi_structs, 0);
    let gi_twins = gpu_types::twins();
    assert!(!gi_twins.is_empty());
    assert!(gi_twins.iter().all(|t| checked.structs.contains_key(t.wgsl)));
    assert_eq!(checked.twins, engine::gpu_layout::twins().len() + gi_twins.len());
}

/// The CPU's sizes of structs it has no twin of.
#[test]
fn sizes_of_gpu_only_structs_match_wgsl() {
    let (checked, _) = check_all();
    let s = &checked.structs;
    assert_eq!(NODE_SIZE as usize, s["Node"].size, "NODE_SIZE against Node");
    assert_eq!(RETRY_HEADER as usize, s["RetryList"].member("tiles").offset, "RETRY_HEADER against RetryList.tiles");
    assert_eq!(GATHER_STATS_SIZE as usize, s["Stats"].size, "GATHER_STATS_SIZE against Stats");
    assert_eq!(VOLUME_LIGHT_SIZE as usize, s["VolumeLight"].size, "VOLUME_LIGHT_SIZE against VolumeLight");
    // What the GPU writes for wgpu to read as indirect arguments.
    assert_eq!(std::mem::size_of::<wgpu::util::DispatchIndirectArgs>(), s["DispatchArgs"].size);
    assert_eq!(std::mem::size_of::<wgpu::util::DrawIndirectArgs>(), s["Stats"].member("lights").offset);
}

/// The GI's shader files are all in `SHADERS` or `SHADER_INCLUDES`, so the check reads them.
#[test]
fn every_gi_wgsl_file_is_checked() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/gi");
    let known: Vec<&str> = plugin_gi::SHADERS.iter().chain(plugin_gi::SHADER_INCLUDES).map(|f| f.0).collect();
    for entry in std::fs::read_dir(dir).expect("shaders/gi/") {
        let name = entry.expect("an entry").file_name().into_string().expect("a UTF-8 name");
        if name.ends_with(".wgsl") {
            let registered = known.contains(&format!("gi/{name}").as_str()) || known.contains(&name.as_str());
            assert!(registered, "shaders/gi/{name} is neither in plugin_gi::SHADERS nor an include");
        }
    }
}

/// A drifted copy of a real twin fails, naming the struct, the field and both offsets.
#[test]
fn a_drifted_gi_params_fails() {
    let (checked, _) = check_all();
    let mut drifted = GiParams::layout();
    let field = drifted.fields.iter_mut().find(|f| f.name == "view_origin").expect("a field");
    field.offset -= 12;
    let error = compare(&checked.structs["GiParams"], &drifted).expect_err("view_origin moved");
    assert!(error.contains("GiParams.view_origin: WGSL offset 96 (size 16), Rust offset 84 (size 16)"), "{error}");
}
