//! Changing the level under a running window: live reload (a level file saved, or F5) and a
//! level picked from the level menu. The level is loaded and checked on the CPU in `update`;
//! the next `render` (which has the GPU) builds its renderer and swaps it in, so a bad edit
//! never replaces the level that runs.

use std::path::Path;
use std::sync::Arc;

use engine::clock::FixedClock;
use engine::gpu::Gpu;
use engine::renderer::Renderer;
use engine::scene::Level;

use super::{GameWindow, NextLevel, TickSource};
use crate::game_events::Messages;
use crate::level_list::ListedLevel;
use crate::level_watch::FileWatch;
use crate::recording::Recorder;
use crate::sim::{LevelWorld, Simulation};
use crate::view::WorldView;

/// A level as `play` loads it: the scene, then the gameplay world (markers, collision).
fn load(path: &Path) -> anyhow::Result<(Level, Arc<LevelWorld>)> {
    let level = engine::scene::load_level(path)?;
    let world = crate::sim::level_world(&level)?;
    Ok((level, world))
}

impl GameWindow {
    /// Plays `path` live: watches its files for edits from now on.
    pub fn watch_level(&mut self, path: &Path) {
        self.level_path = Some(path.to_path_buf());
        self.watch = Some(FileWatch::new(self.level.files.clone()));
    }

    /// Looks at the level's files; F5 reloads whatever they say.
    pub(super) fn poll_reload(&mut self, dt: f32, f5: bool) {
        let changed = self.watch.as_mut().is_some_and(|w| w.poll(dt));
        if changed || f5 {
            self.reload();
        }
    }

    /// Loads the level again from its files. A failure is shown in a banner, names the file
    /// (and line), and leaves the running level as it is; the failing file is watched too, so
    /// creating a missing one reloads.
    pub fn reload(&mut self) {
        let Some(path) = self.level_path.clone() else { return };
        match load(&path) {
            Ok((level, world)) => {
                self.watch = Some(FileWatch::new(level.files.clone()));
                let keep_pose = !self.recording();
                self.next_level = Some(NextLevel { path, level, world, keep_pose });
            }
            Err(e) => {
                if let (Some(watch), Some(load)) = (&mut self.watch, e.downcast_ref::<engine::scene::LoadError>()) {
                    watch.add(load.path.clone());
                }
                log::error!("reload: {e:#}");
                self.reload_error = Some(format!("{e:#}"));
            }
        }
    }

    /// Starts a level from the level menu, at its spawn.
    pub(super) fn play_listed(&mut self, listed: &ListedLevel) {
        match load(&listed.path) {
            Ok((level, world)) => {
                self.next_level = Some(NextLevel { path: listed.path.clone(), level, world, keep_pose: false });
            }
            Err(e) => {
                self.menus.to_main_menu();
                self.menus.show_warning(format!("{e:#}"));
            }
        }
    }

    fn recording(&self) -> bool {
        matches!(self.source, TickSource::Live { recorder: Some(_), .. })
    }

    /// Swaps in the level `reload` or `play_listed` prepared: its renderer, view and
    /// simulation. While recording, the new level is a new attempt in a new file beside the
    /// last (started at the spawn, as its replay will be).
    pub(super) fn switch_level(&mut self, gpu: &Gpu, next: NextLevel) -> anyhow::Result<()> {
        let (plugins, gi) = crate::plugins(self.config.gi.clone());
        let mut renderer = Renderer::new(gpu, &next.level.scene, plugins)?;
        let mut view = WorldView::new(&next.level);
        view.add_meshes(&mut renderer, gpu);
        let (rate, seed) = (self.sim.tick_rate(), crate::recording::fresh_seed());
        let sim = if next.keep_pose {
            let p = &self.sim.state.player;
            Simulation::at(p.body.position, p.yaw, p.pitch, next.world, rate, seed)
        } else {
            Simulation::new(&next.level, next.world, rate, seed)
        };
        if let TickSource::Live { sampler, recorder } = &mut self.source {
            sampler.clear();
            if let Some(r) = recorder {
                if let Err(e) = r.save() {
                    log::error!("{e:#}");
                }
                let header = crate::recording::header(&next.level, &next.path, rate, seed, &self.config.gi);
                *r = Recorder::new(header, crate::recording::next_attempt_path(&r.path));
            }
        }
        view.at(sim.entities(), &sim.state);
        self.prev = sim.state.clone();
        self.sim = sim;
        self.clock = FixedClock::new(rate);
        self.view = view;
        self.renderer = Some(renderer);
        self.gi = Some(gi);
        self.level = next.level;
        self.since_outcome = 0.0;
        self.messages = Messages::default();
        self.reload_error = None;
        self.reloaded_at = Some(self.time);
        if self.level_path.as_ref() != Some(&next.path) || self.watch.is_none() {
            self.watch_level(&next.path);
        }
        self.apply_config();
        Ok(())
    }
}
