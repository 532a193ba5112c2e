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

impl Messages {
    /// After a tick: its events, with the state they left.
    pub fn push_events(&mut self, events: &[Event], state: &WorldState) {
        for e in events {
            if *e == (Event::Hit { enemy: true }) {
                self.hit = HIT_FOR;
            }
            let text = match e {
                Event::Picked(PickupKind::Battery) => format!("Battery — lamp at {:.0}%", state.lamp.battery * 100.0),
                Event::Picked(PickupKind::Ammo) => format!("Ammo — {} in reserve", state.weapon.reserve),
                Event::Picked(PickupKind::Health) => format!("Health — {:.0}", state.player.health),
                Event::EnemyDown => match state.enemies_left() {
                    0 => "The last crawler is down".to_owned(),
                    1 => "Crawler down — 1 left".to_owned(),
                    n => format!("Crawler down — {n} left"),
                },
                Event::LampPickedUp => "Lamp back on your head".to_owned(),
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
        m.push_events(&[Event::Fired, Event::Hit { enemy: false }], &sim.state);
        assert_eq!((m.current(), m.hit()), (None, 0.0), "a miss says nothing");
        m.push_events(&[Event::Hit { enemy: true }, Event::EnemyDown], &sim.state);
        assert_eq!(m.hit(), 1.0);
        assert_eq!(m.current(), Some("Crawler down — 4 left"), "the state still counts 4 alive");
        m.tick(0.1);
        assert!(m.hit() > 0.0 && m.hit() < 1.0);
        m.tick(SHOW_FOR);
        assert_eq!((m.current(), m.hit()), (None, 0.0));
    }
}
