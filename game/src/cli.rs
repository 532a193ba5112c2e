//! The `headlamp` command line.

use std::path::PathBuf;

use clap::{Parser, Subcommand};
use glam::Vec3;

#[derive(Parser, Debug)]
#[command(
    name = "headlamp",
    version,
    about = "Headlamp: a first-person shooter lit by real-time global illumination from your headlamp"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Play a level in a window (the default).
    Play(PlayArgs),
    /// Render one frame headless (no window, no display) to a PNG or a linear EXR.
    Render(RenderArgs),
    /// Headless timedemo: per-pass GPU times, frame times, and the GI's figures.
    Bench(BenchArgs),
    /// Play a level in a window and record every tick's input to a replay file.
    Record(RecordArgs),
    /// Watch a replay in a window, re-simulate it headless (with snapshots), or verify it.
    Replay(ReplayArgs),
    /// Turn a hand-written input script into a replay, without a window.
    Script(ScriptArgs),
    /// Validate a level without a window or GPU: every error and warning as FILE:LINE:COL lines.
    Check(CheckArgs),
}

#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// A level folder, its level.toml, a .zip of a level folder, or a bare .gltf/.glb/.obj file.
    #[arg(required_unless_present = "reference")]
    pub level: Option<PathBuf>,
    /// Print the findings as one JSON document (for editors and tools).
    #[arg(long)]
    pub json: bool,
    /// Print the level.toml reference (every key, its values and default) as Markdown.
    #[arg(long, conflicts_with_all = ["level", "json"])]
    pub reference: bool,
}

#[derive(clap::Args, Debug, Default)]
pub struct PlayArgs {
    /// Start this level at once, Esc opening the menu: a level folder, a .zip of one, or a bare
    /// .gltf/.glb/.obj file [default: the main menu, its Play starting the shipped level].
    #[arg(long)]
    pub level: Option<PathBuf>,
    /// Also list the levels in this folder in the level menu (repeatable).
    #[arg(long = "levels-dir", value_name = "DIR")]
    pub levels_dirs: Vec<PathBuf>,
}

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// A level folder or a bare .gltf/.glb/.obj file.
    #[arg(long)]
    pub level: PathBuf,
    /// Output file: .png (tonemapped) or .exr (linear values).
    #[arg(long)]
    pub out: PathBuf,
    /// Image size in pixels.
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    pub size: (u32, u32),
    /// What to show: final, direct, albedo, normal, depth; with the GI also indirect, flux,
    /// lights, reference (the exact one bounce from patches fixed in the world, computed on the
    /// CPU), reference_vis (the same with each sender–receiver pair tested for occlusion by the
    /// level's triangles) and reference_screen (the GPU's, every texel of the lamp's view a sender).
    #[arg(long, default_value = "final")]
    pub view: String,
    /// Camera eye and target: EX,EY,EZ:TX,TY,TZ (metres).
    #[arg(long, value_parser = parse_camera, allow_hyphen_values = true)]
    pub camera: Option<(Vec3, Vec3)>,
    /// Detach the headlamp: put it at EX,EY,EZ pointing at TX,TY,TZ (metres) [default: on the camera].
    #[arg(long, value_parser = parse_camera, allow_hyphen_values = true)]
    pub lamp: Option<(Vec3, Vec3)>,
    /// Vertical field of view of both camera and headlamp, in degrees.
    #[arg(long, value_parser = parse_fov)]
    pub fov: Option<f32>,
    /// Indirect light (global illumination) on or off.
    #[arg(long, value_parser = parse_on_off)]
    pub gi: Option<bool>,
    /// A GI setting, e.g. gi.split_ratio=0.3 (repeatable; see docs/gi.md for the names).
    #[arg(long = "set", value_name = "gi.NAME=VALUE", value_parser = parse_setting)]
    pub settings: Vec<(String, String)>,
    /// With --view reference: the longest edge of its patches, in metres [default: 0.02].
    #[arg(long, value_name = "METRES", value_parser = parse_patch_size)]
    pub patch_size: Option<f32>,
}

impl RenderArgs {
    /// The GI settings these flags ask for, starting from the defaults.
    pub fn gi_settings(&self) -> Result<plugin_gi::GiSettings, String> {
        gi_settings(&self.settings, self.gi)
    }

    pub fn patch_size(&self) -> f32 {
        self.patch_size.unwrap_or(gi_reference::DEFAULT_MAX_EDGE)
    }
}

#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// A level folder or a bare .gltf/.glb/.obj file.
    #[arg(long)]
    pub level: PathBuf,
    /// Frame size in pixels [default: 640x360; 160x120 with --pan, whose reference costs
    /// O(pixels × lit patches)].
    #[arg(long, value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Timed frames along the camera path [default: 60; 16 with --pan].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: Option<u32>,
    /// Also write every figure to this file as JSON.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Indirect light (global illumination) on or off.
    #[arg(long, value_parser = parse_on_off, conflicts_with_all = ["compare", "pan"])]
    pub gi: Option<bool>,
    /// A GI setting, e.g. gi.split_ratio=0.3 (repeatable; see docs/gi.md for the names).
    #[arg(long = "set", value_name = "gi.NAME=VALUE", value_parser = parse_setting)]
    pub settings: Vec<(String, String)>,
    /// Render at this fraction of --size and scale up to it, as `play`'s render scale does.
    #[arg(long, default_value_t = 1.0, value_parser = parse_render_scale)]
    pub render_scale: f32,
    /// Hold this frame rate by dynamic resolution, as `play` does with video.dynamic_resolution:
    /// the render scale goes from --render-scale (the ceiling) down to 0.25 as needed. The
    /// camera path runs once untimed for the scale to settle, then timed.
    #[arg(long, value_name = "FPS", value_parser = parse_target_fps, conflicts_with_all = ["compare", "pan"])]
    pub target_fps: Option<f32>,
    /// Render every camera with the GI off and on, alternating, and print both frame times and
    /// their ratio: the GI's cost, measured side by side.
    #[arg(long, conflicts_with = "pan")]
    pub compare: bool,
    /// Pan slowly from a fixed view and print the GI's flicker: how much its error against the
    /// exact reference (its senders fixed in the world) moves from one frame to the next.
    #[arg(long)]
    pub pan: bool,
    /// With --pan: camera eye and target, EX,EY,EZ:TX,TY,TZ (metres) [default: the level's start].
    #[arg(long, value_parser = parse_camera, allow_hyphen_values = true, requires = "pan")]
    pub camera: Option<(Vec3, Vec3)>,
    /// With --pan: vertical field of view of camera and headlamp, degrees.
    #[arg(long, value_parser = parse_fov, requires = "pan")]
    pub fov: Option<f32>,
    /// With --pan: degrees turned right (towards +X when looking down −Z) per frame.
    #[arg(long, default_value_t = 0.5, value_parser = parse_pan_deg, requires = "pan")]
    pub pan_deg: f32,
    /// With --pan: also walk forward this many centimetres a frame (along the first frame's
    /// view, level), e.g. `--pan-deg 0 --walk-cm 2` for a walk.
    #[arg(long, default_value_t = 0.0, value_parser = parse_walk_cm, requires = "pan")]
    pub walk_cm: f32,
    /// With --pan: the headlamp set down at EX,EY,EZ pointing at TX,TY,TZ (metres) for the
    /// whole pan, while the camera turns [default: on the camera].
    #[arg(long = "lamp", value_parser = parse_camera, allow_hyphen_values = true, requires = "pan")]
    pub pan_lamp: Option<(Vec3, Vec3)>,
    /// With --pan: write each frame's linear indirect light and reference as
    /// DIR/indirect_NNN.exr and DIR/reference_NNN.exr (the folder is created), and with
    /// --converge DIR/reference_half_NNN.exr.
    #[arg(long, value_name = "DIR", requires = "pan")]
    pub out_dir: Option<PathBuf>,
    /// The world reference's patches: their longest edge in metres [default: 0.02].
    #[arg(long, value_name = "METRES", value_parser = parse_patch_size, conflicts_with = "compare")]
    pub patch_size: Option<f32>,
    /// With --pan: evaluate the reference on every K-th flicker block across and down (the
    /// same blocks every frame; every figure is taken over them) [default: 1 up to 640x480;
    /// 2, a quarter of them, above].
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=64), requires = "pan")]
    pub reference_every: Option<u32>,
    /// With --pan: also evaluate the reference with patches of half the size (four times the
    /// cost) and print how far the reference is from it: its error and its own flicker.
    #[arg(long, requires = "pan")]
    pub converge: bool,
    /// With --pan: frames rendered along the same path before the first measured one, so the
    /// GI's history is that of a camera already moving [default: until the first frame's
    /// share of the history falls under 1 %: 7 at gi.history 0.5, none without history].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(0..=1000), requires = "pan")]
    pub warmup: Option<u32>,
}

impl BenchArgs {
    pub fn size(&self) -> (u32, u32) {
        self.size.unwrap_or(if self.pan { (160, 120) } else { (640, 360) })
    }

    pub fn frames(&self) -> u32 {
        self.frames.unwrap_or(if self.pan { 16 } else { 60 })
    }

    pub fn patch_size(&self) -> f32 {
        self.patch_size.unwrap_or(gi_reference::DEFAULT_MAX_EDGE)
    }
}

#[derive(clap::Args, Debug)]
pub struct RecordArgs {
    /// A level folder or a bare .gltf/.glb/.obj file [default: the shipped level].
    #[arg(long)]
    pub level: Option<PathBuf>,
    /// The replay file to write (written when the window closes).
    #[arg(long)]
    pub out: PathBuf,
    /// Seed of the simulation's random numbers [default: from the clock].
    #[arg(long)]
    pub seed: Option<u64>,
    /// Indirect light (global illumination) on or off; stored in the replay.
    #[arg(long, value_parser = parse_on_off)]
    pub gi: Option<bool>,
    /// A GI setting, e.g. gi.split_ratio=0.3 (repeatable); stored in the replay.
    #[arg(long = "set", value_name = "gi.NAME=VALUE", value_parser = parse_setting)]
    pub settings: Vec<(String, String)>,
}

#[derive(clap::Args, Debug)]
pub struct ReplayArgs {
    /// The .replay file.
    pub file: PathBuf,
    /// The level to replay on [default: the replay's level, found by its id].
    #[arg(long)]
    pub level: Option<PathBuf>,
    /// No window: re-simulate every tick (checking the stored hashes) and print `ticks=N hash=H`.
    #[arg(long)]
    pub headless: bool,
    /// With --headless (or --goldens --update): render a PNG after each of these ticks
    /// (0 = the start), e.g. 60,120.
    #[arg(long, value_delimiter = ',')]
    pub snapshots: Vec<u32>,
    /// Folder for the snapshots (created if missing).
    #[arg(long, value_name = "DIR", requires = "headless")]
    pub out_dir: Option<PathBuf>,
    /// Snapshot size in pixels [default: 640x360; with --goldens, the goldens' size].
    #[arg(long, value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Re-simulate without rendering and check every tick's state hash; prints `ok ticks=N`.
    #[arg(long, conflicts_with_all = ["headless", "snapshots", "out_dir", "goldens"])]
    pub verify: bool,
    /// Headless regression test: render the frames of the ticks whose goldens DIR holds
    /// (DIR/tick_NNNNNN.png) and compare them by FLIP, as the project's frame tests do; a line
    /// per frame, exit 1 on any failure, `.actual.png` and `.diff.png` beside each failure.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["headless", "out_dir"])]
    pub goldens: Option<PathBuf>,
    /// With --goldens: write the goldens instead (of --snapshots ticks, else of the ticks
    /// already there, else of four ticks spread over the replay).
    #[arg(long, requires = "goldens")]
    pub update: bool,
}

impl ReplayArgs {
    pub const DEFAULT_SIZE: (u32, u32) = (640, 360);
}

#[derive(clap::Args, Debug)]
pub struct ScriptArgs {
    /// The input script (see docs/replays.md: one `TICKS ACTION...` step per line).
    pub script: PathBuf,
    /// A level folder or a bare .gltf/.glb/.obj file.
    #[arg(long)]
    pub level: PathBuf,
    /// The replay file to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Seed of the simulation's random numbers.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Indirect light (global illumination) on or off; stored in the replay.
    #[arg(long, value_parser = parse_on_off)]
    pub gi: Option<bool>,
    /// A GI setting, e.g. gi.split_ratio=0.3 (repeatable); stored in the replay.
    #[arg(long = "set", value_name = "gi.NAME=VALUE", value_parser = parse_setting)]
    pub settings: Vec<(String, String)>,
    /// Print the world after each line of the script, with the turn and look that would aim
    /// at each crawler: for authoring scripts against the game.
    #[arg(long)]
    pub trace: bool,
}

/// The GI settings `--set` and `--gi` ask for, starting from the defaults.
pub fn gi_settings(settings: &[(String, String)], gi: Option<bool>) -> Result<plugin_gi::GiSettings, String> {
    let mut out = plugin_gi::GiSettings::default();
    for (name, value) in settings {
        out.set(name, value)?;
    }
    if let Some(on) = gi {
        out.enabled = on;
    }
    Ok(out)
}

pub fn parse_on_off(s: &str) -> Result<bool, String> {
    match s {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(format!("'{s}': expected on or off")),
    }
}

/// `gi.NAME=VALUE` → (NAME, VALUE); the value is checked against the setting later.
pub fn parse_setting(s: &str) -> Result<(String, String), String> {
    let (key, value) = s.split_once('=').ok_or_else(|| format!("'{s}' is not gi.NAME=VALUE"))?;
    let name = key.trim().strip_prefix("gi.").ok_or_else(|| format!("'{key}': only gi.* settings exist"))?;
    Ok((name.to_owned(), value.trim().to_owned()))
}

pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("'{s}' is not WIDTHxHEIGHT (e.g. 1280x720)"))?;
    let largest = scene::limits::MAX_OUTPUT_SIZE;
    let parse = |v: &str| v.trim().parse::<u32>().ok().filter(|&n| (1..=largest).contains(&n));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("'{s}': width and height must be whole numbers from 1 to {largest}")),
    }
}

fn parse_vec3(s: &str) -> Option<Vec3> {
    let v: Vec<f32> = s.split(',').map(|c| c.trim().parse::<f32>()).collect::<Result<_, _>>().ok()?;
    (v.len() == 3 && v.iter().all(|c| c.is_finite())).then(|| Vec3::new(v[0], v[1], v[2]))
}

pub fn parse_camera(s: &str) -> Result<(Vec3, Vec3), String> {
    let bad = || format!("'{s}' is not EX,EY,EZ:TX,TY,TZ (six numbers)");
    let (eye, target) = s.split_once(':').ok_or_else(bad)?;
    let (eye, target) = (parse_vec3(eye).ok_or_else(bad)?, parse_vec3(target).ok_or_else(bad)?);
    if (eye - target).length() < 1e-6 {
        return Err(format!("'{s}': eye and target are the same point"));
    }
    Ok((eye, target))
}

pub fn parse_render_scale(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if (0.25..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("'{s}': the render scale must be a number from 0.25 to 1")),
    }
}

pub fn parse_target_fps(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if (10.0..=144.0).contains(&v) => Ok(v),
        _ => Err(format!("'{s}': the target frame rate must be a number from 10 to 144")),
    }
}

pub fn parse_pan_deg(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() && v.abs() <= 45.0 => Ok(v),
        _ => Err(format!("'{s}': the pan must be a number of degrees per frame from -45 to 45")),
    }
}

pub fn parse_walk_cm(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() && v.abs() <= 100.0 => Ok(v),
        _ => Err(format!("'{s}': the walk must be a number of centimetres per frame from -100 to 100")),
    }
}

/// A patch edge in metres: from 2 mm (a frame's worth of patches grows as 1/edge²) to 1 m.
pub fn parse_patch_size(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if (0.002..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("'{s}': the patch size must be a number of metres from 0.002 to 1")),
    }
}

pub fn parse_fov(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v > 0.5 && v < 179.5 => Ok(v),
        _ => Err(format!("'{s}': field of view must be a number of degrees between 0.5 and 179.5")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes() {
        assert_eq!(parse_size("640x360"), Ok((640, 360)));
        assert!(parse_size("640").is_err());
        assert!(parse_size("0x10").is_err());
        assert!(parse_size("axb").is_err());
    }

    #[test]
    fn cameras() {
        let (e, t) = parse_camera("0,1,2:3,4,5").unwrap();
        assert_eq!((e, t), (Vec3::new(0.0, 1.0, 2.0), Vec3::new(3.0, 4.0, 5.0)));
        assert!(parse_camera("0,1:3,4,5").is_err());
        assert!(parse_camera("1,1,1:1,1,1").is_err());
        assert!(parse_camera("nan,1,1:0,0,0").is_err());
    }

    #[test]
    fn fovs() {
        assert_eq!(parse_fov("60"), Ok(60.0));
        assert!(parse_fov("0").is_err());
        assert!(parse_fov("180").is_err());
    }

    #[test]
    fn patch_sizes_are_metres_from_2_mm_to_1_m() {
        assert_eq!((parse_patch_size("0.02"), parse_patch_size("1")), (Ok(0.02), Ok(1.0)));
        for bad in ["0", "0.001", "2", "-0.02", "x", "nan"] {
            assert!(parse_patch_size(bad).unwrap_err().contains("0.002 to 1"), "{bad}");
        }
    }
}
