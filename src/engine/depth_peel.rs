//! `DepthPeel`: depth peeling of the light's translucent fragments (Everitt 2001), the
//! capture AVSM needs on GL 3.3, which has no atomics or image stores
//! (`crate::shadows::avsm`). Layer k keeps, per texel, the nearest fragment behind layer
//! k - 1: its program discards what is not behind the previous layer's depth (read from
//! the other of two depth textures) and the depth test keeps the nearest of the rest. An
//! `ANY_SAMPLES_PASSED` query says whether a layer caught anything, so peeling stops at
//! the first empty one. Each layer goes to its own layer of one texture array, so a single
//! pass can read them all afterwards. Past the last layer allowed, one more pass folds
//! whatever is left into a single crossing ([`DepthPeel::begin_rest`]), so nothing behind
//! the medium is lost.

use glow::HasContext;

use super::framebuffer::{Attachment, Framebuffer, Part};
use super::owned::OwnedQuery;
use super::state::PixelRect;
use super::texture::Texture;
use super::Gl;
use crate::error::Result;
use crate::settings::{DepthFormat, MapSize};

/// The colour of a layer's texel that caught nothing: past every fitted depth (0 to 1),
/// no opacity.
pub const NO_CROSSING: [f32; 4] = [2.0, 0.0, 0.0, 0.0];

/// Owns the two depth textures (32-bit float, so a depth compares equal to itself when
/// the next layer reads it), the layers' RG32F array (depth, opacity), a framebuffer per
/// depth texture and the query; all freed on drop.
pub struct DepthPeel {
    gl: Gl,
    depth: [Texture; 2],
    layers: Texture,
    count: u32,
    fbos: [Framebuffer; 2],
    /// The rest past the last layer: RGB the product of what they let through, A the
    /// farthest depth; and its framebuffer.
    rest: Texture,
    rest_fbo: Framebuffer,
    query: OwnedQuery,
}

impl DepthPeel {
    /// A `size` peel of at most `layers` layers (at least 1).
    pub fn new(gl: &Gl, size: MapSize, layers: u32) -> Result<DepthPeel> {
        let (w, h) = (size.width, size.height);
        let count = layers.max(1);
        let depth = [
            Texture::depth(gl, w, h, DepthFormat::D32F)?,
            Texture::depth(gl, w, h, DepthFormat::D32F)?,
        ];
        let layers = Texture::float_rg_array(gl, w, h, count)?;
        let rest = Texture::float_target(gl, w, h, 4)?;
        let query = OwnedQuery::new(gl, "depth peel query")?;
        let layer_target = |i: usize| {
            Framebuffer::build(gl, "depth peel")?
                .texture(Attachment::Colour(0), &layers, Part::Layer(0))
                .texture(Attachment::Depth, &depth[i], Part::Image)
                .finish(&format!("depth peel {w}x{h} ({i})"))
        };
        let fbos = [layer_target(0)?, layer_target(1)?];
        let rest_fbo = Framebuffer::build(gl, "depth peel")?
            .texture(Attachment::Colour(0), &rest, Part::Image)
            .finish(&format!("depth peel {w}x{h} (rest)"))?;
        Ok(DepthPeel {
            gl: gl.clone(),
            depth,
            layers,
            count,
            fbos,
            rest,
            rest_fbo,
            query,
        })
    }

    /// Starts the rest after `k` layers: every fragment behind layer k - 1 (whose depth is
    /// bound on `unit`), with no depth test, blended into the rest texture cleared to
    /// (1, 1, 1, 0): RGB multiplied by the fragment's (what it lets through), A the larger
    /// depth. Counted as a layer is; within `rect` alone, as a layer is.
    pub fn begin_rest(&self, k: u32, unit: u32, rect: PixelRect) -> PeelPass<'_> {
        let gl = &self.gl;
        self.bind_target(k, unit, &self.rest_fbo, rect);
        unsafe {
            gl.set_capability(glow::DEPTH_TEST, false);
            gl.set_capability(glow::CULL_FACE, false);
            gl.clear_buffer_f32_slice(glow::COLOR, 0, &[1.0, 1.0, 1.0, 0.0]);
            gl.enable(glow::BLEND);
            gl.blend_equation_separate(glow::FUNC_ADD, glow::MAX);
            gl.blend_func_separate(glow::ZERO, glow::SRC_COLOR, glow::ONE, glow::ONE);
            gl.begin_query(glow::ANY_SAMPLES_PASSED, self.query.raw());
        }
        PeelPass {
            peel: self,
            open: true,
        }
    }

    /// Binds the rest on texture `unit` for `texelFetch`, with no sampler object.
    pub fn bind_rest(&self, unit: u32) {
        self.rest.bind(unit);
        unsafe { self.gl.bind_sampler(unit, None) };
    }

    /// Binds layer k - 1's depth on `unit` (no sampler object: `texelFetch` reads it)
    /// and `fbo` over the whole map, scissored to `rect`.
    fn bind_target(&self, k: u32, unit: u32, fbo: &Framebuffer, rect: PixelRect) {
        let gl = &self.gl;
        self.depth[1 - (k % 2) as usize].bind(unit);
        let (w, h) = (self.layers.width() as i32, self.layers.height() as i32);
        unsafe {
            gl.bind_sampler(unit, None);
            fbo.bind();
            gl.viewport(0, 0, w, h);
            gl.set_capability(glow::SCISSOR_TEST, true);
            let (rw, rh) = (rect.width as i32, rect.height as i32);
            gl.scissor(rect.x as i32, rect.y as i32, rw, rh);
        }
    }

    /// The most layers it peels.
    pub fn count(&self) -> u32 {
        self.count
    }

    /// Starts layer `k` (below [`Self::count`]): binds its framebuffer (depth texture k
    /// mod 2) with layer k of the array as its colour, clears that to [`NO_CROSSING`] and
    /// the depth to 1, binds the previous layer's depth texture on
    /// `unit` (no sampler object: `texelFetch` reads it) and starts counting. Depth test
    /// LESS, no culling (a closed mesh is crossed twice), no blending. Everything is
    /// cleared and drawn within `rect` alone (a scissor: the texels the casters can cover;
    /// outside it the layers hold anything). The caller binds the peel program and draws
    /// the casters, then calls [`PeelPass::finish`].
    pub fn begin(&self, k: u32, unit: u32, rect: PixelRect) -> PeelPass<'_> {
        let gl = &self.gl;
        let fbo = &self.fbos[(k % 2) as usize];
        self.bind_target(k, unit, fbo, rect);
        let layer = Part::Layer(k.min(self.count - 1));
        fbo.attach(Attachment::Colour(0), &self.layers, layer);
        unsafe {
            gl.depth_mask(true);
            gl.set_capability(glow::DEPTH_TEST, true);
            gl.depth_func(glow::LESS);
            gl.set_capability(glow::CULL_FACE, false);
            gl.clear_buffer_f32_slice(glow::COLOR, 0, &NO_CROSSING);
            gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[1.0]);
            gl.begin_query(glow::ANY_SAMPLES_PASSED, self.query.raw());
        }
        PeelPass {
            peel: self,
            open: true,
        }
    }

    /// Binds the layers on texture `unit` for `texelFetch` (a `sampler2DArray`), with no
    /// sampler object: per texel and layer its depth and opacity, [`NO_CROSSING`] where the
    /// layer caught nothing.
    pub fn bind_layers(&self, unit: u32) {
        self.layers.bind(unit);
        unsafe { self.gl.bind_sampler(unit, None) };
    }

    /// Bytes allocated: two 4-byte depths, 8 bytes a layer and a 16-byte rest a texel.
    pub fn bytes(&self) -> u64 {
        let texels = u64::from(self.layers.width()) * u64::from(self.layers.height());
        texels * (8 + 8 * u64::from(self.count) + 16)
    }
}

/// A layer being peeled; dropping it ends the query and puts the resting state back.
pub struct PeelPass<'a> {
    peel: &'a DepthPeel,
    open: bool,
}

impl PeelPass<'_> {
    /// Ends the layer: whether any fragment was kept (waits for the query).
    pub fn finish(mut self) -> bool {
        self.close();
        let q = self.peel.query.raw();
        let any = unsafe { self.peel.gl.get_query_parameter_u32(q, glow::QUERY_RESULT) };
        any != 0
    }

    fn close(&mut self) {
        if !self.open {
            return;
        }
        self.open = false;
        let gl = &self.peel.gl;
        unsafe {
            gl.end_query(glow::ANY_SAMPLES_PASSED);
            // What the rest changed; the resting state for a layer's pass too.
            gl.disable(glow::BLEND);
            gl.blend_equation(glow::FUNC_ADD);
            gl.blend_func(glow::ONE, glow::ZERO);
            gl.set_capability(glow::DEPTH_TEST, true);
            gl.set_capability(glow::SCISSOR_TEST, false);
            gl.use_program_once(None);
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
    }
}

impl Drop for PeelPass<'_> {
    fn drop(&mut self) {
        self.close();
    }
}
