//! `MomentMap`: the storage of a filterable shadow map (variance, exponential variance and
//! moment shadow maps): two float colour textures and a depth buffer. The depth pass draws
//! depth's moments into texture 0 (the depth buffer keeps the nearest caster per texel);
//! the separable blur reads 0 into 1 across, then 1 back into 0 down, so the result is
//! always in texture 0.

use glow::HasContext;

use super::framebuffer::{Attachment, Framebuffer, Part};
use super::mesh::FullScreenTriangle;
use super::state::{NoDepthTest, PixelRect};
use super::texture::Texture;
use super::{Gl, ShaderProgram};
use crate::error::Result;
use crate::settings::MapSize;

/// Owns both textures and the two framebuffers (the first with the depth renderbuffer);
/// all freed on drop.
pub struct MomentMap {
    gl: Gl,
    /// Framebuffer `i` draws into `textures[i]`; only the first has the depth buffer.
    fbos: [Framebuffer; 2],
    textures: [Texture; 2],
    components: u32,
}

impl MomentMap {
    /// A `size` map of `components` (1: R32F, 2: RG32F, 4: RGBA32F) float moments per texel.
    pub fn new(gl: &Gl, size: MapSize, components: u32) -> Result<MomentMap> {
        let (w, h) = (size.width, size.height);
        let textures = [
            Texture::float_target(gl, w, h, components)?,
            Texture::float_target(gl, w, h, components)?,
        ];
        let target = |i: usize| {
            let colour = Framebuffer::build(gl, "moment map")?.texture(
                Attachment::Colour(0),
                &textures[i],
                Part::Image,
            );
            let colour = match i {
                0 => colour.renderbuffer(
                    Attachment::Depth,
                    glow::DEPTH_COMPONENT24,
                    (w, h),
                    "moment map depth buffer",
                )?,
                _ => colour,
            };
            colour.finish(&format!("moment map {w}x{h} ({i})"))
        };
        Ok(MomentMap {
            gl: gl.clone(),
            fbos: [target(0)?, target(1)?],
            textures,
            components,
        })
    }

    /// Binds the depth pass' framebuffer, sets the viewport to the map and clears the
    /// moments to `far` (the moments of depth 1, where nothing was drawn) and the depth to 1.
    pub fn begin_depth_pass(&self, far: [f32; 4]) {
        unsafe {
            self.fbos[0].bind();
            self.viewport();
            self.gl.depth_mask(true);
            self.gl.clear_buffer_f32_slice(glow::COLOR, 0, &far);
            self.gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[1.0]);
        }
    }

    /// The separable blur: `program` (a full-screen pass reading the sampler `source` on
    /// unit 0, stepping `stepUv` per tap, `radius` taps either side) from texture 0 into 1
    /// across, then back down. With `footprint` (the texels the casters can cover; the rest
    /// hold the cleared far moments, which a blur leaves as they are) each pass is
    /// scissored to what it can change: across, the footprint grown by the radius sideways
    /// and twice it up and down (the rows the pass down reads); down, grown by the radius.
    /// Leaves the default framebuffer bound, no program and no scissor test.
    pub fn blur(
        &self,
        program: &ShaderProgram,
        triangle: &FullScreenTriangle,
        radius: u32,
        footprint: Option<PixelRect>,
    ) {
        let size = self.size();
        let (w, h) = (size.width, size.height);
        let grow = |r: PixelRect, dx: u32, dy: u32| {
            let x0 = r.x.saturating_sub(dx);
            let y0 = r.y.saturating_sub(dy);
            let x1 = (r.x + r.width).saturating_add(dx).min(w);
            let y1 = (r.y + r.height).saturating_add(dy).min(h);
            PixelRect {
                x: x0,
                y: y0,
                width: x1.saturating_sub(x0),
                height: y1.saturating_sub(y0),
            }
        };
        // One texel more than the kernel reaches, for rounding at the footprint's edges.
        let r = radius + 1;
        let passes = [
            (
                0,
                [1.0 / w as f32, 0.0],
                footprint.map(|f| grow(f, r, 2 * r)),
            ),
            (1, [0.0, 1.0 / h as f32], footprint.map(|f| grow(f, r, r))),
        ];
        let _no_depth = NoDepthTest::begin(&self.gl);
        program.bind();
        program.set_i32("source", 0);
        // Both passes draw into a map-sized target from unit 0, read without a sampler.
        self.viewport();
        unsafe { self.gl.bind_sampler(0, None) };
        for (from, step, scissor) in passes {
            unsafe {
                self.fbos[1 - from].bind();
                match scissor {
                    Some(s) => {
                        self.gl.set_capability(glow::SCISSOR_TEST, true);
                        self.gl
                            .scissor(s.x as i32, s.y as i32, s.width as i32, s.height as i32);
                    }
                    None => self.gl.set_capability(glow::SCISSOR_TEST, false),
                }
            }
            self.textures[from].bind(0);
            program.set_vec2("stepUv", step);
            triangle.draw();
        }
        program.unbind();
        unsafe {
            self.gl.set_capability(glow::SCISSOR_TEST, false);
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
    }

    fn viewport(&self) {
        let t = &self.textures[0];
        unsafe {
            self.gl.viewport(0, 0, t.width() as i32, t.height() as i32);
        }
    }

    /// The moments the scene pass reads (after the blur, if any).
    pub fn texture(&self) -> &Texture {
        &self.textures[0]
    }

    pub fn size(&self) -> MapSize {
        MapSize {
            width: self.textures[0].width(),
            height: self.textures[0].height(),
        }
    }

    pub fn components(&self) -> u32 {
        self.components
    }

    /// Bytes allocated: two float textures and a depth buffer (4 bytes a texel).
    pub fn bytes(&self) -> u64 {
        self.size().texels() * (2 * 4 * u64::from(self.components) + 4)
    }
}
