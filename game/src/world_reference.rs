//! The world-fixed reference of a frame (`render --view reference`, `bench`): the exact one
//! bounce of the headlamp's light from patches fixed in the level (the `gi-reference` crate),
//! onto the frame's own pixel centres. The receivers come from the renderer's public views,
//! `albedo`, `normal` and `depth`, rendered linear: each pixel's world position is rebuilt from
//! the camera and its view depth.

use std::time::Instant;

use anyhow::anyhow;
use engine::camera::Camera;
use engine::frame::ViewState;
use engine::glam::{DVec3, Vec3};
use engine::gpu::Gpu;
use engine::headless::{HeadlessTarget, ImageKind, RenderedImage};
use engine::renderer::Renderer;
use engine::scene::Scene;
use gi_reference::{Lamp, Receiver, World};

/// The views a receiver is read from.
const RECEIVER_VIEWS: [&str; 3] = ["albedo", "normal", "depth"];

/// The reference of one frame.
pub struct ReferenceFrame {
    /// Linear radiance L = ρ/π · E (W·sr⁻¹·m⁻²); black where nothing was evaluated.
    pub image: image::Rgba32FImage,
    /// Patches the lamp lit.
    pub lit_patches: usize,
    /// Receivers evaluated (pixels with a surface, inside the mask).
    pub receivers: usize,
    /// Wall-clock seconds for the lit patches and for the sum over them (not the receivers'
    /// rendering).
    pub patch_seconds: f64,
    pub sum_seconds: f64,
}

impl ReferenceFrame {
    pub fn seconds(&self) -> f64 {
        self.patch_seconds + self.sum_seconds
    }
}

/// The texels a side of each receiver's visibility cube (`gi_reference::VisibilityCube`).
/// The cube only nominates the triangles that may hide a sender, each then tested exactly: its
/// size sets the cost; 128 and 256 give the same Cellar image (to 7e-6 of its mean).
pub const VISIBILITY_CUBE: usize = 128;

/// The level cut into patches, and a renderer for the receivers.
pub struct WorldReference {
    world: World,
    renderer: Renderer,
    target: Option<((u32, u32), HeadlessTarget)>,
    /// Whether each sender–receiver pair is tested for occlusion (`reference_vis`).
    visibility: bool,
}

impl WorldReference {
    pub fn new(gpu: &Gpu, scene: &Scene) -> anyhow::Result<Self> {
        // The receivers' views are the engine's; the GI is not needed for them.
        let (plugins, _) = crate::plugins(plugin_gi::GiSettings { enabled: false, ..plugin_gi::GiSettings::default() });
        let renderer = Renderer::new(gpu, scene, plugins)?;
        Ok(Self { world: World::new(scene), renderer, target: None, visibility: false })
    }

    /// From now on, tests every sender–receiver pair for occlusion by the level's triangles:
    /// the visibility-correct reference (`render --view reference_vis`).
    pub fn with_visibility(mut self) -> Self {
        self.visibility = true;
        self
    }

    pub fn world(&self) -> &World {
        &self.world
    }

    /// Every pixel of `view` at `size` as a receiver, row by row (no surface: a zero normal).
    pub fn receivers(&mut self, gpu: &Gpu, view: &ViewState, size: (u32, u32)) -> anyhow::Result<Vec<Receiver>> {
        if self.target.as_ref().is_none_or(|(s, _)| *s != size) {
            self.target = Some((size, HeadlessTarget::new(gpu, size.0, size.1, ImageKind::Linear)));
        }
        let target = &self.target.as_ref().expect("made above").1;
        let mut images = Vec::with_capacity(3);
        for name in RECEIVER_VIEWS {
            self.renderer.set_view(name).map_err(|e| anyhow!(e))?;
            match target.render(gpu, &mut self.renderer, view)? {
                RenderedImage::Linear(img) => images.push(img),
                RenderedImage::Display(_) => unreachable!("a linear target"),
            }
        }
        Ok(receivers_from_views(&view.camera, &images[0], &images[1], &images[2]))
    }

    /// The reference radiance of `view` at the receivers' pixels (a `size` frame, row by row),
    /// evaluated only where `mask` is true (every pixel without one), with patches of at most
    /// `max_edge` metres.
    pub fn evaluate(
        &self,
        view: &ViewState,
        size: (u32, u32),
        receivers: &[Receiver],
        mask: Option<&[bool]>,
        max_edge: f32,
    ) -> ReferenceFrame {
        let (w, h) = size;
        assert_eq!(receivers.len(), (w * h) as usize, "one receiver a pixel");
        let start = Instant::now();
        let lamp = Lamp::new(&view.headlamp, &view.camera, w as f32 / h as f32);
        let lit = self.world.lit(&lamp, max_edge);
        let patch_seconds = start.elapsed().as_secs_f64();
        let chosen: Vec<usize> =
            (0..receivers.len()).filter(|&i| mask.is_none_or(|m| m[i]) && receivers[i].normal != Vec3::ZERO).collect();
        let picked: Vec<Receiver> = chosen.iter().map(|&i| receivers[i]).collect();
        let radiance = if self.visibility {
            lit.radiance_visible(&picked, &self.world.occluders(), VISIBILITY_CUBE)
        } else {
            lit.radiance(&picked)
        };
        let sum_seconds = start.elapsed().as_secs_f64() - patch_seconds;
        let mut image = image::Rgba32FImage::from_pixel(w, h, image::Rgba([0.0, 0.0, 0.0, 1.0]));
        for (&i, l) in chosen.iter().zip(&radiance) {
            image.put_pixel(i as u32 % w, i as u32 / w, image::Rgba([l[0], l[1], l[2], 1.0]));
        }
        ReferenceFrame { image, lit_patches: lit.len(), receivers: chosen.len(), patch_seconds, sum_seconds }
    }

    /// [`WorldReference::receivers`] then [`WorldReference::evaluate`] over the whole frame.
    pub fn render(
        &mut self,
        gpu: &Gpu,
        view: &ViewState,
        size: (u32, u32),
        max_edge: f32,
    ) -> anyhow::Result<ReferenceFrame> {
        let receivers = self.receivers(gpu, view, size)?;
        Ok(self.evaluate(view, size, &receivers, None, max_edge))
    }
}

/// Receivers from linear `albedo`, `normal` and `depth` views of `camera`: each pixel centre's
/// world position at its view depth along the camera's ray through it (from the inverse
/// view-projection, in double precision), the unit normal and ρ as the G-buffer holds them.
/// Depth 0 (no surface) gives a zero normal.
pub fn receivers_from_views(
    camera: &Camera,
    albedo: &image::Rgba32FImage,
    normal: &image::Rgba32FImage,
    depth: &image::Rgba32FImage,
) -> Vec<Receiver> {
    let (w, h) = depth.dimensions();
    assert!(albedo.dimensions() == (w, h) && normal.dimensions() == (w, h), "three views of one size");
    let inverse = camera.view_projection(w as f32 / h as f32).as_dmat4().inverse();
    let view = camera.view_matrix().as_dmat4();
    let view_depth = |p: DVec3| -view.transform_point3(p).z;
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let d = depth.get_pixel(x, y)[0] as f64;
            let n = Vec3::from_slice(&normal.get_pixel(x, y).0[..3]);
            if d <= 0.0 || n == Vec3::ZERO {
                out.push(Receiver { position: Vec3::ZERO, normal: Vec3::ZERO, albedo: Vec3::ZERO });
                continue;
            }
            let ndc_x = (x as f64 + 0.5) / w as f64 * 2.0 - 1.0;
            let ndc_y = 1.0 - (y as f64 + 0.5) / h as f64 * 2.0;
            // Two points on the pixel's ray (reversed depth: 1 is the near plane), and the point
            // at the view depth between them (view depth is affine along any ray).
            let near = inverse.project_point3(DVec3::new(ndc_x, ndc_y, 1.0));
            let mid = inverse.project_point3(DVec3::new(ndc_x, ndc_y, 0.5));
            let (dn, dm) = (view_depth(near), view_depth(mid));
            let position = near + (mid - near) * ((d - dn) / (dm - dn));
            let albedo = Vec3::from_slice(&albedo.get_pixel(x, y).0[..3]);
            out.push(Receiver { position: position.as_vec3(), normal: n.normalize_or_zero(), albedo });
        }
    }
    out
}

/// A linear radiance image as the present pass shows it: × exposure, ACES (Narkowicz's fit),
/// sRGB-encoded.
pub fn tonemap(linear: &image::Rgba32FImage, exposure: f32) -> image::RgbaImage {
    let aces = |x: f32| ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0);
    let srgb = |c: f32| if c <= 0.0031308 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    image::RgbaImage::from_fn(linear.width(), linear.height(), |x, y| {
        let p = linear.get_pixel(x, y);
        let c = |k: usize| (srgb(aces(p[k] * exposure)) * 255.0 + 0.5).clamp(0.0, 255.0) as u8;
        image::Rgba([c(0), c(1), c(2), 255])
    })
}
