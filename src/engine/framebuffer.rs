//! `Framebuffer`: the one way the engine makes a framebuffer. [`Framebuffer::build`] makes
//! and counts it; the builder attaches textures (whole, a cube face, an array layer, or
//! layered) and renderbuffers it owns, and [`FramebufferBuilder::finish`] sets the draw
//! buffers from the colours attached (none: draw and read buffers NONE, the book's depth
//! map) and checks completeness, naming what the framebuffer is for.

use glow::HasContext;

use super::check::check_framebuffer;
use super::owned::{OwnedFramebuffer, OwnedRenderbuffer};
use super::texture::Texture;
use super::Gl;
use crate::error::Result;

/// Where an image is attached.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Attachment {
    Depth,
    DepthStencil,
    /// Colour attachment `i` (drawn to by fragment output `i`).
    Colour(u32),
}

impl Attachment {
    fn point(self) -> u32 {
        match self {
            Attachment::Depth => glow::DEPTH_ATTACHMENT,
            Attachment::DepthStencil => glow::DEPTH_STENCIL_ATTACHMENT,
            Attachment::Colour(i) => glow::COLOR_ATTACHMENT0 + i,
        }
    }
}

/// Which part of a texture is attached.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Part {
    /// A 2D texture's level 0.
    Image,
    /// Face `f` of a cube map (0..6: +X, -X, +Y, -Y, +Z, -Z).
    Face(u32),
    /// Layer `l` of an array.
    Layer(u32),
    /// Every face or layer at once (a geometry shader picks one with `gl_Layer`).
    Layered,
}

/// An owned framebuffer and the renderbuffers attached to it; all deleted on drop.
pub struct Framebuffer {
    fbo: OwnedFramebuffer,
    renderbuffers: Vec<OwnedRenderbuffer>,
}

/// A framebuffer being put together; bound until [`FramebufferBuilder::finish`].
pub(crate) struct FramebufferBuilder {
    fb: Framebuffer,
    colours: Vec<u32>,
}

impl Framebuffer {
    /// Makes (and counts) a framebuffer, `what` naming it if that fails, and binds it to
    /// attach its images.
    pub(crate) fn build(gl: &Gl, what: &str) -> Result<FramebufferBuilder> {
        let fb = Framebuffer {
            fbo: OwnedFramebuffer::new(gl, &format!("{what} framebuffer"))?,
            renderbuffers: Vec::new(),
        };
        fb.bind();
        Ok(FramebufferBuilder {
            fb,
            colours: Vec::new(),
        })
    }

    fn gl(&self) -> &Gl {
        self.fbo.gl()
    }

    /// Binds it for drawing and reading.
    pub(crate) fn bind(&self) {
        unsafe { (self.gl()).bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo.raw())) };
    }

    pub(crate) fn raw(&self) -> glow::Framebuffer {
        self.fbo.raw()
    }

    /// Binds it and points `at` at `part` of `texture` instead of what was there (a cube
    /// map's next face, a peel's next layer).
    pub(crate) fn attach(&self, at: Attachment, texture: &Texture, part: Part) {
        self.bind();
        attach_texture(self.gl(), at, texture, part);
    }

    /// Checks the framebuffer, bound, is complete; an error names `what`.
    pub(crate) fn check(&self, what: &str) -> Result<()> {
        check_framebuffer(self.gl(), what)
    }
}

impl FramebufferBuilder {
    /// Attaches `part` of `texture` at `at`.
    pub(crate) fn texture(mut self, at: Attachment, texture: &Texture, part: Part) -> Self {
        attach_texture(self.fb.gl(), at, texture, part);
        self.colour(at);
        self
    }

    /// Attaches a new `width` x `height` renderbuffer of `internal` format at `at`; the
    /// framebuffer owns it.
    pub(crate) fn renderbuffer(
        mut self,
        at: Attachment,
        internal: u32,
        (width, height): (u32, u32),
        what: &str,
    ) -> Result<Self> {
        let gl = self.fb.gl().clone();
        let rb = OwnedRenderbuffer::new(&gl, what)?;
        unsafe {
            gl.bind_renderbuffer(glow::RENDERBUFFER, Some(rb.raw()));
            gl.renderbuffer_storage(glow::RENDERBUFFER, internal, width as i32, height as i32);
            gl.bind_renderbuffer(glow::RENDERBUFFER, None);
            let (point, target) = (at.point(), glow::RENDERBUFFER);
            gl.framebuffer_renderbuffer(glow::FRAMEBUFFER, point, target, Some(rb.raw()));
        }
        self.fb.renderbuffers.push(rb);
        self.colour(at);
        Ok(self)
    }

    fn colour(&mut self, at: Attachment) {
        if let Attachment::Colour(i) = at {
            self.colours.push(i);
        }
    }

    /// Draws to the colours attached, in order of their numbers (NONE for a number left
    /// out); with none, draws and reads nothing. Then the completeness check (an error
    /// naming `what`, never a silently black map), and no framebuffer bound.
    pub(crate) fn finish(self, what: &str) -> Result<Framebuffer> {
        let gl = self.fb.gl();
        unsafe {
            match self.colours.iter().max() {
                None => {
                    gl.draw_buffer(glow::NONE);
                    gl.read_buffer(glow::NONE);
                }
                Some(&last) => {
                    let buffers: Vec<u32> = (0..=last)
                        .map(|i| match self.colours.contains(&i) {
                            true => glow::COLOR_ATTACHMENT0 + i,
                            false => glow::NONE,
                        })
                        .collect();
                    gl.draw_buffers(&buffers);
                }
            }
        }
        let status = self.fb.check(what);
        unsafe { gl.bind_framebuffer(glow::FRAMEBUFFER, None) };
        status.map(|()| self.fb)
    }
}

/// Attaches `part` of `texture` at `at` of the bound framebuffer.
fn attach_texture(gl: &Gl, at: Attachment, texture: &Texture, part: Part) {
    let (fb, point, id) = (glow::FRAMEBUFFER, at.point(), Some(texture.id()));
    unsafe {
        match part {
            Part::Image => gl.framebuffer_texture_2d(fb, point, glow::TEXTURE_2D, id, 0),
            Part::Face(f) => {
                let face = glow::TEXTURE_CUBE_MAP_POSITIVE_X + f;
                gl.framebuffer_texture_2d(fb, point, face, id, 0);
            }
            Part::Layer(l) => gl.framebuffer_texture_layer(fb, point, id, 0, l as i32),
            Part::Layered => gl.framebuffer_texture(fb, point, id, 0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::counters::{created, Created};
    use crate::engine::{
        DepthPeel, FullScreenTriangle, HeadlessContext, MomentMap, Sampler, SamplesQuery, Sampling,
        SummedAreaTable, VertexCapture,
    };
    use crate::error::Error;
    use crate::settings::{DepthFormat, MapSize};

    /// What `make` makes, by kind (what it made is dropped after).
    fn made<T>(make: impl FnOnce() -> T) -> Created {
        let before = created();
        drop(make());
        created().since(before)
    }

    /// The objects that once escaped the counters (the summed-area table's and the vertex
    /// capture's framebuffers, queries, vertex arrays, samplers) are counted with the rest.
    #[test]
    fn every_object_is_counted_when_made() {
        let context = HeadlessContext::new().expect("a headless context");
        let gl = context.gl();
        let size = MapSize::square(8);
        let table = made(|| SummedAreaTable::new(gl, size, 2).unwrap());
        let want = Created {
            textures: 2,
            framebuffers: 2,
            ..Created::default()
        };
        assert_eq!(table, want);
        let capture = made(|| VertexCapture::new(gl).unwrap());
        let want = Created {
            buffers: 1,
            framebuffers: 1,
            renderbuffers: 1,
            ..Created::default()
        };
        assert_eq!(capture, want);
        let peel = made(|| DepthPeel::new(gl, size, 2).unwrap());
        let want = Created {
            textures: 4,
            framebuffers: 3,
            queries: 1,
            ..Created::default()
        };
        assert_eq!(peel, want);
        let moments = made(|| MomentMap::new(gl, size, 4).unwrap());
        let want = Created {
            textures: 2,
            framebuffers: 2,
            renderbuffers: 1,
            ..Created::default()
        };
        assert_eq!(moments, want);
        let small = made(|| {
            let triangle = FullScreenTriangle::new(gl).unwrap();
            let query = SamplesQuery::new(gl).unwrap();
            (triangle, query, Sampler::new(gl, Sampling::PLAIN).unwrap())
        });
        let want = Created {
            vertex_arrays: 1,
            queries: 1,
            samplers: 1,
            ..Created::default()
        };
        assert_eq!(small, want);
    }

    /// A framebuffer that cannot be complete says what it was for, and is still counted
    /// (and freed: its owner drops it with the error).
    #[test]
    fn an_incomplete_framebuffer_names_what_it_is_for() {
        let context = HeadlessContext::new().expect("a headless context");
        let gl = context.gl();
        let depth = Texture::depth(gl, 8, 8, DepthFormat::D24).unwrap();
        let before = created();
        let result = Framebuffer::build(gl, "a test")
            .unwrap()
            .texture(Attachment::Colour(0), &depth, Part::Image)
            .finish("a depth texture as colour");
        let Err(Error::IncompleteFramebuffer { what, .. }) = result else {
            panic!("a depth texture as a colour attachment was accepted");
        };
        assert_eq!(what, "a depth texture as colour");
        assert_eq!(created().since(before).framebuffers, 1);
    }
}
