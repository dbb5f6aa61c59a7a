//! The shadow maps past the chapter's one 2D map: a point light's depth cube map and a
//! directional light's depth array (cascades, caster groups), each with its framebuffer.

use glow::HasContext;

use super::fbo::depth_only;
use crate::engine::framebuffer::{Attachment, Framebuffer, Part};
use crate::engine::texture::Texture;
use crate::engine::Gl;
use crate::error::Result;
use crate::settings::DepthFormat;

/// The omnidirectional shadow map of a point light: a depth cube map and the framebuffer its
/// faces are drawn into, one pass per face (LearnOpenGL's "Point Shadows" on GL 3.3 without a
/// geometry shader).
pub struct CubeShadowMap {
    gl: Gl,
    fbo: Framebuffer,
    cube: Texture,
    format: DepthFormat,
}

impl CubeShadowMap {
    pub fn new(gl: &Gl, size: u32, format: DepthFormat) -> Result<CubeShadowMap> {
        let cube = Texture::depth_cube(gl, size, format)?;
        let what = format!("cube shadow map {size}x{size}");
        Ok(CubeShadowMap {
            gl: gl.clone(),
            fbo: depth_only(gl, &cube, Part::Face(0), &what)?,
            cube,
            format,
        })
    }

    /// Binds the framebuffer with face `face` (0..6: +X, -X, +Y, -Y, +Z, -Z) as its depth
    /// attachment, and the viewport to the face's size.
    pub fn bind_face(&self, face: u32) {
        self.fbo
            .attach(Attachment::Depth, &self.cube, Part::Face(face));
        self.viewport();
    }

    /// Binds the framebuffer with the whole cube map attached (layered: a geometry shader
    /// picks each face with gl_Layer), and the viewport to a face's size.
    pub fn bind_layered(&self) -> Result<()> {
        self.fbo
            .attach(Attachment::Depth, &self.cube, Part::Layered);
        self.viewport();
        self.fbo.check("layered cube shadow map")
    }

    fn viewport(&self) {
        let size = self.cube.width() as i32;
        unsafe { self.gl.viewport(0, 0, size, size) };
    }

    pub fn texture(&self) -> &Texture {
        &self.cube
    }

    pub fn format(&self) -> DepthFormat {
        self.format
    }

    pub fn size(&self) -> u32 {
        self.cube.width()
    }
}

/// The cascades of a cascaded shadow map: one depth texture array (a layer per cascade) and
/// a framebuffer per layer, its layer attached once when made (not re-pointed at each layer
/// every frame). GL 3.3 has texture arrays and `glFramebufferTextureLayer`, so no extension
/// is needed.
pub struct CascadeShadowMap {
    gl: Gl,
    fbos: Vec<Framebuffer>,
    array: Texture,
    format: DepthFormat,
    layers: u32,
}

impl CascadeShadowMap {
    pub fn new(gl: &Gl, size: u32, layers: u32, format: DepthFormat) -> Result<CascadeShadowMap> {
        let array = Texture::depth_array(gl, size, layers, format)?;
        let mut fbos = Vec::with_capacity(layers as usize);
        for layer in 0..layers {
            let what = format!("cascaded shadow map {size}x{size}x{layers}, layer {layer}");
            fbos.push(depth_only(gl, &array, Part::Layer(layer), &what)?);
        }
        Ok(CascadeShadowMap {
            gl: gl.clone(),
            fbos,
            array,
            format,
            layers,
        })
    }

    /// Binds the framebuffer of cascade `layer`, and the viewport to the layer's size.
    pub fn bind_layer(&self, layer: u32) {
        self.fbos[layer as usize].bind();
        let size = self.array.width() as i32;
        unsafe { self.gl.viewport(0, 0, size, size) };
    }

    pub fn texture(&self) -> &Texture {
        &self.array
    }

    pub fn format(&self) -> DepthFormat {
        self.format
    }

    pub fn size(&self) -> u32 {
        self.array.width()
    }

    pub fn layers(&self) -> u32 {
        self.layers
    }
}
