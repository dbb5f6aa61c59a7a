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

use super::check::check_framebuffer;
use super::state::PixelRect;
use super::texture::Texture;
use super::Gl;
use crate::error::{Error, Result};
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
    fbos: [Option<glow::Framebuffer>; 2],
    /// The rest past the last layer: RGB the product of what they let through, A the
    /// farthest depth; and its framebuffer.
    rest: Texture,
    rest_fbo: Option<glow::Framebuffer>,
    query: Option<glow::Query>,
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
        // Owned before anything can fail, so a failure frees what was made.
        let mut peel = DepthPeel {
            gl: gl.clone(),
            depth,
            layers,
            count,
            fbos: [None, None],
            rest,
            rest_fbo: None,
            query: None,
        };
        unsafe {
            let query = gl
                .create_query()
                .map_err(|e| Error::Create(format!("depth peel query: {e}")))?;
            peel.query = Some(query);
            for i in 0..2 {
                let fbo = gl
                    .create_framebuffer()
                    .map_err(|e| Error::Create(format!("depth peel framebuffer: {e}")))?;
                super::counters::count(|c| c.framebuffers += 1);
                peel.fbos[i] = Some(fbo);
                gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
                let id = Some(peel.layers.id());
                gl.framebuffer_texture_layer(glow::FRAMEBUFFER, glow::COLOR_ATTACHMENT0, id, 0, 0);
                let depth = Some(peel.depth[i].id());
                let (target, point) = (glow::TEXTURE_2D, glow::DEPTH_ATTACHMENT);
                gl.framebuffer_texture_2d(glow::FRAMEBUFFER, point, target, depth, 0);
                gl.draw_buffers(&[glow::COLOR_ATTACHMENT0]);
                let status = check_framebuffer(gl, &format!("depth peel {w}x{h} ({i})"));
                gl.bind_framebuffer(glow::FRAMEBUFFER, None);
                status?;
            }
            let fbo = gl
                .create_framebuffer()
                .map_err(|e| Error::Create(format!("depth peel framebuffer: {e}")))?;
            super::counters::count(|c| c.framebuffers += 1);
            peel.rest_fbo = Some(fbo);
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
            let id = Some(peel.rest.id());
            gl.framebuffer_texture_2d(
                glow::FRAMEBUFFER,
                glow::COLOR_ATTACHMENT0,
                glow::TEXTURE_2D,
                id,
                0,
            );
            gl.draw_buffers(&[glow::COLOR_ATTACHMENT0]);
            let status = check_framebuffer(gl, &format!("depth peel {w}x{h} (rest)"));
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
            status?;
        }
        Ok(peel)
    }

    /// Starts the rest after `k` layers: every fragment behind layer k - 1 (whose depth is
    /// bound on `unit`), with no depth test, blended into the rest texture cleared to
    /// (1, 1, 1, 0): RGB multiplied by the fragment's (what it lets through), A the larger
    /// depth. Counted as a layer is; within `rect` alone, as a layer is.
    pub fn begin_rest(&self, k: u32, unit: u32, rect: PixelRect) -> PeelPass<'_> {
        let gl = &self.gl;
        self.bind_target(k, unit, self.rest_fbo, rect);
        unsafe {
            gl.set_capability(glow::DEPTH_TEST, false);
            gl.set_capability(glow::CULL_FACE, false);
            gl.clear_buffer_f32_slice(glow::COLOR, 0, &[1.0, 1.0, 1.0, 0.0]);
            gl.enable(glow::BLEND);
            gl.blend_equation_separate(glow::FUNC_ADD, glow::MAX);
            gl.blend_func_separate(glow::ZERO, glow::SRC_COLOR, glow::ONE, glow::ONE);
            if let Some(q) = self.query {
                gl.begin_query(glow::ANY_SAMPLES_PASSED, q);
            }
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
    fn bind_target(&self, k: u32, unit: u32, fbo: Option<glow::Framebuffer>, rect: PixelRect) {
        let gl = &self.gl;
        self.depth[1 - (k % 2) as usize].bind(unit);
        let (w, h) = (self.layers.width() as i32, self.layers.height() as i32);
        unsafe {
            gl.bind_sampler(unit, None);
            gl.bind_framebuffer(glow::FRAMEBUFFER, fbo);
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
        self.bind_target(k, unit, self.fbos[(k % 2) as usize], rect);
        unsafe {
            let (id, layer) = (Some(self.layers.id()), k.min(self.count - 1) as i32);
            gl.framebuffer_texture_layer(glow::FRAMEBUFFER, glow::COLOR_ATTACHMENT0, id, 0, layer);
            gl.depth_mask(true);
            gl.set_capability(glow::DEPTH_TEST, true);
            gl.depth_func(glow::LESS);
            gl.set_capability(glow::CULL_FACE, false);
            gl.clear_buffer_f32_slice(glow::COLOR, 0, &NO_CROSSING);
            gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[1.0]);
            if let Some(q) = self.query {
                gl.begin_query(glow::ANY_SAMPLES_PASSED, q);
            }
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

impl Drop for DepthPeel {
    fn drop(&mut self) {
        unsafe {
            for fbo in self.fbos.iter().chain([&self.rest_fbo]).flatten() {
                self.gl.delete_framebuffer(*fbo);
            }
            if let Some(q) = self.query {
                self.gl.delete_query(q);
            }
        }
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
        let Some(q) = self.peel.query else {
            return false;
        };
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
            if self.peel.query.is_some() {
                gl.end_query(glow::ANY_SAMPLES_PASSED);
            }
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
