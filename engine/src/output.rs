//! Writing rendered views to disk: PNG for pictures, OpenEXR (float RGB) for linear values.

use std::path::Path;

use anyhow::{bail, Context};

use crate::headless::{ImageKind, RenderedImage};

/// The picture kind a file name asks for: `.png` → display, `.exr` → linear.
pub fn kind_for_path(path: &Path) -> anyhow::Result<ImageKind> {
    let ext = path.extension().and_then(|e| e.to_str()).map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("png") => Ok(ImageKind::Display),
        Some("exr") => Ok(ImageKind::Linear),
        _ => bail!("{}: unsupported output extension (expected .png or .exr)", path.display()),
    }
}

pub fn save(image: &RenderedImage, path: &Path) -> anyhow::Result<()> {
    match image {
        RenderedImage::Display(img) => img.save_with_format(path, image::ImageFormat::Png),
        RenderedImage::Linear(img) => {
            let rgb = image::DynamicImage::ImageRgba32F(img.clone()).into_rgb32f();
            rgb.save_with_format(path, image::ImageFormat::OpenExr)
        }
    }
    .with_context(|| format!("{}: could not write image", path.display()))
}
