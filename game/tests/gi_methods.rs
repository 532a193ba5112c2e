//! Both ways of gathering the first bounce (`gi.method`: cuts, and the article's distribution
//! table and light volumes) against the world-fixed reference (CPU, 2 cm patches, no cutoff,
//! no clamp), on the two Cornell views and three Cellar views (lavapipe): the relative L2 of
//! 8×8 block means and the energy (Σ GI / Σ reference − 1). Without `gi.visibility`, as the
//! reference has none (`gi_visibility.rs` holds the cuts with it).
//!
//! The goals: the cuts at their defaults, and the article's method at its accurate settings
//! (`accurate_article`), within 5 % and 3 % of energy; the article's method at its defaults
//! within 10 % and 3 %.

mod common;

use bounds::Tolerance;
use common::cornell::{cornell_box, view, FOV_Y};
use common::settled::settled_indirect;
use engine::frame::ViewState;
use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::scene::Scene;
use engine::start_view::{initial_view, ViewOverrides};
use game::world_reference::WorldReference;
use gi_reference::DEFAULT_MAX_EDGE;
use plugin_gi::metrics::{block_error, energy};
use plugin_gi::{GiSettings, GiStats, Method};

/// The frames the GI renders, and the reference's receivers: a quarter each way.
const FRAME: (u32, u32) = (640, 360);
const REFERENCE: (u32, u32) = (160, 90);

fn cuts() -> GiSettings {
    GiSettings { visibility: 0, ..GiSettings::default() }
}

fn article() -> GiSettings {
    GiSettings { method: Method::Article, ..cuts() }
}

/// The article's method as exact as it goes: every receiver shades every light (no
/// interleaving) and the largest light budget.
fn accurate_article() -> GiSettings {
    GiSettings { article_interleave: 1, light_budget: 4096, ..article() }
}

bounds::tolerance! {
    /// The cuts against the world reference, two box and three Cellar views: block error (the
    /// goal: 5 %).
    CUTS_ERROR: at_most 0.05, measured 0.0464
}
bounds::tolerance! {
    /// The cuts against the world reference, two box and three Cellar views: energy (the goal: 3 %).
    CUTS_ENERGY: magnitude 0.03, measured 0.0264
}
bounds::tolerance! {
    /// The article's method at its defaults: block error (the goal: 10 %).
    ARTICLE_ERROR: at_most 0.1, measured 0.0919
}
bounds::tolerance! {
    /// The article's method at its defaults: energy (the goal: 3 %).
    ARTICLE_ENERGY: magnitude 0.03, measured 0.0169
}
bounds::tolerance! {
    /// The article's method at its accurate settings: block error (the goal: 5 %).
    ACCURATE_ERROR: at_most 0.05, measured 0.0411
}
bounds::tolerance! {
    /// The article's method at its accurate settings: energy (the goal: 3 %).
    ACCURATE_ENERGY: magnitude 0.03, measured 0.017
}

/// Each setting measured, and its tolerances (block error, energy).
fn measured() -> [(&'static str, GiSettings, (Tolerance, Tolerance)); 3] {
    [
        ("cuts", cuts(), (CUTS_ERROR, CUTS_ENERGY)),
        ("article, defaults", article(), (ARTICLE_ERROR, ARTICLE_ENERGY)),
        ("article, accurate", accurate_article(), (ACCURATE_ERROR, ACCURATE_ENERGY)),
    ]
}

/// The GI's indirect light, shrunk to the reference's receivers, and its calls.
fn indirect(gpu: &Gpu, scene: &Scene, view: &ViewState, settings: GiSettings) -> (image::Rgba32FImage, GiStats) {
    settled_indirect(gpu, scene, view, settings, FRAME, FRAME.0 / REFERENCE.0)
}

/// Measures every setting on each view against its tolerances.
fn check(gpu: &Gpu, scene: &Scene, views: &[(&str, ViewState)]) -> Vec<Result<(), String>> {
    let mut checks = Vec::new();
    for (name, v) in views {
        let mut reference = WorldReference::new(gpu, scene).unwrap();
        let exact = reference.render(gpu, v, REFERENCE, DEFAULT_MAX_EDGE).unwrap().image;
        for (label, settings, (error_tolerance, energy_tolerance)) in measured() {
            let (gi, calls) = indirect(gpu, scene, v, settings);
            let (error, gain) = (block_error(&gi, &exact), energy(&gi, &exact));
            println!("{name}, {label}: {} dispatches and {} draws", calls.dispatches, calls.draws);
            checks.push(error_tolerance.check(format!("{name}, {label}: block error"), error));
            checks.push(energy_tolerance.check(format!("{name}, {label}: energy"), gain));
        }
    }
    checks
}

#[test]
fn in_the_box_both_methods_come_within_their_goals_of_the_world_reference() {
    let gpu = Gpu::lavapipe().unwrap();
    let views = [
        ("face-on", view(Vec3::new(0.0, 1.0, 3.4), Vec3::new(0.0, 1.0, 0.0))),
        ("into the corner", {
            let mut v = view(Vec3::new(0.0, 1.0, 3.4), Vec3::ZERO);
            v.camera = engine::camera::Camera::look_at(Vec3::new(0.5, 1.3, 0.9), Vec3::new(-1.0, 0.4, -1.0), FOV_Y);
            v
        }),
    ];
    bounds::assert_all(check(&gpu, &cornell_box(), &views));
}

#[test]
fn in_three_cellar_views_both_methods_come_within_their_goals_of_the_world_reference() {
    let gpu = Gpu::lavapipe().unwrap();
    let level = engine::scene::load_level(&game::default_level()).unwrap();
    let views: Vec<(&str, ViewState)> = [
        ("red/green room", [-1.8, 1.6, -7.0], [-6.0, 1.2, -7.0]),
        ("blue/yellow room", [2.0, 1.6, -10.0], [6.0, 1.2, -5.0]),
        ("hall", [0.0, 1.6, -13.5], [0.0, 1.0, -24.0]),
    ]
    .into_iter()
    .map(|(name, eye, target)| {
        let look = Some((Vec3::from(eye), Vec3::from(target)));
        (name, initial_view(&level, &ViewOverrides { look, fov_y: None }))
    })
    .collect();
    bounds::assert_all(check(&gpu, &level.scene, &views));
}
