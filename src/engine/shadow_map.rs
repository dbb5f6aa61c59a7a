//! `ShadowMap`: the FBO the depth pass renders into, and its depth texture
//! ("Shadows", section "Shadow Mapping": the `ShadowMap` class).

use glow::HasContext;

use super::check::check_framebuffer;
use super::texture::Texture;
use super::Gl;
use crate::error::{Error, Result};
use crate::settings::{DepthFormat, MapSize};

/// Owns the framebuffer and the depth texture attached to it; both are freed on drop.
pub struct ShadowMap {
    gl: Gl,
    fbo: DepthFbo,
    depth_map: Texture,
    format: DepthFormat,
}

impl ShadowMap {
    /// Creates a depth-only framebuffer of `size` (square in the chapters, the canvas' shape
    /// in the shadow-playground). Like the book, it has no colour buffer (draw and read
    /// buffer NONE) and its completeness is checked.
    pub fn new(gl: &Gl, size: impl Into<MapSize>, format: DepthFormat) -> Result<ShadowMap> {
        let size = size.into();
        let texture = Texture::depth(gl, size.width, size.height, format)?;
        Self::from_texture(gl, texture, format)
    }

    /// Builds the framebuffer around an existing texture. A texture that cannot be a depth
    /// attachment gives [`Error::IncompleteFramebuffer`], never a silently black map.
    pub fn from_texture(gl: &Gl, depth_map: Texture, format: DepthFormat) -> Result<ShadowMap> {
        let (width, height) = (depth_map.width(), depth_map.height());
        // The FBO has its owner before the completeness check, so a failure frees it.
        let map = ShadowMap {
            gl: gl.clone(),
            fbo: DepthFbo::new(gl, "shadow-map framebuffer")?,
            depth_map,
            format,
        };
        map.fbo.bind();
        unsafe {
            gl.framebuffer_texture_2d(
                glow::FRAMEBUFFER,
                glow::DEPTH_ATTACHMENT,
                glow::TEXTURE_2D,
                Some(map.depth_map.id()),
                0,
            );
        }
        map.fbo.finish(&format!("shadow map {width}x{height}"))?;
        Ok(map)
    }

    /// Binds the FBO and sets the viewport to the map's size (the start of `renderDepthMap`).
    pub fn bind_for_writing(&self) {
        self.fbo.bind();
        unsafe {
            self.gl.viewport(
                0,
                0,
                self.depth_map.width() as i32,
                self.depth_map.height() as i32,
            );
        }
    }

    pub fn depth_map_texture(&self) -> &Texture {
        &self.depth_map
    }

    pub fn size(&self) -> MapSize {
        MapSize {
            width: self.depth_map.width(),
            height: self.depth_map.height(),
        }
    }

    pub fn format(&self) -> DepthFormat {
        self.format
    }

    /// Reads the depth values back (row 0 at the bottom, as GL stores them).
    pub fn read_depth(&self) -> Vec<f32> {
        let size = self.size();
        let n = size.texels() as usize;
        let mut bytes = vec![0u8; n * 4];
        self.fbo.bind();
        unsafe {
            self.gl.pixel_store_i32(glow::PACK_ALIGNMENT, 4);
            self.gl.read_pixels(
                0,
                0,
                size.width as i32,
                size.height as i32,
                glow::DEPTH_COMPONENT,
                glow::FLOAT,
                glow::PixelPackData::Slice(Some(&mut bytes)),
            );
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
        bytes
            .chunks_exact(4)
            .map(|c| f32::from_ne_bytes([c[0], c[1], c[2], c[3]]))
            .collect()
    }
}

/// A framebuffer with only a depth attachment (draw and read buffers NONE), shared by the
/// three kinds of shadow map; deleted on drop.
struct DepthFbo {
    gl: Gl,
    fbo: glow::Framebuffer,
}

impl DepthFbo {
    fn new(gl: &Gl, what: &str) -> Result<DepthFbo> {
        let fbo = unsafe { gl.create_framebuffer() }
            .map_err(|e| Error::Create(format!("{what}: {e}")))?;
        Ok(DepthFbo {
            gl: gl.clone(),
            fbo,
        })
    }

    fn bind(&self) {
        unsafe { self.gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo)) };
    }

    /// Once the depth attachment is bound: no colour buffers, then the completeness check
    /// (an error naming `what`, never a silently black map).
    fn finish(&self, what: &str) -> Result<()> {
        self.bind();
        unsafe {
            self.gl.draw_buffer(glow::NONE);
            self.gl.read_buffer(glow::NONE);
        }
        let status = check_framebuffer(&self.gl, what);
        unsafe { self.gl.bind_framebuffer(glow::FRAMEBUFFER, None) };
        status
    }
}

impl Drop for DepthFbo {
    fn drop(&mut self) {
        unsafe { self.gl.delete_framebuffer(self.fbo) };
    }
}

/// The omnidirectional shadow map of a point light: a depth cube map and the framebuffer its
/// faces are drawn into, one pass per face (LearnOpenGL's "Point Shadows" on GL 3.3 without a
/// geometry shader).
pub struct CubeShadowMap {
    gl: Gl,
    fbo: DepthFbo,
    cube: Texture,
    format: DepthFormat,
}

impl CubeShadowMap {
    pub fn new(gl: &Gl, size: u32, format: DepthFormat) -> Result<CubeShadowMap> {
        let map = CubeShadowMap {
            gl: gl.clone(),
            fbo: DepthFbo::new(gl, "cube shadow-map framebuffer")?,
            cube: Texture::depth_cube(gl, size, format)?,
            format,
        };
        map.bind_face(0);
        map.fbo.finish(&format!("cube shadow map {size}x{size}"))?;
        Ok(map)
    }

    /// Binds the framebuffer with face `face` (0..6: +X, -X, +Y, -Y, +Z, -Z) as its depth
    /// attachment, and the viewport to the face's size.
    pub fn bind_face(&self, face: u32) {
        self.fbo.bind();
        unsafe {
            self.gl.framebuffer_texture_2d(
                glow::FRAMEBUFFER,
                glow::DEPTH_ATTACHMENT,
                glow::TEXTURE_CUBE_MAP_POSITIVE_X + face,
                Some(self.cube.id()),
                0,
            );
            let size = self.cube.width() as i32;
            self.gl.viewport(0, 0, size, size);
        }
    }

    /// Binds the framebuffer with the whole cube map attached (layered: a geometry shader
    /// picks each face with gl_Layer), and the viewport to a face's size.
    pub fn bind_layered(&self) -> Result<()> {
        self.fbo.bind();
        unsafe {
            self.gl.framebuffer_texture(
                glow::FRAMEBUFFER,
                glow::DEPTH_ATTACHMENT,
                Some(self.cube.id()),
                0,
            );
            let size = self.cube.width() as i32;
            self.gl.viewport(0, 0, size, size);
        }
        check_framebuffer(&self.gl, "layered cube shadow map")
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
/// the framebuffer each layer is drawn into in turn. GL 3.3 has texture arrays and
/// `glFramebufferTextureLayer`, so no extension is needed.
pub struct CascadeShadowMap {
    gl: Gl,
    fbo: DepthFbo,
    array: Texture,
    format: DepthFormat,
    layers: u32,
}

impl CascadeShadowMap {
    pub fn new(gl: &Gl, size: u32, layers: u32, format: DepthFormat) -> Result<CascadeShadowMap> {
        let map = CascadeShadowMap {
            gl: gl.clone(),
            fbo: DepthFbo::new(gl, "cascade shadow-map framebuffer")?,
            array: Texture::depth_array(gl, size, layers, format)?,
            format,
            layers,
        };
        map.bind_layer(0);
        map.fbo
            .finish(&format!("cascaded shadow map {size}x{size}x{layers}"))?;
        Ok(map)
    }

    /// Binds the framebuffer with cascade `layer` as its depth attachment, and the viewport
    /// to the layer's size.
    pub fn bind_layer(&self, layer: u32) {
        self.fbo.bind();
        unsafe {
            self.gl.framebuffer_texture_layer(
                glow::FRAMEBUFFER,
                glow::DEPTH_ATTACHMENT,
                Some(self.array.id()),
                0,
                layer as i32,
            );
            let size = self.array.width() as i32;
            self.gl.viewport(0, 0, size, size);
        }
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
