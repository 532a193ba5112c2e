//! The GI on a surface narrower than a receiver's cell, as a pan slides it across the cells: the
//! Cellar's doorway at 45 rows (a receiver for 8×8 pixels, the CPU settings' fallback), whose
//! jamb is a strip a few pixels wide. Its pixels are lit as the world-fixed reference says in
//! every frame. (A receiver evaluated on its cell's centre only would give the jamb one in the
//! frames where a centre fell on it and the wall's light in the others.)

mod common;

use engine::glam::Quat;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::start_view::{initial_view, ViewOverrides};
use game::world_reference::WorldReference;
use gi_reference::DEFAULT_MAX_EDGE;

const SIZE: (u32, u32) = (640, 360);
/// Rows of the doorway's left jamb that are compared (below the lintel, above the floor).
const ROWS: std::ops::Range<u32> = 160..280;
/// Columns the left jamb stays within over the pan.
const COLUMNS: std::ops::Range<u32> = 220..320;
/// The back face of the wall the door is in (its front is at z = 0): the jamb lies between.
const WALL_BACK: f32 = -0.4;

bounds::tolerance! {
    /// The doorway's jamb, narrower than a receiver's cell, as a pan slides it across the
    /// cells: its light against the world reference's, relative, the worst frame (with
    /// receivers on their cells' centres: −45 to −51 % in the frames where none fell on it).
    JAMB: at_most 0.25, measured 0.147
}

#[test]
fn a_jamb_narrower_than_a_receiver_keeps_its_light_as_the_view_slides() {
    let gpu = Gpu::lavapipe().unwrap();
    let level = engine::scene::load_level(std::path::Path::new(&common::cellar())).expect("the shipped level");
    // 8×8-pixel receivers, and the gather's own answer each frame: no history to average the frames.
    let settings = plugin_gi::GiSettings { history: 0.0, min_rows: 45, ..plugin_gi::GiSettings::default() };
    let (plugins, _) = game::plugins(settings);
    let mut renderer = Renderer::new(&gpu, &level.scene, plugins).unwrap();
    renderer.set_view("indirect").unwrap();
    let mut reference = WorldReference::new(&gpu, &level.scene).unwrap();
    let target = HeadlessTarget::new(&gpu, SIZE.0, SIZE.1, ImageKind::Linear);
    let start = initial_view(&level, &ViewOverrides::default());
    let (mut errors, mut jamb_pixels) = (Vec::new(), Vec::new());
    // A quarter of a degree a frame: the jamb moves about two pixels, across two cells in all.
    for step in 0..8 {
        let mut v = start.clone();
        let turn = Quat::from_rotation_y(-(0.25 * step as f32).to_radians());
        v.camera.rotation = (turn * start.camera.rotation).normalize();
        let indirect = match target.render(&gpu, &mut renderer, &v).unwrap() {
            RenderedImage::Linear(img) => img,
            RenderedImage::Display(_) => unreachable!(),
        };
        let receivers = reference.receivers(&gpu, &v, SIZE).unwrap();
        // The jamb: the pixels facing +x (into the doorway) within the wall's thickness (the
        // corridor's wall beyond, which faces +x too, starts past it).
        let mask: Vec<bool> = (0..SIZE.0 * SIZE.1)
            .map(|i| {
                let (x, y, r) = (i % SIZE.0, i / SIZE.0, &receivers[i as usize]);
                ROWS.contains(&y) && COLUMNS.contains(&x) && r.normal.x > 0.9 && r.position.z > WALL_BACK
            })
            .collect();
        jamb_pixels.push(mask.iter().filter(|&&m| m).count() as f64);
        let exact = reference.evaluate(&v, SIZE, &receivers, Some(&mask), DEFAULT_MAX_EDGE);
        let error = common::masked_sum(&indirect, &mask) / common::masked_sum(&exact.image, &mask) - 1.0;
        println!("turned {:.2}°: the jamb {:+.1} % off the reference", 0.25 * step as f32, 100.0 * error);
        errors.push(error.abs());
    }
    // Not vacuous: the jamb is there in every frame, a strip narrower than a cell (at most 6
    // pixels wide).
    let rows = ROWS.len() as f64;
    bounds::assert_all([
        bounds::at_least(
            "the jamb's pixels in the frame with fewest",
            bounds::least(jamb_pixels.iter().copied()),
            rows,
        ),
        bounds::at_most("the jamb's pixels in the frame with most", bounds::worst(jamb_pixels), 6.0 * rows),
        JAMB.check("on the jamb, the worst frame", bounds::worst(errors)),
    ]);
}
