//! The GI as the camera turns: its receivers and senders move with the picture, so turning by
//! a fraction of a receiver's cell moves the indirect light with the picture instead of
//! resampling it. (Grids fixed to the screen would give every pixel of a pan its light from
//! other points of the walls each frame.)

mod common;

use common::*;
use engine::camera::Camera;
use engine::glam::Vec3;
use plugin_gi::GiSettings;

/// Receivers of 8×8 pixels (45 rows, the CPU settings) and blocks of 8×8 lamp texels.
const SIZE: (u32, u32) = (640, 360);
const ROWS: u32 = 45;
const CELL: i64 = 8;
/// The window compared: the middle of the view, where turning moves the picture nearly evenly
/// (at its sides 6 % faster than at the centre), and which holds the block and the folds.
const HALF: i64 = 96;

bounds::tolerance! {
    /// Turned by half a receiver's cell: the indirect light against the picture moved with the
    /// turn (relative L2; with the grids fixed to the screen, 5.9 %).
    MOVED: at_most 0.04, measured 0.037
}

/// The camera of `cornell_view` turned left by `pixels` at the centre of a `SIZE` frame.
fn turned(pixels: f32) -> engine::view_state::ViewState {
    let mut v = cornell_view(4.0);
    let pixels_per_radian = SIZE.1 as f32 * 0.5 / (FOV_Y * 0.5).tan();
    v.camera = Camera::from_yaw_pitch(Vec3::new(0.0, 1.0, 3.4), pixels / pixels_per_radian, 0.0, FOV_Y);
    v
}

/// Relative L2 difference between `b` and `a` moved right by `shift` pixels, over the window.
fn moved_difference(a: &image::Rgba32FImage, b: &image::Rgba32FImage, shift: i64) -> f64 {
    let (cx, cy) = (i64::from(SIZE.0) / 2, i64::from(SIZE.1) / 2);
    let (mut diff, mut norm) = (0.0, 0.0);
    for y in cy - HALF..cy + HALF {
        for x in cx - HALF..cx + HALF {
            let (p, q) = (a.get_pixel(x as u32, y as u32), b.get_pixel((x + shift) as u32, y as u32));
            for c in 0..3 {
                diff += f64::from(q[c] - p[c]).powi(2);
                norm += f64::from(p[c]).powi(2);
            }
        }
    }
    (diff / norm).sqrt()
}

#[test]
fn turning_half_a_cell_moves_the_indirect_light_with_the_picture() {
    let gpu = gpu();
    // The gather's own answer each frame: no history to carry anything over.
    let settings = GiSettings { history: 0.0, min_rows: ROWS, ..GiSettings::default() };
    let mut r = renderer(&gpu, &cornell_box(), settings);
    let still = render_linear(&gpu, &mut r, &turned(0.0), "indirect", SIZE);
    let half = render_linear(&gpu, &mut r, &turned(CELL as f32 / 2.0), "indirect", SIZE);
    let moved = moved_difference(&still, &half, CELL / 2);
    // Against the light not moved: how much that much turning changes the picture.
    let unmoved = moved_difference(&still, &half, 0);
    println!(
        "turned by half a cell: {:.2} % from the picture moved, {:.2} % from it not moved",
        100.0 * moved,
        100.0 * unmoved
    );
    // Most of what is left is where the sides of the window move a quarter of a pixel more than
    // its centre.
    bounds::assert_all([
        MOVED.check("turned half a cell: against the picture moved", moved),
        bounds::at_least("the change not moved over the change moved (the test turns enough)", unmoved / moved, 3.0),
    ]);
}
