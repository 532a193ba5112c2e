//! Turns what happened in the simulation's ticks into the short messages the HUD shows
//! ("Battery +50%", "Crawler down — 2 left") and the hit marker.

use crate::sim::{Event, PickupKind, WorldState};

/// A message stays this long, s.
const SHOW_FOR: f32 = 2.5;
/// The hit marker fades over this long, s.
const HIT_FOR: f32 = 0.25;

#[derive(Default)]
pub struct Messages {
    current: Option<(String, f32)>,
    /// Seconds of hit marker left.
    hit: f32,
}

/// Where `p` lies from the player's view: ahead, to the left or right, or behind.
fn direction(state: &WorldState, p: glam::Vec3) -> &'static str {
    let yaw = crate::sim::command::radians(state.player.yaw as f32);
    let to = p - state.player.body.position;
    // The view's forward (0 looks down −Z) and left (positive yaw turns left).
    let (ahead, left) = (-to.x * yaw.sin() - to.z * yaw.cos(), -to.x * yaw.cos() + to.z * yaw.sin());
    match left.atan2(ahead).to_degrees() {
        a if a.abs() <= 45.0 => "ahead",
        a if a.abs() >= 135.0 => "behind you",
        a if a > 0.0 => "to your left",
        _ => "to your right",
    }
}

impl Messages {
    /// After a tick: its events, with the state they left. With `captions`, what is heard and
    /// matters is written too (a crawler noticing you: where, and whether you can see it).
    pub fn push_events(&mut self, events: &[Event], state: &WorldState, captions: bool) {
        for e in events {
            if matches!(e, Event::Hit { enemy: Some(_), .. }) {
                self.hit = HIT_FOR;
            }
            let text = match e {
                Event::Picked(PickupKind::Battery) => format!("Battery — lamp at {:.0}%", state.lamp.battery * 100.0),
                Event::Picked(PickupKind::Ammo) => format!("Ammo — {} in reserve", state.weapon.reserve),
                Event::Picked(PickupKind::Health) => format!("Health — {:.0}", state.player.health),
                Event::EnemyDown { .. } => match state.enemies_left() {
                    0 => "The last crawler is down".to_owned(),
                    1 => "Crawler down — 1 left".to_owned(),
                    n => format!("Crawler down — {n} left"),
                },
                Event::LampPickedUp => "Lamp back on your head".to_owned(),
                Event::Noticed { enemy, in_sight } if captions => {
                    let Some(e) = state.enemies.get(*enemy as usize) else { continue };
                    let seen = if *in_sight { "" } else { ", out of sight" };
                    format!("[A crawler noticed you — {}{seen}]", direction(state, e.body.position))
                }
                _ => continue,
            };
            self.current = Some((text, SHOW_FOR));
        }
    }

    /// Frame time passes.
    pub fn tick(&mut self, dt: f32) {
        self.hit = (self.hit - dt).max(0.0);
        if let Some((_, left)) = &mut self.current {
            *left -= dt;
            if *left <= 0.0 {
                self.current = None;
            }
        }
    }

    /// The hit marker's strength, 1 just after a hit.
    pub fn hit(&self) -> f32 {
        self.hit / HIT_FOR
    }

    pub fn current(&self) -> Option<&str> {
        self.current.as_ref().map(|(t, _)| t.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn events_become_messages_and_a_fading_hit_marker() {
        let level = engine::scene::load_level(&crate::default_level()).unwrap();
        let sim = crate::sim::Simulation::new(&level, crate::sim::level_world(&level).unwrap(), 60, 1);
        let mut m = Messages::default();
        m.push_events(&[Event::Fired, Event::Hit { enemy: None, at: glam::Vec3::ZERO }], &sim.state, true);
        assert_eq!((m.current(), m.hit()), (None, 0.0), "a miss says nothing");
        m.push_events(
            &[Event::Hit { enemy: Some(0), at: glam::Vec3::ZERO }, Event::EnemyDown { enemy: 0 }],
            &sim.state,
            true,
        );
        assert_eq!(m.hit(), 1.0);
        assert_eq!(m.current(), Some("Crawler down — 4 left"), "the state still counts 4 alive");
        m.tick(0.1);
        assert!(m.hit() > 0.0 && m.hit() < 1.0);
        m.tick(SHOW_FOR);
        assert_eq!((m.current(), m.hit()), (None, 0.0));
    }

    #[test]
    fn a_crawler_noticing_you_is_captioned_with_where_it_is() {
        let level = engine::scene::load_level(&crate::default_level()).unwrap();
        let sim = crate::sim::Simulation::new(&level, crate::sim::level_world(&level).unwrap(), 60, 1);
        let mut state = sim.state.clone();
        // The player at the origin looking down −Z (yaw 0); the crawler placed around them.
        state.player.body.position = glam::Vec3::ZERO;
        state.player.yaw = 0;
        let caption = |state: &mut WorldState, x: f32, z: f32, in_sight: bool, captions: bool| {
            state.enemies[0].body.position = glam::Vec3::new(x, 0.0, z);
            let mut m = Messages::default();
            m.push_events(&[Event::Noticed { enemy: 0, in_sight }], state, captions);
            m.current().map(str::to_owned)
        };
        let said = |t: &str| Some(t.to_owned());
        assert_eq!(caption(&mut state, 0.0, -5.0, true, true), said("[A crawler noticed you — ahead]"));
        assert_eq!(
            caption(&mut state, -5.0, 0.0, false, true),
            said("[A crawler noticed you — to your left, out of sight]")
        );
        assert_eq!(
            caption(&mut state, 5.0, 1.0, false, true),
            said("[A crawler noticed you — to your right, out of sight]")
        );
        assert_eq!(
            caption(&mut state, 0.0, 5.0, false, true),
            said("[A crawler noticed you — behind you, out of sight]")
        );
        assert_eq!(caption(&mut state, 0.0, 5.0, false, false), None, "captions off");
        // Turned a quarter left (looking down −X), the crawler at −X is ahead.
        state.player.yaw = 16384;
        assert_eq!(caption(&mut state, -5.0, 0.0, true, true), said("[A crawler noticed you — ahead]"));
    }
}
