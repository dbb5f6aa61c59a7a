//! Per-instance data for instanced draws: one RGBA32F texture read with `texelFetch` by
//! `gl_InstanceID`, filled once per pass with one upload. A vertex shader reads instance
//! `instanceBase + gl_InstanceID`'s texels at `instanceStride` apart, texel t at
//! (t % [`ROW`], t / [`ROW`]) (glow has no `glTexBuffer`, so a 2D texture stands in for a
//! buffer texture). The values are computed on the CPU exactly as the per-item uniforms
//! were, so the shader's float math and the pictures stay the same.

use std::cell::RefCell;

use glam::{Mat3, Mat4, Vec4};
use glow::HasContext;

use super::{Gl, Mesh, ShaderProgram};
use crate::error::{Error, Result};

/// The texture unit the instance data is bound on, above every unit a pass samples.
pub const INSTANCE_UNIT: u32 = 31;

/// Texels per row of the texture (the shaders' `INSTANCE_ROW`; GL 3.3 guarantees 1024).
pub const ROW: usize = 1024;

/// The texture; deleted on drop.
pub struct InstanceBuffer {
    gl: Gl,
    texture: glow::Texture,
    /// Rows allocated so far: it grows, never shrinks.
    rows: std::cell::Cell<usize>,
    /// The texels being gathered for the next upload (kept to reuse its allocation).
    texels: RefCell<Vec<Vec4>>,
}

impl InstanceBuffer {
    pub fn new(gl: &Gl) -> Result<InstanceBuffer> {
        unsafe {
            let texture = gl
                .create_texture()
                .map_err(|e| Error::Create(format!("instance texture: {e}")))?;
            super::counters::count(|c| c.textures += 1);
            gl.bind_texture(glow::TEXTURE_2D, Some(texture));
            let p = |k, v: u32| gl.tex_parameter_i32(glow::TEXTURE_2D, k, v as i32);
            p(glow::TEXTURE_MIN_FILTER, glow::NEAREST);
            p(glow::TEXTURE_MAG_FILTER, glow::NEAREST);
            gl.bind_texture(glow::TEXTURE_2D, None);
            gl.forget_bindings();
            Ok(InstanceBuffer {
                gl: gl.clone(),
                texture,
                rows: std::cell::Cell::new(0),
                texels: RefCell::new(Vec::new()),
            })
        }
    }

    /// Gathers the pass' texels with `fill` (every instance `stride` texels), uploads them
    /// in one call, binds the buffer on [`INSTANCE_UNIT`] and points `program` at it; the
    /// program reads its per-item uniforms again when the returned guard drops.
    pub fn fill<'p>(
        &self,
        program: &'p ShaderProgram,
        stride: usize,
        fill: impl FnOnce(&mut Texels),
    ) -> Instanced<'p> {
        let mut texels = self.texels.borrow_mut();
        texels.clear();
        fill(&mut Texels(&mut texels));
        debug_assert_eq!(texels.len() % stride.max(1), 0);
        program.set_i32("instanced", 1);
        let guard = Instanced(program);
        if texels.is_empty() {
            return guard;
        }
        let rows = texels.len().div_ceil(ROW);
        texels.resize(rows * ROW, Vec4::ZERO);
        self.gl
            .bind_texture_active(INSTANCE_UNIT, glow::TEXTURE_2D, self.texture);
        let data = glow::PixelUnpackData::Slice(Some(bytemuck::cast_slice(texels.as_slice())));
        unsafe {
            if rows > self.rows.get() {
                // Grown (the first pass, or more instances than ever): a new allocation.
                self.rows.set(rows);
                self.gl.tex_image_2d(
                    glow::TEXTURE_2D,
                    0,
                    glow::RGBA32F as i32,
                    ROW as i32,
                    rows as i32,
                    0,
                    glow::RGBA,
                    glow::FLOAT,
                    data,
                );
            } else {
                let (w, h) = (ROW as i32, rows as i32);
                self.gl.tex_sub_image_2d(
                    glow::TEXTURE_2D,
                    0,
                    0,
                    0,
                    w,
                    h,
                    glow::RGBA,
                    glow::FLOAT,
                    data,
                );
            }
        }
        program.set_i32("instances", INSTANCE_UNIT as i32);
        program.set_i32("instanceStride", stride as i32);
        guard
    }
}

/// While alive, `program` reads its per-item values from the instance buffer; on drop it
/// reads its uniforms again (the passes that stay per item: translucent, volumetric).
pub struct Instanced<'p>(&'p ShaderProgram);

impl Drop for Instanced<'_> {
    fn drop(&mut self) {
        self.0.set_i32("instanced", 0);
    }
}

impl Drop for InstanceBuffer {
    fn drop(&mut self) {
        self.gl.forget_texture(self.texture);
        unsafe { self.gl.delete_texture(self.texture) };
    }
}

/// The texels of one pass, pushed instance by instance.
pub struct Texels<'a>(&'a mut Vec<Vec4>);

impl Texels<'_> {
    /// A matrix as its four columns.
    pub fn mat4(&mut self, m: &Mat4) {
        self.0
            .extend_from_slice(&[m.x_axis, m.y_axis, m.z_axis, m.w_axis]);
    }

    /// A matrix as its three columns (w unused).
    pub fn mat3(&mut self, m: &Mat3) {
        self.0
            .extend([m.x_axis, m.y_axis, m.z_axis].map(|c| c.extend(0.0)));
    }

    pub fn vec4(&mut self, v: Vec4) {
        self.0.push(v);
    }

    /// `n` texels of zeros: slots the program does not read.
    pub fn zeros(&mut self, n: usize) {
        self.0.extend(std::iter::repeat_n(Vec4::ZERO, n));
    }
}

/// A run of instances drawn with one call: `count` instances of mesh `mesh` from instance
/// `first`, all sharing `key` (a mesh's items with the same texture, say).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Batch<K> {
    pub key: K,
    pub first: usize,
    pub count: usize,
}

/// The runs of equal keys in `keys`, in order: the draw order is kept, only neighbours join.
pub fn batches<K: PartialEq + Copy>(keys: impl IntoIterator<Item = K>) -> Vec<Batch<K>> {
    let mut out: Vec<Batch<K>> = Vec::new();
    for (i, key) in keys.into_iter().enumerate() {
        match out.last_mut() {
            Some(b) if b.key == key => b.count += 1,
            _ => out.push(Batch {
                key,
                first: i,
                count: 1,
            }),
        }
    }
    out
}

/// Draws `batch` of `mesh` with `program` reading the uploaded instances.
pub fn draw_batch<K>(program: &ShaderProgram, mesh: &Mesh, batch: &Batch<K>) {
    program.set_i32("instanceBase", batch.first as i32);
    mesh.render_instanced(batch.count);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn batches_join_only_neighbours() {
        let b = batches([0, 0, 1, 1, 1, 0]);
        let got: Vec<_> = b.iter().map(|b| (b.key, b.first, b.count)).collect();
        assert_eq!(got, vec![(0, 0, 2), (1, 2, 3), (0, 5, 1)]);
        assert!(batches(std::iter::empty::<u8>()).is_empty());
    }
}
