//! Turns what happened in the simulation's ticks into the short messages the HUD shows
//! ("Battery +50%", "Crawler down — 2 left").

use crate::sim::{Event, PickupKind, WorldState};

/// A message stays this long, s.
const SHOW_FOR: f32 = 2.5;

#[derive(Default)]
pub struct Messages {
    current: Option<(String, f32)>,
}

impl Messages {
    /// After a tick: its events, with the state they left.
    pub fn push_events(&mut self, events: &[Event], state: &WorldState) {
        for e in events {
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
        if let Some((_, left)) = &mut self.current {
            *left -= dt;
            if *left <= 0.0 {
                self.current = None;
            }
        }
    }

    pub fn current(&self) -> Option<&str> {
        self.current.as_ref().map(|(t, _)| t.as_str())
    }
}
