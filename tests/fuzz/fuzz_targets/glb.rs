#![no_main]
// Any bytes as a glb: an error or an accepted file, never a panic or a hang.
use headlamp_tests::fuzz_targets::{run, Target};

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = run(Target::Glb, data);
});
