//! `Texture`: the book's texture class, with its file constructor and its depth constructor
//! ("Shadows", section "Shadow Mapping": `new Texture(width, height, pixelFormat)`).

use std::path::Path;

use glow::HasContext;

use super::Gl;
use crate::error::{Error, Result};
use crate::image_data::ImageData;
use crate::settings::DepthFormat;

/// The GL internal format of a depth map.
pub(super) fn depth_internal_format(format: DepthFormat) -> u32 {
    match format {
        DepthFormat::D16 => glow::DEPTH_COMPONENT16,
        DepthFormat::D24 => glow::DEPTH_COMPONENT24,
        DepthFormat::D32F => glow::DEPTH_COMPONENT32F,
    }
}

/// An owned GL texture (2D, cube map or 2D array: `target`); deleted on drop.
pub struct Texture {
    gl: Gl,
    id: glow::Texture,
    target: u32,
    width: u32,
    height: u32,
}

impl Texture {
    /// Uploads an RGBA8 image (decoded from a PNG by [`ImageData::load_png`]), with mipmaps and
    /// REPEAT wrapping so floors can tile it.
    pub fn from_image(gl: &Gl, image: &ImageData) -> Result<Texture> {
        let texture = Texture::create(
            gl,
            glow::TEXTURE_2D,
            image.width,
            image.height,
            "colour texture",
        )?;
        unsafe {
            gl.bind_texture(glow::TEXTURE_2D, Some(texture.id));
            gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 1);
            gl.tex_image_2d(
                glow::TEXTURE_2D,
                0,
                glow::RGBA8 as i32,
                image.width as i32,
                image.height as i32,
                0,
                glow::RGBA,
                glow::UNSIGNED_BYTE,
                glow::PixelUnpackData::Slice(Some(&image.rgba)),
            );
            gl.generate_mipmap(glow::TEXTURE_2D);
            let p = |k, v: u32| gl.tex_parameter_i32(glow::TEXTURE_2D, k, v as i32);
            p(glow::TEXTURE_MIN_FILTER, glow::LINEAR_MIPMAP_LINEAR);
            p(glow::TEXTURE_MAG_FILTER, glow::LINEAR);
            p(glow::TEXTURE_WRAP_S, glow::REPEAT);
            p(glow::TEXTURE_WRAP_T, glow::REPEAT);
            gl.bind_texture(glow::TEXTURE_2D, None);
        }
        Ok(texture)
    }

    /// The book's file constructor: loads a PNG and uploads it.
    pub fn from_file(gl: &Gl, path: &Path) -> Result<Texture> {
        Texture::from_image(gl, &ImageData::load_png(path)?)
    }

    /// The book's depth constructor: an empty depth texture with NEAREST filtering and
    /// CLAMP_TO_EDGE, ready to be a framebuffer's depth attachment.
    pub fn depth(gl: &Gl, width: u32, height: u32, format: DepthFormat) -> Result<Texture> {
        let texture = Texture::create(gl, glow::TEXTURE_2D, width, height, "depth texture")?;
        unsafe {
            gl.bind_texture(glow::TEXTURE_2D, Some(texture.id));
            gl.tex_image_2d(
                glow::TEXTURE_2D,
                0,
                depth_internal_format(format) as i32,
                width as i32,
                height as i32,
                0,
                glow::DEPTH_COMPONENT,
                glow::FLOAT,
                glow::PixelUnpackData::Slice(None),
            );
        }
        texture.nearest_clamped();
        Ok(texture)
    }

    /// An empty RGBA8 colour texture.
    pub fn colour(gl: &Gl, width: u32, height: u32) -> Result<Texture> {
        Texture::attachment(
            gl,
            width,
            height,
            glow::RGBA8,
            glow::RGBA,
            glow::UNSIGNED_BYTE,
        )
    }

    /// An empty depth cube map, `size` texels a side per face (LearnOpenGL's point shadows):
    /// NEAREST, clamped on all three axes.
    pub fn depth_cube(gl: &Gl, size: u32, format: DepthFormat) -> Result<Texture> {
        let texture = Texture::create(gl, glow::TEXTURE_CUBE_MAP, size, size, "depth cube map")?;
        unsafe {
            gl.bind_texture(glow::TEXTURE_CUBE_MAP, Some(texture.id));
            for face in 0..6 {
                gl.tex_image_2d(
                    glow::TEXTURE_CUBE_MAP_POSITIVE_X + face,
                    0,
                    depth_internal_format(format) as i32,
                    size as i32,
                    size as i32,
                    0,
                    glow::DEPTH_COMPONENT,
                    glow::FLOAT,
                    glow::PixelUnpackData::Slice(None),
                );
            }
        }
        texture.nearest_clamped();
        Ok(texture)
    }

    /// An empty array of `layers` depth textures, `size` texels a side (the cascades of a
    /// cascaded shadow map): NEAREST, clamped, each layer a framebuffer attachment.
    pub fn depth_array(gl: &Gl, size: u32, layers: u32, format: DepthFormat) -> Result<Texture> {
        let texture = Texture::create(gl, glow::TEXTURE_2D_ARRAY, size, size, "depth array")?;
        unsafe {
            gl.bind_texture(glow::TEXTURE_2D_ARRAY, Some(texture.id));
            gl.tex_image_3d(
                glow::TEXTURE_2D_ARRAY,
                0,
                depth_internal_format(format) as i32,
                size as i32,
                size as i32,
                layers as i32,
                0,
                glow::DEPTH_COMPONENT,
                glow::FLOAT,
                glow::PixelUnpackData::Slice(None),
            );
        }
        texture.nearest_clamped();
        Ok(texture)
    }

    /// An empty 32-bit float colour texture of 2 or 4 components (a moment shadow map):
    /// NEAREST, clamped, ready to be a framebuffer's colour attachment. Float colour
    /// targets are core in GL 3.3.
    pub fn float_target(gl: &Gl, width: u32, height: u32, components: u32) -> Result<Texture> {
        let (internal, format) = match components {
            2 => (glow::RG32F, glow::RG),
            4 => (glow::RGBA32F, glow::RGBA),
            n => {
                return Err(Error::Invalid(format!(
                    "float target with {n} components: expected 2 or 4"
                )))
            }
        };
        let texture = Texture::attachment(gl, width, height, internal, format, glow::FLOAT)?;
        texture.nearest_clamped();
        Ok(texture)
    }

    /// An empty array of `layers` RGBA32F textures (a translucent map's layers, each a
    /// colour attachment of one framebuffer): LINEAR, clamped; the lookups sum them, and
    /// what they sum is linear in the crossings, so filtering them is exact.
    pub fn float_array(gl: &Gl, width: u32, height: u32, layers: u32) -> Result<Texture> {
        let texture = Texture::float_layers(gl, width, height, layers, glow::RGBA32F)?;
        texture.sampling(glow::LINEAR, glow::CLAMP_TO_EDGE);
        Ok(texture)
    }

    /// An empty array of `layers` RG32F textures (depth peeling's layers, one a pass, read
    /// back with `texelFetch`): NEAREST, clamped.
    pub fn float_rg_array(gl: &Gl, width: u32, height: u32, layers: u32) -> Result<Texture> {
        let texture = Texture::float_layers(gl, width, height, layers, glow::RG32F)?;
        texture.nearest_clamped();
        Ok(texture)
    }

    /// An empty 2D array of `layers` float textures of `internal` (RG32F or RGBA32F).
    fn float_layers(
        gl: &Gl,
        width: u32,
        height: u32,
        layers: u32,
        internal: u32,
    ) -> Result<Texture> {
        let texture = Texture::create(gl, glow::TEXTURE_2D_ARRAY, width, height, "float array")?;
        let format = match internal {
            glow::RG32F => glow::RG,
            _ => glow::RGBA,
        };
        unsafe {
            gl.bind_texture(glow::TEXTURE_2D_ARRAY, Some(texture.id));
            gl.tex_image_3d(
                glow::TEXTURE_2D_ARRAY,
                0,
                internal as i32,
                width as i32,
                height as i32,
                layers as i32,
                0,
                format,
                glow::FLOAT,
                glow::PixelUnpackData::Slice(None),
            );
            gl.bind_texture(glow::TEXTURE_2D_ARRAY, None);
        }
        Ok(texture)
    }

    /// An empty colour texture used as a render-target attachment.
    pub(crate) fn attachment(
        gl: &Gl,
        width: u32,
        height: u32,
        internal_format: u32,
        format: u32,
        ty: u32,
    ) -> Result<Texture> {
        let texture =
            Texture::create(gl, glow::TEXTURE_2D, width, height, "render-target texture")?;
        unsafe {
            gl.bind_texture(glow::TEXTURE_2D, Some(texture.id));
            gl.tex_image_2d(
                glow::TEXTURE_2D,
                0,
                internal_format as i32,
                width as i32,
                height as i32,
                0,
                format,
                ty,
                glow::PixelUnpackData::Slice(None),
            );
            let p = |k, v: u32| gl.tex_parameter_i32(glow::TEXTURE_2D, k, v as i32);
            p(glow::TEXTURE_MIN_FILTER, glow::NEAREST);
            p(glow::TEXTURE_MAG_FILTER, glow::NEAREST);
            gl.bind_texture(glow::TEXTURE_2D, None);
        }
        Ok(texture)
    }

    /// A depth texture's sampling: NEAREST (the book's), clamped on every axis.
    fn nearest_clamped(&self) {
        self.sampling(glow::NEAREST, glow::CLAMP_TO_EDGE);
    }

    /// `filter` for minifying and magnifying, `wrap` on every axis.
    pub(super) fn sampling(&self, filter: u32, wrap: u32) {
        unsafe {
            self.gl.bind_texture(self.target, Some(self.id));
            let p = |k, v: u32| self.gl.tex_parameter_i32(self.target, k, v as i32);
            p(glow::TEXTURE_MIN_FILTER, filter);
            p(glow::TEXTURE_MAG_FILTER, filter);
            for axis in [
                glow::TEXTURE_WRAP_S,
                glow::TEXTURE_WRAP_T,
                glow::TEXTURE_WRAP_R,
            ] {
                p(axis, wrap);
            }
            self.gl.bind_texture(self.target, None);
        }
    }

    fn create(gl: &Gl, target: u32, width: u32, height: u32, what: &str) -> Result<Texture> {
        if width == 0 || height == 0 {
            return Err(Error::Invalid(format!(
                "{what}: size {width}x{height}: expected both sides at least 1"
            )));
        }
        let id =
            unsafe { gl.create_texture() }.map_err(|e| Error::Create(format!("{what}: {e}")))?;
        super::counters::count(|c| c.textures += 1);
        // The caller binds it to set it up, on whatever unit is active.
        gl.forget_bindings();
        Ok(Texture {
            gl: gl.clone(),
            id,
            target,
            width,
            height,
        })
    }

    /// Binds the texture to a texture unit (0-based).
    pub fn bind(&self, unit: u32) {
        self.gl.bind_texture_once(unit, self.target, self.id);
    }

    pub fn id(&self) -> glow::Texture {
        self.id
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }
}

impl Drop for Texture {
    fn drop(&mut self) {
        self.gl.forget_texture(self.id);
        unsafe { self.gl.delete_texture(self.id) };
    }
}
