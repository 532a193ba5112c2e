//! The pistol in the player's hand: a mesh made here from boxes and cylinders (slide, frame,
//! grip, barrel, sights with glowing dots, trigger and guard, magazine), placed in front of the
//! camera as the engine's view models (`ViewState::view_models`: drawn over the scene with their
//! own depth, lit by the headlamp and the GI, never seen by the GI). Posed from the weapon's
//! timers: recoil kicks it up and cycles the slide, a reload lowers and tilts it while the
//! magazine drops out and comes back, a shot shows a flash at the muzzle.

use engine::camera::Camera;
use engine::frame::{Instance, MeshId};
use engine::glam::{Mat4, Quat, Vec3};
use engine::gpu::Gpu;
use engine::primitives;
use engine::renderer::Renderer;
use engine::scene::Vertex;

use crate::sim::weapon::{self, Weapon};

/// How the gun is held this frame, each 0..=1.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GunPose {
    /// 1 as a shot leaves, falling to 0 before the next.
    pub recoil: f32,
    /// 1 at the brightest of the muzzle flash, 0 without one.
    pub flash: f32,
    /// 0 held up, 1 fully lowered (mid-reload).
    pub lowered: f32,
    /// 0 magazine in the grip, 1 dropped out of it (mid-reload).
    pub magazine_out: f32,
}

impl GunPose {
    /// The pose the weapon's timers give.
    pub fn of(w: &Weapon) -> Self {
        let (lowered, magazine_out) = if w.reloading > 0 {
            let done = 1.0 - w.reloading as f32 / weapon::RELOAD_TICKS as f32;
            // Down and back up over the reload, a sine arch; the magazine out in the middle.
            let out = ((done - 0.15) / 0.25).min((0.85 - done) / 0.25).clamp(0.0, 1.0);
            ((done * std::f32::consts::PI).sin(), out)
        } else {
            (0.0, 0.0)
        };
        Self {
            recoil: w.cooldown as f32 / weapon::FIRE_INTERVAL as f32,
            flash: w.flash as f32 / weapon::FLASH_TICKS as f32,
            lowered,
            magazine_out,
        }
    }

    /// Between `a` (t = 0) and `b` (t = 1).
    pub fn lerp(a: Self, b: Self, t: f32) -> Self {
        let mix = |x: f32, y: f32| x + (y - x) * t;
        Self {
            recoil: mix(a.recoil, b.recoil),
            flash: mix(a.flash, b.flash),
            lowered: mix(a.lowered, b.lowered),
            magazine_out: mix(a.magazine_out, b.magazine_out),
        }
    }
}

/// Where the gun's pivot (the top of the grip, where the hand holds it) sits in camera space
/// (m; x right, y up, −z forward): low and right, as a right hand holds it.
const HELD_AT: Vec3 = Vec3::new(0.14, -0.17, -0.35);
/// Turned a little inwards, so the muzzle points near the crosshair's line (radians).
const HELD_YAW: f32 = 0.07;

/// Linear albedos: blued steel, black polymer, a dark rubbery grip, the magazine's steel.
const STEEL: [f32; 3] = [0.03, 0.032, 0.037];
const POLYMER: [f32; 3] = [0.02, 0.02, 0.022];
const GRIP: [f32; 3] = [0.03, 0.024, 0.019];
const BORE: [f32; 3] = [0.01, 0.01, 0.01];
/// The sights' tritium dots: green, glowing faintly (emitted radiance, W·sr⁻¹·m⁻²), so the
/// gun can be found in the dark.
const DOT_GLOW: [f32; 3] = [0.1, 1.2, 0.25];
/// The muzzle flash's emitted radiance at its brightest: a warm white core in an orange cone.
const FLASH_CORE: [f32; 3] = [60.0, 50.0, 30.0];
const FLASH_CONE: [f32; 3] = [30.0, 14.0, 3.0];

/// The grip's rake: it leans back from the slide (radians about x).
const GRIP_RAKE: f32 = 0.3;
/// The grip's centre below the pivot, in the pivot's frame.
const GRIP_CENTRE: Vec3 = Vec3::new(0.0, -0.045, 0.01);
/// The muzzle, in the pivot's frame.
const MUZZLE: Vec3 = Vec3::new(0.0, 0.03, -0.168);

/// The gun's meshes, added to a renderer once.
pub struct GunModel {
    /// Slide with its sights (steel).
    slide: MeshId,
    /// Frame, dust cover, trigger guard and trigger (polymer).
    frame: MeshId,
    grip: MeshId,
    magazine: MeshId,
    bore: MeshId,
    dots: MeshId,
    /// A unit sphere, stretched into the flash.
    flash: MeshId,
}

impl GunModel {
    pub fn add_to(renderer: &mut Renderer, gpu: &Gpu) -> Self {
        let v = Vec3::new;
        let slide = primitives::boxes(&[
            (v(0.0, 0.03, -0.068), v(0.0135, 0.016, 0.097)),
            // The rear sight, a notch between two posts, and the front sight's post.
            (v(-0.0085, 0.05, 0.02), v(0.005, 0.004, 0.004)),
            (v(0.0085, 0.05, 0.02), v(0.005, 0.004, 0.004)),
            (v(0.0, 0.0495, -0.152), v(0.0025, 0.0035, 0.003)),
        ]);
        let frame = primitives::boxes(&[
            // Dust cover under the slide, from the grip to the muzzle.
            (v(0.0, 0.006, -0.08), v(0.012, 0.009, 0.08)),
            // Trigger guard: bottom bar and front bar; the trigger.
            (v(0.0, -0.03, -0.042), v(0.005, 0.003, 0.03)),
            (v(0.0, -0.016, -0.07), v(0.005, 0.014, 0.003)),
            (v(0.0, -0.012, -0.034), v(0.003, 0.01, 0.003)),
        ]);
        let grip = primitives::boxes(&[(Vec3::ZERO, v(0.0145, 0.056, 0.024))]);
        // The magazine inside the grip, its base plate just below it.
        let magazine =
            primitives::boxes(&[(Vec3::ZERO, v(0.011, 0.052, 0.018)), (v(0.0, -0.055, 0.0), v(0.0135, 0.004, 0.021))]);
        let (mut bore, bore_indices) = primitives::cylinder(0.0065, 0.004, 12);
        // Its axis from +y to the barrel's, −z, at the slide's front face.
        let turn = Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2);
        for p in &mut bore {
            p.position = (turn * Vec3::from(p.position) + v(0.0, 0.03, -0.165)).to_array();
            p.normal = (turn * Vec3::from(p.normal)).to_array();
        }
        let dots = primitives::boxes(&[
            (v(0.0, 0.05, -0.1488), v(0.0013, 0.0013, 0.0003)),
            (v(-0.0085, 0.0495, 0.0158), v(0.0013, 0.0013, 0.0003)),
            (v(0.0085, 0.0495, 0.0158), v(0.0013, 0.0013, 0.0003)),
        ]);
        let mut add = |(v, i): (Vec<Vertex>, Vec<u32>)| renderer.add_mesh(gpu, &v, &i);
        Self {
            slide: add(slide),
            frame: add(frame),
            grip: add(grip),
            magazine: add(magazine),
            bore: add((bore, bore_indices)),
            dots: add(dots),
            flash: add(primitives::uv_sphere(1.0, 10, 6)),
        }
    }

    /// The gun in `pose`, held in front of `camera`, as world-space view models. `flash`
    /// scales the muzzle flash (the player's "reduce flashing").
    pub fn instances(&self, camera: &Camera, pose: GunPose, flash: f32) -> Vec<Instance> {
        let recoil = pose.recoil.clamp(0.0, 1.0);
        let lowered = pose.lowered.clamp(0.0, 1.0);
        // Kick: back and muzzle up about the hand; reload: drawn in towards the middle, its
        // muzzle lowered and rolled left, so the magazine well turns towards the eye.
        let offset = Vec3::new(-0.06 * lowered, 0.0, 0.035 * recoil + 0.03 * lowered);
        let turn = Quat::from_rotation_y(HELD_YAW)
            * Quat::from_rotation_z(0.7 * lowered)
            * Quat::from_rotation_x(0.2 * recoil - 0.25 * lowered);
        let hand = Mat4::from_rotation_translation(camera.rotation, camera.position)
            * Mat4::from_rotation_translation(turn, HELD_AT + offset);
        let part =
            |mesh, local: Mat4, base_color, emissive| Instance { mesh, transform: hand * local, base_color, emissive };
        // The slide runs back as the shot leaves and springs home.
        let slide_back = Mat4::from_translation(Vec3::Z * 0.028 * recoil * recoil);
        let grip = Mat4::from_rotation_translation(Quat::from_rotation_x(GRIP_RAKE), GRIP_CENTRE);
        let magazine =
            grip * Mat4::from_translation(Vec3::new(0.0, -0.004 - 0.17 * pose.magazine_out.clamp(0.0, 1.0), 0.0));
        let mut out = vec![
            part(self.slide, slide_back, STEEL, [0.0; 3]),
            part(self.dots, slide_back, [0.3; 3], DOT_GLOW),
            part(self.frame, Mat4::IDENTITY, POLYMER, [0.0; 3]),
            part(self.bore, Mat4::IDENTITY, BORE, [0.0; 3]),
            part(self.grip, grip, GRIP, [0.0; 3]),
            part(self.magazine, magazine, STEEL, [0.0; 3]),
        ];
        let strength = (pose.flash * flash).clamp(0.0, 1.0);
        if strength > 0.0 {
            let size = 0.6 + 0.4 * strength;
            let sphere = |scale: Vec3, ahead: f32| {
                Mat4::from_scale_rotation_translation(scale * size, Quat::IDENTITY, MUZZLE - Vec3::Z * ahead * size)
            };
            let glow = |c: [f32; 3]| c.map(|x| x * strength);
            out.push(part(self.flash, sphere(Vec3::new(0.03, 0.03, 0.07), 0.07), [0.0; 3], glow(FLASH_CONE)));
            out.push(part(self.flash, sphere(Vec3::new(0.016, 0.016, 0.03), 0.025), [0.0; 3], glow(FLASH_CORE)));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pose_follows_the_weapon_timers() {
        let rest = Weapon { cooldown: 0, reloading: 0, flash: 0, ..Weapon::default() };
        assert_eq!(GunPose::of(&rest), GunPose::default());
        let fired = Weapon { cooldown: weapon::FIRE_INTERVAL, flash: weapon::FLASH_TICKS, ..rest };
        let pose = GunPose::of(&fired);
        assert_eq!((pose.recoil, pose.flash), (1.0, 1.0));
        let mid_reload = Weapon { reloading: weapon::RELOAD_TICKS / 2, ..rest };
        let pose = GunPose::of(&mid_reload);
        assert!(pose.lowered > 0.99 && pose.magazine_out == 1.0, "{pose:?}");
        let starting = Weapon { reloading: weapon::RELOAD_TICKS, ..rest };
        assert_eq!(GunPose::of(&starting).magazine_out, 0.0, "in the grip as the reload starts");
        // A dry click is no shot: the gun does not kick.
        let mut empty = Weapon { magazine: 0, reserve: 0, ..rest };
        let fire = crate::sim::TickCommand { buttons: crate::sim::command::buttons::FIRE, ..Default::default() };
        assert_eq!(empty.step(&fire), weapon::WeaponAction::DryClick);
        assert_eq!(GunPose::of(&empty).recoil, 0.0);
        let half = GunPose::lerp(GunPose::default(), GunPose::of(&fired), 0.5);
        assert_eq!(half.recoil, 0.5);
    }
}
