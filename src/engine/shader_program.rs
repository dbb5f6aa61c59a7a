//! `ShaderProgram`: compiles and links GLSL, caches uniform locations, and turns driver logs
//! into `file:line:column` messages (the book's `ShaderProgram` class).

use std::cell::RefCell;

use glam::{Mat3, Mat4, Vec3, Vec4};
use glow::HasContext;

use super::owned::{OwnedProgram, OwnedShader};
use super::Gl;
use crate::error::{Error, Result};

/// Lines per file in the numbering of a shader with includes ([`crate::shaders::resolve`]):
/// file K's line L is `K * LINE_BLOCK + L` (the main file keeps its own numbers).
pub const LINE_BLOCK: u32 = 100_000;

/// The GLSL a driver takes. The project's files are written once, for desktop GL 3.3 core
/// (`#version 330 core`); OpenGL ES 3.0, which WebGL2 is, gets the same text under
/// `#version 300 es` with the precision every type must state there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dialect {
    Desktop,
    Es,
}

/// What an ES shader states after its `#version`: full precision for everything the
/// project's shaders read (ES's defaults are lower, or none for the shadow samplers), and
/// that a map's lit border and its interpolated depths are the shader's to draw
/// (shaders/lib/shadow_border.glsl, shaders/lib/shadow_depth.glsl).
const ES_PRECISION: &str = "precision highp float;\nprecision highp int;\n\
    #define SHADOW_BORDER_IN_SHADER 1\n#define SHADOW_DEPTH_IN_SHADER 1\n\
    precision highp sampler2D;\nprecision highp sampler2DShadow;\n\
    precision highp sampler2DArray;\nprecision highp sampler2DArrayShadow;\n\
    precision highp samplerCube;\nprecision highp samplerCubeShadow;\n\
    precision highp sampler3D;\n";

impl Dialect {
    /// The dialect of the current context.
    pub fn of(gl: &Gl) -> Dialect {
        match gl.version().is_embedded {
            true => Dialect::Es,
            false => Dialect::Desktop,
        }
    }

    /// `text` in this dialect: the desktop's unchanged; for ES its `#version 330 core` line
    /// becomes `#version 300 es` and the precision statements, and `#line 2` keeps the
    /// file's own line numbers in the driver's messages.
    pub fn apply(self, text: &str) -> std::borrow::Cow<'_, str> {
        match self {
            Dialect::Desktop => text.into(),
            Dialect::Es => match text.split_once('\n') {
                Some((first, rest)) if first.trim() == "#version 330 core" => {
                    format!("#version 300 es\n{ES_PRECISION}#line 2\n{rest}").into()
                }
                _ => text.into(),
            },
        }
    }
}

/// A shader's text and the files it came from, so errors can name them.
#[derive(Debug, Clone)]
pub struct ShaderSource {
    pub name: String,
    pub text: String,
    /// The file of each GLSL source-string number (`#line N K`): 0 is `name`, the others
    /// are the files it includes (see [`crate::shaders::resolve`]).
    pub files: Vec<String>,
}

impl ShaderSource {
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> Self {
        let name = name.into();
        ShaderSource {
            files: vec![name.clone()],
            name,
            text: text.into(),
        }
    }

    /// The text with `#define`s inserted after the `#version` line, and a `#line` directive so
    /// the driver's line numbers still match the file.
    pub fn with_defines(&self, defines: &[(String, String)]) -> String {
        if defines.is_empty() {
            return self.text.clone();
        }
        let (first, rest) = match self.text.split_once('\n') {
            Some((first, rest)) if first.trim_start().starts_with("#version") => (first, rest),
            _ => {
                // No #version line: defines go first and line numbering restarts at 1.
                let mut out = String::new();
                for (k, v) in defines {
                    out.push_str(&format!("#define {k} {v}\n"));
                }
                out.push_str("#line 1\n");
                out.push_str(&self.text);
                return out;
            }
        };
        let mut out = String::with_capacity(self.text.len() + 64 * defines.len());
        out.push_str(first);
        out.push('\n');
        for (k, v) in defines {
            out.push_str(&format!("#define {k} {v}\n"));
        }
        out.push_str("#line 2\n");
        out.push_str(rest);
        out
    }
}

/// Rewrites a driver info log so each message starts with `file:line:column:`; `files`
/// names each source-string number (the first number of a message), so a message from an
/// included snippet names the snippet.
///
/// Mesa writes `0:12(5): error: ...`; NVIDIA writes `0(12) : error ...`. Lines in neither form
/// are kept as they are.
pub fn annotate_log(files: &[String], log: &str) -> String {
    let main = files.first().map(String::as_str).unwrap_or("shader");
    let mut out = Vec::new();
    for line in log.lines().filter(|l| !l.trim().is_empty()) {
        out.push(annotate_line(files, line).unwrap_or_else(|| format!("{main}: {line}")));
    }
    out.join("\n")
}

fn annotate_line(files: &[String], line: &str) -> Option<String> {
    let digits = |s: &str| -> Option<(u32, usize)> {
        let n = s.bytes().take_while(|b| b.is_ascii_digit()).count();
        if n == 0 {
            return None;
        }
        Some((s[..n].parse().ok()?, n))
    };
    let (string, n) = digits(line)?;
    let rest = &line[n..];
    // The file: the source-string number, or (Mesa reports 0 for every string) the block
    // its line number falls in ([`LINE_BLOCK`]).
    let locate = |ln: u32| -> Option<(&str, u32)> {
        let block = LINE_BLOCK;
        match (string, ln / block) {
            (0, k) if k > 0 => Some((files.get(k as usize)?.as_str(), ln % block)),
            (s, _) => Some((files.get(s as usize)?.as_str(), ln % block)),
        }
    };
    if let Some(rest) = rest.strip_prefix(':') {
        // Mesa: <string>:<line>(<col>): message
        let (ln, n) = digits(rest)?;
        let (file, ln) = locate(ln)?;
        let rest = &rest[n..];
        let (col, rest) = match rest.strip_prefix('(') {
            Some(r) => {
                let (c, n) = digits(r)?;
                (Some(c), r[n..].strip_prefix(')')?)
            }
            None => (None, rest),
        };
        let msg = rest.trim_start_matches(':').trim();
        Some(match col {
            Some(c) => format!("{file}:{ln}:{c}: {msg}"),
            None => format!("{file}:{ln}: {msg}"),
        })
    } else if let Some(rest) = rest.strip_prefix('(') {
        // NVIDIA: <string>(<line>) : message
        let (ln, n) = digits(rest)?;
        let (file, ln) = locate(ln)?;
        let msg = rest[n..]
            .strip_prefix(')')?
            .trim()
            .trim_start_matches(':')
            .trim();
        Some(format!("{file}:{ln}: {msg}"))
    } else {
        None
    }
}

/// A linked program; deleted on drop.
pub struct ShaderProgram {
    gl: Gl,
    program: OwnedProgram,
    uniforms: RefCell<Uniforms>,
    /// Reads instanced values as per-instance vertex attributes (`instanceMatrix`), not
    /// from the `Instances` block.
    instance_attributes: bool,
    /// Reads no per-vertex attribute but the position (and instanced ones): a depth pass,
    /// which can draw a mesh's welded positions.
    positions_only: bool,
}

impl ShaderProgram {
    /// Compiles a vertex and a fragment shader with the given `#define`s and links them.
    pub fn new(
        gl: &Gl,
        vertex: &ShaderSource,
        fragment: &ShaderSource,
        defines: &[(String, String)],
    ) -> Result<ShaderProgram> {
        Self::from_stages(
            gl,
            &[
                (glow::VERTEX_SHADER, vertex),
                (glow::FRAGMENT_SHADER, fragment),
            ],
            defines,
        )
    }

    /// Compiles and links any set of stages (a geometry shader between the two above, say).
    pub fn from_stages(
        gl: &Gl,
        stages: &[(u32, &ShaderSource)],
        defines: &[(String, String)],
    ) -> Result<ShaderProgram> {
        Self::capturing(gl, stages, defines, &[])
    }

    /// [`ShaderProgram::from_stages`], recording the vertex outputs `varyings` into the
    /// bound transform feedback buffer, interleaved ([`super::VertexCapture`]).
    pub fn capturing(
        gl: &Gl,
        stages: &[(u32, &ShaderSource)],
        defines: &[(String, String)],
        varyings: &[&str],
    ) -> Result<ShaderProgram> {
        let owned = OwnedProgram::new(gl, "program")?;
        let program = owned.raw();
        let mut this = ShaderProgram {
            gl: gl.clone(),
            program: owned,
            uniforms: RefCell::new(Uniforms::default()),
            instance_attributes: false,
            positions_only: false,
        };
        let shaders = stages
            .iter()
            .map(|(kind, source)| compile(gl, *kind, source, defines))
            .collect::<Result<Vec<_>>>()?;
        let names: Vec<&str> = stages.iter().map(|(_, s)| s.name.as_str()).collect();
        unsafe {
            for s in &shaders {
                gl.attach_shader(program, s.raw());
            }
            if !varyings.is_empty() {
                gl.transform_feedback_varyings(program, varyings, glow::INTERLEAVED_ATTRIBS);
            }
            gl.link_program(program);
            for s in shaders {
                gl.detach_shader(program, s.raw());
            }
            if !gl.get_program_link_status(program) {
                let log = gl.get_program_info_log(program);
                let file = names.join(" + ");
                return Err(Error::Shader {
                    log: annotate_log(std::slice::from_ref(&file), &log),
                    file,
                });
            }
            // Instanced draws read their values from one uniform buffer binding.
            if let Some(block) = gl.get_uniform_block_index(program, "Instances") {
                gl.uniform_block_binding(program, block, super::mesh::INSTANCE_BINDING);
            }
        }
        this.instance_attributes =
            unsafe { gl.get_attrib_location(program, "instanceMatrix") }.is_some();
        this.positions_only = reads_positions_only(gl, program);
        Ok(this)
    }

    /// Whether instanced draws hand this program its values as vertex attributes.
    pub fn reads_instance_attributes(&self) -> bool {
        self.instance_attributes
    }

    /// Whether the program's only per-vertex input is the position (location 0), so a
    /// mesh's welded positions serve it ([`super::Mesh::render_from`]).
    pub fn reads_positions_only(&self) -> bool {
        self.positions_only
    }

    pub fn bind(&self) {
        self.gl.use_program_once(Some(self.program.raw()));
    }

    pub fn unbind(&self) {
        self.gl.use_program_once(None);
    }

    /// Looks a uniform up once and remembers it (the book's `createUniform`, done lazily),
    /// and returns its location only when `bits` differ from the value it holds: a value
    /// already there is not sent again. Uniforms the compiler removed as unused resolve to
    /// `None` and are skipped. Names are found by address (a literal's address does not
    /// change), so no name is hashed per call.
    fn changed(&self, name: &'static str, bits: &[u32]) -> Option<glow::UniformLocation> {
        let slot = self.slot(name);
        let mut u = self.uniforms.borrow_mut();
        let (loc, held) = &mut u.slots[slot];
        // A clone: WebGL's locations are JavaScript objects (on the desktop, a copy).
        #[allow(clippy::clone_on_copy)]
        let loc = loc.clone()?;
        if held.as_slice() == bits {
            return None;
        }
        held.clear();
        held.extend_from_slice(bits);
        Some(loc)
    }

    /// The slot of uniform `name`, looked up the first time.
    fn slot(&self, name: &'static str) -> usize {
        let mut u = self.uniforms.borrow_mut();
        if let Some(n) = u.names.iter().find(|n| std::ptr::eq(n.0, name)) {
            return n.1;
        }
        let slot = match u.names.iter().find(|n| n.0 == name) {
            // The same name at another address: the same uniform.
            Some(n) => n.1,
            None => {
                let loc = unsafe { self.gl.get_uniform_location(self.program.raw(), name) };
                u.slots.push((loc, Vec::new()));
                u.slots.len() - 1
            }
        };
        u.names.push((name, slot));
        slot
    }

    /// Whether the program reads uniform `name` (the compiler keeps only those), so a
    /// caller can skip computing a value no one reads.
    pub fn uses(&self, name: &'static str) -> bool {
        let slot = self.slot(name);
        self.uniforms.borrow().slots[slot].0.is_some()
    }

    fn changed_f32(&self, name: &'static str, v: &[f32]) -> Option<glow::UniformLocation> {
        self.changed(name, bytemuck::cast_slice(v))
    }

    pub fn set_mat4(&self, name: &'static str, m: &Mat4) {
        let v = m.to_cols_array();
        if let Some(loc) = self.changed_f32(name, &v) {
            unsafe { self.gl.uniform_matrix_4_f32_slice(Some(&loc), false, &v) };
        }
    }

    /// Sets `name[0]`, `name[1]`, ... from a slice (`name` without the index).
    pub fn set_mat4_array(&self, name: &'static str, ms: &[Mat4]) {
        // glam's matrices and vectors are plain f32s: no copy per call.
        let flat: &[f32] = bytemuck::cast_slice(ms);
        if let Some(loc) = self.changed_f32(name, flat) {
            unsafe { self.gl.uniform_matrix_4_f32_slice(Some(&loc), false, flat) };
        }
    }

    /// Sets `name[0]`, `name[1]`, ... from a slice.
    pub fn set_vec3_array(&self, name: &'static str, vs: &[Vec3]) {
        let flat: &[f32] = bytemuck::cast_slice(vs);
        if let Some(loc) = self.changed_f32(name, flat) {
            unsafe { self.gl.uniform_3_f32_slice(Some(&loc), flat) };
        }
    }

    /// Sets `name[0]`, `name[1]`, ... from a slice.
    pub fn set_vec4_array(&self, name: &'static str, vs: &[Vec4]) {
        let flat: &[f32] = bytemuck::cast_slice(vs);
        if let Some(loc) = self.changed_f32(name, flat) {
            unsafe { self.gl.uniform_4_f32_slice(Some(&loc), flat) };
        }
    }

    /// Sets `name[0]`, `name[1]`, ... from a slice.
    pub fn set_f32_array(&self, name: &'static str, vs: &[f32]) {
        if let Some(loc) = self.changed_f32(name, vs) {
            unsafe { self.gl.uniform_1_f32_slice(Some(&loc), vs) };
        }
    }

    /// Sets `name[0]`, `name[1]`, ... from a slice.
    pub fn set_mat3_array(&self, name: &'static str, ms: &[Mat3]) {
        let flat: &[f32] = bytemuck::cast_slice(ms);
        if let Some(loc) = self.changed_f32(name, flat) {
            unsafe { self.gl.uniform_matrix_3_f32_slice(Some(&loc), false, flat) };
        }
    }

    pub fn set_mat3(&self, name: &'static str, m: &Mat3) {
        let v = m.to_cols_array();
        if let Some(loc) = self.changed_f32(name, &v) {
            unsafe { self.gl.uniform_matrix_3_f32_slice(Some(&loc), false, &v) };
        }
    }

    pub fn set_vec2(&self, name: &'static str, v: [f32; 2]) {
        if let Some(loc) = self.changed_f32(name, &v) {
            unsafe { self.gl.uniform_2_f32(Some(&loc), v[0], v[1]) };
        }
    }

    pub fn set_vec3(&self, name: &'static str, v: Vec3) {
        if let Some(loc) = self.changed_f32(name, &v.to_array()) {
            unsafe { self.gl.uniform_3_f32(Some(&loc), v.x, v.y, v.z) };
        }
    }

    pub fn set_vec4(&self, name: &'static str, v: Vec4) {
        if let Some(loc) = self.changed_f32(name, &v.to_array()) {
            unsafe { self.gl.uniform_4_f32(Some(&loc), v.x, v.y, v.z, v.w) };
        }
    }

    pub fn set_f32(&self, name: &'static str, v: f32) {
        if let Some(loc) = self.changed_f32(name, &[v]) {
            unsafe { self.gl.uniform_1_f32(Some(&loc), v) };
        }
    }

    pub fn set_i32(&self, name: &'static str, v: i32) {
        if let Some(loc) = self.changed(name, &[v as u32]) {
            unsafe { self.gl.uniform_1_i32(Some(&loc), v) };
        }
    }
}

/// A program's uniforms: each name's slot (by the name's address), and each slot's location
/// and the value last sent there (as bits, so -0.0 and NaN compare as sent).
#[derive(Default)]
struct Uniforms {
    names: Vec<(&'static str, usize)>,
    slots: Vec<(Option<glow::UniformLocation>, Vec<u32>)>,
}

/// Whether every active attribute of `program` is the position (location 0) or a
/// per-instance one (locations [`super::mesh::INSTANCE_LOCATION`] on). The compiler drops
/// inputs a program never reads from its active attributes.
fn reads_positions_only(gl: &Gl, program: glow::Program) -> bool {
    unsafe {
        (0..gl.get_active_attributes(program)).all(|k| {
            let location = gl
                .get_active_attribute(program, k)
                .and_then(|a| gl.get_attrib_location(program, &a.name));
            matches!(location, Some(l) if l == 0 || l >= super::mesh::INSTANCE_LOCATION)
        })
    }
}

fn compile(
    gl: &Gl,
    kind: u32,
    source: &ShaderSource,
    defines: &[(String, String)],
) -> Result<OwnedShader> {
    if kind == glow::GEOMETRY_SHADER && gl.version().is_embedded {
        return Err(Error::Invalid(format!(
            "{}: this picture needs a geometry shader (stencil shadow volumes' silhouettes, a \
             point light's six faces in one pass), which OpenGL ES 3.0 and WebGL2 lack",
            source.name
        )));
    }
    let owned = OwnedShader::with(gl, &format!("shader {}", source.name), kind)?;
    let shader = owned.raw();
    unsafe {
        let text = source.with_defines(defines);
        gl.shader_source(shader, &Dialect::of(gl).apply(&text));
        gl.compile_shader(shader);
        if !gl.get_shader_compile_status(shader) {
            let log = gl.get_shader_info_log(shader);
            return Err(Error::Shader {
                file: source.name.clone(),
                log: annotate_log(&source.files, &log),
            });
        }
    }
    Ok(owned)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesa_and_nvidia_logs_get_file_and_line() {
        let files = |f: &[&str]| f.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        let mesa = "0:12(5): error: syntax error, unexpected '}'\n";
        assert_eq!(
            annotate_log(&files(&["shaders/scene.frag"]), mesa),
            "shaders/scene.frag:12:5: error: syntax error, unexpected '}'"
        );
        let nv = "0(7) : error C0000: syntax error";
        assert_eq!(
            annotate_log(&files(&["a.vert"]), nv),
            "a.vert:7: error C0000: syntax error"
        );
        assert_eq!(
            annotate_log(&files(&["a.vert"]), "odd text"),
            "a.vert: odd text"
        );
        // A message from source string 2 names the second included file.
        let included = files(&[
            "shaders/scene.frag",
            "shaders/lib/a.glsl",
            "shaders/lib/b.glsl",
        ]);
        assert_eq!(
            annotate_log(&included, "2:7(3): error: `x' undeclared"),
            "shaders/lib/b.glsl:7:3: error: `x' undeclared"
        );
        // Mesa's way: source 0, the file in the line number's block.
        assert_eq!(
            annotate_log(&included, "0:100007(3): error: `x' undeclared"),
            "shaders/lib/a.glsl:7:3: error: `x' undeclared"
        );
    }

    #[test]
    fn defines_keep_line_numbers() {
        let s = ShaderSource::new("x", "#version 330 core\nvoid main() {}\n");
        let out = s.with_defines(&[("PCF_RADIUS".into(), "1".into())]);
        assert_eq!(
            out,
            "#version 330 core\n#define PCF_RADIUS 1\n#line 2\nvoid main() {}\n"
        );
    }
}
