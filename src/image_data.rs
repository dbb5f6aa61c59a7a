//! CPU-side RGBA images: PNG textures read with limits (a regular file, a bounded size, a
//! decoded-memory budget checked from the header), and PNG output written through
//! [`crate::output::write_file`], so a failed write is an error naming the path.

use std::io::Read;
use std::path::Path;

use crate::error::{Error, Result};

/// The largest texture side we accept; a tiny corrupt file cannot claim gigabytes.
pub const MAX_TEXTURE_SIDE: u32 = 16384;
/// The most memory a texture's decoding may allocate.
pub const MAX_TEXTURE_BYTES: u64 = 512 * 1024 * 1024;
/// The most a decoded texture may take as RGBA (and its decoder's own buffer): checked from
/// the PNG header, before anything is decoded.
pub const TEXTURE_BUDGET_BYTES: u64 = 256 * 1024 * 1024;
/// The largest PNG file read; more is refused before reading.
pub const MAX_PNG_FILE_BYTES: u64 = 64 * 1024 * 1024;

const MIB: u64 = 1024 * 1024;

/// An RGBA8 image, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct ImageData {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
}

impl ImageData {
    /// Reads and decodes a PNG file. Only a regular file of at most [`MAX_PNG_FILE_BYTES`] is
    /// read (a FIFO or a device could block or never end).
    pub fn load_png(path: &Path) -> Result<ImageData> {
        let bytes = read_png_file(path)?;
        Self::decode_png(path, &bytes)
    }

    /// Decodes PNG bytes; `path` only names the source in errors. The header's size is
    /// checked against [`MAX_TEXTURE_SIDE`] and [`TEXTURE_BUDGET_BYTES`] before decoding.
    pub fn decode_png(path: &Path, bytes: &[u8]) -> Result<ImageData> {
        let unreadable = |e: image::ImageError| {
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
        };
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(MAX_TEXTURE_SIDE);
        limits.max_image_height = Some(MAX_TEXTURE_SIDE);
        limits.max_alloc = Some(MAX_TEXTURE_BYTES);
        let decoder =
            image::codecs::png::PngDecoder::with_limits(std::io::Cursor::new(bytes), limits)
                .map_err(unreadable)?;
        let (width, height) = image::ImageDecoder::dimensions(&decoder);
        let rgba_bytes = u64::from(width) * u64::from(height) * 4;
        let needed = rgba_bytes.max(image::ImageDecoder::total_bytes(&decoder));
        if needed > TEXTURE_BUDGET_BYTES {
            return Err(Error::file(
                path,
                format!(
                    "not a usable PNG texture: {width}x{height} pixels take {} MiB decoded, over \
                     the {} MiB budget for a texture; expected at most {} pixels (e.g. 8192x8192)",
                    needed.div_ceil(MIB),
                    TEXTURE_BUDGET_BYTES / MIB,
                    TEXTURE_BUDGET_BYTES / 4
                ),
            ));
        }
        let image = image::DynamicImage::from_decoder(decoder).map_err(unreadable)?;
        let rgba = image.to_rgba8();
        Ok(ImageData {
            width: rgba.width(),
            height: rgba.height(),
            rgba: rgba.into_raw(),
        })
    }

    /// The image as PNG bytes (to write later, with the other outputs of a command).
    pub fn encode_png(&self) -> Result<Vec<u8>> {
        encode_png(self.width, self.height, image::ColorType::Rgba8, &self.rgba)
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

/// The bytes of a PNG texture file: a regular file, at most [`MAX_PNG_FILE_BYTES`] long.
fn read_png_file(path: &Path) -> Result<Vec<u8>> {
    let cannot = |e: std::io::Error| Error::file(path, format!("cannot read texture: {e}"));
    let meta = std::fs::metadata(path).map_err(cannot)?;
    if !meta.is_file() {
        return Err(Error::file(
            path,
            "cannot read texture: not a regular file (a folder, device or pipe); expected a \
             PNG file",
        ));
    }
    let too_big = || {
        Error::file(
            path,
            format!(
                "cannot read texture: larger than {} MiB; expected a PNG file of at most that size",
                MAX_PNG_FILE_BYTES / MIB
            ),
        )
    };
    if meta.len() > MAX_PNG_FILE_BYTES {
        return Err(too_big());
    }
    // The file may grow after the check: read one byte past the limit at most.
    let file = std::fs::File::open(path).map_err(cannot)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(MAX_PNG_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() as u64 > MAX_PNG_FILE_BYTES {
        return Err(too_big());
    }
    Ok(bytes)
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

/// PNG bytes of an image (`ty` says what `data` holds).
pub fn encode_png(width: u32, height: u32, ty: image::ColorType, data: &[u8]) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    image::ImageEncoder::write_image(
        image::codecs::png::PngEncoder::new(&mut bytes),
        data,
        width,
        height,
        ty.into(),
    )
    .map_err(|e| Error::Invalid(format!("cannot encode a {width}x{height} PNG: {e}")))?;
    Ok(bytes)
}

fn save_png(path: &Path, width: u32, height: u32, ty: image::ColorType, data: &[u8]) -> Result<()> {
    let bytes = encode_png(width, height, ty, data)?;
    crate::output::write_file(path, "the image", &bytes)
}
