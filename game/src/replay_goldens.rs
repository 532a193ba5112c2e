//! `headlamp replay F.replay --goldens DIR [--update]`: the project's replay-based frame
//! regression test for anyone's level, without Rust. The frames after chosen ticks are
//! rendered headless and compared with `DIR/tick_NNNNNN.png` by [`crate::golden`], the metric
//! and tolerance of the project's own frame tests.

use std::path::Path;

use anyhow::{bail, Context};
use engine::gpu::Gpu;

use crate::recording::LoadedReplay;
use crate::replay_frames::{frames, snapshot_name};

/// Compares (or with `update`, writes) the goldens; one line per frame, an error when any
/// frame differs.
pub fn run(
    loaded: &LoadedReplay,
    dir: &Path,
    snapshots: &[u32],
    size: Option<(u32, u32)>,
    update: bool,
) -> anyhow::Result<()> {
    let existing = golden_ticks(dir)?;
    let ticks = if !snapshots.is_empty() {
        snapshots.to_vec()
    } else if !existing.is_empty() {
        existing.clone()
    } else if update {
        spread(loaded.commands.len() as u32)
    } else {
        bail!("{}: no goldens (tick_NNNNNN.png) to compare with; write them with --update", dir.display());
    };
    let golden_size = goldens_size(dir, &existing)?;
    let size = size.or(golden_size).unwrap_or(crate::cli::ReplayArgs::DEFAULT_SIZE);
    if update {
        std::fs::create_dir_all(dir).with_context(|| format!("--goldens {}", dir.display()))?;
        frames(loaded, &ticks, size, Gpu::lavapipe, |tick, image| {
            let path = dir.join(snapshot_name(tick));
            crate::golden::write(&path, image).map_err(anyhow::Error::msg)?;
            println!("{}: written", path.display());
            Ok(())
        })?;
        return Ok(());
    }
    let mut failed = 0;
    frames(loaded, &ticks, size, Gpu::lavapipe, |tick, image| {
        match crate::golden::compare(&dir.join(snapshot_name(tick)), image) {
            Ok(difference) => println!("{}: ok ({difference})", dir.join(snapshot_name(tick)).display()),
            Err(e) => {
                failed += 1;
                println!("{e}");
            }
        }
        Ok(())
    })?;
    if failed > 0 {
        bail!(
            "{} of {} frames differ from their goldens in {} (if the change is intended, rerun with --update)",
            failed,
            ticks.len(),
            dir.display()
        );
    }
    Ok(())
}

/// The ticks of the goldens in `dir` (`tick_NNNNNN.png`; the `.actual` and `.diff` images a
/// failure leaves are not goldens), sorted. A missing folder has none.
fn golden_ticks(dir: &Path) -> anyhow::Result<Vec<u32>> {
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => bail!("--goldens {}: {e}", dir.display()),
    };
    let mut ticks: Vec<u32> = entries
        .filter_map(|e| {
            let name = e.ok()?.file_name();
            let tick = name.to_str()?.strip_prefix("tick_")?.strip_suffix(".png")?.parse().ok()?;
            (snapshot_name(tick) == name.to_str()?).then_some(tick)
        })
        .collect();
    ticks.sort_unstable();
    Ok(ticks)
}

/// The goldens' common size (from their headers), None when there are none.
fn goldens_size(dir: &Path, ticks: &[u32]) -> anyhow::Result<Option<(u32, u32)>> {
    let mut size = None;
    for &tick in ticks {
        let path = dir.join(snapshot_name(tick));
        let this = image::image_dimensions(&path).with_context(|| format!("golden {}", path.display()))?;
        match size {
            Some(s) if s != this => {
                bail!("{}: {this:?}, but the other goldens are {s:?} (render them at one size)", path.display())
            }
            _ => size = Some(this),
        }
    }
    Ok(size)
}

/// Four ticks spread over a replay of `ticks` ticks: the start, a third, two thirds, the end.
fn spread(ticks: u32) -> Vec<u32> {
    let mut out: Vec<u32> = (0..4).map(|k| ticks * k / 3).collect();
    out.dedup();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_ticks_spread_over_the_replay() {
        assert_eq!(spread(300), vec![0, 100, 200, 300]);
        assert_eq!(spread(0), vec![0]);
    }

    #[test]
    fn only_tick_pngs_are_goldens() {
        let dir = std::env::temp_dir().join(format!("headlamp-golden-ticks-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for name in [
            "tick_000060.png",
            "tick_000006.png",
            "tick_000060.actual.png",
            "tick_000060.diff.png",
            "notes.txt",
            "tick_60.png",
        ] {
            std::fs::write(dir.join(name), b"").unwrap();
        }
        assert_eq!(golden_ticks(&dir).unwrap(), vec![6, 60]);
        assert_eq!(golden_ticks(&dir.join("missing")).unwrap(), Vec::<u32>::new());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
