//! `headlamp check LEVEL`: validates a level without a window or a GPU, through the same code
//! the game loads it with (`scene::load_level`, then `sim::level_world`), so what `check`
//! accepts, the game loads. On top of that it checks what only shows in play: a spawn inside a
//! wall, a pickup or exit nobody can walk to, a crawler that cannot reach the player.
//!
//! Each finding is one line, `FILE:LINE:COL: error|warning: MESSAGE` (`FILE: …` where no
//! place in the file is known), or with `--json` one JSON document for tools.

mod diagnostic;
mod gameplay;

use std::path::Path;
use std::process::ExitCode;

use scene::Level;
use serde::Serialize;

use crate::cli::CheckArgs;

pub use diagnostic::{Diagnostic, Severity};

/// Everything `check` finds wrong with the level at `path`, errors and warnings, in the order
/// the game would meet them. No errors: the game loads and starts it.
pub fn check_level(path: &Path) -> Vec<Diagnostic> {
    match scene::load_level(path) {
        Ok(level) => check_loaded(&level),
        Err(e) => vec![load_error(&e)],
    }
}

/// [`check_level`] of a level already loaded.
pub fn check_loaded(level: &Level) -> Vec<Diagnostic> {
    let mut found: Vec<Diagnostic> =
        level.warnings.iter().map(|w| Diagnostic::warning(&w.path, w.at, w.message.clone())).collect();
    found.extend(gameplay::check(level));
    found.extend(occupancy_grid(level));
    found
}

/// What the GI's world-space visibility makes of the level: a grid coarser than its finest,
/// or none (light then passes the walls the camera does not see).
fn occupancy_grid(level: &Level) -> Option<Diagnostic> {
    let limits = occupancy::Limits::default();
    let message = match occupancy::Occupancy::of_scene(&level.scene, limits) {
        Err(e) => format!("the GI cannot see this level's walls where the camera does not: {e}"),
        Ok(grid) if grid.coarsened => format!(
            "the GI's occupancy grid takes {:.0} cm voxels to fit {} MiB (the finest is {:.0} cm): light is \
             stopped up to a voxel from surfaces",
            grid.voxel * 100.0,
            limits.max_bytes >> 20,
            limits.finest_voxel * 100.0
        ),
        Ok(_) => return None,
    };
    Some(Diagnostic::warning(&level.scene_path, None, message))
}

/// A load's error as a finding.
pub fn load_error(e: &scene::LoadError) -> Diagnostic {
    Diagnostic::error(&e.path, e.at, e.kind.to_string())
}

/// Runs `headlamp check`: prints the findings and exits 1 when there is an error.
pub fn run(args: &CheckArgs) -> ExitCode {
    let Some(level) = &args.level else {
        print!("{}", reference());
        return ExitCode::SUCCESS;
    };
    // The loader also logs its warnings for `play`; here they are the report itself.
    log::set_max_level(log::LevelFilter::Error);
    let found = check_level(level);
    let errors = found.iter().filter(|d| d.severity == Severity::Error).count();
    let warnings = found.len() - errors;
    if args.json {
        println!("{}", to_json(level, &found));
    } else {
        for d in &found {
            println!("{d}");
        }
        let verdict = if errors == 0 { "ok" } else { "not playable" };
        println!(
            "{}: {verdict} ({} error{}, {} warning{})",
            level.display(),
            errors,
            plural(errors),
            warnings,
            plural(warnings)
        );
    }
    if errors == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

#[derive(Serialize)]
struct JsonReport<'a> {
    level: String,
    ok: bool,
    errors: usize,
    warnings: usize,
    diagnostics: Vec<JsonDiagnostic<'a>>,
}

#[derive(Serialize)]
struct JsonDiagnostic<'a> {
    file: String,
    line: Option<usize>,
    column: Option<usize>,
    severity: Severity,
    message: &'a str,
}

/// `{"level", "ok", "errors", "warnings", "diagnostics": [{"file", "line", "column",
/// "severity", "message"}]}`; line and column are null where no place is known.
pub fn to_json(level: &Path, found: &[Diagnostic]) -> String {
    let errors = found.iter().filter(|d| d.severity == Severity::Error).count();
    let report = JsonReport {
        level: level.display().to_string(),
        ok: errors == 0,
        errors,
        warnings: found.len() - errors,
        diagnostics: found
            .iter()
            .map(|d| JsonDiagnostic {
                file: d.file.display().to_string(),
                line: d.at.map(|a| a.line),
                column: d.at.map(|a| a.column),
                severity: d.severity,
                message: &d.message,
            })
            .collect(),
    };
    serde_json::to_string_pretty(&report).expect("a report of strings and numbers serialises")
}

/// The level.toml reference in Markdown, from the tables the loader and the game are held to
/// (`scene::LEVEL_KEYS`, the game's `[game]` keys): what `headlamp check --reference` prints
/// and MODDING.md carries.
pub fn reference() -> String {
    let mut out = String::from("| key | value | default | meaning |\n| --- | --- | --- | --- |\n");
    let keys = scene::LEVEL_KEYS.iter().chain(crate::sim::level_entities::GAME_KEYS);
    for k in keys {
        let (table, name) = match k.key.split_once('.') {
            Some((table, name)) if table.ends_with("[]") => (format!("[[{}]] ", table.trim_end_matches("[]")), name),
            Some((table, name)) => (format!("[{table}] "), name),
            None => (String::new(), k.key),
        };
        out.push_str(&format!("| {table}`{name}` | {} | {} | {} |\n", k.kind, k.default, k.meaning));
    }
    out
}
