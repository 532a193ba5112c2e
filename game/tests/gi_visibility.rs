//! No light through walls (lavapipe): with `gi.visibility` the GI's one bounce (by the cuts,
//! and in the Cellar by the article's method too) comes within 8 % (4×4 blocks) and 5 % of
//! energy of the visibility-correct world-fixed reference
//! (`reference_vis`, CPU, every sender–receiver pair tested against the level's triangles),
//! where the GI without it is far off, in a box with a tall block, in one with a short and a
//! tall block, and in three Cellar views;
//! and a lamp set down by a wall (down to 10 cm thick), or worn by a player standing at it,
//! lights nothing measurable in the room behind it, from inside, from its doorway and on a slow
//! pan from the corridor into it.

mod common;

use common::cornell::{tall_block_box, two_block_box, two_rooms_with_a_thin_wall, view, THIN_WALL_HALF};
use common::settled::settled_indirect;
use engine::frame::ViewState;
use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::scene::Scene;
use engine::start_view::{initial_view, ViewOverrides};
use game::world_reference::WorldReference;
use gi_reference::DEFAULT_MAX_EDGE;
use plugin_gi::metrics::{block_error_masked_sized, block_error_sized, block_mask, energy, energy_masked, shrink};
use plugin_gi::{GiSettings, Method};

/// The frames the GI renders, and the reference's receivers: a quarter each way.
const FRAME: (u32, u32) = (640, 360);
const REFERENCE: (u32, u32) = (160, 90);

bounds::tolerance! {
    /// The box with a tall block, face-on and into a corner, and the box with both blocks
    /// face-on, defaults and CPU settings: against `reference_vis`, 4×4 block error (the goal
    /// is 6 %, not yet met; this holds what is reached).
    BOX_ERROR: at_most 0.08, measured 0.0741
}
bounds::tolerance! {
    /// The box with a tall block, face-on and into a corner, and the box with both blocks
    /// face-on, defaults and CPU settings: against `reference_vis`, energy (the goal: 5 %).
    BOX_ENERGY: magnitude 0.05, measured 0.0315
}
bounds::tolerance! {
    /// The boxes without visibility: how much further from `reference_vis` (block error,
    /// points): the blocks hide enough to tell the two apart.
    BOX_WITHOUT: at_least 0.04, measured 0.0800
}
bounds::tolerance! {
    /// The lamp set down by the spawn room's wall: the room behind it, ÷ the lit mean (the goal:
    /// 1 %), defaults, CPU settings and the article's method.
    SET_DOWN_LEAK: at_most 0.004, measured 0.00228
}
bounds::tolerance! {
    /// The lamp set down by the spawn room's wall, without visibility: the room behind it ÷ the
    /// lit mean, the leak visibility stops.
    SET_DOWN_WITHOUT: at_least 0.03, measured 0.0339
}
bounds::tolerance! {
    /// The lamp worn at the red/green room's wall: the room's light beyond the reference's, ÷
    /// the lit mean (the goal: 1 %).
    WORN_LEAK: at_most 0.008, measured 0.00449
}
bounds::tolerance! {
    /// Three Cellar views, defaults, CPU settings and the article's method: against
    /// `reference_vis` on every other 4×4 block, block error (the goal: 8 %).
    CELLAR_ERROR: at_most 0.08, measured 0.0778
}
bounds::tolerance! {
    /// A lamp set down by a wall, the room behind it seen where the camera sees neither the lit
    /// floor nor the wall (the Cellar's red/green room from inside, from its doorway, both
    /// methods, and on a slow pan from the corridor into it, its worst frame; the Gallery's
    /// vault; the Hall's crypt; two rooms with a 10 cm wall between, three settings): the
    /// room's light beyond the reference's ÷ the lit mean (the goal: 1 %).
    ROOM_LEAK: at_most 0.01, measured 1.95e-6, wider "the goal's 1 %: the world sight leaves the rooms at or a little below the reference, so its worst is near zero"
}
bounds::tolerance! {
    /// Every such case through the screen's depth alone
    /// (`gi.world_sight` 0): the leak the world sight stops.
    ROOM_WITHOUT: at_least 0.03, measured 0.0518
}
bounds::tolerance! {
    /// Three Cellar views, defaults, CPU settings and the article's method: against
    /// `reference_vis` on every other 4×4 block, energy (the goal: 5 %).
    CELLAR_ENERGY: magnitude 0.05, measured 0.0303
}
bounds::tolerance! {
    /// Three Cellar views, the article's method: how much visibility may cost it (points of block error:
    /// its one march per receiver and light sees some lights along a surface beside a fold as
    /// hidden where little stands between, as in the corner).
    ARTICLE_COST: at_most 0.005, measured 0.00279
}

fn indirect(gpu: &Gpu, scene: &Scene, view: &ViewState, settings: GiSettings) -> image::Rgba32FImage {
    settled_indirect(gpu, scene, view, settings, FRAME, FRAME.0 / REFERENCE.0).0
}

fn visible_reference(gpu: &Gpu, scene: &Scene, view: &ViewState) -> image::Rgba32FImage {
    let mut reference = WorldReference::new(gpu, scene).unwrap().with_visibility();
    reference.render(gpu, view, REFERENCE, DEFAULT_MAX_EDGE).unwrap().image
}

/// A pixel's luminance, the mean of its channels.
fn lum(p: &image::Rgba<f32>) -> f32 {
    (p[0] + p[1] + p[2]) / 3.0
}

/// The mean luminance of `img`'s pixels where `mask` holds.
fn mean(img: &image::Rgba32FImage, mask: &[bool]) -> f32 {
    let (sum, n) = img.pixels().zip(mask).filter(|(_, &m)| m).fold((0.0, 0), |(s, n), (p, _)| (s + lum(p), n + 1));
    sum / n as f32
}

fn off(settings: GiSettings) -> GiSettings {
    GiSettings { visibility: 0, ..settings }
}

#[test]
fn in_a_box_with_a_tall_block_and_with_two_blocks_the_gi_sees_what_the_visible_reference_sees() {
    let gpu = Gpu::lavapipe().unwrap();
    let face_on = view(Vec3::new(0.0, 1.0, 3.4), Vec3::new(0.0, 1.0, 0.0));
    let (tall, both) = (tall_block_box(), two_block_box());
    let views = [
        ("face-on", &tall, face_on.clone()),
        ("into a corner", &tall, view(Vec3::new(0.5, 1.4, 2.4), Vec3::new(-0.9, 0.4, -0.9))),
        ("two blocks, face-on", &both, face_on),
    ];
    for (name, scene, v) in views {
        let reference = visible_reference(&gpu, scene, &v);
        for (settings, label) in [(GiSettings::default(), "defaults"), (GiSettings::cpu_preset(), "CPU settings")] {
            let with = indirect(&gpu, scene, &v, settings.clone());
            let without = indirect(&gpu, scene, &v, off(settings));
            let (error, gain) = (block_error_sized(&with, &reference, 4), energy(&with, &reference));
            let (leaky, leaky_gain) = (block_error_sized(&without, &reference, 4), energy(&without, &reference));
            // The block hides enough that the GI without visibility misses by far, with more light.
            bounds::assert_all([
                BOX_ERROR.check(format!("{name}, {label}: block error"), error),
                BOX_ENERGY.check(format!("{name}, {label}: energy"), gain),
                BOX_WITHOUT.check(format!("{name}, {label}: block error without visibility, less with"), leaky - error),
                bounds::at_least(
                    format!("{name}, {label}: energy without visibility, less with"),
                    leaky_gain - gain,
                    f64::MIN_POSITIVE,
                ),
            ]);
        }
    }
}

#[test]
fn a_lamp_set_down_by_a_wall_lights_nothing_in_the_room_behind_it() {
    let gpu = Gpu::lavapipe().unwrap();
    let level = engine::scene::load_level(&game::default_level()).unwrap();
    // Set down in the corridor, lighting the floor beside the wall of the room the player
    // starts in; the player looks through that room's doorway into the corridor.
    let mut v = initial_view(&level, &ViewOverrides { look: None, fov_y: None });
    v.headlamp.detach_looking_at(Vec3::new(0.0, 2.6, -5.0), Vec3::new(-0.4, 0.0, -5.2));
    let reference = visible_reference(&gpu, &level.scene, &v);
    let brightest = bounds::worst(reference.pixels().map(|p| f64::from(lum(p)))) as f32;
    // Lit: what the lamp's light reaches after one bounce; behind the wall: surfaces no lit
    // patch can see, however near (the reference gives them exactly nothing).
    let lit: Vec<bool> = reference.pixels().map(|p| lum(p) > 1e-2 * brightest).collect();
    let hidden: Vec<bool> = reference.pixels().map(|p| lum(p) == 0.0).collect();
    bounds::assert_all([
        bounds::at_least("lit pixels", lit.iter().filter(|&&m| m).count() as f64, 51.0),
        bounds::at_least("pixels behind the wall", hidden.iter().filter(|&&m| m).count() as f64, 2001.0),
    ]);
    let article = GiSettings { method: Method::Article, ..GiSettings::default() };
    let all = [(GiSettings::default(), "defaults"), (GiSettings::cpu_preset(), "CPU settings"), (article, "article")];
    for (settings, label) in all {
        let with = indirect(&gpu, &level.scene, &v, settings.clone());
        let without = indirect(&gpu, &level.scene, &v, off(settings));
        let leak = f64::from(mean(&with, &hidden) / mean(&with, &lit));
        let old_leak = f64::from(mean(&without, &hidden) / mean(&without, &lit));
        bounds::assert_all([
            SET_DOWN_LEAK.check(format!("{label}: behind the wall ÷ the lit mean"), leak),
            SET_DOWN_WITHOUT.check(format!("{label}: without visibility, behind the wall ÷ the lit mean"), old_leak),
        ]);
    }
}

/// The red/green room's floor plan (levels/generator/src/cellar.rs): x and z, metres.
const RED_GREEN_ROOM: ([f32; 2], [f32; 2]) = ([-7.4, -1.4], [-10.0, -4.0]);
/// The lamp set down in the Cellar's corridor by the red/green room's wall (where it stands,
/// what it points at), and a view of the floor it lights from the corridor.
const CELLAR_LAMP: (Vec3, Vec3) = (Vec3::new(0.0, 2.6, -5.0), Vec3::new(-0.4, 0.0, -5.2));
const CELLAR_LIT: (Vec3, Vec3) = (Vec3::new(1.0, 1.7, -1.5), Vec3::new(-0.4, 0.3, -5.2));

/// Whether receiver r lies on a surface inside `room` (x and z, metres).
fn in_room(([x0, x1], [z0, z1]): ([f32; 2], [f32; 2]), r: &gi_reference::Receiver) -> bool {
    r.normal != Vec3::ZERO && (x0..x1).contains(&r.position.x) && (z0..z1).contains(&r.position.z)
}

/// The mean of `reference`'s light over the surfaces it lights in `view` (above 1 % of its
/// brightest), what a leak is counted against; at least 2001 of them (`label` says where).
fn lit_mean(gpu: &Gpu, reference: &mut WorldReference, view: &ViewState, label: &str) -> f32 {
    let receivers = reference.receivers(gpu, view, REFERENCE).unwrap();
    let exact = reference.evaluate(view, REFERENCE, &receivers, None, DEFAULT_MAX_EDGE).image;
    let brightest = bounds::worst(exact.pixels().map(|p| f64::from(lum(p)))) as f32;
    let lit: Vec<bool> = exact.pixels().map(|p| lum(p) > 1e-2 * brightest).collect();
    let lit_pixels = lit.iter().filter(|&&m| m).count() as f64;
    bounds::assert(bounds::at_least(format!("{label}: lit pixels"), lit_pixels, 2001.0));
    mean(&exact, &lit)
}

/// A lamp set down by a wall, and views of the room behind it where the camera sees neither
/// the lit floor nor the wall.
struct RoomBehind {
    /// The level's folder under levels/ (`room_leaks`), or the scene's name (`leaks_behind`).
    level: &'static str,
    /// The lamp: where it stands, what it points at.
    lamp: (Vec3, Vec3),
    /// A view of the lit floor from the lamp's side: its lit surfaces' mean is what a leak is
    /// counted against.
    lit: (Vec3, Vec3),
    /// The room behind the wall (x and z, metres), and views of it.
    room: ([f32; 2], [f32; 2]),
    views: &'static [(&'static str, [f32; 3], [f32; 3])],
}

/// For each view of `case` and each of `methods`: the room's light beyond `reference_vis`'s ÷
/// the lit mean, with the world sight and through the screen alone.
fn room_leaks(gpu: &Gpu, case: &RoomBehind, methods: &[(&str, GiSettings)]) -> Vec<(String, f64, f64)> {
    let levels = game::default_level().parent().expect("levels/").to_path_buf();
    let level = engine::scene::load_level(&levels.join(case.level)).unwrap();
    let start =
        |(eye, target): (Vec3, Vec3)| initial_view(&level, &ViewOverrides { look: Some((eye, target)), fov_y: None });
    leaks_behind(gpu, &level.scene, &start, case, methods)
}

/// `room_leaks` in `scene`, whose views `start` makes (the lamp worn) from an eye and a target.
fn leaks_behind(
    gpu: &Gpu,
    scene: &Scene,
    start: &dyn Fn((Vec3, Vec3)) -> ViewState,
    case: &RoomBehind,
    methods: &[(&str, GiSettings)],
) -> Vec<(String, f64, f64)> {
    let view = |look: (Vec3, Vec3)| {
        let mut v = start(look);
        v.headlamp.detach_looking_at(case.lamp.0, case.lamp.1);
        v
    };
    let mut reference = WorldReference::new(gpu, scene).unwrap().with_visibility();
    let lit_mean = lit_mean(gpu, &mut reference, &view(case.lit), case.level);
    let mut leaks = Vec::new();
    for &(name, eye, target) in case.views {
        let v = view((Vec3::from(eye), Vec3::from(target)));
        let receivers = reference.receivers(gpu, &v, REFERENCE).unwrap();
        let exact = reference.evaluate(&v, REFERENCE, &receivers, None, DEFAULT_MAX_EDGE).image;
        let room: Vec<bool> = receivers.iter().map(|r| in_room(case.room, r)).collect();
        let pixels = room.iter().filter(|&&m| m).count() as f64;
        bounds::assert(bounds::at_least(format!("{}, {name}: the room's pixels", case.level), pixels, 3001.0));
        let truth = mean(&exact, &room);
        let leak = |settings| f64::from((mean(&indirect(gpu, scene, &v, settings), &room) - truth) / lit_mean);
        for (method, settings) in methods {
            let screen = GiSettings { world_sight: 0, ..settings.clone() };
            let (with, without) = (leak(settings.clone()), leak(screen));
            let label = format!("{}, {name}, {method}", case.level);
            println!(
                "{label}: the room {:+.2} % of the lit mean beyond the reference's {:.2} % (screen sight alone {:+.2} %)",
                100.0 * with,
                100.0 * truth / lit_mean,
                100.0 * without
            );
            leaks.push((label, with, without));
        }
    }
    leaks
}

fn assert_room_leaks(leaks: &[(String, f64, f64)]) {
    bounds::assert_all(leaks.iter().flat_map(|(label, with, without)| {
        [
            ROOM_LEAK.check(format!("{label}: the room beyond the reference ÷ the lit mean"), *with),
            ROOM_WITHOUT.check(format!("{label}: the same through the screen's depth alone"), *without),
        ]
    }));
}

#[test]
fn a_lamp_set_down_by_a_wall_lights_nothing_in_the_room_behind_it_seen_from_inside() {
    let gpu = Gpu::lavapipe().unwrap();
    // In the Cellar's corridor by the red/green room's wall; the player inside that room.
    let case = RoomBehind {
        level: "cellar",
        lamp: CELLAR_LAMP,
        lit: CELLAR_LIT,
        room: RED_GREEN_ROOM,
        views: &[
            ("inside, facing away from the corridor", [-2.0, 1.6, -5.5], [-7.4, 2.0, -5.0]),
            ("in the doorway, looking in", [-1.2, 1.6, -7.0], [-6.0, 1.0, -8.5]),
        ],
    };
    let article = GiSettings { method: Method::Article, ..GiSettings::default() };
    assert_room_leaks(&room_leaks(&gpu, &case, &[("cuts", GiSettings::default()), ("article", article)]));
}

#[test]
fn on_a_slow_pan_from_the_corridor_into_the_room_the_lamp_by_its_wall_lights_nothing_in_it() {
    let gpu = Gpu::lavapipe().unwrap();
    let level = engine::scene::load_level(&game::default_level()).unwrap();
    let scene = &level.scene;
    let (lamp, lamp_target) = CELLAR_LAMP;
    // Standing in the red/green room's doorway, from the corridor's lit floor (south-east) round
    // through south into the room (west), PAN_STEP a frame, the GI's history carried along:
    // the wall and the lit floor leave the screen while the room comes into it.
    const PAN_STEP: f32 = 2.5;
    let eye = Vec3::new(-1.2, 1.6, -7.0);
    let (from, to) = (Vec3::new(0.6, 0.3, -5.2) - eye, Vec3::new(-6.0, 1.0, -8.5) - eye);
    let heading = |d: Vec3| d.z.atan2(d.x);
    let pitch = |d: Vec3| d.y.atan2(d.x.hypot(d.z));
    let turn = (heading(to) - heading(from)).rem_euclid(std::f32::consts::TAU);
    let frames = (turn.to_degrees() / PAN_STEP).ceil() as usize;
    let views: Vec<ViewState> = (0..=frames)
        .map(|k| {
            let t = k as f32 / frames as f32;
            let (h, p) = (heading(from) + t * turn, pitch(from) + t * (pitch(to) - pitch(from)));
            let dir = Vec3::new(h.cos() * p.cos(), p.sin(), h.sin() * p.cos());
            let look = Some((eye, eye + dir));
            let mut v = initial_view(&level, &ViewOverrides { look, fov_y: None });
            v.headlamp.detach_looking_at(lamp, lamp_target);
            v
        })
        .collect();
    // The lit mean a leak is counted against, as in the views from inside.
    let mut reference = WorldReference::new(&gpu, scene).unwrap().with_visibility();
    let mut lit_view = initial_view(&level, &ViewOverrides { look: Some(CELLAR_LIT), fov_y: None });
    lit_view.headlamp.detach_looking_at(lamp, lamp_target);
    let lit_mean = lit_mean(&gpu, &mut reference, &lit_view, "cellar");
    // The frames checked: every PAN_CHECK-th, once the room fills a fifth of the view; in each,
    // the room's pixels on every other 4×4 block across and down (a quarter of the
    // reference's cost).
    const PAN_CHECK: usize = 12;
    let blocks = block_mask(REFERENCE.0, REFERENCE.1, 4, 2);
    let mut checks = Vec::new();
    for k in (0..=frames).step_by(PAN_CHECK) {
        let receivers = reference.receivers(&gpu, &views[k], REFERENCE).unwrap();
        let room: Vec<bool> = receivers.iter().zip(&blocks).map(|(r, &b)| b && in_room(RED_GREEN_ROOM, r)).collect();
        if receivers.iter().filter(|r| in_room(RED_GREEN_ROOM, r)).count() * 5 >= receivers.len() {
            let truth = reference.evaluate(&views[k], REFERENCE, &receivers, Some(&room), DEFAULT_MAX_EDGE).image;
            let truth = mean(&truth, &room);
            checks.push((k, room, truth));
        }
    }
    bounds::assert(bounds::at_least("frames checked with the room in view", checks.len() as f64, 3.0));
    // The cuts at the defaults, with the world sight and through the screen alone.
    let screen = GiSettings { world_sight: 0, ..GiSettings::default() };
    let [with, without] = [GiSettings::default(), screen].map(|s| {
        let pan = pan_indirect(&gpu, scene, &views, s);
        checks.iter().map(|(k, room, truth)| f64::from((mean(&pan[*k], room) - truth) / lit_mean)).collect::<Vec<_>>()
    });
    for ((k, _, _), (w, o)) in checks.iter().zip(with.iter().zip(&without)) {
        println!(
            "pan, frame {k} ({:.0}°): the room {:+.2} % of the lit mean beyond the reference (screen sight alone {:+.2} %)",
            *k as f32 * turn.to_degrees() / frames as f32,
            100.0 * w,
            100.0 * o
        );
    }
    let worst = |v: &[f64]| bounds::worst(v.iter().copied());
    let leaks = [("the pan into the room, cuts, its worst frame".to_string(), worst(&with), worst(&without))];
    assert_room_leaks(&leaks);
}

/// The indirect light of each of `views` in turn, rendered at PAN_FRAME as one camera path
/// (each frame's history the one before), shrunk to the reference's receivers.
fn pan_indirect(gpu: &Gpu, scene: &Scene, views: &[ViewState], settings: GiSettings) -> Vec<image::Rgba32FImage> {
    // Half FRAME each way: the pan renders some sixty frames.
    const PAN_FRAME: (u32, u32) = (FRAME.0 / 2, FRAME.1 / 2);
    let (plugins, _) = game::plugins(settings);
    let mut renderer = Renderer::new(gpu, scene, plugins).unwrap();
    renderer.set_view("indirect").unwrap();
    let target = HeadlessTarget::new(gpu, PAN_FRAME.0, PAN_FRAME.1, ImageKind::Linear);
    views
        .iter()
        .map(|v| match target.render(gpu, &mut renderer, v).unwrap() {
            RenderedImage::Linear(img) => shrink(&img, PAN_FRAME.0 / REFERENCE.0),
            RenderedImage::Display(_) => unreachable!("a linear target"),
        })
        .collect()
}

#[test]
fn a_lamp_set_down_by_a_wall_10_cm_thick_lights_nothing_in_the_room_behind_it() {
    let gpu = Gpu::lavapipe().unwrap();
    let scene = two_rooms_with_a_thin_wall();
    // In the left room, lighting its floor along the wall; the player in the right room,
    // facing away from the wall. (Facing the wall, the screen's depth already stops the light:
    // the leak is 0.01 % either way.)
    let case = RoomBehind {
        level: "two rooms",
        lamp: (Vec3::new(-0.6, 2.0, 0.0), Vec3::new(-THIN_WALL_HALF - 0.07, 0.0, 0.0)),
        lit: (Vec3::new(-3.5, 1.6, 1.0), Vec3::new(-0.3, 0.3, 0.0)),
        room: ([0.0, 4.1], [-3.1, 3.1]),
        views: &[("facing away", [1.0, 1.6, 2.0], [4.0, 1.0, -2.0])],
    };
    let start = |(eye, target): (Vec3, Vec3)| view(eye, target);
    let article = GiSettings { method: Method::Article, ..GiSettings::default() };
    let methods = [("cuts", GiSettings::default()), ("CPU settings", GiSettings::cpu_preset()), ("article", article)];
    assert_room_leaks(&leaks_behind(&gpu, &scene, &start, &case, &methods));
}

#[test]
fn in_the_gallery_and_the_hall_a_lamp_by_a_wall_lights_nothing_in_the_room_behind_it() {
    let gpu = Gpu::lavapipe().unwrap();
    let cases = [
        // In the blue room by the vault's wall, west of its door; the player in the vault, its
        // ceiling low (3.2 m), facing away from the blue room.
        RoomBehind {
            level: "gallery",
            lamp: (Vec3::new(6.5, 2.6, -9.0), Vec3::new(6.2, 0.0, -10.2)),
            lit: (Vec3::new(9.0, 1.7, -5.0), Vec3::new(6.2, 0.2, -10.2)),
            room: ([5.4, 12.4], [-16.8, -10.8]),
            views: &[("the vault", [6.5, 1.6, -11.5], [6.0, 1.2, -16.5])],
        },
        // In the hall by the crypt's wall, east of its door; the player in the crypt.
        RoomBehind {
            level: "hall",
            lamp: (Vec3::new(2.3, 2.6, -36.5), Vec3::new(2.3, 0.0, -37.8)),
            lit: (Vec3::new(1.0, 1.7, -33.0), Vec3::new(2.3, 0.2, -37.7)),
            room: ([-3.0, 3.0], [-44.4, -38.4]),
            views: &[("the crypt", [1.5, 1.6, -39.2], [-2.5, 1.2, -44.0])],
        },
    ];
    let leaks: Vec<_> = cases.iter().flat_map(|c| room_leaks(&gpu, c, &[("cuts", GiSettings::default())])).collect();
    assert_room_leaks(&leaks);
}

#[test]
fn the_lamp_worn_at_a_wall_lights_nothing_in_the_room_behind_it() {
    let gpu = Gpu::lavapipe().unwrap();
    let level = engine::scene::load_level(&game::default_level()).unwrap();
    // Standing in the corridor by the red/green room's wall, south of its doorway, looking
    // down at the floor beside the wall: the lamp, worn, lights that floor and the wall's foot,
    // and through the doorway (at the frame's right) the player sees into the room behind.
    let look = Some((Vec3::new(0.8, 1.6, -5.4), Vec3::new(-0.6, 0.0, -5.4)));
    let v = initial_view(&level, &ViewOverrides { look, fov_y: None });
    let mut reference = WorldReference::new(&gpu, &level.scene).unwrap().with_visibility();
    let receivers = reference.receivers(&gpu, &v, REFERENCE).unwrap();
    let exact = reference.evaluate(&v, REFERENCE, &receivers, None, DEFAULT_MAX_EDGE).image;
    let room: Vec<bool> = receivers.iter().map(|r| in_room(RED_GREEN_ROOM, r)).collect();
    let brightest = bounds::worst(exact.pixels().map(|p| f64::from(lum(p)))) as f32;
    let lit: Vec<bool> = exact.pixels().map(|p| lum(p) > 1e-2 * brightest).collect();
    bounds::assert_all([
        bounds::at_least(
            "the room's pixels in view through the doorway",
            room.iter().filter(|&&m| m).count() as f64,
            301.0,
        ),
        bounds::at_least("lit pixels", lit.iter().filter(|&&m| m).count() as f64, 2001.0),
    ]);
    // Some light does reach the room, through the doorway from the corridor's floor: the leak
    // is what the GI gives it beyond that, as a share of the lit surfaces' mean.
    let (lit_mean, truth) = (mean(&exact, &lit), mean(&exact, &room));
    for (settings, label) in [(GiSettings::default(), "defaults"), (GiSettings::cpu_preset(), "CPU settings")] {
        let with = indirect(&gpu, &level.scene, &v, settings.clone());
        let without = indirect(&gpu, &level.scene, &v, off(settings));
        let leak = f64::from((mean(&with, &room) - truth) / lit_mean);
        let old_leak = f64::from((mean(&without, &room) - truth) / lit_mean);
        println!(
            "{label}: the room behind the wall {:+.2} % of the lit mean beyond the reference's {:.2} % \
             (without visibility {:+.2} %)",
            100.0 * leak,
            100.0 * truth / lit_mean,
            100.0 * old_leak
        );
        // (Without visibility the leak here is small too: the room's surfaces nearest the lit
        // floor, just behind the wall, are hidden from the camera by the doorway's jamb, so
        // the set-down test above is the one that tells the two apart.)
        WORN_LEAK.assert(format!("{label}: the room beyond the reference ÷ the lit mean"), leak);
    }
}

#[test]
fn in_three_cellar_views_the_gi_sees_what_the_visible_reference_sees() {
    let gpu = Gpu::lavapipe().unwrap();
    let level = engine::scene::load_level(&game::default_level()).unwrap();
    let v = |eye: [f32; 3], target: [f32; 3], fov: Option<f32>| {
        let look = Some((Vec3::from(eye), Vec3::from(target)));
        initial_view(&level, &ViewOverrides { look, fov_y: fov.map(f32::to_radians) })
    };
    let views = [
        ("spawn", initial_view(&level, &ViewOverrides { look: None, fov_y: None })),
        ("red/green room", v([-1.8, 1.6, -7.0], [-6.0, 1.2, -7.0], None)),
        ("corner", v([0.5, 1.3, 0.9], [-1.0, 0.4, -1.0], Some(50.0))),
    ];
    // The reference on every other 4×4 block across and down: a quarter of its cost.
    let mask = block_mask(REFERENCE.0, REFERENCE.1, 4, 2);
    for (name, view) in views {
        let mut reference = WorldReference::new(&gpu, &level.scene).unwrap().with_visibility();
        let receivers = reference.receivers(&gpu, &view, REFERENCE).unwrap();
        let exact = reference.evaluate(&view, REFERENCE, &receivers, Some(&mask), DEFAULT_MAX_EDGE).image;
        let article = GiSettings { method: Method::Article, ..GiSettings::default() };
        let all =
            [(GiSettings::default(), "defaults"), (GiSettings::cpu_preset(), "CPU settings"), (article, "article")];
        for (settings, label) in all {
            let with = indirect(&gpu, &level.scene, &view, settings.clone());
            let without = indirect(&gpu, &level.scene, &view, off(settings.clone()));
            let error = block_error_masked_sized(&with, &exact, &mask, 4);
            let gain = energy_masked(&with, &exact, &mask);
            let leaky = block_error_masked_sized(&without, &exact, &mask, 4);
            // (Where little stands between, as in the corner, the article's one march per
            // receiver and light may cost it a few tenths of a point: its receivers beside a
            // fold see some lights along the surface as hidden, where the cuts blend nine
            // receivers' answers.)
            let closer = if label == "article" {
                ARTICLE_COST.check(format!("{name}, article: block error with visibility, less without"), error - leaky)
            } else {
                bounds::at_least(
                    format!("{name}, {label}: block error without visibility, less with"),
                    leaky - error,
                    f64::MIN_POSITIVE,
                )
            };
            bounds::assert_all([
                CELLAR_ERROR.check(format!("{name}, {label}: block error"), error),
                CELLAR_ENERGY.check(format!("{name}, {label}: energy"), gain),
                closer,
            ]);
        }
    }
}
