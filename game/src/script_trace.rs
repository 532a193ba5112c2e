//! `headlamp script --trace`: the world after each step of a script, one line per step plus
//! one per crawler, with the `turn`/`look` degrees that would put the crosshair on each — what
//! an author needs to write the next line of a script that plays the game.

use std::fmt::Write;

use crate::sim::command::radians;
use crate::sim::enemy::Mind;
use crate::sim::WorldState;

/// Height above a crawler's feet that a script aims at (its chest), m.
const AIM_HEIGHT: f32 = 0.9;

/// The lines for the state after script line `line`.
pub fn describe(line: usize, s: &WorldState) -> String {
    let p = &s.player;
    let (yaw, pitch) = (radians(p.yaw as f32).to_degrees(), radians(p.pitch as f32).to_degrees());
    let mut out = format!(
        "line {line}: tick {} at ({:.2}, {:.2}, {:.2}) yaw {yaw:.1} pitch {pitch:.1} health {:.0} \
         ammo {}/{} battery {:.0}% lamp {} {}",
        s.tick,
        p.body.position.x,
        p.body.position.y,
        p.body.position.z,
        p.health,
        s.weapon.magazine,
        s.weapon.reserve,
        s.lamp.battery * 100.0,
        if s.lamp.on { "on" } else { "off" },
        s.outcome.name(),
    );
    for (i, e) in s.enemies.iter().enumerate() {
        let _ = write!(
            out,
            "\n  crawler {i}: ({:.2}, {:.2}) {:?} health {:.0}",
            e.body.position.x, e.body.position.z, e.mind, e.health
        );
        if e.mind == Mind::Dead {
            continue;
        }
        let d = e.body.position + glam::Vec3::Y * AIM_HEIGHT - p.eye();
        let horizontal = (d.x * d.x + d.z * d.z).sqrt();
        let bearing = (-d.x).atan2(-d.z).to_degrees();
        let turn = (bearing - yaw + 540.0).rem_euclid(360.0) - 180.0;
        let look = d.y.atan2(horizontal).to_degrees() - pitch;
        let _ = write!(out, "; aim: turn {turn:.1} look {look:.1} ({:.1} m)", d.length());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_aim_puts_the_view_on_the_crawler() {
        let level = engine::scene::load_level(&crate::default_level()).unwrap();
        let world = crate::sim::level_world(&level).unwrap();
        let mut sim = crate::sim::Simulation::new(&level, world, 60, 1);
        let text = describe(3, &sim.state);
        assert!(text.starts_with("line 3: tick 0 at (0.00, 0.00, 3.80) yaw 0.0"), "{text}");
        assert_eq!(text.lines().count(), 1 + sim.state.enemies.len());
        // Turn and look by what it says for crawler 0: the view then points at its chest.
        let aim = text.lines().nth(1).unwrap().split("aim: turn ").nth(1).unwrap();
        let mut words = aim.split_whitespace();
        let turn: f32 = words.next().unwrap().parse().unwrap();
        let look: f32 = words.nth(1).unwrap().parse().unwrap();
        let units = |deg: f32| crate::sim::command::angle_units(deg.to_radians()).round() as i16;
        sim.state.player.yaw = sim.state.player.yaw.wrapping_add(units(turn) as u16);
        sim.state.player.pitch += units(look);
        let e = &sim.state.enemies[0];
        let to = (e.body.position + glam::Vec3::Y * AIM_HEIGHT - sim.state.player.eye()).normalize();
        assert!(sim.state.player.aim().dot(to) > 0.9999, "{text}");
    }
}
