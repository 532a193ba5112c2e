//! The gun in hand never goes behind a wall: replaying `walls` (walking into the start room's
//! walls, then facing the corner pressed into it), the frame with the gun differs from the
//! frame without it over a gun-sized patch at the bottom right, while the same meshes drawn as
//! ordinary scene instances (depth-tested against the level) are hidden there by the wall: the
//! camera really is pressed to it, and the view-model pass draws the gun over it.

use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use game::recording::LoadedReplay;
use game::view::WorldView;
use headlamp_tests::replay_files;

const SIZE: (u32, u32) = (160, 90);
/// Ticks of `walls` where the camera is pressed into the corner it faces.
const PRESSED: &[u32] = &[165];

fn render(gpu: &Gpu, renderer: &mut Renderer, view: &engine::frame::ViewState) -> image::RgbaImage {
    let target = HeadlessTarget::new(gpu, SIZE.0, SIZE.1, ImageKind::Display);
    match target.render(gpu, renderer, view).unwrap() {
        RenderedImage::Display(img) => img,
        RenderedImage::Linear(_) => unreachable!("asked for display"),
    }
}

/// The pixels where two frames differ visibly.
fn differing(a: &image::RgbaImage, b: &image::RgbaImage) -> Vec<(u32, u32)> {
    a.enumerate_pixels()
        .filter(|(x, y, p)| {
            let q = b.get_pixel(*x, *y);
            (0..3).any(|c| (p[c] as i32 - q[c] as i32).abs() > 6)
        })
        .map(|(x, y, _)| (x, y))
        .collect()
}

#[test]
fn the_gun_is_drawn_over_a_wall_the_camera_is_pressed_against() {
    let replay = LoadedReplay::open(&replay_files::path("walls"), None).unwrap_or_else(|e| panic!("{e:#}"));
    let gpu = Gpu::lavapipe().unwrap_or_else(|e| panic!("{e}"));
    let (plugins, _) = game::plugins(replay.gi.clone());
    let mut renderer = Renderer::new(&gpu, &replay.level.scene, plugins).unwrap();
    let mut view = WorldView::new(&replay.level);
    view.add_meshes(&mut renderer, &gpu);
    let mut sim = replay.simulation().unwrap();
    let mut tick = 0;
    for &wanted in PRESSED {
        while tick < wanted {
            replay.step_checked(&mut sim, tick as usize).unwrap();
            tick += 1;
        }
        view.at(sim.entities(), &sim.state);
        let gun = view.view.view_models.clone();
        assert!(!gun.is_empty(), "t{tick}: the living player holds the gun");
        let with_gun = render(&gpu, &mut renderer, &view.view);
        let mut without = view.view.clone();
        without.view_models.clear();
        let bare = render(&gpu, &mut renderer, &without);
        let mut in_scene = without.clone();
        in_scene.instances.extend(gun);
        let behind_wall = render(&gpu, &mut renderer, &in_scene);

        let drawn = differing(&with_gun, &bare);
        let hidden = differing(&behind_wall, &bare);
        let frame = (SIZE.0 * SIZE.1) as usize;
        println!("t{tick}: the gun covers {} pixels as a view model, {} as scene geometry", drawn.len(), hidden.len());
        let _ = with_gun.save(std::env::temp_dir().join(format!("headlamp-gun-walls-t{tick}.png")));
        let _ = behind_wall.save(std::env::temp_dir().join(format!("headlamp-gun-walls-t{tick}-in-scene.png")));
        let lower_right = drawn.iter().filter(|(x, y)| *x > SIZE.0 / 2 && *y > SIZE.1 / 2).count();
        let drawn_pixels = drawn.len() as f64;
        // The wall is in front of the gun: depth-tested against the level it would be hidden.
        bounds::assert_all([
            bounds::at_least(format!("t{tick}: the gun's share of the frame"), drawn_pixels / frame as f64, 0.02),
            bounds::at_least(format!("t{tick}: the gun's share low and right"), lower_right as f64 / drawn_pixels, 0.9),
            bounds::at_most(
                format!("t{tick}: the gun's share shown as scene geometry"),
                hidden.len() as f64 / drawn_pixels,
                0.25,
            ),
        ]);
    }
}
