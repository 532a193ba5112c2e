//! The Cornell-like box the GI tests render, built in code.

use engine::camera::Camera;
use engine::frame::ViewState;
use engine::glam::Vec3;
use engine::headlamp::Headlamp;
use engine::scene::{HeadlampProfile, IntensityDistribution, Material, Mesh, Scene, Vertex};

pub const FOV_Y: f32 = 50.0 * std::f32::consts::PI / 180.0;

/// Appends a quad (corners counter-clockwise seen from the side its normal points to).
pub fn quad(scene: &mut Scene, corners: [Vec3; 4], material: usize) {
    let n = (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalize();
    let vertices = corners.iter().map(|p| Vertex::new(p.to_array(), n.to_array(), [0.0; 2])).collect();
    let name = format!("quad{}", scene.meshes.len());
    scene.meshes.push(Mesh { name, vertices, indices: vec![0, 1, 2, 0, 2, 3], material });
}

/// A Cornell-like box open towards +Z (x ∈ [-1, 1], y ∈ [0, 2], z ∈ [-1, 1]): red left wall,
/// green right wall, white floor, ceiling and back wall, a white block on the floor.
pub fn cornell_box() -> Scene {
    let material = |rgb: [f32; 3]| Material { base_color: [rgb[0], rgb[1], rgb[2], 1.0], ..Material::default() };
    let mut s = Scene {
        materials: vec![material([0.75, 0.75, 0.75]), material([0.75, 0.1, 0.1]), material([0.1, 0.7, 0.1])],
        ..Scene::default()
    };
    let v = Vec3::new;
    quad(&mut s, [v(-1.0, 0.0, 1.0), v(1.0, 0.0, 1.0), v(1.0, 0.0, -1.0), v(-1.0, 0.0, -1.0)], 0);
    quad(&mut s, [v(-1.0, 2.0, -1.0), v(1.0, 2.0, -1.0), v(1.0, 2.0, 1.0), v(-1.0, 2.0, 1.0)], 0);
    quad(&mut s, [v(-1.0, 0.0, -1.0), v(1.0, 0.0, -1.0), v(1.0, 2.0, -1.0), v(-1.0, 2.0, -1.0)], 0);
    quad(&mut s, [v(-1.0, 0.0, 1.0), v(-1.0, 0.0, -1.0), v(-1.0, 2.0, -1.0), v(-1.0, 2.0, 1.0)], 1);
    quad(&mut s, [v(1.0, 0.0, -1.0), v(1.0, 0.0, 1.0), v(1.0, 2.0, 1.0), v(1.0, 2.0, -1.0)], 2);
    let (x0, x1, z0, z1, h) = (0.1, 0.6, -0.5, 0.0, 0.6);
    quad(&mut s, [v(x0, 0.0, z1), v(x1, 0.0, z1), v(x1, h, z1), v(x0, h, z1)], 0);
    quad(&mut s, [v(x0, 0.0, z0), v(x0, 0.0, z1), v(x0, h, z1), v(x0, h, z0)], 0);
    quad(&mut s, [v(x0, h, z1), v(x1, h, z1), v(x1, h, z0), v(x0, h, z0)], 0);
    s
}

/// A uniform 10 W/sr lamp on a camera looking into the box, from `eye` at `target`.
pub fn view(eye: Vec3, target: Vec3) -> ViewState {
    let profile =
        HeadlampProfile { power: 10.0, fov_y: FOV_Y, color: [1.0; 3], distribution: IntensityDistribution::Uniform };
    ViewState { camera: Camera::look_at(eye, target, FOV_Y), headlamp: Headlamp::new(profile), ..ViewState::default() }
}

/// The Cornell-like box with a tall block instead of the low one: 0.5 × 0.5 m, 1.2 m high, five
/// faces, standing left of the middle, so it hides parts of the walls and floor from each other.
pub fn tall_block_box() -> Scene {
    let mut s = cornell_box();
    s.meshes.truncate(5);
    let v = Vec3::new;
    let (x0, x1, z0, z1, h) = (-0.55, -0.05, -0.6, -0.1, 1.2);
    quad(&mut s, [v(x0, 0.0, z1), v(x1, 0.0, z1), v(x1, h, z1), v(x0, h, z1)], 0);
    quad(&mut s, [v(x1, 0.0, z0), v(x0, 0.0, z0), v(x0, h, z0), v(x1, h, z0)], 0);
    quad(&mut s, [v(x0, 0.0, z0), v(x0, 0.0, z1), v(x0, h, z1), v(x0, h, z0)], 0);
    quad(&mut s, [v(x1, 0.0, z1), v(x1, 0.0, z0), v(x1, h, z0), v(x1, h, z1)], 0);
    quad(&mut s, [v(x0, h, z1), v(x1, h, z1), v(x1, h, z0), v(x0, h, z0)], 0);
    s
}

/// The Cornell-like box with both blocks, its low one and `tall_block_box`'s tall one beside it:
/// the classic two-block scene, each block hiding parts of the other and of the walls.
pub fn two_block_box() -> Scene {
    let mut s = cornell_box();
    s.meshes.extend(tall_block_box().meshes.split_off(5));
    s
}

/// Half the thickness of the wall between `two_rooms_with_a_thin_wall`'s rooms: 10 cm in all.
pub const THIN_WALL_HALF: f32 = 0.05;

/// Two closed rooms side by side, 4 m wide each (x ∈ [-4.05, -0.05] and [0.05, 4.05]), 6 m
/// deep (z ∈ [-3, 3]), 2.5 m high, white, with one floor and one ceiling, between them a wall
/// 10 cm thick from floor to ceiling and wall to wall: nothing of one room sees the other.
pub fn two_rooms_with_a_thin_wall() -> Scene {
    let material = Material { base_color: [0.75, 0.75, 0.75, 1.0], ..Material::default() };
    let mut s = Scene { materials: vec![material], ..Scene::default() };
    let v = Vec3::new;
    let (w, x, z, h) = (THIN_WALL_HALF, 4.0 + THIN_WALL_HALF, 3.0, 2.5);
    // Floor and ceiling, facing in.
    quad(&mut s, [v(-x, 0.0, z), v(x, 0.0, z), v(x, 0.0, -z), v(-x, 0.0, -z)], 0);
    quad(&mut s, [v(-x, h, -z), v(x, h, -z), v(x, h, z), v(-x, h, z)], 0);
    // The outer walls, facing in: back, front, left, right.
    quad(&mut s, [v(-x, 0.0, -z), v(x, 0.0, -z), v(x, h, -z), v(-x, h, -z)], 0);
    quad(&mut s, [v(x, 0.0, z), v(-x, 0.0, z), v(-x, h, z), v(x, h, z)], 0);
    quad(&mut s, [v(-x, 0.0, z), v(-x, 0.0, -z), v(-x, h, -z), v(-x, h, z)], 0);
    quad(&mut s, [v(x, 0.0, -z), v(x, 0.0, z), v(x, h, z), v(x, h, -z)], 0);
    // The thin wall's two faces, each facing its room.
    quad(&mut s, [v(-w, 0.0, -z), v(-w, 0.0, z), v(-w, h, z), v(-w, h, -z)], 0);
    quad(&mut s, [v(w, 0.0, z), v(w, 0.0, -z), v(w, h, -z), v(w, h, z)], 0);
    s
}
