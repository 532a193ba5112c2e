//! Scenes and lamps the engine's rendering tests share.
// Each test file uses some of these.
#![allow(dead_code)]

use engine::glam::Vec3;
use engine::headlamp::Headlamp;
use engine::scene::{HeadlampProfile, IntensityDistribution, Material, Mesh, Scene, Vertex};

/// A 20 m square plane through `centre` with normal `normal`, of `material`.
pub fn plane(centre: Vec3, normal: Vec3, material: Material) -> Scene {
    let n = normal.normalize();
    let u = n.cross(if n.y.abs() > 0.9 { Vec3::X } else { Vec3::Y }).normalize() * 10.0;
    let v = n.cross(u);
    let corners = [centre - u - v, centre + u - v, centre + u + v, centre - u + v];
    let vertices = corners.iter().map(|p| Vertex::new(p.to_array(), n.to_array(), [0.0; 2])).collect();
    Scene {
        meshes: vec![Mesh { name: "plane".into(), vertices, indices: vec![0, 1, 2, 0, 2, 3], material: 0 }],
        materials: vec![material],
        ..Scene::default()
    }
}

/// A grey Lambertian material of albedo `rho`.
pub fn grey(rho: f32) -> Material {
    Material { base_color: [rho, rho, rho, 1.0], ..Material::default() }
}

/// A 20 m grey wall of albedo `rho` facing +Z at z = `z`.
pub fn wall(z: f32, rho: f32) -> Scene {
    plane(Vec3::new(0.0, 0.0, z), Vec3::Z, grey(rho))
}

/// A white headlamp of `power` W/sr, lighting its whole `fov_y` frustum evenly.
pub fn uniform_lamp(power: f32, fov_y: f32) -> Headlamp {
    Headlamp::new(HeadlampProfile { power, fov_y, color: [1.0; 3], distribution: IntensityDistribution::Uniform })
}
