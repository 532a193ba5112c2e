//! Descriptors of graph resources, and their resolution against a view size.

/// How big a texture is: a fraction of the view, or fixed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SizeRule {
    ViewScaled(f32),
    /// The view scaled by the factor, but at least this many pixels high (and never larger than
    /// the view), keeping the aspect: for targets that must sample the scene finely enough
    /// whatever the output size.
    ViewScaledAtLeast(f32, u32),
    /// The view halved (rounding up) as many times as it stays at least as tall as
    /// `ViewScaledAtLeast(scale, min_height)`, at most `max_halvings` times: the coarsest mip
    /// of the view that still samples as finely as that target, for inputs subsampled to it.
    ViewHalvedToward(f32, u32, u32),
    Fixed(u32, u32),
}

impl SizeRule {
    /// The size in pixels for a view of `view` pixels (never 0).
    pub fn resolve(&self, view: (u32, u32)) -> (u32, u32) {
        match *self {
            SizeRule::ViewScaled(s) => {
                (((view.0 as f32 * s).round() as u32).max(1), ((view.1 as f32 * s).round() as u32).max(1))
            }
            SizeRule::ViewScaledAtLeast(s, min_height) => {
                let floor = (min_height as f32 / view.1.max(1) as f32).min(1.0);
                SizeRule::ViewScaled(s.max(floor)).resolve(view)
            }
            SizeRule::ViewHalvedToward(s, min_height, max_halvings) => {
                let k = SizeRule::halvings_toward(view, s, min_height, max_halvings);
                (view.0.max(1).div_ceil(1 << k), view.1.max(1).div_ceil(1 << k))
            }
            SizeRule::Fixed(w, h) => (w.max(1), h.max(1)),
        }
    }

    /// How many times [`SizeRule::ViewHalvedToward`] halves a view of `view` pixels.
    pub fn halvings_toward(view: (u32, u32), scale: f32, min_height: u32, max_halvings: u32) -> u32 {
        let target = SizeRule::ViewScaledAtLeast(scale, min_height).resolve(view).1;
        let mut k = 0;
        while k < max_halvings && view.1.max(1).div_ceil(1 << (k + 1)) >= target {
            k += 1;
        }
        k
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halving_toward_a_target_stops_before_it_gets_shorter() {
        let rule = |view| SizeRule::ViewHalvedToward(0.25, 90, 3).resolve(view);
        // 360 rows → 180 → 90: two halvings reach the 90-row target exactly.
        assert_eq!(rule((640, 360)), (160, 90));
        // 720 rows: a quarter is 180 rows, so two halvings; a third would give 90 < 180.
        assert_eq!(rule((1280, 720)), (320, 180));
        // 240 rows: the target is 90; 120 ≥ 90 but 60 < 90.
        assert_eq!(rule((320, 240)), (160, 120));
        assert_eq!(rule((160, 120)), (160, 120));
        assert_eq!(rule((1281, 721)), (321, 181));
        // Never more than max_halvings.
        assert_eq!(SizeRule::ViewHalvedToward(0.01, 1, 2).resolve((1024, 1024)), (256, 256));
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureDesc {
    pub format: wgpu::TextureFormat,
    pub size: SizeRule,
    pub usage: wgpu::TextureUsages,
    pub mip_levels: u32,
}

impl TextureDesc {
    /// A full-resolution render target that later passes sample (and tests can read back).
    pub fn target(format: wgpu::TextureFormat) -> Self {
        Self {
            format,
            size: SizeRule::ViewScaled(1.0),
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            mip_levels: 1,
        }
    }
    pub fn scaled(mut self, scale: f32) -> Self {
        self.size = SizeRule::ViewScaled(scale);
        self
    }
    pub fn fixed(mut self, width: u32, height: u32) -> Self {
        self.size = SizeRule::Fixed(width, height);
        self
    }
    pub fn usage(mut self, usage: wgpu::TextureUsages) -> Self {
        self.usage |= usage;
        self
    }
    pub fn mips(mut self, mip_levels: u32) -> Self {
        self.mip_levels = mip_levels.max(1);
        self
    }

    pub(crate) fn resolve(&self, view: (u32, u32)) -> ResolvedTexture {
        let (width, height) = self.size.resolve(view);
        ResolvedTexture { format: self.format, width, height, usage: self.usage, mip_levels: self.mip_levels }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BufferDesc {
    pub size: u64,
    pub usage: wgpu::BufferUsages,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ResourceDesc {
    Texture(TextureDesc),
    Buffer(BufferDesc),
}

/// A descriptor with concrete sizes: the pool's key.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ResolvedTexture {
    pub format: wgpu::TextureFormat,
    pub width: u32,
    pub height: u32,
    pub usage: wgpu::TextureUsages,
    pub mip_levels: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ResolvedDesc {
    Texture(ResolvedTexture),
    Buffer(BufferDesc),
}

impl ResourceDesc {
    pub(crate) fn resolve(&self, view: (u32, u32)) -> ResolvedDesc {
        match self {
            ResourceDesc::Texture(t) => ResolvedDesc::Texture(t.resolve(view)),
            ResourceDesc::Buffer(b) => ResolvedDesc::Buffer(*b),
        }
    }
}
