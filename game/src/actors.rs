//! How the simulation's things look: crawlers, pickups, the lamp lying somewhere, shot marks and
//! the exit sign, as engine mesh instances. They are drawn into the G-buffer and the lamp's view
//! like the level, so the headlamp lights them, they cast shadows and they bounce light. A
//! crawler's body and its animation are in [`crate::crawler_body`].

use engine::frame::{Instance, MeshId};
use engine::glam::{Mat4, Quat, Vec3};
use engine::gpu::Gpu;
use engine::primitives;
use engine::renderer::Renderer;

use crate::crawler_body::{CrawlerMeshes, LampLight};
use crate::sim::{LevelEntities, PickupKind, WorldState};

/// Shot marks are drawn this long (a spark for the first few ticks, then a dark mark).
const SPARK_TICKS: u32 = 5;

/// The meshes, added to a renderer once.
pub struct ActorMeshes {
    crawler: CrawlerMeshes,
    battery: MeshId,
    ammo: MeshId,
    medkit: MeshId,
    /// The raised red cross on a medkit: health tells itself from ammo by shape as well as
    /// colour, for colour-blind players.
    cross: MeshId,
    lamp: MeshId,
    lens: MeshId,
    mark: MeshId,
    sign: MeshId,
}

/// The medkit's half extents, m.
const MEDKIT: Vec3 = Vec3::new(0.17, 0.1, 0.13);
const CROSS_HALF_THICKNESS: f32 = 0.012;
const CROSS_RED: [f32; 3] = [0.8, 0.05, 0.05];
const CROSS_GLOW: [f32; 3] = [0.3, 0.01, 0.01];

/// A plus sign of two crossed plates, lying flat.
fn cross() -> (Vec<engine::scene::Vertex>, Vec<u32>) {
    primitives::boxes(&[
        (Vec3::ZERO, Vec3::new(0.11, CROSS_HALF_THICKNESS, 0.035)),
        (Vec3::ZERO, Vec3::new(0.035, CROSS_HALF_THICKNESS, 0.11)),
    ])
}

impl ActorMeshes {
    pub fn add_to(renderer: &mut Renderer, gpu: &Gpu) -> Self {
        let crawler = CrawlerMeshes::add_to(renderer, gpu);
        let mut add = |(v, i): (Vec<_>, Vec<u32>)| renderer.add_mesh(gpu, &v, &i);
        Self {
            crawler,
            battery: add(primitives::cylinder(0.08, 0.26, 12)),
            ammo: add(primitives::cuboid(Vec3::new(0.16, 0.09, 0.11))),
            medkit: add(primitives::cuboid(MEDKIT)),
            cross: add(cross()),
            lamp: add(primitives::cylinder(0.06, 0.12, 12)),
            lens: add(primitives::cylinder(0.045, 0.01, 12)),
            mark: add(primitives::cuboid(Vec3::new(0.05, 0.05, 0.004))),
            sign: add(primitives::cuboid(Vec3::new(0.35, 0.12, 0.02))),
        }
    }

    /// The instances of `state`, blending moving things between `prev` (t = 0) and it (t = 1).
    /// `time` (seconds, for the pickups' idle spin only) never feeds back into the simulation;
    /// `lamp` is the headlamp as the crawlers' eyes catch it.
    pub fn instances(
        &self,
        entities: &LevelEntities,
        prev: &WorldState,
        state: &WorldState,
        t: f32,
        time: f32,
        lamp: &LampLight,
    ) -> Vec<Instance> {
        let mut out = Vec::new();
        // The world's tick clock, blended: crawlers breathe by it, so replays breathe alike.
        let clock = prev.tick as f32 + state.tick.saturating_sub(prev.tick) as f32 * t;
        for (i, e) in state.enemies.iter().enumerate() {
            let p = prev.enemies.get(i).unwrap_or(e);
            self.crawler.instances(&mut out, (p, e), t, clock, i, lamp);
        }
        for p in state.pickups.iter().filter(|p| !p.taken) {
            // Turn slowly and glow faintly, so they can be found in the dark.
            let spin = Quat::from_rotation_y(time * 1.5);
            let (mesh, color, glow, lift) = match p.kind {
                PickupKind::Battery => (self.battery, [0.8, 0.65, 0.1], [0.25, 0.2, 0.02], 0.0),
                PickupKind::Ammo => (self.ammo, [0.3, 0.33, 0.18], [0.06, 0.07, 0.03], 0.09),
                PickupKind::Health => (self.medkit, [0.85, 0.85, 0.85], [0.3, 0.02, 0.02], 0.1),
            };
            let transform = Mat4::from_rotation_translation(spin, p.position + Vec3::Y * (lift + 0.02));
            out.push(Instance { mesh, transform, base_color: color, emissive: glow });
            if p.kind == PickupKind::Health {
                let on_top = transform * Mat4::from_translation(Vec3::Y * (MEDKIT.y + CROSS_HALF_THICKNESS));
                out.push(Instance { mesh: self.cross, transform: on_top, base_color: CROSS_RED, emissive: CROSS_GLOW });
            }
        }
        let lamp = &state.lamp;
        if !lamp.attached {
            let position = lamp.drawn_position(&prev.lamp, t);
            let aim = crate::sim::player::aim(lamp.yaw, lamp.pitch);
            // The cylinder's axis (+Y) along the beam, the whole lamp just behind the point the
            // light leaves from: it must not stand in its own beam (the lamp's view, which casts
            // its shadows, sees only what is in front of that point).
            let turn = Quat::from_rotation_arc(Vec3::Y, aim);
            let body = Mat4::from_rotation_translation(turn, position - aim * 0.15);
            out.push(Instance { mesh: self.lamp, transform: body, base_color: [0.08, 0.08, 0.09], emissive: [0.0; 3] });
            let glow = 6.0 * lamp.brightness();
            let lens = Mat4::from_rotation_translation(turn, position - aim * 0.03);
            out.push(Instance {
                mesh: self.lens,
                transform: lens,
                base_color: [0.9; 3],
                emissive: [glow, glow * 0.9, glow * 0.75],
            });
        }
        for m in &state.impacts {
            let age = state.tick.saturating_sub(m.tick);
            if m.on_enemy && age > SPARK_TICKS {
                continue;
            }
            // Flat against the surface (the mark's thin axis is Z), a hair off it.
            let turn = Quat::from_rotation_arc(Vec3::Z, m.normal);
            let transform = Mat4::from_rotation_translation(turn, m.position + m.normal * 0.006);
            let (color, glow) =
                if age <= SPARK_TICKS { ([1.0, 0.8, 0.5], [8.0, 4.0, 1.2]) } else { ([0.02; 3], [0.0; 3]) };
            out.push(Instance { mesh: self.mark, transform, base_color: color, emissive: glow });
        }
        if let Some(exit) = &entities.exit {
            // A green sign over the way out, facing the way the marker does.
            let transform =
                Mat4::from_rotation_translation(Quat::from_rotation_y(exit.yaw), exit.position + Vec3::Y * 2.2);
            out.push(Instance { mesh: self.sign, transform, base_color: [0.1, 0.5, 0.15], emissive: [0.1, 1.6, 0.35] });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::level_entities::PickupSpawn;
    use crate::sim::Pickup;

    #[test]
    fn a_medkit_wears_a_red_cross_and_ammo_does_not() {
        let meshes = ActorMeshes {
            crawler: CrawlerMeshes::fake(10),
            battery: MeshId(2),
            ammo: MeshId(3),
            medkit: MeshId(4),
            cross: MeshId(5),
            lamp: MeshId(6),
            lens: MeshId(7),
            mark: MeshId(8),
            sign: MeshId(9),
        };
        let level = engine::scene::load_level(&crate::default_level()).unwrap();
        let sim = crate::sim::Simulation::new(&level, crate::sim::level_world(&level).unwrap(), 60, 1);
        let mut state = sim.state.clone();
        let at = |kind, x| {
            Pickup::spawn(&PickupSpawn { name: String::new(), kind, position: Vec3::new(x, 0.0, 0.0), amount: 1.0 })
        };
        state.pickups = vec![at(PickupKind::Ammo, 0.0), at(PickupKind::Health, 2.0)];
        let instances = meshes.instances(sim.entities(), &state, &state, 1.0, 0.0, &LampLight::OFF);
        let crosses: Vec<&Instance> = instances.iter().filter(|i| i.mesh == meshes.cross).collect();
        assert_eq!(crosses.len(), 1, "one cross, on the medkit only");
        let medkit = instances.iter().find(|i| i.mesh == meshes.medkit).unwrap();
        let (top, box_centre) = (crosses[0].transform.w_axis.truncate(), medkit.transform.w_axis.truncate());
        assert!(
            (top.x - box_centre.x).abs() < 1e-5 && top.y > box_centre.y + MEDKIT.y,
            "on top: {top} over {box_centre}"
        );
        assert!(crosses[0].base_color[0] > 5.0 * crosses[0].base_color[1], "red");
    }
}
