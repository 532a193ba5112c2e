//! `headlamp record`, `headlamp replay` and `headlamp script`.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context};
use engine::clock::FixedClock;
use engine::gpu::Gpu;

use crate::cli::{RecordArgs, ReplayArgs, ScriptArgs};
use crate::play::{GameWindow, TickSource};
use crate::recording::{self, LoadedReplay, Recorder};
use crate::replay_frames::{frames, snapshot_name};
use crate::sim::{Simulation, TickCommand, WorldState};

/// Plays in a window while recording; the replay is written when the window closes, and also
/// when the game stops on an error, so what was played is never lost.
pub fn record(args: &RecordArgs) -> anyhow::Result<()> {
    let gi = crate::cli::gi_settings(&args.settings, args.gi).map_err(|e| anyhow!("--set {e}"))?;
    let level_path = args.level.clone().unwrap_or_else(crate::default_level);
    let level = engine::scene::load_level(&level_path)?;
    let world = crate::sim::level_world(&level)?;
    let seed = args.seed.unwrap_or_else(recording::fresh_seed);
    let tick_rate = FixedClock::DEFAULT_TICK_RATE;
    let header = recording::header(&level, &level_path, tick_rate, seed, &gi);
    let recorder = Recorder::new(header, args.out.clone());
    // Writing the empty replay first finds an unwritable --out before anything is played.
    recorder.save()?;
    let sim = Simulation::new(&level, world, tick_rate, seed);
    // The player's controls, but the GI the recording names; the config file is left as it
    // is (settings changed while recording last for this session only).
    let config = game_ui::Config { gi, ..crate::play::user_config().0 };
    let mut app = GameWindow::new(level, sim, TickSource::live(&config, Some(recorder)), config);
    app.watch_level(&level_path);
    app.open_sound();
    let played = engine::window::run("Headlamp — recording", &mut app);
    if let TickSource::Live { recorder: Some(r), .. } = &app.source {
        r.save()?;
        println!("wrote {} ({} ticks, final hash {:016x})", r.path.display(), r.tick_count(), app.sim.state.hash());
    }
    played
}

pub fn replay(args: &ReplayArgs) -> anyhow::Result<()> {
    if !args.snapshots.is_empty() && !args.headless && args.goldens.is_none() {
        bail!("--snapshots needs --headless or --goldens");
    }
    let loaded = LoadedReplay::open(&args.file, args.level.as_deref())?;
    if let Some(dir) = &args.goldens {
        return crate::replay_goldens::run(&loaded, dir, &args.snapshots, args.size, args.update);
    }
    if args.verify {
        let end = loaded.verify()?;
        println!("ok ticks={} outcome={}", end.tick, end.outcome.name());
        return Ok(());
    }
    if args.headless {
        let size = args.size.unwrap_or(ReplayArgs::DEFAULT_SIZE);
        let end = headless(&loaded, &args.snapshots, args.out_dir.as_deref(), size)?;
        println!("ticks={} hash={:016x} outcome={}", end.tick, end.hash(), end.outcome.name());
        return Ok(());
    }
    let sim = loaded.simulation()?;
    let (level, gi) = (loaded.level.clone(), loaded.gi.clone());
    let source = TickSource::Replay { replay: Box::new(loaded), next: 0, diverged: None };
    let config = game_ui::Config { gi, ..crate::play::user_config().0 };
    let mut app = GameWindow::new(level, sim, source, config);
    app.open_sound();
    engine::window::run("Headlamp — replay", &mut app)
}

/// Re-simulates a replay without a window, checking every tick's hash, and renders a PNG after
/// each snapshot tick into `out_dir` as `tick_NNNNNN.png`.
pub fn headless(
    loaded: &LoadedReplay,
    snapshots: &[u32],
    out_dir: Option<&Path>,
    size: (u32, u32),
) -> anyhow::Result<WorldState> {
    let dir = match (snapshots.is_empty(), out_dir) {
        (true, _) => None,
        (false, None) => bail!("--snapshots needs --out-dir to write them to"),
        (false, Some(dir)) => {
            std::fs::create_dir_all(dir).with_context(|| format!("--out-dir {}", dir.display()))?;
            Some(dir)
        }
    };
    frames(loaded, snapshots, size, Gpu::headless, |tick, image| match dir {
        Some(dir) => Ok(image.save(dir.join(snapshot_name(tick)))?),
        None => Ok(()),
    })
}

/// Simulates a script's commands and writes them, with their hashes, as a replay; with
/// `--trace`, printing the world after each line.
pub fn script(args: &ScriptArgs) -> anyhow::Result<()> {
    let same = |a: &Path, b: &Path| a.canonicalize().ok().is_some_and(|a| b.canonicalize().ok() == Some(a));
    if same(&args.script, &args.out) {
        bail!("--out {} is the script itself: the replay would overwrite it", args.out.display());
    }
    let gi = crate::cli::gi_settings(&args.settings, args.gi).map_err(|e| anyhow!("--set {e}"))?;
    let (commands, steps) = crate::script::read_steps(&args.script).map_err(|e| anyhow!(e))?;
    let level = engine::scene::load_level(&args.level)?;
    // Each line's step ends after some tick: with --trace, the world is shown there.
    let mut steps = steps.into_iter().peekable();
    let mut stdout = std::io::stdout().lock();
    let mut tracing = args.trace;
    let recorder =
        record_commands_seen(&level, &args.level, &commands, args.seed, &gi, args.out.clone(), |ticks, state| {
            while let Some((line, _)) = steps.next_if(|&(_, end)| end == ticks) {
                // A reader that stops early (`| head`) is not an error worth a panic.
                if tracing && writeln!(stdout, "{}", crate::script_trace::describe(line, state)).is_err() {
                    tracing = false;
                }
            }
        })?;
    drop(stdout);
    recorder.save()?;
    println!(
        "wrote {} ({} ticks, final hash {:016x})",
        args.out.display(),
        recorder.tick_count(),
        recorder.last_hash()
    );
    Ok(())
}

/// Runs `commands` from the level's start and records them as a replay would be recorded live.
pub fn record_commands(
    level: &engine::scene::Level,
    level_path: &Path,
    commands: &[TickCommand],
    seed: u64,
    gi: &plugin_gi::GiSettings,
    out: PathBuf,
) -> anyhow::Result<Recorder> {
    record_commands_seen(level, level_path, commands, seed, gi, out, |_, _| {})
}

/// [`record_commands`], showing `seen` the world after every tick (with the ticks run so far).
fn record_commands_seen(
    level: &engine::scene::Level,
    level_path: &Path,
    commands: &[TickCommand],
    seed: u64,
    gi: &plugin_gi::GiSettings,
    out: PathBuf,
    mut seen: impl FnMut(usize, &WorldState),
) -> anyhow::Result<Recorder> {
    let tick_rate = FixedClock::DEFAULT_TICK_RATE;
    let header = recording::header(level, level_path, tick_rate, seed, gi);
    let mut sim = Simulation::new(level, crate::sim::level_world(level)?, tick_rate, seed);
    let mut recorder = Recorder::new(header, out);
    for (i, cmd) in commands.iter().enumerate() {
        sim.step(cmd);
        recorder.push(cmd, &sim.state);
        seen(i + 1, &sim.state);
    }
    Ok(recorder)
}
