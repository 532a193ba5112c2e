//! Headless frames of the shipped levels against golden PNGs (see harness.rs for the metric and
//! `HEADLAMP_UPDATE_GOLDENS=1` to regenerate them).

use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::start_view::{initial_view, ViewOverrides};
use headlamp_tests::{check_golden, engine, load_level};

const SIZE: (u32, u32) = (320, 180);

type Look = Option<(Vec3, Vec3)>;

/// A golden's name, where the camera is (None: the spawn), where the lamp is put down (None: on
/// the camera) and the view.
type Shot = (&'static str, Look, Look, &'static str);

fn look(eye: [f32; 3], target: [f32; 3]) -> Look {
    Some((Vec3::from(eye), Vec3::from(target)))
}

/// Renders `view` of a level from the spawn point or from `look` (eye, target), the headlamp
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

/// Renders each shot of the shipped level `id` and compares it with its golden.
fn check_frames(id: &str, shots: &[Shot]) {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("{e}"));
    let level = load_level(id);
    let mut failures = Vec::new();
    for &(name, look, lamp, view) in shots {
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

#[test]
fn cellar_frames_match_goldens() {
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
    check_frames("cellar", &shots);
}

#[test]
fn gallery_frames_match_goldens() {
    let shots = [
        ("gallery_spawn_final", None, None, "final"),
        // The white atrium: the red cube on its plinth under its spotlight, the red and green
        // rooms' doors beyond.
        ("gallery_atrium_final", look([3.5, 1.6, -1.5], [-1.0, 0.9, -8.0]), None, "final"),
        // The red room's corner: the lamp on the red wall, its colour on the white wall, floor
        // and ceiling beside it, the white monolith; the yellow room through the door.
        ("gallery_red_final", look([-6.5, 1.7, -4.6], [-12.4, 1.0, -9.0]), None, "final"),
        // The green room's tiles and floor tiles: the textures, unlit.
        ("gallery_green_albedo", look([3.8, 1.6, -13.6], [-1.5, 1.2, -20.8]), None, "albedo"),
        // Detached lamp: put down in the blue room facing its blue wall, the camera looking on
        // from the door, the white monolith between.
        (
            "gallery_blue_lamp_final",
            look([5.8, 1.7, -6.4], [12.4, 1.2, -6.4]),
            look([8.0, 0.4, -4.0], [12.4, 1.5, -8.0]),
            "final",
        ),
    ];
    check_frames("gallery", &shots);
}

#[test]
fn hall_frames_match_goldens() {
    let shots = [
        // The nave from the porch door: pillars, balconies, the lamps' pools, the blue wall.
        ("hall_nave_final", look([0.0, 1.7, -5.0], [0.0, 3.0, -38.0]), None, "final"),
        // The stairs up the west wall to the balcony, its pillars and banners.
        ("hall_stairs_final", look([2.5, 1.7, -6.5], [-9.0, 3.2, -18.0]), None, "final"),
        // The blue wall, the north balcony over the crypt door.
        ("hall_blue_final", look([3.0, 1.7, -28.0], [-2.0, 3.5, -38.0]), None, "final"),
        // From the west balcony over the nave: the east balcony and its ramp.
        ("hall_balcony_final", look([-8.7, 5.35, -17.0], [6.0, 1.5, -10.0]), None, "final"),
    ];
    check_frames("hall", &shots);
}
