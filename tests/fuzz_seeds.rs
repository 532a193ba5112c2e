//! `cargo run --release -p headlamp-tests --bin fuzz-seeds -- DIR`: writes each fuzz target's
//! seeds (the shipped files of its kind) to `DIR/TARGET/seed_N`, cargo-fuzz's starting corpus.

use std::path::PathBuf;
use std::process::ExitCode;

use headlamp_tests::fuzz_targets::{seed_files, Target};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [dir] = args.as_slice() else {
        eprintln!("usage: fuzz-seeds DIR (e.g. tests/fuzz/corpus)");
        return ExitCode::FAILURE;
    };
    for target in Target::ALL {
        let out = PathBuf::from(dir).join(target.name());
        let files = seed_files(target);
        let written = std::fs::create_dir_all(&out).and_then(|()| {
            files.iter().enumerate().try_for_each(|(i, seed)| std::fs::write(out.join(format!("seed_{i}")), seed))
        });
        if let Err(e) = written {
            eprintln!("fuzz-seeds: {}: {e}", out.display());
            return ExitCode::FAILURE;
        }
        println!("{}: {} seeds", out.display(), files.len());
    }
    ExitCode::SUCCESS
}
