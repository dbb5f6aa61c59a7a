//! Per-instance data for instanced draws: one buffer, filled once per pass with one upload.
//! The depth programs read it as per-instance vertex attributes (`instanceMatrix`, divisor
//! 1; [`Mesh::render_instanced_attributes`]); the scene program, whose values do not fit in
//! GL 3.3's 16 attributes, reads it as the `Instances` uniform block, an array of vec4s:
//! instance `gl_InstanceID`'s values start at `instanceBase + gl_InstanceID *
//! instanceStride`. The block is [`BLOCK_VEC4S`] vec4s (16 KiB, what GL 3.3 guarantees), so a
//! run of instances is bound a window at a time, each draw as many instances as fit. The
//! values are computed on the CPU exactly as the per-item uniforms were, so the shader's
//! float math and the pictures stay the same.

use std::cell::{Cell, RefCell};
use std::sync::OnceLock;

use glam::{Mat3, Mat4, Vec4};
use glow::HasContext;

use super::owned::OwnedBuffer;
use super::{Gl, Mesh, ShaderProgram};
use crate::error::Result;

use super::mesh::INSTANCE_BINDING;

/// The block's length in vec4s (the shaders' `INSTANCE_VEC4S`): 16 KiB, GL 3.3's minimum
/// `GL_MAX_UNIFORM_BLOCK_SIZE`.
pub const BLOCK_VEC4S: usize = 1024;

/// The uniform buffer; deleted on drop.
pub struct InstanceBuffer {
    gl: Gl,
    buffer: OwnedBuffer,
    /// Bytes allocated so far: it grows, never shrinks.
    bytes: Cell<usize>,
    /// `GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT`: where a bound window may start.
    align: usize,
    /// The values being gathered for the next upload (kept to reuse its allocation).
    values: RefCell<Vec<Vec4>>,
}

impl InstanceBuffer {
    pub fn new(gl: &Gl) -> Result<InstanceBuffer> {
        let buffer = OwnedBuffer::new(gl, "instance buffer")?;
        let align = unsafe { gl.get_parameter_i32(glow::UNIFORM_BUFFER_OFFSET_ALIGNMENT) };
        let align = usize::try_from(align).unwrap_or(256).max(16);
        // One block's room, bound from the start: a program that draws an item through its
        // uniforms still declares the block, and OpenGL ES (WebGL2) refuses a draw whose
        // declared block has no buffer (desktop GL reads zeros).
        let bytes = (BLOCK_VEC4S * 16 + align).next_power_of_two();
        unsafe {
            gl.bind_buffer(glow::UNIFORM_BUFFER, Some(buffer.raw()));
            gl.buffer_data_size(glow::UNIFORM_BUFFER, bytes as i32, glow::STREAM_DRAW);
            gl.bind_buffer(glow::UNIFORM_BUFFER, None);
            gl.bind_buffer_range(
                glow::UNIFORM_BUFFER,
                INSTANCE_BINDING,
                Some(buffer.raw()),
                0,
                (BLOCK_VEC4S * 16) as i32,
            );
        }
        Ok(InstanceBuffer {
            gl: gl.clone(),
            buffer,
            bytes: Cell::new(bytes),
            align,
            values: RefCell::new(Vec::new()),
        })
    }

    /// Gathers the pass' values with `fill` (every instance `stride` vec4s) and uploads them
    /// in one call; `program` reads its per-item values from them until the returned guard,
    /// which draws the runs, drops.
    pub fn fill<'p>(
        &'p self,
        program: &'p ShaderProgram,
        stride: usize,
        fill: impl FnOnce(&mut Values),
    ) -> Instanced<'p> {
        let mut values = self.values.borrow_mut();
        values.clear();
        fill(&mut Values(&mut values));
        debug_assert_eq!(values.len() % stride.max(1), 0);
        // A window starts up to an alignment before its first instance.
        assert!(
            stride + self.align / 16 <= BLOCK_VEC4S,
            "an instance larger than the block"
        );
        program.set_i32("instanced", 1);
        program.set_i32("instanceStride", stride as i32);
        let guard = Instanced {
            program,
            buffer: self,
            stride,
        };
        if values.is_empty() {
            return guard;
        }
        // A window may start up to an alignment before an instance and always spans the
        // whole block: room for it past the last value.
        let needed = values.len() * 16 + BLOCK_VEC4S * 16 + self.align;
        let data: &[u8] = bytemuck::cast_slice(values.as_slice());
        unsafe {
            self.gl
                .bind_buffer(glow::UNIFORM_BUFFER, Some(self.buffer.raw()));
            if needed > self.bytes.get() {
                // Grown (the first pass, or more instances than ever): a new allocation.
                let bytes = needed.next_power_of_two();
                self.bytes.set(bytes);
                self.gl
                    .buffer_data_size(glow::UNIFORM_BUFFER, bytes as i32, glow::STREAM_DRAW);
            }
            self.gl
                .buffer_sub_data_u8_slice(glow::UNIFORM_BUFFER, 0, data);
            self.gl.bind_buffer(glow::UNIFORM_BUFFER, None);
        }
        guard
    }
}

/// While alive, `program` reads its per-item values from the instance buffer, and draws runs
/// of them; on drop it reads its uniforms again (the passes that stay per item: translucent,
/// volumetric).
pub struct Instanced<'p> {
    program: &'p ShaderProgram,
    buffer: &'p InstanceBuffer,
    stride: usize,
}

impl Instanced<'_> {
    /// Draws `batch` of `mesh`: one instanced call where the program takes attributes, else
    /// one per window of the block the run needs (one for up to 1024 / stride instances).
    pub fn draw<K>(&self, mesh: &Mesh, batch: &Batch<K>) {
        let b = self.buffer;
        if self.program.reads_instance_attributes() {
            let offset = batch.first * self.stride * 16;
            let positions_only = self.program.reads_positions_only();
            mesh.render_instanced_attributes(
                b.buffer.raw(),
                (offset, self.stride),
                batch.count,
                positions_only,
            );
            return;
        }
        for w in windows(batch.first, batch.count, self.stride, b.align) {
            unsafe {
                b.gl.bind_buffer_range(
                    glow::UNIFORM_BUFFER,
                    INSTANCE_BINDING,
                    Some(b.buffer.raw()),
                    w.start as i32,
                    (BLOCK_VEC4S * 16) as i32,
                );
            }
            self.program.set_i32("instanceBase", w.base as i32);
            mesh.render_instanced(w.count);
        }
    }

    /// Draws one item of `mesh` through the program's per-item uniforms, which `set` sets:
    /// a run of one gains nothing from instancing, and on a software rasteriser its vertices
    /// would each fetch the instance's values where a uniform is one broadcast load (the
    /// terrain's thousands of vertices, say).
    pub fn draw_one(&self, mesh: &Mesh, set: impl FnOnce(&ShaderProgram)) {
        self.program.set_i32("instanced", 0);
        set(self.program);
        mesh.render_from(self.program.reads_positions_only());
        self.program.set_i32("instanced", 1);
    }
}

/// One bound range of the buffer: from byte `start` (a multiple of the alignment), `count`
/// instances whose values begin `base` vec4s in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Window {
    start: usize,
    base: usize,
    count: usize,
}

/// The windows that draw instances `first..first + count` of `stride` vec4s each, every
/// instance's values inside its window's [`BLOCK_VEC4S`].
fn windows(first: usize, count: usize, stride: usize, align: usize) -> Vec<Window> {
    let (mut first, mut left) = (first, count);
    let mut out = Vec::new();
    while left > 0 {
        let byte = first * stride * 16;
        let start = byte / align * align;
        let base = (byte - start) / 16;
        let count = ((BLOCK_VEC4S - base) / stride).clamp(1, left);
        out.push(Window { start, base, count });
        first += count;
        left -= count;
    }
    out
}

impl Drop for Instanced<'_> {
    fn drop(&mut self) {
        self.program.set_i32("instanced", 0);
    }
}

/// The values of one pass (vec4s: the block's elements), pushed instance by instance.
pub struct Values<'a>(&'a mut Vec<Vec4>);

impl Values<'_> {
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

    /// `n` zeros: slots the program does not read.
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

/// Whether items sharing a mesh are drawn with one instanced call (the default), or each
/// with a call of its own through its per-item uniforms, as the chapters draw them: with
/// `SHADOWMAP_INSTANCING=off` in the environment (read once), for measuring what
/// instancing saves on a driver. The pictures are the same either way.
pub fn instancing() -> bool {
    static ON: OnceLock<bool> = OnceLock::new();
    *ON.get_or_init(|| {
        let value = std::env::var("SHADOWMAP_INSTANCING").unwrap_or_default();
        match value.as_str() {
            "" | "on" => true,
            "off" => false,
            other => {
                eprintln!(
                    "warning: SHADOWMAP_INSTANCING={other}: expected on or off; instancing \
                     stays on"
                );
                true
            }
        }
    })
}

/// The runs of equal keys in `keys`, in order: the draw order is kept, only neighbours
/// join; with [`instancing`] off every key is a run of its own.
pub fn batches<K: PartialEq + Copy>(keys: impl IntoIterator<Item = K>) -> Vec<Batch<K>> {
    batches_joined(keys, instancing())
}

/// [`batches`], neighbours with equal keys joined only when `join`.
fn batches_joined<K: PartialEq + Copy>(
    keys: impl IntoIterator<Item = K>,
    join: bool,
) -> Vec<Batch<K>> {
    let mut out: Vec<Batch<K>> = Vec::new();
    for (i, key) in keys.into_iter().enumerate() {
        match out.last_mut() {
            Some(b) if join && b.key == key => b.count += 1,
            _ => out.push(Batch {
                key,
                first: i,
                count: 1,
            }),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_cover_each_instance_once_inside_the_block() {
        for (stride, align) in [(4, 16), (5, 16), (16, 256), (35, 256), (5, 64)] {
            let (first, count) = (37, 900);
            let mut next = first;
            for w in windows(first, count, stride, align) {
                assert_eq!(w.start % align, 0, "stride {stride} align {align}");
                assert!(w.base + w.count * stride <= BLOCK_VEC4S, "{w:?}");
                assert_eq!(w.start / 16 + w.base, next * stride, "{w:?}");
                next += w.count;
            }
            assert_eq!(next, first + count);
        }
        assert!(windows(3, 0, 4, 16).is_empty());
    }

    #[test]
    fn batches_join_only_neighbours() {
        let b = batches_joined([0, 0, 1, 1, 1, 0], true);
        let got: Vec<_> = b.iter().map(|b| (b.key, b.first, b.count)).collect();
        assert_eq!(got, vec![(0, 0, 2), (1, 2, 3), (0, 5, 1)]);
        assert!(batches_joined(std::iter::empty::<u8>(), true).is_empty());
    }

    #[test]
    fn without_instancing_every_item_is_a_run_of_one() {
        let b = batches_joined([0, 0, 1, 1, 1, 0], false);
        let got: Vec<_> = b.iter().map(|b| (b.key, b.first, b.count)).collect();
        assert_eq!(
            got,
            (0..6)
                .map(|i| ([0, 0, 1, 1, 1, 0][i], i, 1))
                .collect::<Vec<_>>()
        );
    }
}
