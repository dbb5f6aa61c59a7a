//! How a shadow map is read, as a value: GL 3.3's sampler objects. A texture keeps the
//! parameters it was made with; the scene pass binds a sampler with the filter's compare
//! mode, filtering and wrap next to it, and unbinds it when the pass ends, so nothing is
//! changed on the texture per use.

use glow::HasContext;

use super::owned::OwnedSampler;
use super::texture::Filtering;
use super::Gl;
use crate::error::{Error, Result};
use crate::settings::Wrap;

/// What a sampler does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Sampling {
    /// Depth comparison in the sampler (`sampler2DShadow`: reference <= stored depth).
    pub compare: bool,
    /// LINEAR filtering (with `compare`: the hardware's 2 x 2 PCF); otherwise NEAREST, as the
    /// book samples its map.
    pub linear: bool,
    /// Outside [0, 1]. A border is depth 1 (LearnOpenGL's fix: "far away", so lit).
    pub wrap: Wrap,
    /// The program draws the border itself where the sampler has none (OpenGL ES:
    /// shaders/lib/shadow_border.glsl): there the sampler clamps to the edge instead.
    pub border_in_shader: bool,
    /// The program interpolates depths itself where the sampler cannot (OpenGL ES, `linear`
    /// without `compare`: shaders/lib/shadow_depth.glsl): there the sampler reads NEAREST.
    pub interpolate_in_shader: bool,
}

impl Sampling {
    /// Plain NEAREST reads, clamped: the book's depth texture, a cube map, the depth view.
    pub const PLAIN: Sampling = Sampling {
        compare: false,
        linear: false,
        wrap: Wrap::ClampToEdge,
        border_in_shader: false,
        interpolate_in_shader: false,
    };
}

fn wrap_mode(wrap: Wrap) -> u32 {
    match wrap {
        Wrap::ClampToEdge => glow::CLAMP_TO_EDGE,
        Wrap::ClampToBorder => glow::CLAMP_TO_BORDER,
        Wrap::Repeat => glow::REPEAT,
    }
}

/// Refuses a way of reading `texture` that OpenGL ES (WebGL2) cannot do, with what it is:
/// depth texels interpolated without a comparison (the shadow-playground's `depth_lookup =
/// "linear"`; ES leaves such a texture incomplete, so every lookup would read 0), unless the
/// program interpolates them itself. Desktop GL reads both.
pub fn check_readable(gl: &Gl, texture: &super::Texture, sampling: Sampling) -> Result<()> {
    let es = gl.version().is_embedded;
    if sampling.linear
        && !sampling.compare
        && !sampling.interpolate_in_shader
        && es
        && texture.is_depth()
    {
        return Err(Error::Invalid(
            "this picture reads the shadow map's depths interpolated (depth_lookup = \
             \"linear\", the playground's colour map), which OpenGL ES and WebGL2 cannot \
             filter without a comparison"
                .into(),
        ));
    }
    Ok(())
}

/// An owned sampler object; deleted with its name.
pub struct Sampler {
    name: OwnedSampler,
    sampling: Sampling,
}

impl Sampler {
    pub fn new(gl: &Gl, sampling: Sampling) -> Result<Sampler> {
        let es = gl.version().is_embedded;
        let wrap = match sampling.wrap {
            Wrap::ClampToBorder if es && sampling.border_in_shader => Wrap::ClampToEdge,
            wrap => wrap,
        };
        if wrap == Wrap::ClampToBorder && es {
            return Err(Error::Invalid(
                "this picture needs the shadow map clamped to a lit border (--wrap clamp-to-border, \
                 the chapters' over-sampling fix), which OpenGL ES and WebGL2 lack"
                    .into(),
            ));
        }
        let name = OwnedSampler::new(gl, "sampler")?;
        let id = name.raw();
        let filter = if sampling.linear && !(es && sampling.interpolate_in_shader) {
            glow::LINEAR
        } else {
            glow::NEAREST
        };
        unsafe {
            let p = |k, v: u32| gl.sampler_parameter_i32(id, k, v as i32);
            Filtering::new(filter, wrap_mode(wrap)).apply(p);
            if wrap == Wrap::ClampToBorder {
                gl.sampler_parameter_f32_slice(id, glow::TEXTURE_BORDER_COLOR, &[1.0; 4]);
            }
            if sampling.compare {
                p(glow::TEXTURE_COMPARE_MODE, glow::COMPARE_REF_TO_TEXTURE);
                p(glow::TEXTURE_COMPARE_FUNC, glow::LEQUAL);
            } else {
                p(glow::TEXTURE_COMPARE_MODE, glow::NONE);
            }
        }
        Ok(Sampler { name, sampling })
    }

    /// Binds the sampler to texture unit `unit` until the returned guard drops.
    pub fn bind(&self, unit: u32) -> BoundSampler {
        let gl = self.name.gl();
        unsafe { gl.bind_sampler(unit, Some(self.name.raw())) };
        BoundSampler {
            gl: gl.clone(),
            unit,
        }
    }
}

/// A sampler bound to a unit; the unit goes back to its texture's own parameters on drop.
pub struct BoundSampler {
    gl: Gl,
    unit: u32,
}

impl Drop for BoundSampler {
    fn drop(&mut self) {
        unsafe { self.gl.bind_sampler(self.unit, None) };
    }
}

/// The samplers in use, made once per kind of sampling (a scene needs two or three).
#[derive(Default)]
pub struct Samplers {
    made: Vec<Sampler>,
}

impl Samplers {
    /// The sampler for `sampling`, made on first use.
    pub fn get(&mut self, gl: &Gl, sampling: Sampling) -> Result<&Sampler> {
        let i = match self.made.iter().position(|s| s.sampling == sampling) {
            Some(i) => i,
            None => {
                self.made.push(Sampler::new(gl, sampling)?);
                self.made.len() - 1
            }
        };
        Ok(&self.made[i])
    }
}
