//! What each golden image shows, and how it is rendered: the shots of the shipped levels and
//! the snapshot ticks of the test replays. The frame tests compare these frames with
//! `goldens/`; `update-goldens` (the one way to re-make them) writes them there.

use engine::glam::Vec3;
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::start_view::{initial_view, ViewOverrides};

use crate::replay_files;

/// Golden frames are small, because lavapipe renders the GI on the CPU.
pub const SIZE: (u32, u32) = (320, 180);

/// An eye and the point it looks at.
pub type Look = ([f32; 3], [f32; 3]);

/// One golden frame of a shipped level.
pub struct LevelShot {
    pub name: &'static str,
    /// Where the camera is; None: the level's spawn.
    pub camera: Option<Look>,
    /// Where the headlamp is put down; None: on the camera.
    pub lamp: Option<Look>,
    /// The renderer's view (`final`, `albedo`, `normal`, `depth`).
    pub view: &'static str,
}

const fn shot(name: &'static str, camera: Option<Look>, lamp: Option<Look>, view: &'static str) -> LevelShot {
    LevelShot { name, camera, lamp, view }
}

/// Each shipped level and its golden frames.
pub const LEVEL_SHOTS: &[(&str, &[LevelShot])] = &[
    (
        "cellar",
        &[
            shot("cellar_spawn_final", None, None, "final"),
            shot("cellar_spawn_normal", None, None, "normal"),
            shot("cellar_spawn_depth", None, None, "depth"),
            // Red/green/white room seen from its corridor doorway.
            shot("cellar_cornell_final", Some(([-1.8, 1.6, -7.0], [-6.0, 1.2, -7.0])), None, "final"),
            shot("cellar_cornell_albedo", Some(([-1.8, 1.6, -7.0], [-6.0, 1.2, -7.0])), None, "albedo"),
            // Blue (east) and yellow (south) walls around a crate stack.
            shot("cellar_blue_yellow_final", Some(([2.0, 1.6, -10.0], [6.0, 1.2, -5.0])), None, "final"),
            // The open hall with pillars, crates and the dais.
            shot("cellar_hall_final", Some(([0.0, 1.6, -13.5], [0.0, 1.0, -24.0])), None, "final"),
            // Detached lamp: put down high by the Cornell room's red wall, it throws the short
            // block's shadow across the floor towards the green wall; the camera looks on from
            // the tall block.
            shot(
                "cellar_cornell_lamp_final",
                Some(([-4.6, 1.7, -4.3], [-3.8, 0.6, -10.0])),
                Some(([-2.0, 2.5, -5.0], [-4.5, 0.0, -8.5])),
                "final",
            ),
            // Detached lamp in the hall just behind the south-west pillar: the pillar's shadow
            // runs across the floor and up the west wall.
            shot(
                "cellar_hall_lamp_final",
                Some(([-0.5, 2.6, -19.5], [-6.5, 0.6, -15.5])),
                Some(([-2.4, 1.4, -15.6], [-7.0, 0.4, -18.0])),
                "final",
            ),
        ],
    ),
    (
        "gallery",
        &[
            shot("gallery_spawn_final", None, None, "final"),
            // The white atrium: the red cube on its plinth under its spotlight, the red and
            // green rooms' doors beyond.
            shot("gallery_atrium_final", Some(([3.5, 1.6, -1.5], [-1.0, 0.9, -8.0])), None, "final"),
            // The red room's corner: the lamp on the red wall, its colour on the white wall,
            // floor and ceiling beside it, the white monolith; the yellow room through the door.
            shot("gallery_red_final", Some(([-6.5, 1.7, -4.6], [-12.4, 1.0, -9.0])), None, "final"),
            // The green room's tiles and floor tiles: the textures, unlit.
            shot("gallery_green_albedo", Some(([3.8, 1.6, -13.6], [-1.5, 1.2, -20.8])), None, "albedo"),
            // Detached lamp: put down in the blue room facing its blue wall, the camera looking
            // on from the door, the white monolith between.
            shot(
                "gallery_blue_lamp_final",
                Some(([5.8, 1.7, -6.4], [12.4, 1.2, -6.4])),
                Some(([8.0, 0.4, -4.0], [12.4, 1.5, -8.0])),
                "final",
            ),
        ],
    ),
    (
        "hall",
        &[
            // The nave from the porch door: pillars, balconies, the lamps' pools, the blue wall.
            shot("hall_nave_final", Some(([0.0, 1.7, -5.0], [0.0, 3.0, -38.0])), None, "final"),
            // The stairs up the west wall to the balcony, its pillars and banners.
            shot("hall_stairs_final", Some(([2.5, 1.7, -6.5], [-9.0, 3.2, -18.0])), None, "final"),
            // The blue wall, the north balcony over the crypt door.
            shot("hall_blue_final", Some(([3.0, 1.7, -28.0], [-2.0, 3.5, -38.0])), None, "final"),
            // From the west balcony over the nave: the east balcony and its ramp.
            shot("hall_balcony_final", Some(([-8.7, 5.35, -17.0], [6.0, 1.5, -10.0])), None, "final"),
        ],
    ),
];

/// The golden frames of the shipped level `id`.
pub fn level_shots(id: &str) -> &'static [LevelShot] {
    LEVEL_SHOTS.iter().find(|(level, _)| *level == id).unwrap_or_else(|| panic!("no shots of level '{id}'")).1
}

/// Renders `shot` of `level` headless at [`SIZE`].
pub fn render_level_shot(gpu: &Gpu, level: &engine::scene::Level, shot: &LevelShot) -> image::RgbaImage {
    let (plugins, _gi) = game::plugins(plugin_gi::GiSettings::default());
    let mut renderer = Renderer::new(gpu, &level.scene, plugins).unwrap();
    renderer.set_view(shot.view).unwrap();
    let look = shot.camera.map(|(eye, target)| (Vec3::from(eye), Vec3::from(target)));
    let mut state = initial_view(level, &ViewOverrides { look, fov_y: None });
    if let Some((eye, target)) = shot.lamp {
        state.headlamp.detach_looking_at(Vec3::from(eye), Vec3::from(target));
    }
    let target = HeadlessTarget::new(gpu, SIZE.0, SIZE.1, ImageKind::Display);
    match target.render(gpu, &mut renderer, &state).unwrap() {
        RenderedImage::Display(img) => img,
        RenderedImage::Linear(_) => unreachable!("asked for a display image"),
    }
}

/// Each test replay and the ticks whose frames are goldens (the frame after that many ticks),
/// in the order of their scripts' names.
pub const REPLAY_SHOTS: &[(&str, &[u32])] = &[
    // A crawler's body posed by the simulation: walking up; the strike drawn back mid-windup;
    // the blow at full reach as the windup ends; recovering.
    ("crawler_strike", &[230, 268, 280, 296]),
    // The Gallery won: the blue room's crawler seen through its door from the atrium; the first
    // shot's muzzle flash lighting the blue room; the vault's guard in its doorway; at the way
    // out, won.
    ("gallery_win", &[232, 235, 372, 560]),
    // The Hall won: on the west balcony at the top of the stairs; a shot from the balcony at the
    // nave's crawler below; a shot across the nave at the west arcade's crawler; the crypt's
    // guard in its doorway in the blue wall.
    ("hall_win", &[393, 490, 1075, 1430]),
    // In the corridor; near the top of the jump; crouched; standing again.
    ("jumping", &[60, 88, 161, 201]),
    // The moment the lamp is put down; backing out; in the corridor, the room lit by the lamp
    // left inside; turned a little.
    ("lamp_detach", &[229, 247, 265, 285]),
    // Lamp on; off, a shot's muzzle flash lighting the dark corridor; on again; turned. (The
    // dark frame with the lamp just off is checked apart, in `replay_frames.rs`: a golden of
    // black would check almost nothing.)
    ("lamp_toggle", &[30, 46, 61, 90]),
    ("turning", &[30, 60, 90, 120]),
    // The spawn view; backed against the south wall; pressed into the east wall; backed away
    // from that corner, looking at it.
    ("walls", &[0, 60, 120, 190]),
    // The Cellar won: the first shot's muzzle flash lighting the red/green room; that
    // crawler falling; the hall's crawler lying in the corridor; the storeroom's guard lying
    // in the storeroom, won.
    ("win", &[171, 189, 478, 795]),
];

/// The golden's name of replay `name`'s frame after `tick` ticks.
pub fn replay_shot_name(name: &str, tick: u32) -> String {
    format!("replay_{name}_t{tick:03}")
}

/// Re-simulates the test replay `name` (every tick's state hash checked against the file) and
/// renders the frames after `ticks` at [`SIZE`], in tick order.
pub fn render_replay_ticks(name: &str, ticks: &[u32]) -> Vec<(u32, image::RgbaImage)> {
    let replay = replay_files::open(name);
    let mut frames = Vec::new();
    let end = game::replay_frames::frames(&replay, ticks, SIZE, Gpu::lavapipe, |tick, image| {
        frames.push((tick, image.clone()));
        Ok(())
    })
    .unwrap_or_else(|e| panic!("{name}: {e:#}"));
    assert_eq!(end.tick as usize, replay.commands.len(), "{name}: played to its end");
    frames
}

/// The name of every golden frame, level shots and replay shots.
pub fn golden_names() -> Vec<String> {
    let levels = LEVEL_SHOTS.iter().flat_map(|(_, shots)| shots.iter().map(|s| s.name.to_string()));
    let replays = REPLAY_SHOTS.iter().flat_map(|(name, ticks)| ticks.iter().map(move |&t| replay_shot_name(name, t)));
    levels.chain(replays).collect()
}
