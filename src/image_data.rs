//! CPU-side RGBA images: PNG textures read with limits, and PNG output written with a
//! clear error when the path is not writable.

use std::path::Path;

use crate::error::{Error, Result};

/// The largest texture side we accept; a tiny corrupt file cannot claim gigabytes.
pub const MAX_TEXTURE_SIDE: u32 = 16384;
/// The most memory a texture's decoding may allocate.
pub const MAX_TEXTURE_BYTES: u64 = 512 * 1024 * 1024;

/// An RGBA8 image, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct ImageData {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
}

impl ImageData {
    /// Decodes a PNG file, rejecting absurd dimensions before allocating for them.
    pub fn load_png(path: &Path) -> Result<ImageData> {
        let bytes = std::fs::read(path)
            .map_err(|e| Error::file(path, format!("cannot read texture: {e}")))?;
        Self::decode_png(path, &bytes)
    }

    /// Decodes PNG bytes; `path` only names the source in errors.
    pub fn decode_png(path: &Path, bytes: &[u8]) -> Result<ImageData> {
        let mut reader =
            image::ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Png);
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(MAX_TEXTURE_SIDE);
        limits.max_image_height = Some(MAX_TEXTURE_SIDE);
        limits.max_alloc = Some(MAX_TEXTURE_BYTES);
        reader.limits(limits);
        let image = reader.decode().map_err(|e| {
            let expected = match e {
                // Only a size problem gets the size limit in its message.
                image::ImageError::Limits(_) => format!(
                    "expected a PNG of at most {MAX_TEXTURE_SIDE}x{MAX_TEXTURE_SIDE} pixels"
                ),
                _ => "expected a complete PNG file".to_string(),
            };
            Error::file(
                path,
                format!("not a readable PNG texture ({e}); {expected}"),
            )
        })?;
        let rgba = image.to_rgba8();
        Ok(ImageData {
            width: rgba.width(),
            height: rgba.height(),
            rgba: rgba.into_raw(),
        })
    }

    /// Writes the image as a PNG, creating no directories; the error names the path.
    pub fn save_png(&self, path: &Path) -> Result<()> {
        save_png(
            path,
            self.width,
            self.height,
            image::ColorType::Rgba8,
            &self.rgba,
        )
    }
}

impl ImageData {
    /// A procedural wood-like texture (LearnOpenGL's floor is wood; we draw ours rather than
    /// download one): warm planks with rings and a dark seam between boards.
    pub fn wood(size: u32) -> ImageData {
        let mut rgba = Vec::with_capacity((size * size * 4) as usize);
        for y in 0..size {
            for x in 0..size {
                let (u, v) = (x as f32 / size as f32, y as f32 / size as f32);
                let plank = (u * 4.0).floor();
                let along = v + plank * 0.37;
                let rings = ((u * 4.0).fract() * 9.0 + (along * std::f32::consts::TAU).sin() * 1.7)
                    .sin()
                    * 0.5
                    + 0.5;
                let grain = ((along * 90.0 + plank * 13.0).sin() * 0.5 + 0.5) * 0.15;
                let seam = if (u * 4.0).fract() < 0.03 { 0.55 } else { 1.0 };
                let t = (0.65 + 0.25 * rings - grain) * seam;
                let c = |base: f32| (base * t * 255.0).clamp(0.0, 255.0) as u8;
                rgba.extend_from_slice(&[c(0.78), c(0.55), c(0.33), 255]);
            }
        }
        ImageData {
            width: size,
            height: size,
            rgba,
        }
    }
}

/// Writes an 8-bit grey image as a PNG.
pub fn save_grey_png(path: &Path, width: u32, height: u32, grey: &[u8]) -> Result<()> {
    save_png(path, width, height, image::ColorType::L8, grey)
}

fn save_png(path: &Path, width: u32, height: u32, ty: image::ColorType, data: &[u8]) -> Result<()> {
    let file = std::fs::File::create(path)
        .map_err(|e| Error::file(path, format!("cannot write the image: {e}")))?;
    let encoder = image::codecs::png::PngEncoder::new(std::io::BufWriter::new(file));
    image::ImageEncoder::write_image(encoder, data, width, height, ty.into())
        .map_err(|e| Error::file(path, format!("cannot write the image: {e}")))
}
