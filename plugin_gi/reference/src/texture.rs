//! A material's textures on the CPU, sampled as the G-buffer pass samples them at full size:
//! decoded to linear (sRGB colour images, linear metallic-roughness ones), wrapped by the
//! sampler's modes and filtered by its magnification filter.

use engine::scene::{Filter, Sampler, Texture, TextureRef, Wrap};

/// Linear RGBA texels of one image, row-major from the top-left.
pub(crate) struct LinearTexture {
    width: u32,
    height: u32,
    texels: Vec<[f32; 4]>,
}

/// sRGB-encoded byte → linear, the exact curve an `Rgba8UnormSrgb` texture decodes by.
fn srgb_to_linear(b: u8) -> f32 {
    let c = b as f32 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

impl LinearTexture {
    /// Decodes `t`: rgb through the sRGB curve when `srgb` (alpha is always linear), else as is.
    pub(crate) fn decode(t: &Texture, srgb: bool) -> Self {
        let table: Vec<f32> = (0..=255u8).map(|b| if srgb { srgb_to_linear(b) } else { b as f32 / 255.0 }).collect();
        let texels = t
            .rgba8
            .chunks_exact(4)
            .map(|p| [table[p[0] as usize], table[p[1] as usize], table[p[2] as usize], p[3] as f32 / 255.0])
            .collect::<Vec<_>>();
        if t.width == 0 || t.height == 0 || texels.len() != (t.width * t.height) as usize {
            // The loaders never make one; sample it as the renderer's missing texture, white.
            return Self { width: 1, height: 1, texels: vec![[1.0; 4]] };
        }
        Self { width: t.width, height: t.height, texels }
    }

    /// The texel `i`, `j` after wrapping.
    fn texel(&self, i: i64, j: i64, sampler: &Sampler) -> [f32; 4] {
        let x = wrap(i, self.width as i64, sampler.wrap_u);
        let y = wrap(j, self.height as i64, sampler.wrap_v);
        self.texels[(y * self.width as i64 + x) as usize]
    }

    /// The image at `uv` (texel centres at +0.5), the full-size level.
    pub(crate) fn sample(&self, uv: [f32; 2], sampler: &Sampler) -> [f32; 4] {
        let x = uv[0] * self.width as f32;
        let y = uv[1] * self.height as f32;
        match sampler.mag_filter {
            Filter::Nearest => self.texel(x.floor() as i64, y.floor() as i64, sampler),
            Filter::Linear => {
                let (x, y) = (x - 0.5, y - 0.5);
                let (x0, y0) = (x.floor(), y.floor());
                let (fx, fy) = (x - x0, y - y0);
                let (i, j) = (x0 as i64, y0 as i64);
                let [a, b, c, d] =
                    [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)].map(|(i, j)| self.texel(i, j, sampler));
                std::array::from_fn(|k| {
                    let top = a[k] + (b[k] - a[k]) * fx;
                    let bottom = c[k] + (d[k] - c[k]) * fx;
                    top + (bottom - top) * fy
                })
            }
        }
    }
}

fn wrap(i: i64, n: i64, mode: Wrap) -> i64 {
    match mode {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::ClampToEdge => i.clamp(0, n - 1),
        Wrap::MirroredRepeat => {
            let m = i.rem_euclid(2 * n);
            if m >= n {
                2 * n - 1 - m
            } else {
                m
            }
        }
    }
}

/// The coordinates a texture slot reads: its uv set (0 or 1) through its transform, as
/// `texture_uv` in shaders/scene_surface.wgsl.
pub(crate) fn slot_uv(slot: &TextureRef, uv0: [f32; 2], uv1: [f32; 2]) -> [f32; 2] {
    slot.transform.apply(if slot.tex_coord == 1 { uv1 } else { uv0 })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texture(w: u32, h: u32, values: &[u8]) -> Texture {
        let rgba8 = values.iter().flat_map(|&v| [v, v, v, 255]).collect();
        Texture { name: "t".into(), width: w, height: h, rgba8 }
    }

    #[test]
    fn srgb_decodes_by_the_standard_curve() {
        assert_eq!(srgb_to_linear(0), 0.0);
        assert_eq!(srgb_to_linear(255), 1.0);
        assert!((srgb_to_linear(188) - 0.5029).abs() < 1e-3);
        let t = LinearTexture::decode(&texture(1, 1, &[188]), false);
        assert!((t.texels[0][0] - 188.0 / 255.0).abs() < 1e-6, "linear images stay as they are");
    }

    #[test]
    fn bilinear_sampling_wraps_by_the_samplers_modes() {
        let t = LinearTexture::decode(&texture(2, 1, &[0, 255]), false);
        let repeat = Sampler::default();
        let clamp = Sampler { wrap_u: Wrap::ClampToEdge, wrap_v: Wrap::ClampToEdge, ..Sampler::default() };
        let mirror = Sampler { wrap_u: Wrap::MirroredRepeat, ..Sampler::default() };
        assert_eq!(t.sample([0.25, 0.5], &repeat)[0], 0.0, "a texel centre");
        assert_eq!(t.sample([0.5, 0.5], &repeat)[0], 0.5, "half way");
        // At u = 0 the left texel blends with its wrapped neighbour: the right one, itself, or
        // the mirror image of itself.
        assert_eq!(t.sample([0.0, 0.5], &repeat)[0], 0.5);
        assert_eq!(t.sample([0.0, 0.5], &clamp)[0], 0.0);
        assert_eq!(t.sample([0.0, 0.5], &mirror)[0], 0.0);
        assert_eq!(t.sample([1.25, 0.5], &repeat)[0], 0.0, "repeats");
        assert_eq!(t.sample([1.25, 0.5], &mirror)[0], 1.0, "mirrors");
        let nearest = Sampler { mag_filter: Filter::Nearest, ..Sampler::default() };
        assert_eq!(t.sample([0.49, 0.5], &nearest)[0], 0.0);
        assert_eq!(t.sample([0.51, 0.5], &nearest)[0], 1.0);
    }
}
