//! Numbers the GI's Rust and WGSL share cannot drift: each WGSL constant of
//! `plugin_gi::shared_constants::CONSTANTS`, in every module as the plugin assembles it, has
//! its Rust constant's value; each entry point of `WORKGROUPS` has the workgroup size its Rust
//! dispatch counts with; and where a value could be written out again as a literal, it is not.
//! Values as naga evaluates them. No GPU needed.

#[path = "../../engine/tests/constant_check/mod.rs"]
mod constant_check;

use std::collections::BTreeMap;

use constant_check::{check_constants, check_literals, check_workgroups, global_size, Guard, Value, Within};
use engine::shared_constants::{SharedConstant, Workgroup};
use plugin_gi::shared_constants::{CONSTANTS, WORKGROUPS};

/// The GI's files, assembled as the plugin assembles them.
fn gi_files() -> Vec<(&'static str, String)> {
    plugin_gi::SHADERS
        .iter()
        .map(|(name, source)| (*name, engine::shader::compose(source, plugin_gi::SHADER_INCLUDES)))
        .collect()
}

/// Every GI file and include as written.
fn raw_files() -> Vec<(&'static str, &'static str)> {
    plugin_gi::SHADERS.iter().chain(plugin_gi::SHADER_INCLUDES).copied().collect()
}

/// Each shared constant's Rust value, and the literal suffix of its WGSL type.
fn guarded_values() -> BTreeMap<String, Value> {
    let wgsl: BTreeMap<String, Value> =
        gi_files().iter().flat_map(|(file, source)| constant_check::wgsl_constants(file, source)).collect();
    CONSTANTS
        .iter()
        .filter_map(|c| wgsl.get(c.wgsl).map(|v| (c.wgsl.to_string(), Value { value: c.value, suffix: v.suffix })))
        .collect()
}

/// The values the WGSL must name rather than write out, and where. 8 and 12 are too common to
/// forbid everywhere (tiles, an icosahedron's vertices): they are forbidden where the grids'
/// steps are read.
const GUARDS: &[Guard] = &[
    Guard { constant: "RECEIVER_PERIOD", within: Within::FunctionsNaming("receiver_steps") },
    Guard { constant: "SENDER_STEPS_OFFSET", within: Within::Everywhere },
    Guard { constant: "SENDER_PAD", within: Within::FunctionsNaming("sender_steps") },
];

#[test]
fn every_shared_constant_has_its_rust_value_in_wgsl() {
    let compared = check_constants(&gi_files(), &raw_files(), CONSTANTS)
        .unwrap_or_else(|e| panic!("WGSL constants drifted from Rust:\n{e}"));
    // Not vacuous: every constant was found and compared (those of the includes in each
    // module that includes them).
    bounds::assert(bounds::at_least("the constants compared", compared as f64, CONSTANTS.len() as f64));
}

#[test]
fn every_dispatched_workgroup_size_is_its_entry_points() {
    check_workgroups(&gi_files(), WORKGROUPS).unwrap_or_else(|e| panic!("workgroup sizes drifted from Rust:\n{e}"));
}

#[test]
fn no_wgsl_writes_a_shared_value_as_a_literal_where_its_constant_is_meant() {
    check_literals(&raw_files(), &guarded_values(), GUARDS)
        .unwrap_or_else(|e| panic!("literals repeat constants:\n{e}"));
}

/// The ambient cube the GI adds to is the engine's buffer, of the size the engine makes it.
#[test]
fn the_ambient_cube_has_the_engines_size() {
    let files = gi_files();
    let (file, source) = files.iter().find(|(f, _)| *f == "gi/view_model_irradiance.wgsl").expect("the probe's file");
    let size = global_size(file, source, "ambient_cube");
    assert_eq!(size as u64, engine::passes::VIEW_MODEL_IRRADIANCE_SIZE, "{file}'s ambient_cube");
}

/// A sample whose constant, workgroup size and literal disagree with Rust fails each check,
/// naming the constant, the file and both values.
#[test]
fn a_drifted_sample_fails() {
    let source = "const SENDER_PAD: i32 = 9;\n\
                  @compute @workgroup_size(8, 4) fn main() { let steps = vec2i(1) * 8; }\n\
                  fn shift(sender_steps: u32) -> i32 { return i32(sender_steps) * 8; }\n";
    let files = [("sample.wgsl", source.to_string())];
    let raw = [("sample.wgsl", source)];

    let pad = [SharedConstant { wgsl: "SENDER_PAD", file: "sample.wgsl", rust: "grids::SENDER_PAD", value: 8 }];
    let error = check_constants(&files, &raw, &pad).expect_err("9 is not 8");
    assert_eq!(error.trim(), "SENDER_PAD (sample.wgsl): WGSL 9, Rust grids::SENDER_PAD 8");
    let elsewhere = [SharedConstant { file: "other.wgsl", ..pad[0] }];
    let error = check_constants(&files, &raw, &elsewhere).expect_err("not declared there");
    assert!(error.contains("SENDER_PAD is not declared in other.wgsl"), "{error}");
    let missing = [SharedConstant { wgsl: "CUT_MAX", ..pad[0] }];
    assert!(check_constants(&files, &raw, &missing).is_err(), "no module has CUT_MAX");

    let square = [Workgroup { file: "sample.wgsl", entry: "main", size: [8, 8, 1], rust: "[GROUP, GROUP, 1]" }];
    let error = check_workgroups(&files, &square).expect_err("8×4 is not 8×8");
    assert!(
        error.contains(
            "sample.wgsl main: WGSL workgroup size [8, 4, 1], Rust dispatches count with [GROUP, GROUP, 1] = [8, 8, 1]"
        ),
        "{error}"
    );

    // Only the function that reads the steps may not write the pad out; `main`'s 8 is another.
    let values = BTreeMap::from([("SENDER_PAD".to_string(), Value { value: 8, suffix: Some('i') })]);
    let guard = [Guard { constant: "SENDER_PAD", within: Within::FunctionsNaming("sender_steps") }];
    let error = check_literals(&raw, &values, &guard).expect_err("`* 8` where the steps are read");
    assert_eq!(error.trim(), "sample.wgsl:3: 8 where SENDER_PAD is meant: `fn shift(sender_steps: u32) -> i32 { return i32(sender_steps) * 8; }`");
    // A u32 8 cannot stand for an i32 constant, nor can a float or a literal in a comment.
    let other = "fn f(sender_steps: u32) -> f32 { return f32(sender_steps >> 8u) * 8.0 + 1e-8; } // * 8\n";
    assert!(check_literals(&[("other.wgsl", other)], &values, &guard).is_ok());
}
