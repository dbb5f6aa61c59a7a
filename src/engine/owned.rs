//! One owner for every GL object that is a single name: [`Owned<K>`] creates it through one
//! function (an error naming what it was for), counts it in [`super::counters`] and deletes
//! it on drop. A kind ([`GlKind`]) says how its objects are made, freed and counted.

use glow::HasContext;

use super::bindings::GlContext;
use super::counters::{count, Created};
use super::Gl;
use crate::error::{Error, Result};

/// A kind of GL object: how one is made, deleted and counted.
pub trait GlKind {
    /// The name glow hands back.
    type Raw: Copy;
    /// What making one needs besides the context (a shader's stage; `()` for the rest).
    type Spec: Copy;

    /// # Safety
    /// The context must be current on this thread.
    unsafe fn create(gl: &GlContext, spec: Self::Spec) -> std::result::Result<Self::Raw, String>;

    /// # Safety
    /// The context must be current on this thread and `raw` one of its live names.
    unsafe fn delete(gl: &GlContext, raw: Self::Raw);

    /// Adds one to this kind's count.
    fn count(created: &mut Created);
}

/// A GL object of kind `K`, deleted on drop.
pub struct Owned<K: GlKind> {
    gl: Gl,
    raw: K::Raw,
}

impl<K: GlKind<Spec = ()>> Owned<K> {
    /// Makes one; `what` names it in the error (`could not create {what}: ...`).
    pub(crate) fn new(gl: &Gl, what: &str) -> Result<Owned<K>> {
        Self::with(gl, what, ())
    }
}

impl<K: GlKind> Owned<K> {
    /// Makes one from `spec`; `what` names it in the error.
    pub(crate) fn with(gl: &Gl, what: &str, spec: K::Spec) -> Result<Owned<K>> {
        let raw =
            unsafe { K::create(gl, spec) }.map_err(|e| Error::Create(format!("{what}: {e}")))?;
        count(K::count);
        Ok(Owned {
            gl: gl.clone(),
            raw,
        })
    }

    /// The GL name, for the calls that take it.
    pub fn raw(&self) -> K::Raw {
        self.raw
    }

    /// The context it belongs to.
    pub fn gl(&self) -> &Gl {
        &self.gl
    }
}

impl<K: GlKind> Drop for Owned<K> {
    fn drop(&mut self) {
        unsafe { K::delete(&self.gl, self.raw) };
    }
}

/// Declares a kind whose objects are made with no spec: its name, glow's name type, the
/// create and delete calls, the counter, and what the bindings cache forgets first.
macro_rules! kind {
    ($(#[$doc:meta])* $kind:ident, $raw:ty, $create:ident, $delete:ident, $field:ident $(, $forget:ident)?) => {
        $(#[$doc])*
        pub enum $kind {}

        impl GlKind for $kind {
            type Raw = $raw;
            type Spec = ();

            unsafe fn create(gl: &GlContext, _: ()) -> std::result::Result<$raw, String> {
                gl.$create()
            }

            unsafe fn delete(gl: &GlContext, raw: $raw) {
                $(gl.$forget(raw);)?
                gl.$delete(raw);
            }

            fn count(created: &mut Created) {
                created.$field += 1;
            }
        }
    };
}

kind!(
    /// Textures; a deleted one leaves the units the bindings cache knew it on.
    TextureKind, glow::Texture, create_texture, delete_texture, textures, forget_texture
);
kind!(
    /// Framebuffers (made only by [`super::framebuffer::Framebuffer::build`]).
    FramebufferKind, glow::Framebuffer, create_framebuffer, delete_framebuffer, framebuffers
);
kind!(
    RenderbufferKind,
    glow::Renderbuffer,
    create_renderbuffer,
    delete_renderbuffer,
    renderbuffers
);
kind!(
    BufferKind,
    glow::Buffer,
    create_buffer,
    delete_buffer,
    buffers
);
kind!(
    VertexArrayKind,
    glow::VertexArray,
    create_vertex_array,
    delete_vertex_array,
    vertex_arrays
);
kind!(QueryKind, glow::Query, create_query, delete_query, queries);
kind!(
    SamplerKind,
    glow::Sampler,
    create_sampler,
    delete_sampler,
    samplers
);
kind!(
    /// Programs; a deleted one is no longer known to be in use.
    ProgramKind, glow::Program, create_program, delete_program, programs, forget_program
);

/// Shaders, made for one stage (`glow::VERTEX_SHADER`, ...) and deleted once linked.
pub enum ShaderKind {}

impl GlKind for ShaderKind {
    type Raw = glow::Shader;
    type Spec = u32;

    unsafe fn create(gl: &GlContext, stage: u32) -> std::result::Result<glow::Shader, String> {
        gl.create_shader(stage)
    }

    unsafe fn delete(gl: &GlContext, raw: glow::Shader) {
        gl.delete_shader(raw);
    }

    fn count(created: &mut Created) {
        created.shaders += 1;
    }
}

pub type OwnedTexture = Owned<TextureKind>;
pub type OwnedFramebuffer = Owned<FramebufferKind>;
pub type OwnedRenderbuffer = Owned<RenderbufferKind>;
pub type OwnedBuffer = Owned<BufferKind>;
pub type OwnedVertexArray = Owned<VertexArrayKind>;
pub type OwnedQuery = Owned<QueryKind>;
pub type OwnedSampler = Owned<SamplerKind>;
pub type OwnedProgram = Owned<ProgramKind>;
pub type OwnedShader = Owned<ShaderKind>;
