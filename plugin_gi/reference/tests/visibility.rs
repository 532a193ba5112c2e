//! The visibility-correct reference: the visibility cube against exact rays (which patches of
//! the level a receiver sees), and the one bounce it gives against the one bounce without it
//! and against a ray per sender–receiver pair.

use engine::camera::Camera;
use engine::glam::{Quat, Vec3};
use engine::headlamp::Headlamp;
use engine::scene::{HeadlampProfile, IntensityDistribution, Material, Mesh, Scene, Vertex};
use gi_reference::{Lamp, LitPatches, Patch, Receiver, VisibilityCube, World};

/// A uniform lamp of intensity `power` put down at `eye` looking at `target`.
fn lamp(eye: Vec3, target: Vec3, fov_deg: f32, power: f32) -> Lamp {
    let profile = HeadlampProfile {
        power,
        fov_y: fov_deg.to_radians(),
        color: [1.0; 3],
        distribution: IntensityDistribution::Uniform,
    };
    let mut headlamp = Headlamp::new(profile);
    headlamp.detach_looking_at(eye, target);
    Lamp::new(&headlamp, &Camera::perspective(Vec3::ZERO, Quat::IDENTITY, 1.0), 1.0)
}

fn receiver(position: Vec3, normal: Vec3) -> Receiver {
    Receiver { position, normal, albedo: Vec3::splat(0.7) }
}

/// Appends a quad (corners counter-clockwise seen from its front).
fn quad(scene: &mut Scene, corners: [Vec3; 4], double_sided: bool) {
    let n = (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalize();
    let vertices = corners.iter().map(|p| Vertex::new(p.to_array(), n.to_array(), [0.0; 2])).collect();
    let material = usize::from(double_sided);
    scene.meshes.push(Mesh {
        name: format!("quad{}", scene.meshes.len()),
        vertices,
        indices: vec![0, 1, 2, 0, 2, 3],
        material,
    });
}

fn scene() -> Scene {
    let grey = |double_sided| Material { base_color: [0.7, 0.7, 0.7, 1.0], double_sided, ..Material::default() };
    Scene { materials: vec![grey(false), grey(true)], ..Scene::default() }
}

/// A closed box x ∈ [-1, 1], y ∈ [0, 2], z ∈ [-1, 1] seen from inside, with a block on its
/// floor (single-sided faces) and a double-sided panel hanging in it.
fn box_with_a_block() -> Scene {
    let mut s = scene();
    let v = Vec3::new;
    quad(&mut s, [v(-1.0, 0.0, 1.0), v(1.0, 0.0, 1.0), v(1.0, 0.0, -1.0), v(-1.0, 0.0, -1.0)], false);
    quad(&mut s, [v(-1.0, 2.0, -1.0), v(1.0, 2.0, -1.0), v(1.0, 2.0, 1.0), v(-1.0, 2.0, 1.0)], false);
    quad(&mut s, [v(-1.0, 0.0, -1.0), v(1.0, 0.0, -1.0), v(1.0, 2.0, -1.0), v(-1.0, 2.0, -1.0)], false);
    quad(&mut s, [v(1.0, 0.0, 1.0), v(-1.0, 0.0, 1.0), v(-1.0, 2.0, 1.0), v(1.0, 2.0, 1.0)], false);
    quad(&mut s, [v(-1.0, 0.0, 1.0), v(-1.0, 0.0, -1.0), v(-1.0, 2.0, -1.0), v(-1.0, 2.0, 1.0)], false);
    quad(&mut s, [v(1.0, 0.0, -1.0), v(1.0, 0.0, 1.0), v(1.0, 2.0, 1.0), v(1.0, 2.0, -1.0)], false);
    let (x0, x1, z0, z1, h) = (0.1, 0.6, -0.5, 0.0, 1.2);
    quad(&mut s, [v(x0, 0.0, z1), v(x1, 0.0, z1), v(x1, h, z1), v(x0, h, z1)], false);
    quad(&mut s, [v(x1, 0.0, z0), v(x0, 0.0, z0), v(x0, h, z0), v(x1, h, z0)], false);
    quad(&mut s, [v(x0, 0.0, z0), v(x0, 0.0, z1), v(x0, h, z1), v(x0, h, z0)], false);
    quad(&mut s, [v(x1, 0.0, z1), v(x1, 0.0, z0), v(x1, h, z0), v(x1, h, z1)], false);
    quad(&mut s, [v(x0, h, z1), v(x1, h, z1), v(x1, h, z0), v(x0, h, z0)], false);
    // A double-sided panel across the left half, 1.4 m up.
    quad(&mut s, [v(-0.9, 1.4, 0.5), v(-0.2, 1.4, 0.5), v(-0.2, 1.4, -0.5), v(-0.9, 1.4, -0.5)], true);
    s
}

bounds::tolerance! {
    /// Nothing between: the light with visibility against without, relative, the worst receiver.
    UNBLOCKED: at_most 1.2e-5, measured 7.12e-6
}
bounds::tolerance! {
    /// The visible bounce by the cube against a ray per sender and receiver: relative, the worst
    /// of four receivers.
    RAYS: at_most 1e-7, measured 6.31e-8
}

/// The patch's centre stood off its surface towards `from`, as a shadow ray ends.
fn ray_end(p: &Patch, from: Vec3) -> Vec3 {
    let d = p.centre - from;
    p.centre - d * (gi_reference::SHADOW_OFFSET / d.length())
}

#[test]
fn the_cube_sees_what_rays_see_whatever_its_size() {
    let world = World::new(&box_with_a_block());
    let occluders = world.occluders();
    let patches = world.patches(0.05);
    // Points 1 mm off the box's surfaces and the block's, and the way those face.
    let receivers = [
        (Vec3::new(-0.5, 0.001, 0.5), Vec3::Y), // floor: the block and the panel between it and walls
        (Vec3::new(0.999, 0.7, 0.4), Vec3::NEG_X), // right wall, beside the block
        (Vec3::new(0.3, 1.999, -0.2), Vec3::NEG_Y), // ceiling, above the block
        (Vec3::new(-0.3, 0.6, -0.999), Vec3::Z), // back wall, behind the block and under the panel
        (Vec3::new(0.35, 0.5, 0.001), Vec3::Z), // the block's front face
    ];
    // The light a patch can send a receiver goes as cos·cos·A/d²: pairs that exchange none
    // (a patch on the receiver's own plane, or behind it) are not counted. The cube's size
    // decides only how many pairs a ray settles, not what is seen: none of it may differ.
    let share = |size: usize| {
        let (mut disagree, mut hidden, mut total) = (0.0, 0.0, 0.0);
        for &(r, n) in &receivers {
            let mut cube = VisibilityCube::new(&occluders, r, size);
            for p in &patches {
                let d = p.centre - r;
                let d2 = d.length_squared();
                // (A patch behind the receiver's plane sends it nothing, whichever way it faces.)
                let transfer =
                    if n.dot(d) > 0.0 { (n.dot(d) * -p.normal.dot(d)).max(0.0) / (d2 * d2) * p.area } else { 0.0 };
                if transfer <= 0.0 {
                    continue;
                }
                let ray = world.visible(r, ray_end(p, r));
                total += transfer;
                hidden += if ray { 0.0 } else { transfer };
                disagree += if cube.sees(&occluders, p.centre, p.triangle) == ray { 0.0 } else { transfer };
            }
        }
        (disagree / total, hidden / total)
    };
    for size in [16, 128, 512] {
        let (disagree, hidden) = share(size);
        bounds::assert(bounds::at_least("the share of the transfer hidden", hidden, 0.05));
        assert_eq!(
            disagree, 0.0,
            "with a cube of {size} the cube and the rays disagree on {disagree:.2e} of the transfer"
        );
    }
}

#[test]
fn a_wall_hides_the_room_behind_it_whatever_the_cube_size() {
    // Two rooms side by side, x < 0 and x > 0, the wall at x = 0 single-sided on each side.
    let mut s = scene();
    let v = Vec3::new;
    quad(&mut s, [v(0.0, 0.0, -1.0), v(0.0, 0.0, 1.0), v(0.0, 2.0, 1.0), v(0.0, 2.0, -1.0)], false); // faces -x
    quad(&mut s, [v(0.0, 0.0, 1.0), v(0.0, 0.0, -1.0), v(0.0, 2.0, -1.0), v(0.0, 2.0, 1.0)], false); // faces +x
    quad(&mut s, [v(0.0, 0.0, 1.0), v(2.0, 0.0, 1.0), v(2.0, 0.0, -1.0), v(0.0, 0.0, -1.0)], false); // floor x > 0
    quad(&mut s, [v(-2.0, 0.0, 1.0), v(0.0, 0.0, 1.0), v(0.0, 0.0, -1.0), v(-2.0, 0.0, -1.0)], false); // floor x < 0
    let world = World::new(&s);
    let occluders = world.occluders();
    let behind: Vec<Patch> = world.patches(0.05).into_iter().filter(|p| p.centre.x > 0.01).collect();
    assert!(!behind.is_empty());
    for n in [4, 64, 256] {
        for r in [v(-0.5, 0.001, 0.3), v(-1.5, 1.0, -0.7), v(-0.001, 1.0, 0.0)] {
            let mut cube = VisibilityCube::new(&occluders, r, n);
            let seen = behind.iter().filter(|p| cube.sees(&occluders, p.centre, p.triangle)).count();
            assert_eq!(seen, 0, "{seen} patches behind the wall seen from {r} with a cube of {n}");
        }
    }
}

/// Two rooms side by side (x < 0 and x > 0, each 2 m wide, deep and high) and a wall between
/// them with a doorway at z ∈ [0.6, 1] up to 1.5 m; floors, the wall's two faces.
fn two_rooms() -> Scene {
    let mut s = scene();
    let v = Vec3::new;
    quad(&mut s, [v(-2.0, 0.0, 1.0), v(2.0, 0.0, 1.0), v(2.0, 0.0, -1.0), v(-2.0, 0.0, -1.0)], false); // floor
    quad(&mut s, [v(-2.0, 2.0, -1.0), v(2.0, 2.0, -1.0), v(2.0, 2.0, 1.0), v(-2.0, 2.0, 1.0)], false); // ceiling
    quad(&mut s, [v(-2.0, 0.0, -1.0), v(2.0, 0.0, -1.0), v(2.0, 2.0, -1.0), v(-2.0, 2.0, -1.0)], false); // back
                                                                                                         // The wall at x = 0 from z = -1 to 0.6 (both faces), and above the door.
    quad(&mut s, [v(0.0, 0.0, -1.0), v(0.0, 0.0, 0.6), v(0.0, 2.0, 0.6), v(0.0, 2.0, -1.0)], false); // faces -x
    quad(&mut s, [v(0.0, 0.0, 0.6), v(0.0, 0.0, -1.0), v(0.0, 2.0, -1.0), v(0.0, 2.0, 0.6)], false); // faces +x
    quad(&mut s, [v(0.0, 1.5, 0.6), v(0.0, 1.5, 1.0), v(0.0, 2.0, 1.0), v(0.0, 2.0, 0.6)], false);
    quad(&mut s, [v(0.0, 1.5, 1.0), v(0.0, 1.5, 0.6), v(0.0, 2.0, 0.6), v(0.0, 2.0, 1.0)], false);
    s
}

#[test]
fn a_receiver_the_wall_hides_from_every_lit_patch_gets_exactly_zero_and_the_leak_is_gone() {
    let world = World::new(&two_rooms());
    // The lamp in the left room lights its floor by the wall, away from the door.
    let lit: LitPatches = world.lit(&lamp(Vec3::new(-1.0, 1.8, -0.5), Vec3::new(-0.4, 0.0, -0.5), 40.0, 5.0), 0.02);
    let right_most = bounds::worst(lit.patches().iter().map(|p| f64::from(p.patch.centre.x)));
    bounds::assert(bounds::at_most("the lit patches' largest x (the left room only)", right_most, 0.0));
    // The right room's back corner, its ceiling, and a point on the wall's right face: no line
    // from any of them to the left room's lit floor misses the wall.
    let hidden = [
        receiver(Vec3::new(1.5, 1.0, -0.99), Vec3::Z),
        receiver(Vec3::new(1.0, 1.99, -0.5), Vec3::NEG_Y),
        receiver(Vec3::new(0.3, 1.99, 0.0), Vec3::NEG_Y),
    ];
    let without = lit.irradiance(&hidden);
    let with = lit.irradiance_visible(&hidden, &world.occluders(), 128);
    for ((r, e), leak) in hidden.iter().zip(&with).zip(&without) {
        assert_eq!(*e, [0.0; 3], "light reaches {} through the wall", r.position);
        bounds::assert(bounds::at_least(
            format!("at {}: the light without visibility", r.position),
            leak[0],
            f64::MIN_POSITIVE,
        ));
    }
}

#[test]
fn with_nothing_in_the_way_visibility_changes_nothing() {
    // The left room alone, lit from its middle: its walls and floor are one convex room.
    let world = World::new(&two_rooms());
    let lit = world.lit(&lamp(Vec3::new(-1.0, 1.8, 0.0), Vec3::new(-1.0, 0.0, 0.0), 60.0, 5.0), 0.02);
    let receivers = [
        receiver(Vec3::new(-1.99, 1.0, 0.0), Vec3::X),
        receiver(Vec3::new(-0.01, 1.0, -0.5), Vec3::NEG_X),
        receiver(Vec3::new(-1.0, 1.99, 0.5), Vec3::NEG_Y),
        receiver(Vec3::new(-1.5, 0.5, -0.99), Vec3::Z),
    ];
    let without = lit.irradiance(&receivers);
    let with = lit.irradiance_visible(&receivers, &world.occluders(), 128);
    for ((r, a), b) in receivers.iter().zip(&with).zip(&without) {
        bounds::assert(bounds::at_least(
            format!("at {}: the light without visibility", r.position),
            b[0],
            f64::MIN_POSITIVE,
        ));
        UNBLOCKED.assert(format!("at {}: with visibility against without", r.position), (a[0] - b[0]).abs() / b[0]);
    }
}

#[test]
fn the_visible_bounce_matches_a_ray_per_sender_and_receiver() {
    let scene = box_with_a_block();
    let world = World::new(&scene);
    let lit = world.lit(&lamp(Vec3::new(-0.6, 1.9, 0.9), Vec3::new(0.6, 0.0, -0.6), 70.0, 5.0), 0.05);
    let receivers = [
        receiver(Vec3::new(-0.5, 0.0, 0.5), Vec3::Y),
        receiver(Vec3::new(1.0, 0.7, -0.7), Vec3::NEG_X),
        receiver(Vec3::new(0.3, 1.99, -0.8), Vec3::NEG_Y),
        receiver(Vec3::new(0.35, -0.0, -0.9), Vec3::Y), // behind the block
    ];
    let with = lit.irradiance_visible(&receivers, &world.occluders(), 256);
    // The same sum, a ray per pair (the near field by the point form too: every receiver here
    // is farther than the near radius from most of the light).
    let near = lit.near_radius() * lit.near_radius();
    for (r, e) in receivers.iter().zip(&with) {
        let origin = r.position + r.normal * 1e-3;
        let mut exact = 0.0f64;
        let mut far = 0.0f64;
        for p in lit.patches() {
            let d = r.position - p.patch.centre;
            let d2 = d.length_squared();
            let term = (p.normal.dot(d).max(0.0) * (-r.normal.dot(d)).max(0.0)) as f64 / (d2 * d2) as f64
                * (p.flux.x / std::f32::consts::PI) as f64;
            let end = p.patch.centre + (origin - p.patch.centre).normalize() * gi_reference::SHADOW_OFFSET;
            if d2 > near && world.visible(origin, end) {
                exact += term;
            }
            if d2 > near {
                far += term;
            }
        }
        let rel = (e[0] as f64 - exact).abs() / exact.max(1e-12);
        println!("{}: {:.5} with the cube, {exact:.5} with rays, {far:.5} without visibility", r.position, e[0]);
        bounds::assert(bounds::at_least(format!("at {}: the light by rays", r.position), exact, f64::MIN_POSITIVE));
        RAYS.assert(format!("at {}: the cube against rays", r.position), rel);
    }
}
