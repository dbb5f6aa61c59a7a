//! `RenderTarget`: an offscreen framebuffer that stands in for the window when rendering
//! headless, with optional extra outputs the scene shader writes (visibility, world
//! position, world normal) for tests and for the exact reference.

use glow::HasContext;

use super::framebuffer::{Attachment, Framebuffer, Part};
use super::texture::Texture;
use super::Gl;
use crate::error::{Error, Result};

/// Which extra outputs to attach besides colour.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Outputs {
    /// Attachment 1: R = shadow-test visibility, G = 1 where geometry was drawn.
    pub visibility: bool,
    /// Attachments 2 and 3: world position and world normal (RGBA32F, A = 1 on geometry).
    pub gbuffer: bool,
}

/// World positions and world normals read back from the G-buffer outputs.
pub type GBufferData = (Vec<[f32; 3]>, Vec<[f32; 3]>);

/// An owned framebuffer with a colour texture, a depth-stencil renderbuffer (the stencil for
/// shadow volumes) and the chosen outputs.
pub struct RenderTarget {
    gl: Gl,
    /// With its depth-stencil renderbuffer.
    fbo: Framebuffer,
    colour: Texture,
    visibility: Option<Texture>,
    positions: Option<Texture>,
    normals: Option<Texture>,
    width: u32,
    height: u32,
}

impl RenderTarget {
    pub fn new(gl: &Gl, width: u32, height: u32, outputs: Outputs) -> Result<RenderTarget> {
        let colour = Texture::attachment(
            gl,
            width,
            height,
            glow::RGBA8,
            glow::RGBA,
            glow::UNSIGNED_BYTE,
        )?;
        Self::around(gl, colour, width, height, outputs)
    }

    /// A target whose colour holds `channels` (1 to 4) floats a pixel, exactly (the cached
    /// shadow mask: each light's test as the scene shader computed it).
    pub fn float(gl: &Gl, width: u32, height: u32, channels: usize) -> Result<RenderTarget> {
        let (internal, format) = match channels {
            0 | 1 => (glow::R32F, glow::RED),
            2 => (glow::RG32F, glow::RG),
            3 => (glow::RGB32F, glow::RGB),
            _ => (glow::RGBA32F, glow::RGBA),
        };
        let colour = Texture::attachment(gl, width, height, internal, format, glow::FLOAT)?;
        Self::around(gl, colour, width, height, Outputs::default())
    }

    /// The colour texture (to sample what was drawn).
    pub fn colour(&self) -> &Texture {
        &self.colour
    }

    fn around(
        gl: &Gl,
        colour: Texture,
        width: u32,
        height: u32,
        outputs: Outputs,
    ) -> Result<RenderTarget> {
        let visibility = outputs
            .visibility
            .then(|| {
                Texture::attachment(gl, width, height, glow::RG8, glow::RG, glow::UNSIGNED_BYTE)
            })
            .transpose()?;
        let float_target =
            || Texture::attachment(gl, width, height, glow::RGBA32F, glow::RGBA, glow::FLOAT);
        let positions = outputs.gbuffer.then(float_target).transpose()?;
        let normals = outputs.gbuffer.then(float_target).transpose()?;
        let mut fbo = Framebuffer::build(gl, "render target")?.renderbuffer(
            Attachment::DepthStencil,
            glow::DEPTH24_STENCIL8,
            (width, height),
            "depth renderbuffer",
        )?;
        let outputs = [
            Some(&colour),
            visibility.as_ref(),
            positions.as_ref(),
            normals.as_ref(),
        ];
        for (i, tex) in outputs.into_iter().enumerate() {
            if let Some(tex) = tex {
                fbo = fbo.texture(Attachment::Colour(i as u32), tex, Part::Image);
            }
        }
        let fbo = fbo.finish(&format!("render target {width}x{height}"))?;
        Ok(RenderTarget {
            gl: gl.clone(),
            fbo,
            colour,
            visibility,
            positions,
            normals,
            width,
            height,
        })
    }

    /// The extra outputs this target has (the scene program writes only those).
    pub fn outputs(&self) -> Outputs {
        Outputs {
            visibility: self.visibility.is_some(),
            gbuffer: self.positions.is_some(),
        }
    }

    fn attachments(&self) -> [(u32, Option<&Texture>); 4] {
        [
            (0, Some(&self.colour)),
            (1, self.visibility.as_ref()),
            (2, self.positions.as_ref()),
            (3, self.normals.as_ref()),
        ]
    }

    /// Binds the framebuffer and clears colour to `clear`, the extra outputs to zero.
    pub fn bind_and_clear(&self, clear: [f32; 4]) {
        self.fbo.bind();
        unsafe {
            self.gl
                .viewport(0, 0, self.width as i32, self.height as i32);
            self.gl.depth_mask(true);
            self.gl.clear_buffer_f32_slice(glow::COLOR, 0, &clear);
            for (i, tex) in self.attachments().iter().skip(1) {
                if tex.is_some() {
                    self.gl
                        .clear_buffer_f32_slice(glow::COLOR, *i, &[0.0, 0.0, 0.0, 0.0]);
                }
            }
            self.gl.stencil_mask(0xff);
            self.gl
                .clear_buffer_depth_stencil(glow::DEPTH_STENCIL, 0, 1.0, 0);
        }
    }

    /// Binds the framebuffer and sets the viewport to its size without clearing, for what
    /// is drawn over a finished frame (the HUD).
    pub fn bind(&self) {
        self.fbo.bind();
        unsafe {
            self.gl
                .viewport(0, 0, self.width as i32, self.height as i32);
        }
    }

    pub fn framebuffer(&self) -> glow::Framebuffer {
        self.fbo.raw()
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// The colour image as RGBA8, rows top to bottom.
    pub fn read_colour(&self) -> Vec<u8> {
        read_rgba8(&self.gl, Some(self.fbo.raw()), 0, self.width, self.height)
    }

    /// Per pixel: `Some(visibility)` where geometry was drawn, `None` elsewhere; rows top to
    /// bottom. Errors if the target was made without the visibility output.
    pub fn read_visibility(&self) -> Result<Vec<Option<f32>>> {
        if self.visibility.is_none() {
            return Err(Error::Invalid(
                "render target has no visibility output".into(),
            ));
        }
        // RGBA: the one format OpenGL ES (WebGL2) reads from every 8-bit target.
        let raw = self.read(1, glow::RGBA, glow::UNSIGNED_BYTE, 4);
        Ok(raw
            .chunks_exact(4)
            .map(|p| (p[1] > 127).then_some(p[0] as f32 / 255.0))
            .collect())
    }

    /// Replaces the colour image with `rgba` (RGBA8, rows top to bottom, the target's size):
    /// a picture made from what was drawn (the demo's visibility view) shown through it.
    pub fn write_colour(&self, rgba: &[u8]) -> Result<()> {
        let row = self.width as usize * 4;
        if rgba.len() != row * self.height as usize {
            return Err(Error::Invalid(format!(
                "{} bytes of RGBA for a {}x{} target",
                rgba.len(),
                self.width,
                self.height
            )));
        }
        let mut rows = rgba.to_vec();
        flip_rows(&mut rows, row);
        unsafe {
            self.gl
                .bind_texture(glow::TEXTURE_2D, Some(self.colour.id()));
            self.gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 1);
            self.gl.tex_sub_image_2d(
                glow::TEXTURE_2D,
                0,
                0,
                0,
                self.width as i32,
                self.height as i32,
                glow::RGBA,
                glow::UNSIGNED_BYTE,
                glow::PixelUnpackData::Slice(Some(&rows)),
            );
            self.gl.bind_texture(glow::TEXTURE_2D, None);
        }
        // Bound past the context's record of its units (bindings.rs).
        self.gl.forget_bindings();
        Ok(())
    }

    /// Copies the colour image onto the window's framebuffer at its origin, pixel for pixel.
    pub fn blit_colour_to_window(&self) {
        let (w, h) = (self.width as i32, self.height as i32);
        unsafe {
            self.gl
                .bind_framebuffer(glow::READ_FRAMEBUFFER, Some(self.fbo.raw()));
            self.gl.read_buffer(glow::COLOR_ATTACHMENT0);
            self.gl.bind_framebuffer(glow::DRAW_FRAMEBUFFER, None);
            self.gl.blit_framebuffer(
                0,
                0,
                w,
                h,
                0,
                0,
                w,
                h,
                glow::COLOR_BUFFER_BIT,
                glow::NEAREST,
            );
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
    }

    /// World positions and normals, rows top to bottom; NaN where no geometry was drawn.
    pub fn read_gbuffer(&self) -> Result<GBufferData> {
        if self.positions.is_none() {
            return Err(Error::Invalid(
                "render target has no G-buffer outputs".into(),
            ));
        }
        let unpack = |raw: Vec<u8>| -> Vec<[f32; 3]> {
            raw.chunks_exact(16)
                .map(|c| {
                    let f = |k: usize| f32::from_ne_bytes([c[k], c[k + 1], c[k + 2], c[k + 3]]);
                    if f(12) > 0.5 {
                        [f(0), f(4), f(8)]
                    } else {
                        [f32::NAN; 3]
                    }
                })
                .collect()
        };
        let positions = unpack(self.read(2, glow::RGBA, glow::FLOAT, 16));
        let normals = unpack(self.read(3, glow::RGBA, glow::FLOAT, 16));
        Ok((positions, normals))
    }

    fn read(&self, attachment: u32, format: u32, ty: u32, bytes_per_pixel: usize) -> Vec<u8> {
        let w = self.width as usize;
        let h = self.height as usize;
        let mut data = vec![0u8; w * h * bytes_per_pixel];
        unsafe {
            self.gl
                .bind_framebuffer(glow::READ_FRAMEBUFFER, Some(self.fbo.raw()));
            self.gl.read_buffer(glow::COLOR_ATTACHMENT0 + attachment);
            self.gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
            self.gl.read_pixels(
                0,
                0,
                w as i32,
                h as i32,
                format,
                ty,
                glow::PixelPackData::Slice(Some(&mut data)),
            );
            self.gl.read_buffer(glow::COLOR_ATTACHMENT0);
            self.gl.bind_framebuffer(glow::READ_FRAMEBUFFER, None);
        }
        flip_rows(&mut data, w * bytes_per_pixel);
        data
    }
}

/// Reads RGBA8 pixels from a framebuffer (`None` = the window's back buffer), rows top to
/// bottom, as image files store them.
pub fn read_rgba8(
    gl: &Gl,
    fbo: Option<glow::Framebuffer>,
    attachment: u32,
    width: u32,
    height: u32,
) -> Vec<u8> {
    let mut data = vec![0u8; width as usize * height as usize * 4];
    unsafe {
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, fbo);
        gl.read_buffer(if fbo.is_some() {
            glow::COLOR_ATTACHMENT0 + attachment
        } else {
            glow::BACK
        });
        gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
        gl.read_pixels(
            0,
            0,
            width as i32,
            height as i32,
            glow::RGBA,
            glow::UNSIGNED_BYTE,
            glow::PixelPackData::Slice(Some(&mut data)),
        );
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, None);
    }
    flip_rows(&mut data, width as usize * 4);
    data
}

/// GL's row 0 is the bottom; images want it at the top.
fn flip_rows(data: &mut [u8], row_bytes: usize) {
    if row_bytes == 0 {
        return;
    }
    let rows = data.len() / row_bytes;
    for y in 0..rows / 2 {
        let (top, bottom) = data.split_at_mut((rows - 1 - y) * row_bytes);
        top[y * row_bytes..(y + 1) * row_bytes].swap_with_slice(&mut bottom[..row_bytes]);
    }
}
