//! The GI where two walls meet, as a pan slides the fold across its receivers: the receivers
//! next to the fold are lit as the world-fixed reference says in every frame. (A receiver on
//! the fold's pixel itself would go a third dark for that frame: its light comes half from the
//! wall across the fold, most of it from within a few pixels of the corner, finer than the
//! senders there; receivers are moved off it.)

mod common;

use common::cornell::{cornell_box, view};
use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use game::world_reference::WorldReference;
use gi_reference::DEFAULT_MAX_EDGE;

/// The size people play the box at, where a sender block is 4 pixels and a receiver 5⅓.
const SIZE: (u32, u32) = (640, 480);
/// Rows of the right wall's fold with the back wall that are compared (its middle).
const ROWS: std::ops::Range<u32> = 180..300;
/// Pixels of the right wall next to the fold that are compared: those whose light comes from
/// the receiver nearest the fold.
const STRIP: u32 = 4;

bounds::tolerance! {
    /// The 4 pixels next to the box's fold, as a pan slides it across the receivers: the light
    /// against the world reference's, relative, the worst frame (37 % with receivers left on
    /// the fold's pixel).
    NEXT_TO_THE_FOLD: at_most 0.2, measured 0.193
}

#[test]
fn the_light_next_to_a_fold_holds_as_the_fold_slides_across_the_receivers() {
    let gpu = Gpu::lavapipe().unwrap();
    let scene = cornell_box();
    // The gather's own answer each frame: no history to average the frames.
    let settings = plugin_gi::GiSettings { history: 0.0, ..plugin_gi::GiSettings::default() };
    let (plugins, _) = game::plugins(settings);
    let mut renderer = Renderer::new(&gpu, &scene, plugins).unwrap();
    renderer.set_view("indirect").unwrap();
    let mut reference = WorldReference::new(&gpu, &scene).unwrap();
    let target = HeadlessTarget::new(&gpu, SIZE.0, SIZE.1, ImageKind::Linear);
    let eye = Vec3::new(0.0, 1.0, 3.4);
    let mut errors = Vec::new();
    // Turning right a tenth of a degree at a time: the fold moves about a pixel a frame, across
    // two receivers' spacing.
    for step in 0..10 {
        let yaw = (1.5 + 0.1 * step as f32).to_radians();
        let v = view(eye, eye + Vec3::new(yaw.sin(), 0.0, -yaw.cos()));
        let indirect = match target.render(&gpu, &mut renderer, &v).unwrap() {
            RenderedImage::Linear(img) => img,
            RenderedImage::Display(_) => unreachable!(),
        };
        let receivers = reference.receivers(&gpu, &v, SIZE).unwrap();
        // The fold: per row, the first pixel of the right (green, normal −x) wall.
        let first_green = |y: u32| {
            let green = |x: u32| receivers[(y * SIZE.0 + x) as usize].normal.x < -0.9;
            (SIZE.0 / 2..SIZE.0).find(|&x| green(x)).expect("the right wall")
        };
        let mask: Vec<bool> = (0..SIZE.0 * SIZE.1)
            .map(|i| {
                let (x, y) = (i % SIZE.0, i / SIZE.0);
                ROWS.contains(&y) && (first_green(y)..first_green(y) + STRIP).contains(&x)
            })
            .collect();
        let exact = reference.evaluate(&v, SIZE, &receivers, Some(&mask), DEFAULT_MAX_EDGE);
        let error = common::masked_sum(&indirect, &mask) / common::masked_sum(&exact.image, &mask) - 1.0;
        println!(
            "turned {:.1}°: the {STRIP} pixels next to the fold {:+.1} % off the reference",
            yaw.to_degrees(),
            100.0 * error
        );
        errors.push(error.abs());
    }
    NEXT_TO_THE_FOLD.assert("next to the fold, the worst frame", bounds::worst(errors));
}
