//! Headless frames of the shipped level against golden PNGs (see harness.rs for the metric and
//! `HEADLAMP_UPDATE_GOLDENS=1` to regenerate them).

use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::start_view::{initial_view, ViewOverrides};
use headlamp_tests::{cellar, check_golden, engine};

const SIZE: (u32, u32) = (320, 180);

type Look = Option<(Vec3, Vec3)>;

/// Renders `view` of the cellar from the spawn point or from `look` (eye, target), the headlamp
/// on the camera or, with `lamp` (eye, target), put down there.
fn frame(gpu: &Gpu, level: &engine::scene::Level, look: Look, lamp: Look, view: &str) -> image::RgbaImage {
    let (plugins, _gi) = game::plugins(plugin_gi::GiSettings::default());
    let mut renderer = Renderer::new(gpu, &level.scene, plugins).unwrap();
    renderer.set_view(view).unwrap();
    let mut state = initial_view(level, &ViewOverrides { look, fov_y: None });
    if let Some((eye, target)) = lamp {
        state.headlamp.detach_looking_at(eye, target);
    }
    let target = HeadlessTarget::new(gpu, SIZE.0, SIZE.1, ImageKind::Display);
    match target.render(gpu, &mut renderer, &state).unwrap() {
        RenderedImage::Display(img) => img,
        RenderedImage::Linear(_) => unreachable!("asked for a display image"),
    }
}

#[test]
fn cellar_frames_match_goldens() {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let level = cellar();
    let look = |e: [f32; 3], t: [f32; 3]| Some((Vec3::from(e), Vec3::from(t)));
    let shots = [
        ("cellar_spawn_final", None, None, "final"),
        ("cellar_spawn_normal", None, None, "normal"),
        ("cellar_spawn_depth", None, None, "depth"),
        // Red/green/white room seen from its corridor doorway.
        ("cellar_cornell_final", look([-1.8, 1.6, -7.0], [-6.0, 1.2, -7.0]), None, "final"),
        ("cellar_cornell_albedo", look([-1.8, 1.6, -7.0], [-6.0, 1.2, -7.0]), None, "albedo"),
        // Blue (east) and yellow (south) walls around a crate stack.
        ("cellar_blue_yellow_final", look([2.0, 1.6, -10.0], [6.0, 1.2, -5.0]), None, "final"),
        // The open hall with pillars, crates and the dais.
        ("cellar_hall_final", look([0.0, 1.6, -13.5], [0.0, 1.0, -24.0]), None, "final"),
        // Detached lamp: put down high by the Cornell room's red wall, it throws the short
        // block's shadow across the floor towards the green wall; the camera looks on from the
        // tall block.
        (
            "cellar_cornell_lamp_final",
            look([-4.6, 1.7, -4.3], [-3.8, 0.6, -10.0]),
            look([-2.0, 2.5, -5.0], [-4.5, 0.0, -8.5]),
            "final",
        ),
        // Detached lamp in the hall just behind the south-west pillar: the pillar's shadow runs
        // across the floor and up the west wall.
        (
            "cellar_hall_lamp_final",
            look([-0.5, 2.6, -19.5], [-6.5, 0.6, -15.5]),
            look([-2.4, 1.4, -15.6], [-7.0, 0.4, -18.0]),
            "final",
        ),
    ];
    let mut failures = Vec::new();
    for (name, look, lamp, view) in shots {
        let img = frame(&gpu, &level, look, lamp, view);
        // A black frame must never pass as "matching", even against a black golden.
        let lit = img.pixels().filter(|p| p[0] > 8 || p[1] > 8 || p[2] > 8).count();
        assert!(lit > (SIZE.0 * SIZE.1 / 10) as usize, "{name}: frame is nearly black ({lit} lit pixels)");
        if let Err(e) = check_golden(name, &img) {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
