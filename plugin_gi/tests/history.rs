//! The GI's temporal history (`gi_temporal`): it follows the world as the view moves, leaves no
//! trail when something moves through the beam, and is gone after a cut.

mod common;

use common::*;
use engine::frame::{Instance, MeshId, ViewState};
use engine::glam::{Mat4, Quat, Vec3};
use engine::primitives;
use plugin_gi::GiSettings;

const SIZE: (u32, u32) = (160, 120);

bounds::tolerance! {
    /// A bright box's trail: its indirect light 4 frames after it stopped, against a render
    /// without history (block error).
    TRAIL: at_most 0.004, measured 0.00204
}
bounds::tolerance! {
    /// After a 12° turn with the lamp set down: the history against a render without it (block
    /// error; the gather's own screen-space error moves as the view turns and the history
    /// averages it).
    TURNED: at_most 0.01, measured 0.00661
}

fn bright_box(mesh: MeshId, x: f32) -> Instance {
    let transform = Mat4::from_translation(Vec3::new(x, 0.2, 0.5));
    Instance { mesh, transform, base_color: [0.95, 0.95, 0.95], emissive: [0.0; 3] }
}

/// `view` rendered from no history: what every frame would be without `gi.history`.
fn fresh(gpu: &engine::gpu::Gpu, r: &mut GiRender, view: &ViewState) -> image::Rgba32FImage {
    r.renderer.reset_history();
    render_linear(gpu, r, view, "indirect", SIZE)
}

#[test]
fn a_bright_box_moved_through_the_beam_leaves_no_trail() {
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), GiSettings::default());
    let (vertices, indices) = primitives::cuboid(Vec3::splat(0.2));
    let mesh = r.renderer.add_mesh(&gpu, &vertices, &indices);
    let mut view = cornell_view(4.0);
    let stop = 0.3;
    let empty = fresh(&gpu, &mut r, &view);
    // Across the beam at 10 cm a frame, then still.
    r.renderer.reset_history();
    for i in 0..=10 {
        view.instances = vec![bright_box(mesh, -0.7 + 0.1 * i as f32)];
        render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    }
    let mut still = Vec::new();
    for _ in 0..4 {
        still.push(render_linear(&gpu, &mut r, &view, "indirect", SIZE));
    }
    assert_eq!(view.instances[0].transform.w_axis.x, stop);
    let without_history = fresh(&gpu, &mut r, &view);
    let trail: Vec<f64> = still.iter().map(|f| block_error(f, &without_history)).collect();
    let the_box = block_error(&empty, &without_history);
    println!("the box changes the indirect light by {:.1} %; frames after it stopped: {trail:.4?}", 100.0 * the_box);
    bounds::assert_all([
        bounds::at_least("the box's change of the indirect light", the_box, 2.0 * TRAIL.limit),
        bounds::at_least("the trail as the box stops (the history in play)", trail[0], 0.005),
        TRAIL.check("the trail 4 frames after the box stopped", trail[3]),
        bounds::at_most("the trail 4 frames after the box stopped", trail[3], trail[0]),
    ]);
}

/// A lamp set down and a camera turning: the light holds still in the world, so the history
/// reprojected to each receiver's world point is last frame's light there, and the result is
/// the fresh render of the last view.
#[test]
fn history_follows_the_world_as_the_camera_turns() {
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), GiSettings::default());
    let start = cornell_view(4.0);
    let mut view = start.clone();
    view.headlamp.detach_looking_at(Vec3::new(0.3, 1.4, 2.5), Vec3::new(-0.2, 0.6, -1.0));
    let mut last = None;
    for i in 0..12 {
        let turn = Quat::from_rotation_y(-(1.0 * i as f32).to_radians());
        view.camera.rotation = (turn * start.camera.rotation).normalize();
        last = Some(render_linear(&gpu, &mut r, &view, "indirect", SIZE));
    }
    let accumulated = last.expect("frames rendered");
    let without_history = fresh(&gpu, &mut r, &view);
    // The gather's own screen-space error moves as the view turns; the history averages it, so
    // the two differ by about that error, far less than light dragged across the view would.
    TURNED.assert("after a 12° turn: history against none", block_error(&accumulated, &without_history));
}

#[test]
fn a_cut_starts_from_no_history_and_a_still_view_holds_exactly() {
    let gpu = gpu();
    let mut r = renderer(&gpu, &cornell_box(), GiSettings::default());
    let view = cornell_view(4.0);
    let first = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
    // A still view's history is this frame's light: nothing drifts.
    for i in 0..3 {
        let again = render_linear(&gpu, &mut r, &view, "indirect", SIZE);
        assert!(again.as_raw() == first.as_raw(), "frame {} of a still view differs from the first", i + 2);
    }
    let mut moved = view.clone();
    moved.camera.position += Vec3::new(0.0, 0.0, -0.05);
    moved.headlamp.on = true;
    render_linear(&gpu, &mut r, &moved, "indirect", SIZE);
    let mut other = renderer(&gpu, &cornell_box(), GiSettings::default());
    let new_renderer = render_linear(&gpu, &mut other, &view, "indirect", SIZE);
    assert!(fresh(&gpu, &mut r, &view).as_raw() == new_renderer.as_raw(), "a reset is a new renderer");
}
