//! `Texture`: the book's texture class, with its file constructor and its depth constructor
//! ("Shadows", section "Shadow Mapping": `new Texture(width, height, pixelFormat)`).

use std::path::Path;

use glow::HasContext;
use serde::{Deserialize, Serialize};

use super::Gl;
use crate::error::{Error, Result};
use crate::image_data::ImageData;

/// Depth precision of a shadow map. The book asks for plain `GL_DEPTH_COMPONENT`, which Mesa
/// stores as 24 bits; we name the size so the choice is explicit and measurable.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default, clap::ValueEnum,
)]
pub enum DepthFormat {
    #[serde(rename = "16")]
    #[value(name = "16")]
    D16,
    #[default]
    #[serde(rename = "24")]
    #[value(name = "24")]
    D24,
    #[serde(rename = "32f")]
    #[value(name = "32f")]
    D32F,
}

impl DepthFormat {
    pub const ALL: [DepthFormat; 3] = [DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F];

    fn internal_format(self) -> u32 {
        match self {
            DepthFormat::D16 => glow::DEPTH_COMPONENT16,
            DepthFormat::D24 => glow::DEPTH_COMPONENT24,
            DepthFormat::D32F => glow::DEPTH_COMPONENT32F,
        }
    }

    /// The name used on the command line and in scene files.
    pub fn name(self) -> &'static str {
        match self {
            DepthFormat::D16 => "16",
            DepthFormat::D24 => "24",
            DepthFormat::D32F => "32f",
        }
    }
}

/// How lookups outside [0, 1] behave. The book clamps to the edge; LearnOpenGL's first steps
/// REPEAT (showing over-sampling) and its final step clamps to a border of depth 1.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default, clap::ValueEnum,
)]
#[serde(rename_all = "kebab-case")]
pub enum Wrap {
    #[default]
    ClampToEdge,
    ClampToBorder,
    Repeat,
}

impl Wrap {
    fn gl(self) -> u32 {
        match self {
            Wrap::ClampToEdge => glow::CLAMP_TO_EDGE,
            Wrap::ClampToBorder => glow::CLAMP_TO_BORDER,
            Wrap::Repeat => glow::REPEAT,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Wrap::ClampToEdge => "clamp-to-edge",
            Wrap::ClampToBorder => "clamp-to-border",
            Wrap::Repeat => "repeat",
        }
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
                format.internal_format() as i32,
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
                    format.internal_format() as i32,
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
                format.internal_format() as i32,
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
        unsafe {
            self.gl.bind_texture(self.target, Some(self.id));
            let p = |k, v: u32| self.gl.tex_parameter_i32(self.target, k, v as i32);
            p(glow::TEXTURE_MIN_FILTER, glow::NEAREST);
            p(glow::TEXTURE_MAG_FILTER, glow::NEAREST);
            for axis in [
                glow::TEXTURE_WRAP_S,
                glow::TEXTURE_WRAP_T,
                glow::TEXTURE_WRAP_R,
            ] {
                p(axis, glow::CLAMP_TO_EDGE);
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
        Ok(Texture {
            gl: gl.clone(),
            id,
            target,
            width,
            height,
        })
    }

    /// Sets the wrap mode; a border wrap gets a border of depth 1 (LearnOpenGL's fix), so
    /// lookups outside the map read "far away" and stay lit.
    pub fn set_wrap(&self, wrap: Wrap) {
        unsafe {
            self.gl.bind_texture(self.target, Some(self.id));
            let p = |k, v: u32| self.gl.tex_parameter_i32(self.target, k, v as i32);
            p(glow::TEXTURE_WRAP_S, wrap.gl());
            p(glow::TEXTURE_WRAP_T, wrap.gl());
            if wrap == Wrap::ClampToBorder {
                self.gl.tex_parameter_f32_slice(
                    self.target,
                    glow::TEXTURE_BORDER_COLOR,
                    &[1.0, 1.0, 1.0, 1.0],
                );
            }
            self.gl.bind_texture(self.target, None);
        }
    }

    /// Turns the depth comparison on (for `sampler2DShadow`, with LINEAR for hardware 2x2 PCF)
    /// or off (plain `sampler2D` reads, NEAREST as the book has it).
    pub fn set_compare(&self, compare: bool, linear: bool) {
        unsafe {
            self.gl.bind_texture(self.target, Some(self.id));
            let p = |k, v: u32| self.gl.tex_parameter_i32(self.target, k, v as i32);
            if compare {
                p(glow::TEXTURE_COMPARE_MODE, glow::COMPARE_REF_TO_TEXTURE);
                p(glow::TEXTURE_COMPARE_FUNC, glow::LEQUAL);
            } else {
                p(glow::TEXTURE_COMPARE_MODE, glow::NONE);
            }
            let filter = if linear { glow::LINEAR } else { glow::NEAREST };
            p(glow::TEXTURE_MIN_FILTER, filter);
            p(glow::TEXTURE_MAG_FILTER, filter);
            self.gl.bind_texture(self.target, None);
        }
    }

    /// Binds the texture to a texture unit (0-based).
    pub fn bind(&self, unit: u32) {
        unsafe {
            self.gl.active_texture(glow::TEXTURE0 + unit);
            self.gl.bind_texture(self.target, Some(self.id));
        }
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
        unsafe { self.gl.delete_texture(self.id) };
    }
}
