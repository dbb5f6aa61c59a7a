//! `SummedAreaTable`: a moment map's summed-area table in unsigned integers (RG32UI or
//! RGBA32UI), so that the mean over any box of the map is four reads. GL 3.3 has no compute:
//! the table is built by full-screen passes of recursive doubling, each adding
//! [`SAT_RADIX`] texels `step` apart (`step` = 1, 4, 16, ...) along one axis, ping-ponging
//! between two textures. The first pass also turns the float moments into fixed point
//! ([`SAT_SCALE`]); unsigned sums wrap around, and a box's difference of corners is right
//! as long as the box's own sum fits in 32 bits.

use glow::HasContext;

use super::framebuffer::{Attachment, Framebuffer, Part};
use super::mesh::FullScreenTriangle;
use super::state::NoDepthTest;
use super::texture::Texture;
use super::{Gl, ShaderProgram};
use crate::error::{Error, Result};
use crate::settings::MapSize;

/// Texels each build pass adds along its axis: log4 of a side passes per axis.
pub const SAT_RADIX: u32 = 4;

/// The widest box a lookup may read, in texels a side: a kernel of 64 texels either side,
/// and a texel more each way for the corners' interpolation.
pub const SAT_MAX_BOX: u32 = 130;

/// Fixed-point units per unit of a moment (moments lie in [0, 1]): 2^17, the most for which
/// a box of [`SAT_MAX_BOX`]^2 texels of ones stays below 2^32.
pub const SAT_SCALE: u32 = 1 << 17;

/// The build passes a `side` texels long axis takes: the fewest for which
/// `SAT_RADIX`^passes reaches it (one at least).
pub fn axis_passes(side: u32) -> u32 {
    let mut passes = 1;
    let mut reach = SAT_RADIX;
    while reach < side {
        reach = reach.saturating_mul(SAT_RADIX);
        passes += 1;
    }
    passes
}

/// Owns both integer textures and their framebuffers; freed on drop.
pub struct SummedAreaTable {
    gl: Gl,
    /// Framebuffer `i` draws into `textures[i]`.
    fbos: [Framebuffer; 2],
    textures: [Texture; 2],
    components: u32,
    /// The texture that holds the table after the last build.
    result: usize,
}

impl SummedAreaTable {
    /// A `size` table of `components` (2 or 4) unsigned sums per texel.
    pub fn new(gl: &Gl, size: MapSize, components: u32) -> Result<SummedAreaTable> {
        let (internal, format) = match components {
            2 => (glow::RG32UI, glow::RG_INTEGER),
            4 => (glow::RGBA32UI, glow::RGBA_INTEGER),
            n => {
                return Err(Error::Invalid(format!(
                    "summed-area table with {n} components: expected 2 or 4"
                )))
            }
        };
        let (w, h) = (size.width, size.height);
        let make = || Texture::attachment(gl, w, h, internal, format, glow::UNSIGNED_INT);
        let textures = [make()?, make()?];
        let target = |i: usize| {
            Framebuffer::build(gl, "summed-area table")?
                .texture(Attachment::Colour(0), &textures[i], Part::Image)
                .finish(&format!("summed-area table {w}x{h} ({i})"))
        };
        Ok(SummedAreaTable {
            gl: gl.clone(),
            fbos: [target(0)?, target(1)?],
            textures,
            components,
            result: 0,
        })
    }

    /// Builds the table of `source` (float moments, the table's size): `convert` (reading
    /// the sampler `source` on unit 0) makes the first pass across, `add` (reading the
    /// sampler `partial`) every other; both take `stepTexels`, the distance between the
    /// texels a pass adds. Leaves the default framebuffer bound and no program.
    pub fn build(
        &mut self,
        convert: &ShaderProgram,
        add: &ShaderProgram,
        source: &Texture,
        triangle: &FullScreenTriangle,
    ) {
        let size = self.size();
        let _no_depth = NoDepthTest::begin(&self.gl);
        unsafe {
            self.gl.set_capability(glow::SCISSOR_TEST, false);
            self.gl
                .viewport(0, 0, size.width as i32, size.height as i32);
            self.gl.bind_sampler(0, None);
        }
        let mut steps = Vec::new();
        for (axis, side) in [(0, size.width), (1, size.height)] {
            let mut step = 1u32;
            for _ in 0..axis_passes(side) {
                steps.push(if axis == 0 { [step, 0] } else { [0, step] });
                step = step.saturating_mul(SAT_RADIX);
            }
        }
        let mut from = None;
        for (pass, step) in steps.into_iter().enumerate() {
            let program = if pass == 0 { convert } else { add };
            let target = from.map_or(0, |f: usize| 1 - f);
            program.bind();
            match from {
                None => {
                    program.set_i32("source", 0);
                    source.bind(0);
                }
                Some(f) => {
                    program.set_i32("partial", 0);
                    self.textures[f].bind(0);
                }
            }
            program.set_vec2("stepTexels", [step[0] as f32, step[1] as f32]);
            self.fbos[target].bind();
            triangle.draw();
            from = Some(target);
        }
        self.result = from.unwrap_or(0);
        add.unbind();
        unsafe { self.gl.bind_framebuffer(glow::FRAMEBUFFER, None) };
    }

    /// The table (after [`SummedAreaTable::build`]): texel (x, y) holds the sums over the
    /// map's texels (0..=x, 0..=y), times [`SAT_SCALE`], modulo 2^32.
    pub fn texture(&self) -> &Texture {
        &self.textures[self.result]
    }

    /// Reads the table back, row by row from the bottom, `components` values a texel.
    pub fn read(&self) -> Vec<u32> {
        let size = self.size();
        let n = size.texels() as usize * self.components as usize;
        let mut out = vec![0u32; n];
        let format = match self.components {
            2 => glow::RG_INTEGER,
            _ => glow::RGBA_INTEGER,
        };
        unsafe {
            self.gl
                .bind_framebuffer(glow::READ_FRAMEBUFFER, Some(self.fbos[self.result].raw()));
            self.gl.pixel_store_i32(glow::PACK_ALIGNMENT, 4);
            self.gl.read_pixels(
                0,
                0,
                size.width as i32,
                size.height as i32,
                format,
                glow::UNSIGNED_INT,
                glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut out))),
            );
            self.gl.bind_framebuffer(glow::READ_FRAMEBUFFER, None);
        }
        out
    }

    pub fn size(&self) -> MapSize {
        MapSize {
            width: self.textures[0].width(),
            height: self.textures[0].height(),
        }
    }

    pub fn components(&self) -> u32 {
        self.components
    }

    /// Bytes allocated: two integer textures.
    pub fn bytes(&self) -> u64 {
        self.size().texels() * 2 * 4 * u64::from(self.components)
    }
}

/// A float texture of `components` (2 or 4) moments a texel, filled with `values` (row by
/// row from the bottom): a known map to build a table from.
pub fn float_texture_from(
    gl: &Gl,
    size: MapSize,
    components: u32,
    values: &[f32],
) -> Result<Texture> {
    let expected = size.texels() as usize * components as usize;
    if values.len() != expected {
        return Err(Error::Invalid(format!(
            "{} values for a {size} map of {components} components: expected {expected}",
            values.len()
        )));
    }
    let texture = Texture::float_target(gl, size.width, size.height, components)?;
    let format = if components == 2 {
        glow::RG
    } else {
        glow::RGBA
    };
    unsafe {
        gl.bind_texture(glow::TEXTURE_2D, Some(texture.id()));
        gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 4);
        gl.tex_sub_image_2d(
            glow::TEXTURE_2D,
            0,
            0,
            0,
            size.width as i32,
            size.height as i32,
            format,
            glow::FLOAT,
            glow::PixelUnpackData::Slice(Some(bytemuck::cast_slice(values))),
        );
        gl.bind_texture(glow::TEXTURE_2D, None);
    }
    Ok(texture)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_reach_the_side_and_the_widest_box_fits_32_bits() {
        assert_eq!(axis_passes(1), 1);
        assert_eq!(axis_passes(4), 1);
        assert_eq!(axis_passes(5), 2);
        assert_eq!(axis_passes(1024), 5);
        assert_eq!(axis_passes(1025), 6);
        assert_eq!(axis_passes(400), 5);
        let widest = u64::from(SAT_MAX_BOX).pow(2) * u64::from(SAT_SCALE);
        assert!(widest < 1 << 32, "{widest}");
        assert!(widest * 2 >= 1 << 32, "the scale could double: {widest}");
    }
}
