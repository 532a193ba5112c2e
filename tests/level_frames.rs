//! Headless frames of the shipped level against golden PNGs (see harness.rs for the metric and
//! `HEADLAMP_UPDATE_GOLDENS=1` to regenerate them).

use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::start_view::{initial_view, ViewOverrides};
use headlamp_tests::{check_golden, engine};

const SIZE: (u32, u32) = (320, 180);

fn cellar() -> engine::scene::Level {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../levels/cellar");
    engine::scene::load_level(std::path::Path::new(path)).unwrap_or_else(|e| panic!("{e}"))
}

/// Renders `view` of the cellar from the spawn point or from `look` (eye, target).
fn frame(gpu: &Gpu, level: &engine::scene::Level, look: Option<(Vec3, Vec3)>, view: &str) -> image::RgbaImage {
    let (plugins, _gi) = game::plugins(plugin_gi::GiSettings::default());
    let mut renderer = Renderer::new(gpu, &level.scene, plugins).unwrap();
    renderer.set_view(view).unwrap();
    let state = initial_view(level, &ViewOverrides { look, fov_y: None });
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
        ("cellar_spawn_final", None, "final"),
        ("cellar_spawn_normal", None, "normal"),
        ("cellar_spawn_depth", None, "depth"),
        // Red/green/white room seen from its corridor doorway.
        ("cellar_cornell_final", look([-1.8, 1.6, -7.0], [-6.0, 1.2, -7.0]), "final"),
        ("cellar_cornell_albedo", look([-1.8, 1.6, -7.0], [-6.0, 1.2, -7.0]), "albedo"),
        // Blue (east) and yellow (south) walls around a crate stack.
        ("cellar_blue_yellow_final", look([2.0, 1.6, -10.0], [6.0, 1.2, -5.0]), "final"),
        // The open hall with pillars, crates and the dais.
        ("cellar_hall_final", look([0.0, 1.6, -13.5], [0.0, 1.0, -24.0]), "final"),
    ];
    let mut failures = Vec::new();
    for (name, look, view) in shots {
        let img = frame(&gpu, &level, look, view);
        // A black frame must never pass as "matching", even against a black golden.
        let lit = img.pixels().filter(|p| p[0] > 8 || p[1] > 8 || p[2] > 8).count();
        assert!(lit > (SIZE.0 * SIZE.1 / 10) as usize, "{name}: frame is nearly black ({lit} lit pixels)");
        if let Err(e) = check_golden(name, &img) {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
