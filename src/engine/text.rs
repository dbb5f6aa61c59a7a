//! Text over the frame (the demo's HUD): glyphs rasterised once by `fontdue` into a single
//! R8 atlas, and drawn after the scene as one batch of alpha-blended quads.
//!
//! [`FontAtlas`] is the CPU side (rasterising and placing glyphs, in pixels with y down);
//! [`TextRenderer`] owns the GL side (the atlas texture, a VAO/VBO and the program) and
//! leaves the GL state it touches as it found it, so the renderer's next frame is unaffected.

use std::collections::HashMap;

use glow::HasContext;

use super::check::check_gl;
use super::owned::{OwnedBuffer, OwnedVertexArray};
use super::shader_program::{ShaderProgram, ShaderSource};
use super::texture::{Filtering, Texels, Texture};
use super::Gl;
use crate::error::{Error, Result};

/// Characters rasterised besides printable ASCII; anything else is drawn as '?'.
const EXTRA_CHARS: &[char] = &['°', '×', '²', '…'];
/// The atlas' width in texels; rows of glyphs are added until everything fits.
const ATLAS_WIDTH: u32 = 256;
/// Empty texels around each glyph, so a quad's edge never reads a neighbour.
const PADDING: u32 = 1;
/// Side of the opaque block at the atlas' origin that solid rectangles sample.
const SOLID_SIDE: u32 = 4;

/// One textured, tinted rectangle: `rect` is (left, top, right, bottom) in pixels of the
/// frame with y down, `uv` the same corners in the atlas (0..1), `colour` linear RGBA.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextQuad {
    pub rect: [f32; 4],
    pub uv: [f32; 4],
    pub colour: [f32; 4],
}

/// Where a glyph sits in the atlas and how it sits on the baseline.
#[derive(Debug, Clone, Copy)]
struct Glyph {
    uv: [f32; 4],
    width: f32,
    height: f32,
    /// From the pen position to the bitmap's left edge.
    left: f32,
    /// From the baseline up to the bitmap's top edge.
    top: f32,
    advance: f32,
}

/// Glyph coverage for one font at one size, packed into one image, with what is needed to
/// lay out lines of text.
pub struct FontAtlas {
    width: u32,
    height: u32,
    /// Coverage 0..255, rows top to bottom.
    pixels: Vec<u8>,
    glyphs: HashMap<char, Glyph>,
    /// The centre of the opaque block, for solid rectangles.
    solid_uv: [f32; 2],
    ascent: f32,
    line_height: f32,
}

impl FontAtlas {
    /// Rasterises printable ASCII (and a few symbols) of a TrueType font at `px` pixels per em.
    pub fn new(font_bytes: &[u8], px: f32) -> Result<FontAtlas> {
        if !(4.0..=128.0).contains(&px) {
            return Err(Error::Invalid(format!(
                "font size {px}: expected 4 to 128 pixels"
            )));
        }
        let font = fontdue::Font::from_bytes(font_bytes, fontdue::FontSettings::default())
            .map_err(|e| Error::Invalid(format!("the HUD's font: {e}")))?;
        let lines = font.horizontal_line_metrics(px).ok_or_else(|| {
            Error::Invalid("the HUD's font has no horizontal line metrics".into())
        })?;
        let chars: Vec<char> = (' '..='~').chain(EXTRA_CHARS.iter().copied()).collect();
        let bitmaps: Vec<(char, fontdue::Metrics, Vec<u8>)> = chars
            .iter()
            .filter(|c| font.has_glyph(**c) || **c == ' ')
            .map(|&c| {
                let (m, bitmap) = font.rasterize(c, px);
                (c, m, bitmap)
            })
            .collect();

        // Shelf packing: left to right, a new row when the next glyph does not fit. The
        // opaque block takes the first place.
        let mut places = Vec::with_capacity(bitmaps.len());
        let (mut x, mut y, mut row) = (SOLID_SIDE + 2 * PADDING, 0u32, SOLID_SIDE + 2 * PADDING);
        for (_, m, _) in &bitmaps {
            let (w, h) = (m.width as u32 + 2 * PADDING, m.height as u32 + 2 * PADDING);
            if w > ATLAS_WIDTH {
                return Err(Error::Invalid(format!(
                    "font size {px}: a glyph is wider than the {ATLAS_WIDTH}-texel atlas"
                )));
            }
            if x + w > ATLAS_WIDTH {
                (x, y, row) = (0, y + row, 0);
            }
            places.push((x + PADDING, y + PADDING));
            x += w;
            row = row.max(h);
        }
        let (width, height) = (ATLAS_WIDTH, (y + row).next_power_of_two());
        let mut pixels = vec![0u8; (width * height) as usize];
        for sy in PADDING..PADDING + SOLID_SIDE {
            let start = (sy * width + PADDING) as usize;
            pixels[start..start + SOLID_SIDE as usize].fill(255);
        }
        let mut glyphs = HashMap::with_capacity(bitmaps.len());
        for ((c, m, bitmap), (gx, gy)) in bitmaps.iter().zip(places) {
            for row in 0..m.height {
                let src = &bitmap[row * m.width..(row + 1) * m.width];
                let start = ((gy as usize + row) * width as usize) + gx as usize;
                pixels[start..start + m.width].copy_from_slice(src);
            }
            let (fw, fh) = (width as f32, height as f32);
            glyphs.insert(
                *c,
                Glyph {
                    uv: [
                        gx as f32 / fw,
                        gy as f32 / fh,
                        (gx as f32 + m.width as f32) / fw,
                        (gy as f32 + m.height as f32) / fh,
                    ],
                    width: m.width as f32,
                    height: m.height as f32,
                    left: m.xmin as f32,
                    top: (m.ymin + m.height as i32) as f32,
                    advance: m.advance_width,
                },
            );
        }
        let centre = (PADDING + SOLID_SIDE / 2) as f32;
        Ok(FontAtlas {
            width,
            height,
            pixels,
            glyphs,
            solid_uv: [centre / width as f32, centre / height as f32],
            ascent: lines.ascent.ceil(),
            line_height: lines.new_line_size.ceil(),
        })
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// Coverage per texel, rows top to bottom.
    pub fn pixels(&self) -> &[u8] {
        &self.pixels
    }

    /// Distance from one line's top to the next's, in pixels.
    pub fn line_height(&self) -> f32 {
        self.line_height
    }

    fn glyph(&self, c: char) -> Option<&Glyph> {
        self.glyphs.get(&c).or_else(|| self.glyphs.get(&'?'))
    }

    /// The advance of a line of text in pixels.
    pub fn text_width(&self, text: &str) -> f32 {
        text.chars()
            .filter_map(|c| self.glyph(c))
            .map(|g| g.advance)
            .sum()
    }

    /// Appends the quads of one line whose top-left corner is at (`x`, `top`). Glyphs land
    /// on whole pixels, so each texel of the atlas covers exactly one pixel of the frame.
    pub fn push_text(
        &self,
        quads: &mut Vec<TextQuad>,
        text: &str,
        x: f32,
        top: f32,
        colour: [f32; 4],
    ) {
        let baseline = (top + self.ascent).round();
        let mut pen = x;
        for c in text.chars() {
            let Some(g) = self.glyph(c) else { continue };
            if g.width > 0.0 && g.height > 0.0 {
                let left = (pen + g.left).round();
                let top = baseline - g.top;
                quads.push(TextQuad {
                    rect: [left, top, left + g.width, top + g.height],
                    uv: g.uv,
                    colour,
                });
            }
            pen += g.advance;
        }
    }

    /// Appends a solid rectangle (a panel behind text).
    pub fn push_rect(&self, quads: &mut Vec<TextQuad>, rect: [f32; 4], colour: [f32; 4]) {
        let [u, v] = self.solid_uv;
        quads.push(TextQuad {
            rect,
            uv: [u, v, u, v],
            colour,
        });
    }
}

/// Floats per vertex: clip-space position (2), atlas coordinate (2), colour (4).
const FLOATS_PER_VERTEX: usize = 8;

/// The GL side of the text: the atlas texture, a streamed vertex buffer and the program.
/// Every object is deleted on drop.
pub struct TextRenderer {
    gl: Gl,
    program: ShaderProgram,
    vao: OwnedVertexArray,
    vbo: OwnedBuffer,
    atlas: Texture,
    /// Vertex bytes, kept between frames to avoid reallocating.
    bytes: Vec<u8>,
}

impl TextRenderer {
    /// Uploads the atlas as an R8 texture and builds the program and vertex layout.
    /// `vertex` and `fragment` are the text shaders (`crate::shaders::text_vert` and
    /// `text_frag`; the GL layer does not reach up for them).
    pub fn new(
        gl: &Gl,
        atlas: &FontAtlas,
        vertex: &ShaderSource,
        fragment: &ShaderSource,
    ) -> Result<TextRenderer> {
        let program = ShaderProgram::new(gl, vertex, fragment, &[])?;
        let vao = OwnedVertexArray::new(gl, "text vertex array")?;
        let vbo = OwnedBuffer::new(gl, "text vertex buffer")?;
        unsafe {
            let previous_vao =
                binding(|| gl.get_parameter_vertex_array(glow::VERTEX_ARRAY_BINDING));
            let previous_buffer = binding(|| gl.get_parameter_buffer(glow::ARRAY_BUFFER_BINDING));
            gl.bind_vertex_array(Some(vao.raw()));
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo.raw()));
            let stride = (FLOATS_PER_VERTEX * 4) as i32;
            gl.enable_vertex_attrib_array(0);
            gl.vertex_attrib_pointer_f32(0, 2, glow::FLOAT, false, stride, 0);
            gl.enable_vertex_attrib_array(1);
            gl.vertex_attrib_pointer_f32(1, 2, glow::FLOAT, false, stride, 2 * 4);
            gl.enable_vertex_attrib_array(2);
            gl.vertex_attrib_pointer_f32(2, 4, glow::FLOAT, false, stride, 4 * 4);
            gl.bind_vertex_array(previous_vao);
            gl.bind_buffer(glow::ARRAY_BUFFER, previous_buffer);
        }
        let atlas = upload_atlas(gl, atlas)?;
        check_gl(gl, "uploading the glyph atlas")?;
        Ok(TextRenderer {
            gl: gl.clone(),
            program,
            vao,
            vbo,
            atlas,
            bytes: Vec::new(),
        })
    }

    /// Draws `quads` over what the bound draw framebuffer holds, a `width` x `height` frame:
    /// no depth test, alpha blending that keeps the frame's own alpha, colour attachment 0
    /// only. The state it changes is put back afterwards.
    pub fn draw(&mut self, quads: &[TextQuad], width: u32, height: u32) -> Result<()> {
        if quads.is_empty() || width == 0 || height == 0 {
            return Ok(());
        }
        self.fill_vertices(quads, width, height);
        let gl = &self.gl;
        let count = (quads.len() * 6) as i32;
        unsafe {
            let saved = SavedState::capture(gl);
            gl.viewport(0, 0, width as i32, height as i32);
            for cap in SavedState::CAPS {
                gl.disable(cap);
            }
            gl.enable(glow::BLEND);
            gl.blend_equation(glow::FUNC_ADD);
            gl.blend_func_separate(
                glow::SRC_ALPHA,
                glow::ONE_MINUS_SRC_ALPHA,
                glow::ZERO,
                glow::ONE,
            );
            // Extra outputs (the headless target's visibility, say) keep the scene's values:
            // the text program writes colour only.
            if saved.draw_buffers.len() > 1 {
                gl.draw_buffers(&saved.draw_buffers[..1]);
            }
            self.program.bind();
            self.program.set_i32("atlas", 0);
            gl.active_texture(glow::TEXTURE0);
            gl.bind_texture(glow::TEXTURE_2D, Some(self.atlas.id()));
            gl.bind_vertex_array(Some(self.vao.raw()));
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(self.vbo.raw()));
            gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, &self.bytes, glow::STREAM_DRAW);
            gl.draw_arrays(glow::TRIANGLES, 0, count);
            saved.restore(gl);
            gl.forget_bindings();
        }
        check_gl(gl, "drawing the HUD's text")
    }

    /// Two triangles per quad, positions turned from pixels (y down) into clip space.
    fn fill_vertices(&mut self, quads: &[TextQuad], width: u32, height: u32) {
        let (w, h) = (width as f32, height as f32);
        let clip_x = |x: f32| x / w * 2.0 - 1.0;
        let clip_y = |y: f32| 1.0 - y / h * 2.0;
        self.bytes.clear();
        self.bytes.reserve(quads.len() * 6 * FLOATS_PER_VERTEX * 4);
        for q in quads {
            let [x0, y0, x1, y1] = q.rect;
            let [u0, v0, u1, v1] = q.uv;
            let corners = [
                (x0, y0, u0, v0),
                (x0, y1, u0, v1),
                (x1, y1, u1, v1),
                (x0, y0, u0, v0),
                (x1, y1, u1, v1),
                (x1, y0, u1, v0),
            ];
            for (x, y, u, v) in corners {
                for f in [clip_x(x), clip_y(y), u, v]
                    .into_iter()
                    .chain(q.colour.iter().copied())
                {
                    self.bytes.extend_from_slice(&f.to_ne_bytes());
                }
            }
        }
    }
}

/// A binding as the context reports it, where it can: glow's WebGL backend cannot report an
/// empty binding (WebGL's `null`), so in the browser the text takes nothing to be bound, which
/// is so where it draws (last in the frame, after the passes unbind).
fn binding<T>(query: impl FnOnce() -> Option<T>) -> Option<T> {
    match super::context::CAN_QUERY_BINDINGS {
        true => query(),
        false => None,
    }
}

/// The atlas as an R8 texture on unit 0, leaving unit 0's binding, the active unit and the
/// unpack alignment as they were. Glyphs are placed on whole pixels, one texel to a pixel,
/// so nearest sampling reads what linear would, at a fraction of the cost on a software
/// rasteriser; no mipmaps, the atlas is never minified.
fn upload_atlas(gl: &Gl, atlas: &FontAtlas) -> Result<Texture> {
    unsafe {
        let previous_unit = gl.get_parameter_i32(glow::ACTIVE_TEXTURE) as u32;
        gl.active_texture(glow::TEXTURE0);
        let previous_texture = binding(|| gl.get_parameter_texture(glow::TEXTURE_BINDING_2D));
        let previous_alignment = gl.get_parameter_i32(glow::UNPACK_ALIGNMENT);
        let texels = Texels {
            internal: glow::R8,
            format: glow::RED,
            ty: glow::UNSIGNED_BYTE,
        };
        let size = (atlas.width(), atlas.height());
        let filtering = Filtering::NEAREST_CLAMPED;
        let texture =
            Texture::flat_from(gl, "glyph atlas", size, texels, atlas.pixels(), filtering);
        gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, previous_alignment);
        gl.bind_texture(glow::TEXTURE_2D, previous_texture);
        gl.active_texture(previous_unit);
        gl.forget_bindings();
        texture
    }
}

/// The GL state a text draw changes, read before it and written back after.
struct SavedState {
    caps: [bool; 4],
    blend_func: [u32; 4],
    blend_equation: [u32; 2],
    viewport: [i32; 4],
    /// The bound framebuffer's draw buffers, trailing NONEs left out.
    draw_buffers: Vec<u32>,
    program: Option<glow::Program>,
    vao: Option<glow::VertexArray>,
    array_buffer: Option<glow::Buffer>,
    active_texture: u32,
    texture: Option<glow::Texture>,
}

impl SavedState {
    /// Capabilities the text turns off (blending is turned on again after).
    const CAPS: [u32; 4] = [
        glow::BLEND,
        glow::DEPTH_TEST,
        glow::CULL_FACE,
        glow::SCISSOR_TEST,
    ];

    unsafe fn capture(gl: &Gl) -> SavedState {
        let int = |p| gl.get_parameter_i32(p) as u32;
        let mut viewport = [0i32; 4];
        gl.get_parameter_i32_slice(glow::VIEWPORT, &mut viewport);
        let max_buffers = gl.get_parameter_i32(glow::MAX_DRAW_BUFFERS).clamp(1, 16) as u32;
        // In the browser the text draws on the canvas's framebuffer, which has one buffer.
        let queried = if super::context::CAN_QUERY_BINDINGS {
            max_buffers
        } else {
            0
        };
        let mut draw_buffers: Vec<u32> =
            (0..queried).map(|i| int(glow::DRAW_BUFFER0 + i)).collect();
        while draw_buffers.last() == Some(&glow::NONE) {
            draw_buffers.pop();
        }
        let active_texture = int(glow::ACTIVE_TEXTURE);
        gl.active_texture(glow::TEXTURE0);
        let texture = binding(|| gl.get_parameter_texture(glow::TEXTURE_BINDING_2D));
        gl.active_texture(active_texture);
        SavedState {
            caps: Self::CAPS.map(|cap| gl.is_enabled(cap)),
            blend_func: [
                int(glow::BLEND_SRC_RGB),
                int(glow::BLEND_DST_RGB),
                int(glow::BLEND_SRC_ALPHA),
                int(glow::BLEND_DST_ALPHA),
            ],
            blend_equation: [
                int(glow::BLEND_EQUATION_RGB),
                int(glow::BLEND_EQUATION_ALPHA),
            ],
            viewport,
            draw_buffers,
            program: binding(|| gl.get_parameter_program(glow::CURRENT_PROGRAM)),
            vao: binding(|| gl.get_parameter_vertex_array(glow::VERTEX_ARRAY_BINDING)),
            array_buffer: binding(|| gl.get_parameter_buffer(glow::ARRAY_BUFFER_BINDING)),
            active_texture,
            texture,
        }
    }

    unsafe fn restore(&self, gl: &Gl) {
        for (cap, on) in Self::CAPS.into_iter().zip(self.caps) {
            match on {
                true => gl.enable(cap),
                false => gl.disable(cap),
            }
        }
        let [src_rgb, dst_rgb, src_a, dst_a] = self.blend_func;
        gl.blend_func_separate(src_rgb, dst_rgb, src_a, dst_a);
        gl.blend_equation_separate(self.blend_equation[0], self.blend_equation[1]);
        let [x, y, w, h] = self.viewport;
        gl.viewport(x, y, w, h);
        if self.draw_buffers.len() > 1 {
            gl.draw_buffers(&self.draw_buffers);
        }
        gl.use_program(self.program);
        gl.bind_vertex_array(self.vao);
        gl.bind_buffer(glow::ARRAY_BUFFER, self.array_buffer);
        gl.active_texture(glow::TEXTURE0);
        gl.bind_texture(glow::TEXTURE_2D, self.texture);
        gl.active_texture(self.active_texture);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

    #[test]
    fn atlas_holds_ascii_and_places_glyphs_on_whole_pixels() {
        let atlas = FontAtlas::new(FONT, 16.0).unwrap();
        assert_eq!(
            atlas.pixels().len(),
            (atlas.width() * atlas.height()) as usize
        );
        assert!(atlas.height().is_power_of_two() && atlas.height() <= 256);
        assert!((16.0..=24.0).contains(&atlas.line_height()));
        let mut quads = Vec::new();
        atlas.push_text(&mut quads, "Light angle: 45.0°", 10.3, 7.0, [1.0; 4]);
        // Spaces draw nothing; every other character is one quad.
        assert_eq!(quads.len(), "Lightangle:45.0°".chars().count());
        for q in &quads {
            assert!(q.rect.iter().all(|v| v.fract() == 0.0), "{q:?}");
            assert!(q.rect[0] < q.rect[2] && q.rect[1] < q.rect[3]);
            assert!(q.uv.iter().all(|v| (0.0..=1.0).contains(v)));
        }
        // The glyphs hold coverage: the atlas is not blank, and an unknown character falls
        // back to '?' rather than vanishing.
        assert!(atlas.pixels().iter().filter(|&&p| p > 128).count() > 500);
        assert_eq!(atlas.text_width("\u{4e2d}"), atlas.text_width("?"));
        assert!(atlas.text_width("MMMM") > atlas.text_width("iiii"));
    }

    #[test]
    fn bad_fonts_and_sizes_are_errors() {
        assert!(FontAtlas::new(b"not a font", 16.0).is_err());
        assert!(FontAtlas::new(FONT, f32::NAN).is_err());
        assert!(FontAtlas::new(FONT, 0.0).is_err());
    }
}
