//! Per-pass GPU timing: one non-negative duration per scheduled pass, in schedule order, when
//! timing is on; nothing at all when it is off.

use std::f32::consts::PI;

use engine::camera::Camera;
use engine::frame::ViewState;
use engine::glam::{Quat, Vec3};
use engine::gpu::Gpu;
use engine::headlamp::Headlamp;
use engine::headless::{HeadlessTarget, ImageKind};
use engine::renderer::Renderer;
use engine::scene::{HeadlampProfile, Material, Mesh, Scene, Vertex};

/// One quad 2 m in front of the camera.
fn tiny_scene() -> Scene {
    let corners = [[-1.0, -1.0, -2.0], [1.0, -1.0, -2.0], [1.0, 1.0, -2.0], [-1.0, 1.0, -2.0]];
    let vertices = corners.iter().map(|&position| Vertex::new(position, [0.0, 0.0, 1.0], [0.0; 2])).collect();
    Scene {
        meshes: vec![Mesh { name: "quad".into(), vertices, indices: vec![0, 1, 2, 0, 2, 3], material: 0 }],
        materials: vec![Material::default()],
        ..Scene::default()
    }
}

fn view() -> ViewState {
    let fov_y = 60.0 * PI / 180.0;
    ViewState {
        camera: Camera::perspective(Vec3::ZERO, Quat::IDENTITY, fov_y),
        headlamp: Headlamp::new(HeadlampProfile { fov_y, ..HeadlampProfile::default() }),
        lights: vec![],
        exposure: 1.0,
        instances: vec![],
        camera_flash: [0.0; 3],
        view_models: vec![],
    }
}

fn scheduled(renderer: &Renderer) -> Vec<String> {
    let compiled = renderer.graph().compiled().expect("compiled by the frame");
    compiled.order_names().into_iter().map(str::to_owned).collect()
}

#[test]
fn timing_on_gives_one_duration_per_scheduled_pass_and_off_gives_none() {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let mut renderer = Renderer::new(&gpu, &tiny_scene(), vec![]).unwrap();
    let target = HeadlessTarget::new(&gpu, 32, 24, ImageKind::Display);
    let view = view();

    // Off (the default): nothing is recorded.
    target.render(&gpu, &mut renderer, &view).unwrap();
    assert!(renderer.last_pass_times(&gpu).is_none(), "timing is off by default");

    renderer.set_timing(true);
    for shown in ["final", "direct"] {
        renderer.set_view(shown).unwrap();
        target.render(&gpu, &mut renderer, &view).unwrap();
        let times = renderer.last_pass_times(&gpu);
        if !gpu.timestamps {
            assert!(times.is_none(), "no timings without timestamp support");
            // Documented behaviour on such adapters: timing reports nothing.
            println!("{} cannot write timestamps inside encoders: timing reports none", gpu.adapter_name());
            return;
        }
        let times = times.expect("timing is on and supported");
        let names: Vec<String> = times.iter().map(|(n, _)| n.clone()).collect();
        assert_eq!(names, scheduled(&renderer), "view {shown}: one entry per scheduled pass, in order");
        for (name, ms) in &times {
            assert!(ms.is_finite() && *ms >= 0.0, "view {shown}: pass {name} took {ms} ms");
        }
        println!("view {shown}: {times:?}");
    }
    // The `direct` view needs neither the composite nor anything after direct_light but present
    // (the lamp view stays: direct light reads its shadow map).
    assert_eq!(scheduled(&renderer), ["gbuffer", "lamp_view", "direct_light", "present"]);

    renderer.set_timing(false);
    target.render(&gpu, &mut renderer, &view).unwrap();
    assert!(renderer.last_pass_times(&gpu).is_none(), "timing switched off forgets the timings");
}
