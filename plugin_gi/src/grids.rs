//! Where the receivers' grid (the indirect target's samples) and the senders' grid (the flux
//! G-buffer's blocks of lamp-view texels) lie in the frame. Both turn with the camera: they
//! move with the picture, by as many pixels as its centre has moved since the camera looked
//! down −Z level, and step back whole cells at a time. So as the view turns, each receiver and
//! each sender keeps to its world point (exactly at the centre of the view, within the lens's
//! distortion elsewhere) instead of sliding over the surfaces. Grids fixed to the screen
//! resampled a fold's sharp light at a new place every frame, and that was most of the GI's
//! shimmer on a pan. Walking still moves the samples (parallax), as it moves the picture.

use engine::camera::Camera;
use engine::glam::Vec3;

/// Flux G-buffer blocks added before the view on each axis: the senders' grid steps back this
/// many blocks at a time, so the pyramid's four finest levels keep their grouping as it does.
pub(crate) const SENDER_PAD: u32 = 8;

/// The receivers' grid's steps are kept mod this: a multiple of every interleave side (1 to 4),
/// so each receiver keeps its class as the grid steps.
pub(crate) const RECEIVER_PERIOD: u32 = 12;

/// Added to the senders' grid's steps so that they stay positive in their 16 bits: a turn moves
/// the picture by a few thousand pixels at most, a few hundred periods.
pub(crate) const SENDER_STEPS_OFFSET: u32 = 2048;

/// The grids of one frame (GiParams' `receiver_offset`, `sender_offset`, `receiver_steps`,
/// `sender_steps`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Grids {
    /// The receivers' shift, in cells, −½ to ½ each way.
    pub receiver_offset: [f32; 2],
    /// How many lamp-view texels before the view's corner the flux G-buffer's first block
    /// begins, 0 to SENDER_PAD blocks (0 where its texels are single lamp-view texels).
    pub sender_offset: [f32; 2],
    /// The whole cells the receivers' grid has stepped back, mod RECEIVER_PERIOD, across and
    /// down: the gather's 2×2 interleave pattern follows their parity and the article's N×N
    /// sub-images them, so a world point keeps its class.
    pub receiver_steps: [u32; 2],
    /// The whole periods (SENDER_PAD blocks) the senders' grid has stepped back, plus
    /// SENDER_STEPS_OFFSET, across and down: each moves the content of the flux G-buffer
    /// SENDER_PAD blocks on, and the article's lights keep their subsets by it.
    pub sender_steps: [u32; 2],
}

impl Grids {
    /// For `camera` rendering `size` pixels, an indirect target of `indirect` samples and flux
    /// blocks of `block`×`block` texels (1: the senders are the lamp view's own texels).
    pub fn of(camera: &Camera, size: (u32, u32), indirect: (u32, u32), block: u32) -> Self {
        let Some(fov_y) = camera.fov_y() else {
            return Self::default();
        };
        let forward = (camera.rotation * Vec3::NEG_Z).as_dvec3();
        // Yaw: positive turns left and the picture moves right; pitch: positive looks up and
        // the picture moves down (pixel rows grow downwards).
        let yaw = (-forward.x).atan2(-forward.z);
        let pitch = forward.y.clamp(-1.0, 1.0).asin();
        let pixels_per_radian = f64::from(size.1) * 0.5 / (f64::from(fov_y) * 0.5).tan();
        let moved = [yaw * pixels_per_radian, pitch * pixels_per_radian];
        let cell = [f64::from(size.0) / f64::from(indirect.0.max(1)), f64::from(size.1) / f64::from(indirect.1.max(1))];
        let cells = |i: usize| moved[i] / cell[i] + 0.5;
        let period = f64::from(block * SENDER_PAD);
        let senders = |i: usize| if block > 1 { (period - moved[i].rem_euclid(period)) as f32 } else { 0.0 };
        Self {
            receiver_offset: [(cells(0).rem_euclid(1.0) - 0.5) as f32, (cells(1).rem_euclid(1.0) - 0.5) as f32],
            sender_offset: [senders(0), senders(1)],
            receiver_steps: [0, 1].map(|i| cells(i).floor().rem_euclid(f64::from(RECEIVER_PERIOD)) as u32),
            sender_steps: [0, 1].map(|i| {
                if block > 1 {
                    ((moved[i] / period).floor() + f64::from(SENDER_STEPS_OFFSET)) as u32
                } else {
                    SENDER_STEPS_OFFSET
                }
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FOV: f32 = std::f32::consts::FRAC_PI_2;
    // 360 rows at a 90° vertical field of view: 180 pixels a radian at the centre.
    const SIZE: (u32, u32) = (640, 360);
    const LOW: (u32, u32) = (160, 90);

    fn turned(yaw_pixels: f64, pitch_pixels: f64) -> Camera {
        let radians = |pixels: f64| (pixels / 180.0) as f32;
        Camera::from_yaw_pitch(Vec3::new(1.0, 2.0, 3.0), radians(yaw_pixels), radians(pitch_pixels), FOV)
    }

    #[test]
    fn the_grids_move_with_the_picture_and_step_back_a_cell_at_a_time() {
        let level = Grids::of(&turned(0.0, 0.0), SIZE, LOW, 4);
        assert_eq!(level.receiver_offset, [0.0, 0.0]);
        assert_eq!(level.receiver_steps, [0, 0]);
        // Blocks of 4 texels: the senders' grid begins SENDER_PAD blocks before the view.
        assert_eq!(level.sender_offset, [32.0, 32.0]);
        // Turned left by one pixel (a quarter of a 4-pixel cell): the picture moved right, and
        // so did both grids.
        let left = Grids::of(&turned(1.0, 0.0), SIZE, LOW, 4);
        assert!((left.receiver_offset[0] - 0.25).abs() < 1e-4, "{left:?}");
        assert!((left.sender_offset[0] - 31.0).abs() < 1e-3, "{left:?}");
        // Three pixels: past half a cell the receivers step back a cell.
        let further = Grids::of(&turned(3.0, 0.0), SIZE, LOW, 4);
        assert!((further.receiver_offset[0] + 0.25).abs() < 1e-4, "{further:?}");
        assert_eq!(further.receiver_steps, [1, 0]);
        // Turned right by as much: a cell the other way, mod the period.
        assert_eq!(Grids::of(&turned(-3.0, 0.0), SIZE, LOW, 4).receiver_steps, [RECEIVER_PERIOD - 1, 0]);
        // Looking up moves the picture down, rows likewise.
        let up = Grids::of(&turned(0.0, 1.0), SIZE, LOW, 4);
        assert!((up.receiver_offset[1] - 0.25).abs() < 1e-4, "{up:?}");
        assert!((up.sender_offset[1] - 31.0).abs() < 1e-3, "{up:?}");
        // A whole period of blocks (32 pixels) later both grids are where they were after one
        // pixel.
        let period = Grids::of(&turned(33.0, 0.0), SIZE, LOW, 4);
        let offset = SENDER_STEPS_OFFSET;
        assert_eq!((level.sender_steps, period.sender_steps), ([offset, offset], [offset + 1, offset]));
        assert!((period.sender_offset[0] - 31.0).abs() < 1e-3, "{period:?}");
        assert!((period.receiver_offset[0] - 0.25).abs() < 1e-4, "{period:?}");
        assert_eq!(period.receiver_steps, [8, 0], "32 pixels are 8 cells more");
    }

    /// Each receiver keeps its class only where the period is a whole number of patterns.
    #[test]
    fn every_interleave_side_the_settings_allow_divides_the_receivers_period() {
        for name in ["interleave", "article_interleave"] {
            let info = crate::GiSettings::FIELDS.iter().find(|f| f.name == name).expect("a setting");
            for side in info.min as u32..=info.max as u32 {
                assert_eq!(RECEIVER_PERIOD % side, 0, "gi.{name} = {side}");
            }
        }
    }

    /// The senders' grid steps whole nodes of pyramid level GROUP_LEVELS, so its four finest
    /// levels (to GROUP_LEVELS) keep their grouping.
    #[test]
    fn the_senders_pad_is_whole_pyramid_workgroups() {
        assert_eq!(SENDER_PAD % crate::passes::GROUP_SIDE, 0);
    }

    #[test]
    fn single_texel_senders_and_orthographic_views_stay_put() {
        assert_eq!(Grids::of(&turned(5.0, 7.0), SIZE, LOW, 1).sender_offset, [0.0, 0.0]);
        let mut camera = turned(5.0, 7.0);
        camera.projection = engine::camera::CameraProjection::Orthographic { half_height: 4.0 };
        assert_eq!(Grids::of(&camera, SIZE, LOW, 4), Grids::default());
    }
}
