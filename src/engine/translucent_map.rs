//! `TranslucentMap`: the storage of a translucent shadow map (`crate::shadows::volumetric`):
//! an array of RGBA32F layers, each a colour attachment of one framebuffer, so one pass
//! writes every layer (GL 3.3 guarantees eight draw buffers). The additive techniques sum
//! each crossing's share into it; the sum does not depend on the order of the crossings.

use glow::HasContext;

use super::framebuffer::{Attachment, Framebuffer, Part};
use super::state::PixelRect;
use super::texture::{Filtering, Texels, Texture};
use super::Gl;
use crate::error::{Error, Result};
use crate::settings::MapSize;

/// The most layers one pass can write: GL 3.3's guaranteed draw buffers.
pub const MAX_LAYERS: u32 = 8;

/// Owns the layered texture and its framebuffer; both freed on drop.
pub struct TranslucentMap {
    gl: Gl,
    fbo: Framebuffer,
    texture: Texture,
    layers: u32,
}

impl TranslucentMap {
    /// A `size` map of `layers` RGBA32F layers (1 to [`MAX_LAYERS`]).
    pub fn new(gl: &Gl, size: MapSize, layers: u32) -> Result<TranslucentMap> {
        if !(1..=MAX_LAYERS).contains(&layers) {
            return Err(Error::Invalid(format!(
                "translucent map with {layers} layers: expected 1 to {MAX_LAYERS}"
            )));
        }
        let texture = Texture::float_array(gl, size.width, size.height, layers)?;
        let mut fbo = Framebuffer::build(gl, "translucent map")?;
        for l in 0..layers {
            fbo = fbo.texture(Attachment::Colour(l), &texture, Part::Layer(l));
        }
        let what = format!("translucent map {}x{} ({layers})", size.width, size.height);
        Ok(TranslucentMap {
            gl: gl.clone(),
            fbo: fbo.finish(&what)?,
            texture,
            layers,
        })
    }

    /// Binds the framebuffer, sets the viewport to the map and clears every layer to 0
    /// within `region` (a scissor: the texels outside keep what they hold); while the
    /// returned pass lives, fragments add into the layers there (blending ONE, ONE), with
    /// no depth test and no culling (every crossing counts, front face or back).
    pub fn begin_additive(&self, region: PixelRect) -> MapPass {
        let pass = self.begin(region, true);
        unsafe {
            for l in 0..self.layers {
                self.gl.clear_buffer_f32_slice(glow::COLOR, l, &[0.0; 4]);
            }
            self.gl.enable(glow::BLEND);
            self.gl.blend_equation(glow::FUNC_ADD);
            self.gl.blend_func(glow::ONE, glow::ONE);
        }
        pass
    }

    fn begin(&self, rect: PixelRect, additive: bool) -> MapPass {
        begin_pass(&self.gl, &self.fbo, self.size(), rect, additive)
    }

    /// Clears every layer to `value`.
    pub fn clear(&self, value: [f32; 4]) {
        self.fbo.bind();
        unsafe {
            for l in 0..self.layers {
                self.gl.clear_buffer_f32_slice(glow::COLOR, l, &value);
            }
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
    }

    /// Binds the framebuffer to overwrite the texels of `rect` alone (scissored), with no
    /// blending, depth test or culling (an AVSM build); dropping the pass puts the resting
    /// state back.
    pub fn begin_write(&self, rect: PixelRect) -> MapPass {
        self.begin(rect, false)
    }

    /// Binds the layers on texture `unit` for a `sampler2DArray`, with no sampler object
    /// (the texture's own LINEAR, clamped sampling).
    pub fn bind(&self, unit: u32) {
        self.texture.bind(unit);
        unsafe { self.gl.bind_sampler(unit, None) };
    }

    /// Layer `layer` read back, texel by texel (row 0 at the bottom, as GL stores them).
    pub fn read_layer(&self, layer: u32) -> Vec<[f32; 4]> {
        let size = self.size();
        let n = size.texels() as usize;
        let mut bytes = vec![0u8; n * 16];
        self.fbo.bind();
        unsafe {
            self.gl.read_buffer(glow::COLOR_ATTACHMENT0 + layer);
            self.gl.pixel_store_i32(glow::PACK_ALIGNMENT, 4);
            self.gl.read_pixels(
                0,
                0,
                size.width as i32,
                size.height as i32,
                glow::RGBA,
                glow::FLOAT,
                glow::PixelPackData::Slice(Some(&mut bytes)),
            );
            self.gl.read_buffer(glow::COLOR_ATTACHMENT0);
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
        let float = |c: &[u8]| f32::from_ne_bytes([c[0], c[1], c[2], c[3]]);
        bytes
            .chunks_exact(16)
            .map(|t| [0, 4, 8, 12].map(|o| float(&t[o..o + 4])))
            .collect()
    }

    pub fn size(&self) -> MapSize {
        MapSize {
            width: self.texture.width(),
            height: self.texture.height(),
        }
    }

    pub fn layers(&self) -> u32 {
        self.layers
    }

    /// Bytes allocated: 16 a texel per layer.
    pub fn bytes(&self) -> u64 {
        self.size().texels() * 16 * u64::from(self.layers)
    }
}

/// Binds `fbo` (a `size` target) to draw into `rect` alone (scissored) with no depth test
/// or culling; the pass restores the resting state (and blending, if `additive`) on drop.
fn begin_pass(
    gl: &Gl,
    fbo: &Framebuffer,
    size: MapSize,
    rect: PixelRect,
    additive: bool,
) -> MapPass {
    fbo.bind();
    unsafe {
        gl.viewport(0, 0, size.width as i32, size.height as i32);
        gl.set_capability(glow::SCISSOR_TEST, true);
        let (w, h) = (rect.width as i32, rect.height as i32);
        gl.scissor(rect.x as i32, rect.y as i32, w, h);
        gl.set_capability(glow::DEPTH_TEST, false);
        gl.set_capability(glow::CULL_FACE, false);
    }
    MapPass {
        gl: gl.clone(),
        additive,
    }
}

/// A translucent map resolved for opaque receivers (`opaque_receivers = "resolved"`,
/// `crate::shadows::volumetric::resolved`): one R32F transmittance a texel, read with
/// LINEAR filtering, clamped, and its framebuffer; both freed on drop.
pub struct ResolvedMap {
    gl: Gl,
    fbo: Framebuffer,
    texture: Texture,
}

impl ResolvedMap {
    /// A `size` map, every texel 1 (nothing in the way).
    pub fn new(gl: &Gl, size: MapSize) -> Result<ResolvedMap> {
        let (w, h) = (size.width, size.height);
        let texels = Texels {
            internal: glow::R32F,
            format: glow::RED,
            ty: glow::FLOAT,
        };
        // Filtered: opaque receivers read it with one linear fetch.
        let filtering = Filtering::LINEAR_CLAMPED;
        let texture = Texture::flat(gl, "resolved map", (w, h), texels, filtering)?;
        let fbo = Framebuffer::build(gl, "resolved map")?
            .texture(Attachment::Colour(0), &texture, Part::Image)
            .finish(&format!("resolved map {w}x{h}"))?;
        fbo.bind();
        unsafe {
            gl.clear_buffer_f32_slice(glow::COLOR, 0, &[1.0; 4]);
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
        Ok(ResolvedMap {
            gl: gl.clone(),
            fbo,
            texture,
        })
    }

    /// Binds the framebuffer to overwrite the texels of `rect` alone (scissored), with no
    /// blending, depth test or culling; dropping the pass puts the resting state back.
    pub fn begin_write(&self, rect: PixelRect) -> MapPass {
        begin_pass(&self.gl, &self.fbo, self.size(), rect, false)
    }

    /// Binds the map on texture `unit` for a `sampler2D`, with no sampler object.
    pub fn bind(&self, unit: u32) {
        self.texture.bind(unit);
        unsafe { self.gl.bind_sampler(unit, None) };
    }

    /// Binds a light's depth map on `unit` with no sampler object, for the resolve's
    /// `texelFetch` (its own NEAREST sampling, no comparison).
    pub fn bind_depth(&self, depth: &Texture, unit: u32) {
        depth.bind(unit);
        unsafe { self.gl.bind_sampler(unit, None) };
    }

    /// The map read back, texel by texel (row 0 at the bottom).
    pub fn read(&self) -> Vec<f32> {
        let size = self.size();
        let mut bytes = vec![0u8; size.texels() as usize * 4];
        self.fbo.bind();
        unsafe {
            self.gl.pixel_store_i32(glow::PACK_ALIGNMENT, 4);
            let (w, h) = (size.width as i32, size.height as i32);
            let data = glow::PixelPackData::Slice(Some(&mut bytes));
            self.gl
                .read_pixels(0, 0, w, h, glow::RED, glow::FLOAT, data);
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
        let float = |c: &[u8]| f32::from_ne_bytes([c[0], c[1], c[2], c[3]]);
        bytes.chunks_exact(4).map(float).collect()
    }

    pub fn size(&self) -> MapSize {
        MapSize {
            width: self.texture.width(),
            height: self.texture.height(),
        }
    }

    /// Bytes allocated: 4 a texel.
    pub fn bytes(&self) -> u64 {
        self.size().texels() * 4
    }
}

/// A pass into a [`TranslucentMap`] in progress; dropping it restores the resting state
/// (no scissor, depth test on, no blending, the default framebuffer, no program).
pub struct MapPass {
    gl: Gl,
    additive: bool,
}

impl Drop for MapPass {
    fn drop(&mut self) {
        unsafe {
            self.gl.use_program_once(None);
            self.gl.set_capability(glow::SCISSOR_TEST, false);
            if self.additive {
                self.gl.blend_func(glow::ONE, glow::ZERO);
                self.gl.disable(glow::BLEND);
            }
            self.gl.set_capability(glow::DEPTH_TEST, true);
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
    }
}
