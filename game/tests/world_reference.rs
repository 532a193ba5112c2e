//! The world-fixed reference on the GPU's receivers (lavapipe): its pixels are where the
//! G-buffer says, it integrates the same bounce as the GPU's lamp-texel reference
//! (`reference_screen`), and it has converged at its 2 cm patches; its visibility test agrees
//! with exact rays in the Cellar.

mod common;

use common::cornell::{cornell_box, view};
use engine::frame::ViewState;
use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::start_view::{initial_view, ViewOverrides};
use game::world_reference::{WorldReference, VISIBILITY_CUBE};
use gi_reference::{Lamp, VisibilityCube, World, DEFAULT_MAX_EDGE, SHADOW_OFFSET};
use plugin_gi::metrics::block_error;

const SIZE: (u32, u32) = (160, 120);

fn render_linear(gpu: &Gpu, renderer: &mut Renderer, view: &ViewState, name: &str) -> image::Rgba32FImage {
    renderer.set_view(name).unwrap();
    match HeadlessTarget::new(gpu, SIZE.0, SIZE.1, ImageKind::Linear).render(gpu, renderer, view).unwrap() {
        RenderedImage::Linear(img) => img,
        RenderedImage::Display(_) => unreachable!(),
    }
}

bounds::tolerance! {
    /// A receiver on the box's back wall or floor: its distance from that plane, metres.
    ON_THE_PLANE: at_most 1e-6, measured 5.96e-7
}
bounds::tolerance! {
    /// The world-fixed reference against `reference_screen`, two box views: block error.
    SCREEN_ERROR: at_most 0.03, measured 0.0194
}
bounds::tolerance! {
    /// The world-fixed reference against `reference_screen`, two box views: energy.
    SCREEN_ENERGY: magnitude 0.012, measured 0.00718
}
bounds::tolerance! {
    /// The world-fixed reference's 2 cm patches against 1 cm ones: block error.
    CONVERGED: at_most 0.002, measured 0.00133
}
bounds::tolerance! {
    /// The visibility cube against parry's rays in the Cellar: the share of the transfer they
    /// disagree on (grazing pairs within f32 rounding).
    CUBE_AGAINST_RAYS: at_most 2.5e-8, measured 1.34e-8
}

fn sum(img: &image::Rgba32FImage) -> f64 {
    img.pixels().map(|p| p[0] as f64 + p[1] as f64 + p[2] as f64).sum()
}

#[test]
fn receivers_lie_where_the_gbuffer_sees_the_walls() {
    let gpu = Gpu::lavapipe().unwrap();
    let scene = cornell_box();
    let mut reference = WorldReference::new(&gpu, &scene).unwrap();
    let v = view(Vec3::new(0.3, 1.2, 3.4), Vec3::new(-0.2, 0.8, 0.0));
    let receivers = reference.receivers(&gpu, &v, SIZE).unwrap();
    let (mut back, mut floor) = (Vec::new(), Vec::new());
    let surfaces: Vec<_> = receivers.iter().filter(|r| r.normal != Vec3::ZERO).collect();
    for r in &surfaces {
        // Every surface point is on one of the box's planes, facing into it.
        let (on_back, on_floor) = (r.normal.z > 0.99 && r.position.z < -0.9, r.normal.y > 0.99 && r.position.y < 0.1);
        if on_back {
            back.push(f64::from((r.position.z + 1.0).abs()));
        }
        if on_floor {
            floor.push(f64::from(r.position.y.abs()));
        }
    }
    let palest = bounds::least(surfaces.iter().map(|r| f64::from(r.albedo.max_element())));
    bounds::assert_all([
        bounds::at_least("back wall receivers", back.len() as f64, 3001.0),
        bounds::at_least("floor receivers", floor.len() as f64, 1001.0),
        ON_THE_PLANE.check("a back wall receiver off its plane, the worst", bounds::worst(back)),
        ON_THE_PLANE.check("a floor receiver off its plane, the worst", bounds::worst(floor)),
        bounds::at_least("the least albedo of a receiver (ρ from the albedo view)", palest, 0.05),
    ]);
}

#[test]
fn the_world_reference_integrates_the_bounce_the_gpu_reference_does_and_has_converged() {
    let gpu = Gpu::lavapipe().unwrap();
    let scene = cornell_box();
    let (plugins, _) = game::plugins(plugin_gi::GiSettings::default());
    let mut renderer = Renderer::new(&gpu, &scene, plugins).unwrap();
    let mut reference = WorldReference::new(&gpu, &scene).unwrap();
    for v in [
        view(Vec3::new(0.0, 1.0, 3.4), Vec3::new(0.0, 1.0, 0.0)),
        view(Vec3::new(0.5, 1.4, 2.4), Vec3::new(-0.9, 0.4, -0.9)),
    ] {
        let screen = render_linear(&gpu, &mut renderer, &v, "reference_screen");
        let receivers = reference.receivers(&gpu, &v, SIZE).unwrap();
        let world = reference.evaluate(&v, SIZE, &receivers, None, DEFAULT_MAX_EDGE);
        let error = block_error(&world.image, &screen);
        let energy = sum(&world.image) / sum(&screen) - 1.0;
        let at = v.camera.position;
        println!("camera at {at}: {} lit patches", world.lit_patches);
        bounds::assert_all([
            SCREEN_ERROR.check(format!("camera at {at}: world against screen reference, block error"), error),
            SCREEN_ENERGY.check(format!("camera at {at}: world against screen reference, energy"), energy),
        ]);
        // Convergence: 2 cm patches against 1 cm ones, on the same receivers.
        let fine = reference.evaluate(&v, SIZE, &receivers, None, DEFAULT_MAX_EDGE / 2.0);
        let converged = block_error(&world.image, &fine.image);
        let more = fine.lit_patches as f64 / world.lit_patches as f64;
        bounds::assert_all([
            bounds::at_least("1 cm patches over 2 cm ones", more, 3.0),
            CONVERGED.check(format!("camera at {at}: 2 cm patches against 1 cm ones"), converged),
        ]);
    }
}

/// On the Cellar's own triangles, from the pixels of two views, the visibility cube sees what
/// an exact ray (parry's, through the level's BVH) sees, for every lit patch that can light a
/// receiver, weighted by the light the pair exchanges.
#[test]
fn in_the_cellar_the_visibility_cube_sees_what_rays_see() {
    let gpu = Gpu::lavapipe().unwrap();
    let level = engine::scene::load_level(&game::default_level()).unwrap();
    let corridor = Some((Vec3::new(-1.8, 1.6, -7.0), Vec3::new(-6.0, 1.2, -7.0)));
    let mut reference = WorldReference::new(&gpu, &level.scene).unwrap();
    let world = World::new(&level.scene);
    let occluders = world.occluders();
    let size = (16, 12);
    for look in [None, corridor] {
        let v = initial_view(&level, &ViewOverrides { look, fov_y: None });
        let receivers = reference.receivers(&gpu, &v, size).unwrap();
        let lamp = Lamp::new(&v.headlamp, &v.camera, size.0 as f32 / size.1 as f32);
        let patches = world.lit_patches(&lamp, 0.05);
        let (mut disagree, mut hidden, mut total) = (0.0f64, 0.0f64, 0.0f64);
        for r in receivers.iter().filter(|r| r.normal != Vec3::ZERO) {
            // (From 1 mm off the surface, as the reference looks.)
            let origin = r.position + r.normal * 1e-3;
            let mut cube = VisibilityCube::new(&occluders, origin, VISIBILITY_CUBE);
            for p in &patches {
                let d = p.patch.centre - r.position;
                let (cos_r, cos_s) = (r.normal.dot(d), -p.normal.dot(d));
                if cos_r <= 0.0 || cos_s <= 0.0 {
                    continue;
                }
                let transfer = f64::from(cos_r * cos_s / d.length_squared().powi(2) * p.flux.element_sum());
                let to = p.patch.centre - origin;
                let ray = world.visible(origin, p.patch.centre - to * (SHADOW_OFFSET / to.length()));
                total += transfer;
                hidden += if ray { 0.0 } else { transfer };
                if cube.sees(&occluders, p.patch.centre, p.patch.triangle) != ray {
                    disagree += transfer;
                }
            }
        }
        let name = if look.is_none() { "spawn" } else { "corridor" };
        bounds::assert_all([
            bounds::at_least(format!("{name}: the share of the transfer hidden"), hidden / total, 0.01),
            CUBE_AGAINST_RAYS.check(format!("{name}: the cube against the rays"), disagree / total),
        ]);
    }
}
