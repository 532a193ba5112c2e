//! The game's side of `.replay` files: what goes in the header (level, tick rate, seed, the
//! settings a recording was made with), how a replay finds its level again, and re-simulating
//! a replay against the state hashes it stores.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context};
use engine::replay::{Replay, ReplayHeader, ReplayWriter};
use plugin_gi::GiSettings;
use scene::Level;

use crate::sim::{Simulation, TickCommand, WorldState};

/// A level's id in a replay: its folder's name (or a bare scene file's name).
fn level_id(level: &Level, path: &Path) -> String {
    let base = level.root.as_deref().unwrap_or(path);
    base.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| level.name.clone())
}

/// The header of a new recording of `level`, loaded from `level_path`: the GI settings ride
/// along so a replay renders as it was seen.
pub fn header(level: &Level, level_path: &Path, tick_rate: u32, seed: u64, gi: &GiSettings) -> ReplayHeader {
    let mut settings = vec![("gi.enabled".to_owned(), gi.enabled.to_string())];
    for f in GiSettings::FIELDS {
        let value = gi.get(f.name).expect("every listed field has a value");
        let text = f.choice_name(value).map_or_else(|| value.to_string(), str::to_owned);
        settings.push((format!("gi.{}", f.name), text));
    }
    ReplayHeader {
        level_id: level_id(level, level_path),
        level_hash: level.content_hash,
        tick_rate,
        seed,
        settings,
        command_size: TickCommand::SIZE,
    }
}

/// Where the next attempt of a recording goes after a restart: `game.replay` → `game-2.replay`,
/// `game-2.replay` → `game-3.replay`, skipping files that exist.
pub fn next_attempt_path(path: &Path) -> PathBuf {
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let ext = path.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_else(|| "replay".into());
    let (base, mut n) = match stem.rsplit_once('-').and_then(|(b, n)| Some((b.to_owned(), n.parse::<u32>().ok()?))) {
        Some((base, n)) => (base, n + 1),
        None => (stem, 2),
    };
    loop {
        let candidate = path.with_file_name(format!("{base}-{n}.{ext}"));
        if !candidate.exists() {
            return candidate;
        }
        n += 1;
    }
}

/// Records a live game tick by tick.
pub struct Recorder {
    writer: ReplayWriter,
    pub path: PathBuf,
    last_hash: u64,
}

impl Recorder {
    pub fn new(header: ReplayHeader, path: PathBuf) -> Self {
        Self { writer: ReplayWriter::new(header), path, last_hash: 0 }
    }
    pub fn push(&mut self, cmd: &TickCommand, after: &WorldState) {
        self.last_hash = after.hash();
        self.writer.push(&cmd.encode(), self.last_hash);
    }
    /// The state hash after the last recorded tick.
    pub fn last_hash(&self) -> u64 {
        self.last_hash
    }
    pub fn tick_count(&self) -> u32 {
        self.writer.tick_count()
    }
    pub fn save(&self) -> anyhow::Result<()> {
        Ok(self.writer.save(&self.path)?)
    }
    pub fn writer(&self) -> &ReplayWriter {
        &self.writer
    }
}

/// A replay with its level found, checked and loaded, and its commands decoded.
pub struct LoadedReplay {
    pub path: PathBuf,
    pub replay: Replay,
    pub commands: Vec<TickCommand>,
    pub level: Level,
    pub gi: GiSettings,
}

impl LoadedReplay {
    /// Reads `path`; the level is `level` if given, else the replay's level id looked up among
    /// the shipped levels, then under `levels/` in the working directory.
    pub fn open(path: &Path, level: Option<&Path>) -> anyhow::Result<Self> {
        let replay = Replay::read(path)?;
        let (commands, gi) = decode(&replay, path)?;
        let h = &replay.header;
        let level_path = match level {
            Some(p) => p.to_owned(),
            None => find_level(&h.level_id).ok_or_else(|| {
                anyhow!(
                    "{}: recorded on level '{}', which is not among the shipped levels nor under ./levels; name it with --level",
                    path.display(),
                    h.level_id
                )
            })?,
        };
        let level = scene::load_level(&level_path)?;
        if level.content_hash != h.level_hash {
            bail!(
                "{}: recorded on level '{}' with content hash {:016x}, but {} now hashes {:016x}: the level changed since \
                 the recording, so it would not replay the same game (record it again)",
                path.display(),
                h.level_id,
                h.level_hash,
                level_path.display(),
                level.content_hash
            );
        }
        Ok(Self { path: path.to_owned(), replay, commands, level, gi })
    }

    /// A fresh simulation at the replay's start.
    pub fn simulation(&self) -> anyhow::Result<Simulation> {
        let world = crate::sim::level_world(&self.level)?;
        Ok(Simulation::new(&self.level, world, self.replay.header.tick_rate, self.replay.header.seed))
    }

    /// Runs tick `i` (0-based) and checks the state hash recorded after it.
    pub fn step_checked(&self, sim: &mut Simulation, i: usize) -> Result<(), Divergence> {
        sim.step(&self.commands[i]);
        let (found, recorded) = (sim.state.hash(), self.replay.state_hash(i));
        if found != recorded {
            return Err(Divergence { tick: i as u32 + 1, found, recorded });
        }
        Ok(())
    }

    /// Re-simulates every tick against the recorded hashes; returns the final state.
    pub fn verify(&self) -> anyhow::Result<WorldState> {
        let mut sim = self.simulation()?;
        for i in 0..self.commands.len() {
            self.step_checked(&mut sim, i).with_context(|| self.path.display().to_string())?;
        }
        Ok(sim.state)
    }
}

/// What the game reads from a replay's container besides its level: the GI settings it was
/// recorded with and its commands, decoded. `path` names the file in errors.
pub fn decode(replay: &Replay, path: &Path) -> anyhow::Result<(Vec<TickCommand>, GiSettings)> {
    let h = &replay.header;
    if h.command_size != TickCommand::SIZE {
        bail!(
            "{}: commands are {} bytes, this build's are {} (recorded by another version)",
            path.display(),
            h.command_size,
            TickCommand::SIZE
        );
    }
    let mut gi = GiSettings::default();
    for (key, value) in &h.settings {
        let name = key.strip_prefix("gi.").ok_or_else(|| anyhow!("{}: unknown setting '{key}'", path.display()))?;
        gi.set(name, value).map_err(|e| anyhow!("{}: {e}", path.display()))?;
    }
    let commands = (0..replay.tick_count())
        .map(|i| TickCommand::decode(replay.command(i)).map_err(|e| anyhow!("{}: tick {}: {e}", path.display(), i + 1)))
        .collect::<anyhow::Result<Vec<_>>>()?;
    Ok((commands, gi))
}

/// The first tick whose state hash differs from the recording.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Divergence {
    pub tick: u32,
    pub found: u64,
    pub recorded: u64,
}

impl std::fmt::Display for Divergence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "diverged at tick {}: the simulation reached state hash {:016x}, the recording says {:016x}",
            self.tick, self.found, self.recorded
        )
    }
}

impl std::error::Error for Divergence {}

fn find_level(id: &str) -> Option<PathBuf> {
    // An id is a plain name; anything with a path separator is not looked up.
    if id.is_empty() || id.contains(['/', '\\']) || id == ".." {
        return None;
    }
    let shipped = crate::default_level().parent().map(|p| p.join(id));
    [shipped, Some(Path::new("levels").join(id))].into_iter().flatten().find(|p| p.exists())
}

/// Seeds for new live games come from the clock: randomness differs per game, and the seed is
/// in the recording, so replays still draw the same numbers.
pub fn fresh_seed() -> u64 {
    let t = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap_or_default();
    t.as_nanos() as u64 ^ 0x5eed_1a4b_c0ff_ee00
}
