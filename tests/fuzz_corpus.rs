//! The fuzz targets (`fuzz_targets.rs`) on a mutated seed corpus of the shipped files, in the
//! test command: a fixed number of deterministic mutations per target (about a minute in
//! all on 2 cores), each input required to return without a panic. An input that panics is
//! written to a file the failure names, to replay with `cargo fuzz run TARGET FILE` or here.
//! `HEADLAMP_FUZZ_CORPUS=DIR` also writes the seeds to `DIR/TARGET/` for cargo-fuzz.

use std::panic::{catch_unwind, AssertUnwindSafe};

use headlamp_tests::fuzz_targets::{run, seeds, Mutator, Target};

/// Mutated inputs per target; the file loaders cost more per input than the parsers.
fn rounds(target: Target) -> usize {
    match target {
        Target::Gltf | Target::Glb => 5_000,
        Target::Obj | Target::Mtl | Target::LevelToml => 10_000,
        Target::Replay | Target::Script | Target::Config => 50_000,
    }
}

#[test]
fn mutated_shipped_files_never_panic_any_reader() {
    let out = std::env::temp_dir().join(format!("headlamp-fuzz-crashes-{}", std::process::id()));
    let mut crashes = Vec::new();
    for target in Target::ALL {
        let seeds = seeds(target);
        assert!(!seeds.is_empty(), "{}: no seeds", target.name());
        // HEADLAMP_FUZZ_CORPUS=DIR also writes them out, as cargo-fuzz's starting corpus.
        if let Some(dir) = std::env::var_os("HEADLAMP_FUZZ_CORPUS") {
            let dir = std::path::Path::new(&dir).join(target.name());
            std::fs::create_dir_all(&dir).unwrap();
            for (i, seed) in seeds.iter().enumerate() {
                std::fs::write(dir.join(format!("seed_{i}")), seed).unwrap();
            }
        }
        // Every seed is a file Headlamp ships or writes: each must be accepted as it is.
        for (i, seed) in seeds.iter().enumerate() {
            if let Err(e) = run(target, seed) {
                panic!("{}: seed {i} is refused: {e}", target.name());
            }
        }
        let mut mutator = Mutator::new(0x9e37_79b9_7f4a_7c15 ^ target.name().len() as u64);
        let mut accepted = 0;
        for n in 0..rounds(target) {
            let input = mutator.mutate(&seeds[n % seeds.len()]);
            match catch_unwind(AssertUnwindSafe(|| run(target, &input))) {
                Ok(result) => accepted += result.is_ok() as usize,
                Err(_) => {
                    std::fs::create_dir_all(&out).unwrap();
                    let file = out.join(format!("{}-{n}.bin", target.name()));
                    std::fs::write(&file, &input).unwrap();
                    crashes.push(format!("{} panicked on mutation {n}: {}", target.name(), file.display()));
                }
            }
        }
        println!("{}: {} seeds, {} mutations, {accepted} accepted", target.name(), seeds.len(), rounds(target));
    }
    assert!(crashes.is_empty(), "{}", crashes.join("\n"));
}
