//! Descriptors of graph resources, and their resolution against a view size.

/// How big a texture is: a fraction of the view, or fixed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SizeRule {
    ViewScaled(f32),
    /// The view scaled by the factor, but at least this many pixels high (and never larger than
    /// the view), keeping the aspect: for targets that must sample the scene finely enough
    /// whatever the output size.
    ViewScaledAtLeast(f32, u32),
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
            SizeRule::Fixed(w, h) => (w.max(1), h.max(1)),
        }
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
