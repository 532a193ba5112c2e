//! The fuzz targets (`fuzz_targets.rs`) on a mutated seed corpus of the shipped files, in the
//! test command: a fixed number of deterministic mutations per target (about a minute in
//! all on 2 cores), each input required to return without a panic within its time and memory
//! limits (`fuzz_bounds.rs`). An input that breaks one is written to a file the failure names,
//! to replay with `cargo fuzz run TARGET FILE` or here.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use headlamp_tests::fuzz_bounds::{BoundedRunner, CountingAlloc, Limits, Outcome};
use headlamp_tests::fuzz_targets::{prepare, run, seeds, Mutator, Target};

#[global_allocator]
static ALLOC: CountingAlloc = CountingAlloc;

/// What one input may take. The shipped files, the largest inputs, take at most 0.3 s and
/// 40 MiB each on the 2-core VM (the Hall's glTF with its textures).
const LIMITS: Limits = Limits { time: Duration::from_secs(2), memory: 256 << 20 };

/// The fewest mutated inputs a target's reader must accept: half of what it accepted when the
/// floor was set (the counts printed below). Fewer means the mutations no longer reach past
/// the reader's first checks, and the fuzz no longer tests what lies behind them.
fn accepted_floor(target: Target) -> usize {
    match target {
        Target::Gltf => 86,       // of 5,000 (172 accepted)
        Target::Glb => 112,       // of 5,000 (225)
        Target::Obj => 1_303,     // of 10,000 (2,607)
        Target::Mtl => 2_746,     // of 10,000 (5,493)
        Target::LevelToml => 945, // of 10,000 (1,891)
        Target::Replay => 445,    // of 10,000 (891)
        Target::Script => 11_832, // of 50,000 (23,664)
        Target::Config => 10_031, // of 50,000 (20,063)
    }
}

/// Whether `accepted` of a target's mutated inputs show the fuzz reaching deep into its reader.
fn deep_enough(target: Target, accepted: usize) -> Result<(), String> {
    let figure = format!("{}: mutated inputs accepted", target.name());
    bounds::at_least(figure, accepted as f64, accepted_floor(target) as f64)
}

/// Mutated inputs per target; the file loaders and the replay's simulated ticks cost more per
/// input than the parsers.
fn rounds(target: Target) -> usize {
    match target {
        Target::Gltf | Target::Glb => 5_000,
        Target::Obj | Target::Mtl | Target::LevelToml | Target::Replay => 10_000,
        Target::Script | Target::Config => 50_000,
    }
}

fn crash_dir() -> PathBuf {
    std::env::temp_dir().join(format!("headlamp-fuzz-crashes-{}", std::process::id()))
}

/// What [`drive`] found: a line per input that panicked or broke a limit, naming the file it
/// was written to; how many inputs were accepted; the most memory and time one took.
struct Driven {
    failures: Vec<String>,
    accepted: usize,
    peak: usize,
    slowest: Duration,
}

/// Runs each input under `limits`.
fn drive(
    name: &str,
    limits: Limits,
    reader: impl Fn(&[u8]) -> Result<(), String> + Send + Clone + 'static,
    inputs: impl Iterator<Item = Vec<u8>>,
) -> Driven {
    let dir = crash_dir();
    std::fs::create_dir_all(&dir).unwrap();
    let new_runner = || BoundedRunner::new(limits, Box::new(reader.clone()));
    let mut runner = new_runner();
    let mut driven = Driven { failures: Vec::new(), accepted: 0, peak: 0, slowest: Duration::ZERO };
    for (n, input) in inputs.enumerate() {
        let file = dir.join(format!("{name}-{n}.bin"));
        let started = Instant::now();
        let (outcome, peak) = runner.run(&input, file.clone());
        driven.slowest = driven.slowest.max(started.elapsed());
        driven.peak = driven.peak.max(peak);
        let broke = match outcome {
            Outcome::Returned(result) => {
                driven.accepted += result.is_ok() as usize;
                continue;
            }
            Outcome::Panicked(message) => format!("panicked ({message})"),
            Outcome::TimedOut => {
                // The worker is still busy with it: the next input gets a new one.
                runner = new_runner();
                format!("ran past {:?}", limits.time)
            }
            Outcome::OverMemory(peak) => format!("held {} MiB, over {} MiB", peak >> 20, limits.memory >> 20),
        };
        std::fs::write(&file, &input).unwrap();
        driven.failures.push(format!("{name}: input {n} {broke}: {}", file.display()));
    }
    driven
}

#[test]
fn mutated_shipped_files_never_panic_hang_or_hog_any_reader() {
    let mut failures = Vec::new();
    for target in Target::ALL {
        let seeds = seeds(target);
        assert!(!seeds.is_empty(), "{}: no seeds", target.name());
        prepare(target);
        let started = Instant::now();
        // Every seed is a file Headlamp ships or writes: each must be accepted as it is.
        let files: Vec<Vec<u8>> = seeds.iter().map(|s| s.encode()).collect();
        let driven = drive(target.name(), LIMITS, move |d| run(target, d), files.into_iter());
        let ok = driven.failures.is_empty() && driven.accepted == seeds.len();
        assert!(ok, "{}: seeds refused or broke a limit: {:?}", target.name(), driven.failures);
        let seed_figures = format!("at most {} MiB and {:?}", driven.peak >> 20, driven.slowest);
        let mut mutator = Mutator::new(0x9e37_79b9_7f4a_7c15 ^ target.name().len() as u64);
        let inputs = (0..rounds(target)).map(|n| mutator.mutate_seed(&seeds[n % seeds.len()]));
        let driven = drive(target.name(), LIMITS, move |d| run(target, d), inputs);
        println!(
            "{}: {} seeds ({seed_figures}), {} mutations, {} accepted, at most {} MiB and {:?}; {:.1} s in all",
            target.name(),
            seeds.len(),
            rounds(target),
            driven.accepted,
            driven.peak >> 20,
            driven.slowest,
            started.elapsed().as_secs_f64()
        );
        failures.extend(driven.failures);
        failures.extend(deep_enough(target, driven.accepted).err());
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The limits are real: an input that hangs or holds too much fails, named; the next input is
/// run as usual.
#[test]
fn a_hanging_or_hogging_input_fails_by_name() {
    let limits = Limits { time: Duration::from_millis(300), memory: 16 << 20 };
    let reader = |d: &[u8]| {
        match d {
            b"hang" => std::thread::sleep(Duration::from_secs(2)),
            b"hog" => drop(std::hint::black_box(vec![1u8; 32 << 20])),
            b"panic" => panic!("a reader's bug"),
            // Wraps silently where overflow checks are off.
            b"overflow" => drop(std::hint::black_box(u32::MAX) + std::hint::black_box(d.len() as u32)),
            _ => {}
        }
        Ok(())
    };
    let inputs = [&b"ok"[..], b"hang", b"ok", b"hog", b"panic", b"ok", b"overflow"].map(<[u8]>::to_vec);
    let Driven { failures, accepted, peak, .. } = drive("limits", limits, reader, inputs.clone().into_iter());
    assert_eq!(accepted, 3, "{failures:?}");
    bounds::assert(bounds::at_least("the hog's peak, bytes", peak as f64, f64::from(32u32 << 20)));
    assert_eq!(failures.len(), 4, "{failures:?}");
    let expect = [
        (1, "ran past 300ms"),
        (3, "held 32 MiB, over 16 MiB"),
        (4, "panicked (a reader's bug)"),
        (6, "panicked (attempt to add with overflow)"),
    ];
    for ((n, what), line) in expect.iter().zip(&failures) {
        let file = crash_dir().join(format!("limits-{n}.bin"));
        assert!(line.contains(what) && line.contains(&file.display().to_string()), "{line}");
        assert_eq!(std::fs::read(&file).unwrap(), inputs[*n], "{}", file.display());
    }
}

/// The floors are real: a fuzz whose mutations every reader refused fails each target, by name.
#[test]
fn a_fuzz_that_stops_at_the_surface_fails_its_floor() {
    for target in Target::ALL {
        let e = deep_enough(target, 0).expect_err(target.name());
        assert!(e.starts_with(&format!("{}: mutated inputs accepted", target.name())), "{e}");
        assert!(deep_enough(target, accepted_floor(target)).is_ok());
    }
}

/// The readers the fuzz reaches (scene, engine, game, the config's crate) are ours, and every
/// crate of ours is built with overflow checks in release too, where the test command runs:
/// the workspace's release profile turns them on, and only others' crates off.
#[test]
fn every_crate_of_ours_checks_for_overflow_in_release() {
    let manifest = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../Cargo.toml")).unwrap();
    let table: toml::Table = manifest.parse().unwrap();
    let release = &table["profile"]["release"];
    assert_eq!(release.get("overflow-checks").and_then(|v| v.as_bool()), Some(true), "[profile.release]");
    let packages = release.get("package").and_then(|p| p.as_table()).cloned().unwrap_or_default();
    for (name, settings) in packages {
        if settings.get("overflow-checks").and_then(|v| v.as_bool()) == Some(false) {
            assert_eq!(name, "*", "[profile.release.package.{name}] turns overflow checks off for a crate of ours");
        }
    }
    let members = table["workspace"]["members"].as_array().unwrap();
    for dir in ["engine/scene", "engine", "game", "game/ui"] {
        assert!(members.iter().any(|m| m.as_str() == Some(dir)), "{dir} is a workspace member");
    }
}
