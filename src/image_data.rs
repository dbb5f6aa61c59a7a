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
    /// download one): four planks side by side across u, running along v, with grain along
    /// them and a dark seam between boards.
    ///
    /// Band-limited at the source: along v (the direction a floor foreshortens, where regular
    /// stripes read as shadow acne) every term repeats at most twice per tile, so the tiled
    /// floor shows no bands at any distance; across u the finest term (the grain) has a period
    /// of about 13 texels at 256. Every term is periodic in u and v, so tiles meet without a
    /// seam, and each texel is the average of 4 x 4 samples of the pattern, so the seams'
    /// edges are anti-aliased rather than stepped.
    pub fn wood(size: u32) -> ImageData {
        use std::f32::consts::TAU;
        const PLANKS: f32 = 4.0;
        const SUB: u32 = 4;
        // Brightness of the pattern at (u, v) in [0, 1)^2.
        let tone = |u: f32, v: f32| {
            let across = u * PLANKS;
            let plank = across.floor();
            let x = across - plank; // 0..1 across this plank
            let shift = plank * 0.37; // each plank's pattern starts elsewhere along v
            let sway = 0.06 * (TAU * (v + shift)).sin() + 0.03 * (2.0 * TAU * (v + shift)).sin();
            // Grain: five lines per plank along its length, swaying gently.
            let grain = 0.5 + 0.5 * (TAU * (5.0 * x + sway + 0.3 * plank)).sin();
            // Broad growth rings: one darker band per plank, drifting across it along v.
            let ring = (TAU * (x - 0.5 + 1.5 * sway)).cos() * 0.5 + 0.5;
            // Each plank a slightly different shade.
            let shade = [1.0, 0.94, 1.02, 0.97][(plank as usize) % 4];
            // The seam: a narrow dark line where planks meet (x near 0 or 1).
            let edge = x.min(1.0 - x);
            let seam = if edge < 0.025 { 0.55 } else { 1.0 };
            (0.7 + 0.18 * ring - 0.12 * grain) * shade * seam
        };
        let mut rgba = Vec::with_capacity((size * size * 4) as usize);
        let n = size as f32 * SUB as f32;
        for y in 0..size {
            for x in 0..size {
                let mut t = 0.0;
                for j in 0..SUB {
                    for i in 0..SUB {
                        let u = ((x * SUB + i) as f32 + 0.5) / n;
                        let v = ((y * SUB + j) as f32 + 0.5) / n;
                        t += tone(u, v);
                    }
                }
                let t = t / (SUB * SUB) as f32;
                let c = |base: f32| (base * t * 255.0).round().clamp(0.0, 255.0) as u8;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The wood's red channel at texel (x, y).
    fn red(w: &ImageData, x: u32, y: u32) -> f64 {
        f64::from(w.rgba[((y * w.width + x) * 4) as usize])
    }

    #[test]
    fn wood_has_no_stripes_along_its_planks_and_tiles_without_a_seam() {
        let w = ImageData::wood(256);
        let n = w.height as usize;
        // Along v (the way a floor foreshortens), per column: the share of the varying
        // part's energy at more than 2 cycles per tile. Regular stripes across the planks
        // (the old grain, 14 cycles per tile) would put most of it there.
        let (mut high, mut all) = (0.0, 0.0);
        for x in 0..w.width {
            let col: Vec<f64> = (0..w.height).map(|y| red(&w, x, y)).collect();
            let mean = col.iter().sum::<f64>() / n as f64;
            for k in 1..n / 2 {
                let (mut re, mut im) = (0.0, 0.0);
                for (y, v) in col.iter().enumerate() {
                    let a = std::f64::consts::TAU * (k * y) as f64 / n as f64;
                    re += (v - mean) * a.cos();
                    im += (v - mean) * a.sin();
                }
                let e = re * re + im * im;
                all += e;
                if k > 2 {
                    high += e;
                }
            }
        }
        let share = high / all;
        assert!(
            share < 0.02,
            "{:.1}% of the energy along v above 2 cycles",
            share * 100.0
        );
        // Tiles meet like neighbours: the step from the last row to the first, and from the
        // last column to the first, is no larger than steps inside.
        let step = |a: (u32, u32), b: (u32, u32)| (red(&w, a.0, a.1) - red(&w, b.0, b.1)).abs();
        let inside_v = (0..w.width)
            .flat_map(|x| (1..w.height).map(move |y| (x, y)))
            .map(|(x, y)| step((x, y), (x, y - 1)))
            .fold(0.0, f64::max);
        let wrap_v = (0..w.width)
            .map(|x| step((x, 0), (x, w.height - 1)))
            .fold(0.0, f64::max);
        assert!(
            wrap_v <= inside_v,
            "seam along v: {wrap_v} against {inside_v}"
        );
        let inside_u = (0..w.height)
            .flat_map(|y| (1..w.width).map(move |x| (x, y)))
            .map(|(x, y)| step((x, y), (x - 1, y)))
            .fold(0.0, f64::max);
        let wrap_u = (0..w.height)
            .map(|y| step((0, y), (w.width - 1, y)))
            .fold(0.0, f64::max);
        assert!(
            wrap_u <= inside_u,
            "seam along u: {wrap_u} against {inside_u}"
        );
    }
}
