//! `headlamp record`, `headlamp replay` and `headlamp script`.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context};
use engine::clock::FixedClock;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;

use crate::cli::{RecordArgs, ReplayArgs, ScriptArgs};
use crate::play::{GameWindow, TickSource};
use crate::recording::{self, LoadedReplay, Recorder};
use crate::sim::{Simulation, TickCommand, WorldState};
use crate::view::WorldView;

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
    frames(loaded, snapshots, size, |tick, image| match dir {
        Some(dir) => Ok(image.save(dir.join(snapshot_name(tick)))?),
        None => Ok(()),
    })
}

/// Re-simulates a replay without a window, checking every tick's hash, and hands `frame` the
/// picture after each of `ticks` (0 = the start; in tick order, each once).
pub fn frames(
    loaded: &LoadedReplay,
    ticks: &[u32],
    size: (u32, u32),
    mut frame: impl FnMut(u32, &image::RgbaImage) -> anyhow::Result<()>,
) -> anyhow::Result<WorldState> {
    let end = loaded.commands.len() as u32;
    if let Some(&late) = ticks.iter().find(|&&t| t > end) {
        bail!("--snapshots: tick {late} is past the end of {} ({end} ticks)", loaded.path.display());
    }
    let mut ticks = ticks.to_vec();
    ticks.sort_unstable();
    ticks.dedup();
    let mut shooter = if ticks.is_empty() { None } else { Some(SnapshotRenderer::new(loaded, size)?) };
    let mut sim = loaded.simulation()?;
    let mut wanted = ticks.iter().peekable();
    for i in 0..=loaded.commands.len() {
        while wanted.next_if_eq(&&(i as u32)).is_some() {
            if let Some(s) = &mut shooter {
                frame(i as u32, &s.shoot(&sim)?)?;
            }
        }
        if i < loaded.commands.len() {
            loaded.step_checked(&mut sim, i).with_context(|| loaded.path.display().to_string())?;
        }
    }
    Ok(sim.state)
}

/// Renders the game's view of a simulation, headless.
struct SnapshotRenderer {
    gpu: Gpu,
    renderer: Renderer,
    target: HeadlessTarget,
    view: WorldView,
}

impl SnapshotRenderer {
    fn new(loaded: &LoadedReplay, size: (u32, u32)) -> anyhow::Result<Self> {
        let gpu = Gpu::headless()?;
        let (plugins, _) = crate::plugins(loaded.gi.clone());
        let mut renderer = Renderer::new(&gpu, &loaded.level.scene, plugins)?;
        let target = HeadlessTarget::new(&gpu, size.0, size.1, ImageKind::Display);
        let mut view = WorldView::new(&loaded.level);
        view.add_meshes(&mut renderer, &gpu);
        Ok(Self { gpu, renderer, target, view })
    }

    fn shoot(&mut self, sim: &Simulation) -> anyhow::Result<image::RgbaImage> {
        self.view.at(sim.entities(), &sim.state);
        // Snapshots are far apart in time: each is a cut for the renderer's history.
        self.renderer.reset_history();
        match self.target.render(&self.gpu, &mut self.renderer, &self.view.view)? {
            RenderedImage::Display(image) => Ok(image),
            RenderedImage::Linear(_) => bail!("a display target rendered linear values"),
        }
    }
}

/// The file name `replay --headless --snapshots` gives the frame after `tick` ticks.
pub fn snapshot_name(tick: u32) -> String {
    format!("tick_{tick:06}.png")
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
