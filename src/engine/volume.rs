//! The GL side of stencil shadow volumes (`crate::shadows::volumes`): a mesh drawn as
//! triangles with adjacency, the stencil pass and the per-light pass as state values
//! restored on drop, and a `GL_SAMPLES_PASSED` query for the fill the volumes cost.

use glow::HasContext;

use super::mesh::{as_bytes, upload, Uploaded};
use super::owned::OwnedQuery;
use super::Gl;
use crate::error::{Error, Result};

/// Positions and a `GL_TRIANGLES_ADJACENCY` index list (six indices per triangle); its VAO
/// and buffers are deleted on drop.
pub struct AdjacencyMesh {
    gl: Gl,
    uploaded: Uploaded,
    index_count: i32,
}

impl AdjacencyMesh {
    /// Uploads `positions` (attribute 0) and `indices`, six per triangle, each below
    /// `positions.len()` (checked).
    pub fn new(gl: &Gl, name: &str, positions: &[[f32; 3]], indices: &[u32]) -> Result<Self> {
        let bad = |what: String| Error::Invalid(format!("mesh '{name}' with adjacency: {what}"));
        if !indices.len().is_multiple_of(6) {
            return Err(bad(format!(
                "{} indices, not six per triangle",
                indices.len()
            )));
        }
        if let Some(i) = indices.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(bad(format!("index {i} past {} vertices", positions.len())));
        }
        let index_count =
            i32::try_from(indices.len()).map_err(|_| bad("too many indices".into()))?;
        let uploaded = upload(gl, as_bytes(positions), &[(0, 3)], indices)?;
        Ok(AdjacencyMesh {
            gl: gl.clone(),
            uploaded,
            index_count,
        })
    }

    /// Draws the mesh once per item, `before_each` setting that item's uniforms.
    pub fn render_list<T>(
        &self,
        items: impl IntoIterator<Item = T>,
        mut before_each: impl FnMut(T),
    ) {
        unsafe {
            self.gl.bind_vertex_array(Some(self.uploaded.vao()));
            for item in items {
                before_each(item);
                self.gl.draw_elements(
                    glow::TRIANGLES_ADJACENCY,
                    self.index_count,
                    glow::UNSIGNED_INT,
                    0,
                );
            }
            self.gl.bind_vertex_array(None);
        }
    }
}

/// How the volumes of one light are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VolumeDraw {
    /// Into the stencil only: z-fail (Carmack's reverse) with two-sided stencil, back faces
    /// behind the scene count up, front faces behind it count down; `GL_DEPTH_CLAMP` keeps
    /// the caps at infinity (clamped to the far plane) instead of clipping them.
    Stencil,
    /// The debug view: every face in colour, blended over the frame, depth-tested but
    /// not written.
    Debug,
}

/// A volume pass in progress; dropping it puts the resting state back (depth test LESS
/// and written, colour written, no stencil test, no depth clamp, no blending).
pub struct VolumePassGuard {
    gl: Gl,
}

impl VolumePassGuard {
    pub fn begin(gl: &Gl, draw: VolumeDraw) -> VolumePassGuard {
        unsafe {
            gl.set_capability(glow::DEPTH_TEST, true);
            gl.depth_func(glow::LESS);
            gl.depth_mask(false);
            gl.set_capability(glow::CULL_FACE, false);
            gl.set_capability(glow::DEPTH_CLAMP, true);
            match draw {
                VolumeDraw::Stencil => {
                    gl.color_mask(false, false, false, false);
                    gl.set_capability(glow::STENCIL_TEST, true);
                    gl.stencil_mask(0xff);
                    gl.stencil_func(glow::ALWAYS, 0, 0xff);
                    gl.stencil_op_separate(glow::BACK, glow::KEEP, glow::INCR_WRAP, glow::KEEP);
                    gl.stencil_op_separate(glow::FRONT, glow::KEEP, glow::DECR_WRAP, glow::KEEP);
                }
                VolumeDraw::Debug => {
                    gl.enable_draw_buffer(glow::BLEND, 0);
                    gl.blend_func(glow::SRC_ALPHA, glow::ONE_MINUS_SRC_ALPHA);
                    for i in 1..4 {
                        gl.color_mask_draw_buffer(i, false, false, false, false);
                    }
                }
            }
        }
        VolumePassGuard { gl: gl.clone() }
    }
}

impl Drop for VolumePassGuard {
    fn drop(&mut self) {
        unsafe { rest(&self.gl) };
    }
}

/// The resting state the guards put back.
unsafe fn rest(gl: &Gl) {
    gl.use_program_once(None);
    gl.depth_func(glow::LESS);
    gl.depth_mask(true);
    gl.color_mask(true, true, true, true);
    gl.set_capability(glow::STENCIL_TEST, false);
    gl.stencil_op(glow::KEEP, glow::KEEP, glow::KEEP);
    gl.stencil_func(glow::ALWAYS, 0, 0xff);
    gl.set_capability(glow::DEPTH_CLAMP, false);
    gl.disable(glow::BLEND);
    gl.blend_func(glow::ONE, glow::ZERO);
}

/// What one light's pass of a multipass frame (the volumes' frame) needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LightPass {
    /// Only where the stencil is 0 (lit: as many volume faces entered as left behind the
    /// pixel); off for a light with a map, which tests itself.
    pub stencil_lit: bool,
    /// Write the extra outputs (visibility, G-buffer) too: the measured light's pass.
    pub extra_outputs: bool,
}

/// A light's pass in progress: the scene's surfaces again (depth LEQUAL, not written), its
/// light added to the colour (blending ONE, ONE on the first output only). Dropping it
/// restores the resting state.
pub struct LightPassGuard {
    gl: Gl,
}

impl LightPassGuard {
    pub fn begin(gl: &Gl, pass: LightPass) -> LightPassGuard {
        unsafe {
            gl.set_capability(glow::DEPTH_TEST, true);
            gl.depth_func(glow::LEQUAL);
            gl.depth_mask(false);
            gl.enable_draw_buffer(glow::BLEND, 0);
            gl.blend_func(glow::ONE, glow::ONE);
            if !pass.extra_outputs {
                for i in 1..4 {
                    gl.color_mask_draw_buffer(i, false, false, false, false);
                }
            }
            if pass.stencil_lit {
                gl.set_capability(glow::STENCIL_TEST, true);
                gl.stencil_func(glow::EQUAL, 0, 0xff);
                gl.stencil_op(glow::KEEP, glow::KEEP, glow::KEEP);
            }
        }
        LightPassGuard { gl: gl.clone() }
    }
}

impl Drop for LightPassGuard {
    fn drop(&mut self) {
        unsafe { rest(&self.gl) };
    }
}

/// Clears the bound framebuffer's stencil to 0 (before each light's volumes).
pub fn clear_stencil(gl: &Gl) {
    unsafe {
        gl.stencil_mask(0xff);
        gl.clear_stencil(0);
        gl.clear(glow::STENCIL_BUFFER_BIT);
    }
}

/// Counts the samples that pass the depth test while it is active (`GL_SAMPLES_PASSED`,
/// core since 1.5): the volume pixels a frame draws. Owned, deleted on drop.
pub struct SamplesQuery {
    query: OwnedQuery,
}

impl SamplesQuery {
    pub fn new(gl: &Gl) -> Result<SamplesQuery> {
        let query = OwnedQuery::new(gl, "samples-passed query")?;
        Ok(SamplesQuery { query })
    }

    pub fn begin(&self) {
        unsafe { (self.query.gl()).begin_query(glow::SAMPLES_PASSED, self.query.raw()) };
    }

    pub fn end(&self) {
        unsafe { self.query.gl().end_query(glow::SAMPLES_PASSED) };
    }

    /// The count of the last begin/end (waits for it).
    pub fn read(&self) -> u64 {
        let mut n: u64 = 0;
        // With no query buffer bound, the "offset" is the address to write to.
        unsafe {
            self.query.gl().get_query_parameter_u64_with_offset(
                self.query.raw(),
                glow::QUERY_RESULT,
                &mut n as *mut u64 as usize,
            )
        };
        n
    }
}
