//! Image files to [`Texture`]s (RGBA8, sRGB-encoded, top-left origin).
//!
//! Decoding goes through the `image` crate with size limits set *before* decoding, so a
//! header claiming 100000×100000 pixels is refused without allocating anything.

use std::io::Cursor;
use std::path::Path;

use image::{DynamicImage, ImageError, ImageFormat, ImageReader, Limits};

use crate::error::{one_line, LoadError, LoadErrorKind};
use crate::limits::MAX_TEXTURE_SIZE;
use crate::sources::Sources;
use crate::Texture;

/// Most bytes the decoder may allocate: an 8192² RGBA image of 16-bit channels needs 512 MiB.
const MAX_DECODE_ALLOC: u64 = 1 << 30;

/// Loads a PNG, JPEG or EXR file as a texture. The texture is named after the file.
pub fn load_texture(path: &Path) -> Result<Texture, LoadError> {
    let bytes = Sources::new(None).read(path)?;
    decode_texture(&bytes, path, "", file_label(path))
}

/// Converts a decoded image to an RGBA8 sRGB texture.
///
/// 8- and 16-bit images are taken as already sRGB-encoded (the PNG/JPEG convention, and what
/// glTF requires of base colour textures); float images (EXR) hold linear values, which are
/// encoded to sRGB here so that every [`Texture`] means the same thing.
pub fn texture_from_image(name: impl Into<String>, image: DynamicImage) -> Texture {
    let (width, height) = (image.width(), image.height());
    let rgba8 = match image {
        DynamicImage::ImageRgb32F(_) | DynamicImage::ImageRgba32F(_) => image
            .to_rgba32f()
            .pixels()
            .flat_map(|p| [linear_to_srgb8(p[0]), linear_to_srgb8(p[1]), linear_to_srgb8(p[2]), unorm8(p[3])])
            .collect(),
        other => other.to_rgba8().into_raw(),
    };
    Texture { name: name.into(), width, height, rgba8 }
}

/// Decodes `bytes` (named `path` in errors; `what` says which image inside that file, or "")
/// into a texture called `name`.
pub(crate) fn decode_texture(bytes: &[u8], path: &Path, what: &str, name: String) -> Result<Texture, LoadError> {
    Ok(texture_from_image(name, decode_image(bytes, path, what, MAX_TEXTURE_SIZE)?))
}

/// Decodes an image of at most `max_side` pixels across and down, guessing the format from its
/// first bytes and then from the extension.
pub(crate) fn decode_image(bytes: &[u8], path: &Path, what: &str, max_side: u32) -> Result<DynamicImage, LoadError> {
    let prefix = if what.is_empty() { String::new() } else { format!("{what}: ") };
    let err = |msg: String| LoadError::new(path, LoadErrorKind::Image(format!("{prefix}{msg}")));

    let mut reader = ImageReader::new(Cursor::new(bytes)).with_guessed_format().map_err(|e| err(one_line(e)))?;
    if reader.format().is_none() {
        if let Some(format) = path.extension().and_then(ImageFormat::from_extension) {
            reader.set_format(format);
        }
    }
    if reader.format().is_none() {
        return Err(err("unrecognised image format (supported: PNG, JPEG, EXR)".into()));
    }
    let mut limits = Limits::default();
    limits.max_image_width = Some(max_side);
    limits.max_image_height = Some(max_side);
    limits.max_alloc = Some(MAX_DECODE_ALLOC);
    reader.limits(limits);

    let image = reader.decode().map_err(|e| match e {
        ImageError::Limits(_) => LoadError::too_large(
            path,
            format!("{prefix}image exceeds {max_side}x{max_side} pixels or {MAX_DECODE_ALLOC} bytes"),
        ),
        other => err(one_line(other)),
    })?;
    // Decoders that ignore limits are caught here, after the fact.
    if image.width() > max_side || image.height() > max_side {
        return Err(LoadError::too_large(
            path,
            format!("{prefix}image is {}x{} pixels (limit {max_side})", image.width(), image.height()),
        ));
    }
    if image.width() == 0 || image.height() == 0 {
        return Err(err("image has no pixels".into()));
    }
    Ok(image)
}

/// A texture name for a file: its file name, as a modder would recognise it.
pub(crate) fn file_label(path: &Path) -> String {
    path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
}

fn unorm8(v: f32) -> u8 {
    // NaN clamps to 0 (`as` saturates and maps NaN to 0).
    (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
}

fn linear_to_srgb8(v: f32) -> u8 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    let s = if v <= 0.003_130_8 { v * 12.92 } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 };
    unorm8(s)
}
