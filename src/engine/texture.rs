//! `Texture`: the book's texture class, with its file constructor and its depth constructor
//! ("Shadows", section "Shadow Mapping": `new Texture(width, height, pixelFormat)`).

use std::path::Path;

use glow::HasContext;

use super::owned::OwnedTexture;
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

/// How a texture (or a sampler object) filters and wraps: the one place these parameters
/// are set ([`Filtering::apply`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Filtering {
    pub min: u32,
    pub mag: u32,
    /// On every axis (R is ignored by a 2D texture).
    pub wrap: u32,
}

impl Filtering {
    /// `filter` for minifying and magnifying, `wrap` on every axis.
    pub(crate) const fn new(filter: u32, wrap: u32) -> Filtering {
        Filtering {
            min: filter,
            mag: filter,
            wrap,
        }
    }

    /// A depth texture's (the book's): NEAREST, clamped.
    pub(crate) const NEAREST_CLAMPED: Filtering =
        Filtering::new(glow::NEAREST, glow::CLAMP_TO_EDGE);
    /// A texture whose reads are filtered and summed, clamped.
    pub(crate) const LINEAR_CLAMPED: Filtering = Filtering::new(glow::LINEAR, glow::CLAMP_TO_EDGE);
    /// A render target's colour: NEAREST, and GL's own default wrap (REPEAT).
    pub(crate) const ATTACHMENT: Filtering = Filtering::new(glow::NEAREST, glow::REPEAT);
    /// A colour image from a file: mipmapped, repeated so floors can tile it.
    const IMAGE: Filtering = Filtering {
        min: glow::LINEAR_MIPMAP_LINEAR,
        mag: glow::LINEAR,
        wrap: glow::REPEAT,
    };

    /// Whether the minifying filter reads mipmaps (which are then generated).
    fn mipmapped(self) -> bool {
        matches!(
            self.min,
            glow::LINEAR_MIPMAP_LINEAR
                | glow::LINEAR_MIPMAP_NEAREST
                | glow::NEAREST_MIPMAP_LINEAR
                | glow::NEAREST_MIPMAP_NEAREST
        )
    }

    /// Sets the parameters through `set` (`glTexParameteri` on a bound texture, or
    /// `glSamplerParameteri` on a sampler object).
    pub(crate) fn apply(self, set: impl Fn(u32, u32)) {
        set(glow::TEXTURE_MIN_FILTER, self.min);
        set(glow::TEXTURE_MAG_FILTER, self.mag);
        for axis in [
            glow::TEXTURE_WRAP_S,
            glow::TEXTURE_WRAP_T,
            glow::TEXTURE_WRAP_R,
        ] {
            set(axis, self.wrap);
        }
    }
}

/// What a texel holds: GL's internal format, and the format and type of data sent to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Texels {
    pub internal: u32,
    pub format: u32,
    pub ty: u32,
}

impl Texels {
    const RGBA8: Texels = Texels {
        internal: glow::RGBA8,
        format: glow::RGBA,
        ty: glow::UNSIGNED_BYTE,
    };

    /// No texels are sent, but OpenGL ES (WebGL2) still takes only the type that matches
    /// the internal format; desktop GL takes any.
    fn depth(format: DepthFormat) -> Texels {
        Texels {
            internal: depth_internal_format(format),
            format: glow::DEPTH_COMPONENT,
            ty: match format {
                DepthFormat::D16 => glow::UNSIGNED_SHORT,
                DepthFormat::D24 => glow::UNSIGNED_INT,
                DepthFormat::D32F => glow::FLOAT,
            },
        }
    }

    /// 32-bit floats of 2 or 4 components.
    fn float(components: u32, what: &str) -> Result<Texels> {
        let (internal, format) = match components {
            1 => (glow::R32F, glow::RED),
            2 => (glow::RG32F, glow::RG),
            4 => (glow::RGBA32F, glow::RGBA),
            n => {
                return Err(Error::Invalid(format!(
                    "{what} with {n} components: expected 1, 2 or 4"
                )))
            }
        };
        Ok(Texels {
            internal,
            format,
            ty: glow::FLOAT,
        })
    }
}

/// The texture's kind: one 2D image, a cube map's six faces, or an array of `n` layers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shape {
    Flat,
    Cube,
    Layers(u32),
}

impl Shape {
    fn target(self) -> u32 {
        match self {
            Shape::Flat => glow::TEXTURE_2D,
            Shape::Cube => glow::TEXTURE_CUBE_MAP,
            Shape::Layers(_) => glow::TEXTURE_2D_ARRAY,
        }
    }
}

/// An owned GL texture (2D, cube map or 2D array: `target`); deleted on drop.
pub struct Texture {
    name: OwnedTexture,
    target: u32,
    width: u32,
    height: u32,
    /// Depth texels (a shadow map): what OpenGL ES cannot filter without a comparison.
    depth: bool,
}

impl Texture {
    /// Uploads an RGBA8 image (decoded from a PNG by [`ImageData::load_png`]), with mipmaps and
    /// REPEAT wrapping so floors can tile it.
    pub fn from_image(gl: &Gl, image: &ImageData) -> Result<Texture> {
        let (w, h) = (image.width, image.height);
        let pixels = Some(image.rgba.as_slice());
        let texels = Texels::RGBA8;
        Texture::make(
            gl,
            "colour texture",
            Shape::Flat,
            (w, h),
            texels,
            pixels,
            Filtering::IMAGE,
        )
    }

    /// The book's file constructor: loads a PNG and uploads it.
    pub fn from_file(gl: &Gl, path: &Path) -> Result<Texture> {
        Texture::from_image(gl, &ImageData::load_png(path)?)
    }

    /// The book's depth constructor: an empty depth texture with NEAREST filtering and
    /// CLAMP_TO_EDGE, ready to be a framebuffer's depth attachment.
    pub fn depth(gl: &Gl, width: u32, height: u32, format: DepthFormat) -> Result<Texture> {
        let texels = Texels::depth(format);
        let filtering = Filtering::NEAREST_CLAMPED;
        Texture::make(
            gl,
            "depth texture",
            Shape::Flat,
            (width, height),
            texels,
            None,
            filtering,
        )
    }

    /// An empty RGBA8 colour texture.
    pub fn colour(gl: &Gl, width: u32, height: u32) -> Result<Texture> {
        Texture::flat(
            gl,
            "colour texture",
            (width, height),
            Texels::RGBA8,
            Filtering::ATTACHMENT,
        )
    }

    /// An empty depth cube map, `size` texels a side per face (LearnOpenGL's point shadows):
    /// NEAREST, clamped on all three axes.
    pub fn depth_cube(gl: &Gl, size: u32, format: DepthFormat) -> Result<Texture> {
        let texels = Texels::depth(format);
        let filtering = Filtering::NEAREST_CLAMPED;
        Texture::make(
            gl,
            "depth cube map",
            Shape::Cube,
            (size, size),
            texels,
            None,
            filtering,
        )
    }

    /// An empty array of `layers` depth textures, `size` texels a side (the cascades of a
    /// cascaded shadow map): NEAREST, clamped, each layer a framebuffer attachment.
    pub fn depth_array(gl: &Gl, size: u32, layers: u32, format: DepthFormat) -> Result<Texture> {
        let shape = Shape::Layers(layers);
        let texels = Texels::depth(format);
        let filtering = Filtering::NEAREST_CLAMPED;
        Texture::make(
            gl,
            "depth array",
            shape,
            (size, size),
            texels,
            None,
            filtering,
        )
    }

    /// An empty 32-bit float colour texture of 2 or 4 components (a moment shadow map):
    /// NEAREST, clamped, ready to be a framebuffer's colour attachment. Float colour
    /// targets are core in GL 3.3.
    pub fn float_target(gl: &Gl, width: u32, height: u32, components: u32) -> Result<Texture> {
        let texels = Texels::float(components, "float target")?;
        Texture::flat(
            gl,
            "float target",
            (width, height),
            texels,
            Filtering::NEAREST_CLAMPED,
        )
    }

    /// An empty array of `layers` RGBA32F textures (a translucent map's layers, each a
    /// colour attachment of one framebuffer): LINEAR, clamped; the lookups sum them, and
    /// what they sum is linear in the crossings, so filtering them is exact.
    pub fn float_array(gl: &Gl, width: u32, height: u32, layers: u32) -> Result<Texture> {
        let texels = Texels::float(4, "float array")?;
        let (shape, filtering) = (Shape::Layers(layers), Filtering::LINEAR_CLAMPED);
        Texture::make(
            gl,
            "float array",
            shape,
            (width, height),
            texels,
            None,
            filtering,
        )
    }

    /// An empty array of `layers` RG32F textures (depth peeling's layers, one a pass, read
    /// back with `texelFetch`): NEAREST, clamped.
    pub fn float_rg_array(gl: &Gl, width: u32, height: u32, layers: u32) -> Result<Texture> {
        let texels = Texels::float(2, "float array")?;
        let (shape, filtering) = (Shape::Layers(layers), Filtering::NEAREST_CLAMPED);
        Texture::make(
            gl,
            "float array",
            shape,
            (width, height),
            texels,
            None,
            filtering,
        )
    }

    /// An empty colour texture used as a render-target attachment (NEAREST).
    pub(crate) fn attachment(
        gl: &Gl,
        width: u32,
        height: u32,
        internal: u32,
        format: u32,
        ty: u32,
    ) -> Result<Texture> {
        let texels = Texels {
            internal,
            format,
            ty,
        };
        let size = (width, height);
        Texture::flat(
            gl,
            "render-target texture",
            size,
            texels,
            Filtering::ATTACHMENT,
        )
    }

    /// An empty 2D texture of `texels`, sampled with `filtering`.
    pub(crate) fn flat(
        gl: &Gl,
        what: &str,
        size: (u32, u32),
        texels: Texels,
        filtering: Filtering,
    ) -> Result<Texture> {
        Texture::make(gl, what, Shape::Flat, size, texels, None, filtering)
    }

    /// A 2D texture holding `pixels` (tightly packed, its first row at v = 0), sampled with
    /// `filtering`.
    pub(crate) fn flat_from(
        gl: &Gl,
        what: &str,
        size: (u32, u32),
        texels: Texels,
        pixels: &[u8],
        filtering: Filtering,
    ) -> Result<Texture> {
        Texture::make(gl, what, Shape::Flat, size, texels, Some(pixels), filtering)
    }

    /// The one way a texture is made: its name, its storage of `shape` (filled from
    /// `pixels` when given, tightly packed), mipmaps if `filtering` reads them, and its
    /// sampling. Leaves no texture bound on the active unit.
    fn make(
        gl: &Gl,
        what: &str,
        shape: Shape,
        (width, height): (u32, u32),
        texels: Texels,
        pixels: Option<&[u8]>,
        filtering: Filtering,
    ) -> Result<Texture> {
        let target = shape.target();
        if texels.ty == glow::FLOAT && texels.format != glow::DEPTH_COMPONENT && pixels.is_none() {
            check_float_targets(gl, what)?;
        }
        let texture = Texture::create(gl, target, width, height, what)?;
        let (w, h) = (width as i32, height as i32);
        let Texels {
            internal,
            format,
            ty,
        } = texels;
        let internal = internal as i32;
        unsafe {
            gl.bind_texture(target, Some(texture.id()));
            if pixels.is_some() {
                gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 1);
            }
            let data = || glow::PixelUnpackData::Slice(pixels);
            match shape {
                Shape::Flat => gl.tex_image_2d(target, 0, internal, w, h, 0, format, ty, data()),
                Shape::Cube => {
                    for face in 0..6 {
                        let face = glow::TEXTURE_CUBE_MAP_POSITIVE_X + face;
                        gl.tex_image_2d(face, 0, internal, w, h, 0, format, ty, data());
                    }
                }
                Shape::Layers(n) => {
                    let n = n as i32;
                    gl.tex_image_3d(target, 0, internal, w, h, n, 0, format, ty, data());
                }
            }
            if filtering.mipmapped() {
                gl.generate_mipmap(target);
            }
        }
        texture.sampling(filtering);
        Ok(Texture {
            depth: format == glow::DEPTH_COMPONENT,
            ..texture
        })
    }

    /// Whether the texels are depths (a shadow map's).
    pub fn is_depth(&self) -> bool {
        self.depth
    }

    /// Sets how the texture filters and wraps ([`Filtering::apply`]).
    pub(crate) fn sampling(&self, filtering: Filtering) {
        let gl = self.name.gl();
        unsafe {
            gl.bind_texture(self.target, Some(self.id()));
            filtering.apply(|k, v| gl.tex_parameter_i32(self.target, k, v as i32));
            gl.bind_texture(self.target, None);
        }
    }

    fn create(gl: &Gl, target: u32, width: u32, height: u32, what: &str) -> Result<Texture> {
        if width == 0 || height == 0 {
            return Err(Error::Invalid(format!(
                "{what}: size {width}x{height}: expected both sides at least 1"
            )));
        }
        let name = OwnedTexture::new(gl, what)?;
        // The caller binds it to set it up, on whatever unit is active.
        gl.forget_bindings();
        Ok(Texture {
            name,
            target,
            width,
            height,
            depth: false,
        })
    }

    /// Binds the texture to a texture unit (0-based).
    pub fn bind(&self, unit: u32) {
        self.name
            .gl()
            .bind_texture_once(unit, self.target, self.id());
    }

    pub fn id(&self) -> glow::Texture {
        self.name.raw()
    }

    /// GL's target: `TEXTURE_2D`, `TEXTURE_CUBE_MAP` or `TEXTURE_2D_ARRAY`.
    pub fn target(&self) -> u32 {
        self.target
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }
}

/// An empty float colour texture is a render target (moment maps, translucent layers, the
/// shadow mask). Desktop GL 3.3 renders into 32-bit floats; OpenGL ES 3.0 and WebGL2 only
/// with EXT_color_buffer_float (glow enables every extension the browser offers), so
/// without it such a picture is refused by name instead of drawn from an incomplete target.
fn check_float_targets(gl: &Gl, what: &str) -> Result<()> {
    const EXTENSION: &str = "EXT_color_buffer_float";
    if gl.version().is_embedded && !gl.supported_extensions().contains(EXTENSION) {
        return Err(Error::Invalid(format!(
            "this picture renders into 32-bit floats ({what}), which OpenGL ES and WebGL2 \
             do only with {EXTENSION}, and this browser or driver lacks it"
        )));
    }
    Ok(())
}
