//! `Mesh`: a VAO with its vertex and index buffers (the book's `Mesh` class), uploaded from
//! CPU-side [`MeshData`]. Attribute locations match the book: 0 position, 1 texture
//! coordinate, 2 normal; instanced depth passes add per-instance values from 3 on. A second
//! vertex array holds the positions alone, welded ([`MeshData::welded_positions`]), for the
//! programs that read nothing else (the depth passes): fewer vertices to shade, the same
//! triangles, so the same depth map bit for bit.

use glow::HasContext;

use super::owned::{OwnedBuffer, OwnedVertexArray};
use super::Gl;
use crate::error::{Error, Result};
use crate::geometry::MeshData;

/// The first location of per-instance vertex attributes (after the three per-vertex ones).
pub const INSTANCE_LOCATION: u32 = 3;

/// The uniform buffer binding point of the `Instances` block (every program that declares it
/// is pointed here when it is linked; [`super::instances`] fills it).
pub const INSTANCE_BINDING: u32 = 0;

/// An uploaded mesh; its VAOs and buffers are deleted on drop.
pub struct Mesh {
    gl: Gl,
    all: Uploaded,
    /// The welded positions.
    positions: Uploaded,
    index_count: i32,
    vertex_count: i32,
}

impl Mesh {
    /// Uploads interleaved position / texture coordinate / normal data and the indices.
    /// The data was validated when it was built ([`MeshData::validate`]), so every index
    /// points at a vertex.
    pub fn new(gl: &Gl, data: &MeshData) -> Result<Mesh> {
        data.validate()?;
        let mut interleaved = Vec::with_capacity(data.positions.len() * 8);
        for i in 0..data.positions.len() {
            interleaved.extend_from_slice(&data.positions[i]);
            interleaved.extend_from_slice(&data.tex_coords[i]);
            interleaved.extend_from_slice(&data.normals[i]);
        }
        let index_count = i32::try_from(data.indices.len())
            .map_err(|_| Error::Invalid(format!("mesh '{}': too many indices", data.name)))?;
        let attributes = [(0, 3), (1, 2), (2, 3)];
        let all = upload(gl, as_bytes(&interleaved), &attributes, &data.indices)?;
        let (welded, indices) = data.welded_positions();
        let positions = upload(gl, as_bytes(&welded), &[(0, 3)], &indices)?;
        Ok(Mesh {
            gl: gl.clone(),
            all,
            positions,
            index_count,
            vertex_count: data.positions.len() as i32,
        })
    }

    /// The vertex array a program reads: the welded positions for one that reads nothing
    /// else ([`super::ShaderProgram::reads_positions_only`]).
    fn vertices(&self, positions_only: bool) -> glow::VertexArray {
        if positions_only {
            self.positions.vao()
        } else {
            self.all.vao()
        }
    }

    /// Draws the mesh once with whatever program and uniforms are bound.
    pub fn render(&self) {
        self.render_from(false);
    }

    /// Draws the mesh once, from its welded positions when `positions_only`.
    pub fn render_from(&self, positions_only: bool) {
        unsafe {
            self.gl
                .bind_vertex_array(Some(self.vertices(positions_only)));
            self.gl
                .draw_elements(glow::TRIANGLES, self.index_count, glow::UNSIGNED_INT, 0);
            self.gl.bind_vertex_array(None);
        }
        super::counters::count_draw();
    }

    /// Draws the mesh once per item, calling `before_each` to set that item's uniforms
    /// (the book's `renderList`): the VAO is bound once for the whole list.
    pub fn render_list<T>(
        &self,
        items: impl IntoIterator<Item = T>,
        mut before_each: impl FnMut(T),
    ) {
        unsafe {
            self.gl.bind_vertex_array(Some(self.all.vao()));
            for item in items {
                before_each(item);
                self.gl
                    .draw_elements(glow::TRIANGLES, self.index_count, glow::UNSIGNED_INT, 0);
                super::counters::count_draw();
            }
            self.gl.bind_vertex_array(None);
        }
    }

    /// Draws `count` instances of the mesh in one call (the per-instance values come from
    /// [`super::instances::InstanceBuffer`]).
    pub fn render_instanced(&self, count: usize) {
        unsafe {
            self.gl.bind_vertex_array(Some(self.all.vao()));
            self.gl.draw_elements_instanced(
                glow::TRIANGLES,
                self.index_count,
                glow::UNSIGNED_INT,
                0,
                count as i32,
            );
            self.gl.bind_vertex_array(None);
        }
        super::counters::count_draw();
    }

    /// Draws `count` instances whose values are per-instance vertex attributes: `stride`
    /// vec4s an instance from byte `offset` of `buffer`, on locations 3, 4, ... (a mat4
    /// takes four), from the welded positions when `positions_only`. The attributes are
    /// switched off again after the draw, so the mesh's other draws read nothing from the
    /// buffer.
    pub fn render_instanced_attributes(
        &self,
        buffer: glow::Buffer,
        (offset, stride): (usize, usize),
        count: usize,
        positions_only: bool,
    ) {
        let locations = (0..stride as u32).map(|k| INSTANCE_LOCATION + k);
        unsafe {
            self.gl
                .bind_vertex_array(Some(self.vertices(positions_only)));
            self.gl.bind_buffer(glow::ARRAY_BUFFER, Some(buffer));
            for (k, location) in locations.clone().enumerate() {
                self.gl.enable_vertex_attrib_array(location);
                let at = (offset + 16 * k) as i32;
                let bytes = (16 * stride) as i32;
                (self.gl).vertex_attrib_pointer_f32(location, 4, glow::FLOAT, false, bytes, at);
                self.gl.vertex_attrib_divisor(location, 1);
            }
            self.gl.bind_buffer(glow::ARRAY_BUFFER, None);
            self.gl.draw_elements_instanced(
                glow::TRIANGLES,
                self.index_count,
                glow::UNSIGNED_INT,
                0,
                count as i32,
            );
            for location in locations {
                self.gl.disable_vertex_attrib_array(location);
            }
            self.gl.bind_vertex_array(None);
        }
        super::counters::count_draw();
    }

    pub fn index_count(&self) -> usize {
        self.index_count as usize
    }

    /// Vertices in its vertex array (not welded).
    pub fn vertex_count(&self) -> usize {
        self.vertex_count as usize
    }

    /// Draws each vertex once, in order, as a point: a transform feedback pass that
    /// captures one value a vertex ([`super::VertexCapture`]).
    pub fn render_points(&self) {
        unsafe {
            self.gl.bind_vertex_array(Some(self.all.vao()));
            self.gl.draw_arrays(glow::POINTS, 0, self.vertex_count);
            self.gl.bind_vertex_array(None);
        }
        super::counters::count_draw();
    }

    /// Draws the mesh once, with one vec4 a vertex read from `buffer` at byte `offset` on
    /// location [`INSTANCE_LOCATION`] (vertex k's at `offset + 16 k`); switched off again
    /// after the draw.
    pub fn render_with_vertex_values(&self, buffer: glow::Buffer, offset: usize) {
        let location = INSTANCE_LOCATION;
        unsafe {
            self.gl.bind_vertex_array(Some(self.all.vao()));
            self.gl.bind_buffer(glow::ARRAY_BUFFER, Some(buffer));
            self.gl.enable_vertex_attrib_array(location);
            (self.gl).vertex_attrib_pointer_f32(location, 4, glow::FLOAT, false, 16, offset as i32);
            // An instanced draw may have left it per instance.
            self.gl.vertex_attrib_divisor(location, 0);
            self.gl.bind_buffer(glow::ARRAY_BUFFER, None);
            self.gl
                .draw_elements(glow::TRIANGLES, self.index_count, glow::UNSIGNED_INT, 0);
            self.gl.disable_vertex_attrib_array(location);
            self.gl.bind_vertex_array(None);
        }
        super::counters::count_draw();
    }
}

pub(super) fn as_bytes<T: Copy>(data: &[T]) -> &[u8] {
    // f32 and u32 have no padding and any bit pattern is a valid byte sequence.
    unsafe { std::slice::from_raw_parts(data.as_ptr().cast::<u8>(), std::mem::size_of_val(data)) }
}

/// A triangle that covers the whole viewport, generated from `gl_VertexID` (the depth-map
/// view's "quad"). Core profile needs a bound VAO even with no attributes.
pub struct FullScreenTriangle {
    vao: OwnedVertexArray,
}

impl FullScreenTriangle {
    pub fn new(gl: &Gl) -> Result<FullScreenTriangle> {
        let vao = OwnedVertexArray::new(gl, "full-screen triangle vertex array")?;
        Ok(FullScreenTriangle { vao })
    }

    pub fn draw(&self) {
        let gl = self.vao.gl();
        unsafe {
            gl.bind_vertex_array(Some(self.vao.raw()));
            gl.draw_arrays(glow::TRIANGLES, 0, 3);
            gl.bind_vertex_array(None);
        }
    }
}

/// A vertex array with its vertex and index buffers; all deleted on drop.
pub(super) struct Uploaded {
    vao: OwnedVertexArray,
    _vertices: OwnedBuffer,
    _indices: OwnedBuffer,
}

impl Uploaded {
    pub(super) fn vao(&self) -> glow::VertexArray {
        self.vao.raw()
    }
}

/// Creates a vertex array with its vertex and index buffers and uploads `vertices`
/// (interleaved f32s: `attributes` are (location, components) in order) and `indices`;
/// on an error nothing is left behind.
pub(super) fn upload(
    gl: &Gl,
    vertices: &[u8],
    attributes: &[(u32, i32)],
    indices: &[u32],
) -> Result<Uploaded> {
    let vao = OwnedVertexArray::new(gl, "vertex array")?;
    let vbo = OwnedBuffer::new(gl, "vertex buffer")?;
    let ebo = OwnedBuffer::new(gl, "index buffer")?;
    unsafe {
        gl.bind_vertex_array(Some(vao.raw()));
        gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo.raw()));
        gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, vertices, glow::STATIC_DRAW);
        let stride = attributes.iter().map(|(_, n)| n).sum::<i32>() * 4;
        let mut offset = 0;
        for &(location, components) in attributes {
            gl.enable_vertex_attrib_array(location);
            gl.vertex_attrib_pointer_f32(location, components, glow::FLOAT, false, stride, offset);
            offset += components * 4;
        }
        gl.bind_buffer(glow::ELEMENT_ARRAY_BUFFER, Some(ebo.raw()));
        gl.buffer_data_u8_slice(
            glow::ELEMENT_ARRAY_BUFFER,
            as_bytes(indices),
            glow::STATIC_DRAW,
        );
        gl.bind_vertex_array(None);
        gl.bind_buffer(glow::ARRAY_BUFFER, None);
    }
    Ok(Uploaded {
        vao,
        _vertices: vbo,
        _indices: ebo,
    })
}
