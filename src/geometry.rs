//! CPU-side meshes: the built-in shapes of the chapters' scenes and OBJ models read with
//! `tobj`, validated before anything reaches the GPU.

use std::path::Path;

use glam::Vec3;

use crate::error::{Error, Result};
use crate::input::{read_text_file, OBJ_LIMIT};

/// The largest coordinate magnitude accepted in a model; beyond it f32 precision is gone.
pub const MAX_COORDINATE: f32 = 1.0e7;

/// Triangles with interleavable attributes, indexed. Counter-clockwise faces are front faces.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshData {
    pub name: String,
    pub positions: Vec<[f32; 3]>,
    pub tex_coords: Vec<[f32; 2]>,
    pub normals: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
}

impl MeshData {
    /// Checks the invariants the GPU upload relies on; the message names the mesh.
    pub fn validate(&self) -> Result<()> {
        let n = self.positions.len();
        let bad = |what: String| Err(Error::Invalid(format!("mesh '{}': {what}", self.name)));
        if self.tex_coords.len() != n || self.normals.len() != n {
            return bad(format!(
                "{} positions but {} texture coordinates and {} normals",
                n,
                self.tex_coords.len(),
                self.normals.len()
            ));
        }
        if self.indices.is_empty() || !self.indices.len().is_multiple_of(3) {
            return bad(format!(
                "{} indices: expected a non-zero multiple of 3 (triangles)",
                self.indices.len()
            ));
        }
        if let Some(i) = self.indices.iter().find(|&&i| i as usize >= n) {
            return bad(format!("index {i} out of range: the mesh has {n} vertices"));
        }
        if let Some(p) = self
            .positions
            .iter()
            .find(|p| p.iter().any(|c| !c.is_finite() || c.abs() > MAX_COORDINATE))
        {
            return bad(format!(
                "vertex position {p:?}: expected finite coordinates within +-{MAX_COORDINATE:e}"
            ));
        }
        Ok(())
    }

    /// The positions alone, each distinct one once (equal bit for bit), and the indices
    /// into them: what a depth pass reads. A cube's 24 vertices (split for their normals and
    /// texture coordinates) are 8 corners, so a pass that reads only positions shades a
    /// third of the vertices; the triangles, their order and winding are the same.
    pub fn welded_positions(&self) -> (Vec<[f32; 3]>, Vec<u32>) {
        let mut first = std::collections::HashMap::with_capacity(self.positions.len());
        let mut positions = Vec::new();
        let remap: Vec<u32> = (self.positions.iter())
            .map(|p| {
                let bits = p.map(f32::to_bits);
                *first.entry(bits).or_insert_with(|| {
                    positions.push(*p);
                    positions.len() as u32 - 1
                })
            })
            .collect();
        let indices = self.indices.iter().map(|&i| remap[i as usize]).collect();
        (positions, indices)
    }

    /// The triangles as position triples, in model space.
    pub fn triangles(&self) -> impl Iterator<Item = [Vec3; 3]> + '_ {
        self.indices.chunks_exact(3).map(|t| {
            let p = |i: u32| Vec3::from(self.positions[i as usize]);
            [p(t[0]), p(t[1]), p(t[2])]
        })
    }

    /// The plane every vertex lies in, as (a point on it, its normal), if there is one:
    /// such a mesh cannot shadow itself, nor anything on its lit side.
    pub fn flat_plane(&self) -> Option<(Vec3, Vec3)> {
        let first = self.triangles().next()?;
        let n = (first[1] - first[0])
            .cross(first[2] - first[0])
            .try_normalize()?;
        let (lo, hi) = self.bounds();
        let scale = lo.abs().max(hi.abs()).max_element().max(1.0);
        self.positions
            .iter()
            .all(|p| n.dot(Vec3::from(*p) - first[0]).abs() <= 1e-5 * scale)
            .then_some((first[0], n))
    }

    /// Axis-aligned bounds in model space.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(Vec3::from(*p)), hi.max(Vec3::from(*p))),
        )
    }

    /// The built-in cube: [-1, 1] on each axis, one normal per face, counter-clockwise from
    /// outside, with the texture coordinates of LearnOpenGL's `renderCube` (the only one of
    /// the chapters' cubes that is textured): on the +-Z faces s follows x and t follows y; on
    /// the +-Y faces s follows x and t runs against z; on the +-X faces s follows y and t
    /// runs against z. So the -Z face's wood reads mirrored from outside, as in the tutorial.
    pub fn cube() -> MeshData {
        // Each face: outward normal; in-face axes a, b with a x b = normal (the winding); and
        // the axes along which s and t grow from 0 at -1 to 1 at +1.
        #[rustfmt::skip]
        let faces: [[[f32; 3]; 5]; 6] = [
            [[1., 0., 0.], [0., 0., -1.], [0., 1., 0.], [0., 1., 0.], [0., 0., -1.]],
            [[-1., 0., 0.], [0., 0., 1.], [0., 1., 0.], [0., 1., 0.], [0., 0., -1.]],
            [[0., 1., 0.], [1., 0., 0.], [0., 0., -1.], [1., 0., 0.], [0., 0., -1.]],
            [[0., -1., 0.], [1., 0., 0.], [0., 0., 1.], [1., 0., 0.], [0., 0., -1.]],
            [[0., 0., 1.], [1., 0., 0.], [0., 1., 0.], [1., 0., 0.], [0., 1., 0.]],
            [[0., 0., -1.], [-1., 0., 0.], [0., 1., 0.], [1., 0., 0.], [0., 1., 0.]],
        ];
        let mut mesh = MeshData::empty("cube");
        for [n, a, b, s_axis, t_axis] in faces.map(|f| f.map(Vec3::from)) {
            let first = mesh.positions.len();
            mesh.push_quad(n, a, b, n, [1.0, 1.0]);
            for i in first..mesh.positions.len() {
                let p = Vec3::from(mesh.positions[i]);
                mesh.tex_coords[i] = [(p.dot(s_axis) + 1.0) * 0.5, (p.dot(t_axis) + 1.0) * 0.5];
            }
        }
        mesh
    }

    /// The book's `plane.obj`: a 2 x 2 square in the XZ plane at y = 0, facing +Y,
    /// counter-clockwise seen from above. `tiles` repeats the texture (LearnOpenGL tiles 25).
    pub fn plane(tiles: f32) -> MeshData {
        let mut mesh = MeshData::empty("plane");
        mesh.push_quad(Vec3::ZERO, Vec3::X, -Vec3::Z, Vec3::Y, [tiles, tiles]);
        mesh
    }

    /// A UV sphere of radius 1 (the slides' sphere), `segments` around and `rings` from pole
    /// to pole.
    pub fn sphere(segments: u32, rings: u32) -> MeshData {
        let mut mesh = MeshData::empty("sphere");
        for r in 0..=rings {
            let v = r as f32 / rings as f32;
            let theta = v * std::f32::consts::PI;
            for s in 0..=segments {
                let u = s as f32 / segments as f32;
                let phi = u * std::f32::consts::TAU;
                let n = Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    -theta.sin() * phi.sin(),
                );
                mesh.positions.push(n.to_array());
                mesh.normals.push(n.to_array());
                mesh.tex_coords.push([u, 1.0 - v]);
            }
        }
        let row = segments + 1;
        for r in 0..rings {
            for s in 0..segments {
                let (a, b) = (r * row + s, (r + 1) * row + s);
                // Counter-clockwise seen from outside; skip the degenerate pole triangles.
                if r != 0 {
                    mesh.indices.extend_from_slice(&[a, b, a + 1]);
                }
                if r != rings - 1 {
                    mesh.indices.extend_from_slice(&[a + 1, b, b + 1]);
                }
            }
        }
        mesh
    }

    /// A gently hilly height field over [-1, 1]^2 with heights in about [-0.1, 0.1] (the
    /// slides' terrain patch), `cells` x `cells` quads, facing +Y.
    pub fn terrain(cells: u32) -> MeshData {
        let mut mesh = MeshData::empty("terrain");
        let h = |x: f32, z: f32| {
            0.06 * (3.1 * x).sin() * (2.3 * z).cos() + 0.04 * (5.7 * x + 1.3 * z).sin()
        };
        let n = cells + 1;
        for j in 0..n {
            for i in 0..n {
                let (x, z) = (
                    -1.0 + 2.0 * i as f32 / cells as f32,
                    -1.0 + 2.0 * j as f32 / cells as f32,
                );
                mesh.positions.push([x, h(x, z), z]);
                mesh.tex_coords
                    .push([i as f32 / cells as f32, j as f32 / cells as f32]);
                mesh.normals.push([0.0; 3]);
            }
        }
        for j in 0..cells {
            for i in 0..cells {
                let a = j * n + i;
                // z grows towards the viewer: (a, a+n, a+1) is counter-clockwise from above.
                mesh.indices
                    .extend_from_slice(&[a, a + n, a + 1, a + 1, a + n, a + n + 1]);
            }
        }
        mesh.compute_normals(0);
        mesh
    }

    fn empty(name: &str) -> MeshData {
        MeshData {
            name: name.to_string(),
            positions: Vec::new(),
            tex_coords: Vec::new(),
            normals: Vec::new(),
            indices: Vec::new(),
        }
    }

    /// Appends the square centre +- u +- v, wound counter-clockwise about `normal`.
    fn push_quad(&mut self, centre: Vec3, u: Vec3, v: Vec3, normal: Vec3, uv_scale: [f32; 2]) {
        let base = self.positions.len() as u32;
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        for (a, b) in corners {
            self.positions.push((centre + u * a + v * b).to_array());
            self.tex_coords
                .push([(a + 1.0) * 0.5 * uv_scale[0], (b + 1.0) * 0.5 * uv_scale[1]]);
            self.normals.push(normal.to_array());
        }
        self.indices
            .extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
    }

    /// Turns the mesh inside out: reversed winding and normals, to be seen from within.
    pub fn inside_out(self) -> MeshData {
        let mut m = self.flip_winding();
        for n in &mut m.normals {
            *n = n.map(|c| -c);
        }
        m
    }

    /// Reverses every triangle's winding (LearnOpenGL's floor is wound clockwise on purpose).
    pub fn flip_winding(mut self) -> MeshData {
        for t in self.indices.chunks_exact_mut(3) {
            t.swap(1, 2);
        }
        self
    }

    /// Loads an OBJ file (a regular file of at most [`OBJ_LIMIT`] bytes): polygons are
    /// triangulated, missing normals are computed, missing texture coordinates are zero.
    /// Errors name the file and, where possible, the line.
    pub fn load_obj(path: &Path) -> Result<MeshData> {
        let text = read_text_file(path, OBJ_LIMIT, "OBJ model")?;
        Self::parse_obj(path, &text)
    }

    /// Parses OBJ text; `path` names the source in errors.
    ///
    /// Every line is checked here before `tobj` sees it: faces need three corners or more
    /// (shorter ones are refused, not dropped, so a model never loses faces without a
    /// word), and every index must name an earlier `v`/`vt`/`vn` line, compared in
    /// checked arithmetic so that no huge index can wrap around onto a valid one.
    pub fn parse_obj(path: &Path, text: &str) -> Result<MeshData> {
        if let Some((line, why)) = first_bad_obj_line(text) {
            return Err(Error::file(
                path,
                format!("not a valid OBJ model at line {line}: {why}"),
            ));
        }
        let options = tobj::LoadOptions {
            single_index: true,
            triangulate: true,
            ..Default::default()
        };
        let mut reader = std::io::BufReader::new(text.as_bytes());
        let (models, _) = tobj::load_obj_buf(&mut reader, &options, |_| {
            Err(tobj::LoadError::GenericFailure)
        })
        .map_err(|e| Error::file(path, format!("not a valid OBJ model ({e})")))?;
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "model".into());
        let mut mesh = MeshData::empty(&name);
        for model in &models {
            let m = &model.mesh;
            let count = m.positions.len() / 3;
            // Every index below is base + i < base + count: checked once here, so adding
            // base cannot wrap.
            let too_many = || {
                Error::file(
                    path,
                    "the OBJ model has 2^32 vertices or more: expected fewer (32-bit indices)",
                )
            };
            let base = u32::try_from(mesh.positions.len()).map_err(|_| too_many())?;
            let added = u32::try_from(count).map_err(|_| too_many())?;
            base.checked_add(added).ok_or_else(too_many)?;
            let has_normals = m.normals.len() == m.positions.len();
            let has_uv = m.texcoords.len() / 2 == count;
            for i in 0..count {
                mesh.positions.push([
                    m.positions[3 * i],
                    m.positions[3 * i + 1],
                    m.positions[3 * i + 2],
                ]);
                mesh.normals.push(if has_normals {
                    [m.normals[3 * i], m.normals[3 * i + 1], m.normals[3 * i + 2]]
                } else {
                    [0.0; 3]
                });
                mesh.tex_coords.push(if has_uv {
                    [m.texcoords[2 * i], m.texcoords[2 * i + 1]]
                } else {
                    [0.0; 2]
                });
            }
            if let Some(i) = m.indices.iter().find(|&&i| i as usize >= count) {
                return Err(Error::file(
                    path,
                    format!(
                        "face index {} out of range: the model has {count} vertices",
                        i + 1
                    ),
                ));
            }
            mesh.indices.extend(m.indices.iter().map(|i| i + base));
            if !has_normals {
                mesh.compute_normals(base as usize);
            }
        }
        if mesh.indices.is_empty() {
            return Err(Error::file(
                path,
                "the OBJ model has no faces: expected at least one 'f' line with three vertices",
            ));
        }
        mesh.validate()
            .map_err(|e| Error::file(path, e.to_string()))?;
        Ok(mesh)
    }

    /// Area-weighted vertex normals for the vertices from `first` on.
    fn compute_normals(&mut self, first: usize) {
        let mut acc = vec![Vec3::ZERO; self.positions.len() - first];
        for t in self.indices.chunks_exact(3) {
            if (t[0] as usize) < first {
                continue;
            }
            let p = |i: u32| Vec3::from(self.positions[i as usize]);
            let n = (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
            for &i in t {
                acc[i as usize - first] += n;
            }
        }
        for (i, n) in acc.into_iter().enumerate() {
            self.normals[first + i] = n.try_normalize().unwrap_or(Vec3::Y).to_array();
        }
    }
}

/// Finds the first line an OBJ reader would reject, or that `tobj` would take wrongly (a
/// face of fewer than three corners, an index beyond the vertices), to point the user at it.
fn first_bad_obj_line(text: &str) -> Option<(usize, String)> {
    let mut counts = [0u64; 3]; // v, vt, vn lines so far
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let floats = |w: std::str::SplitWhitespace, min: usize| {
            let vals: Vec<_> = w.map(str::parse::<f32>).collect();
            vals.len() >= min && vals.iter().all(|x| x.is_ok())
        };
        let ok = match words.next() {
            Some("v") => {
                counts[0] += 1;
                floats(words, 3)
                    .then_some(())
                    .ok_or_else(|| "expected 'v x y z' with numbers".to_string())
            }
            Some("vt") => {
                counts[1] += 1;
                floats(words, 1)
                    .then_some(())
                    .ok_or_else(|| "expected 'vt u v' with numbers".to_string())
            }
            Some("vn") => {
                counts[2] += 1;
                floats(words, 3)
                    .then_some(())
                    .ok_or_else(|| "expected 'vn x y z' with numbers".to_string())
            }
            Some("f") => check_face(words, counts),
            _ => Ok(()),
        };
        if let Err(why) = ok {
            return Some((i + 1, why));
        }
    }
    None
}

/// Checks one face's corners (`a`, `a/b`, `a//c`, `a/b/c`, negative = relative) against
/// the `v`, `vt` and `vn` lines before it.
fn check_face(
    words: std::str::SplitWhitespace,
    counts: [u64; 3],
) -> std::result::Result<(), String> {
    const KINDS: [&str; 3] = ["v", "vt", "vn"];
    let mut corners = 0;
    for w in words {
        corners += 1;
        for (k, part) in w.split('/').enumerate() {
            if part.is_empty() && k > 0 {
                continue;
            }
            let Some(&count) = counts.get(k) else {
                return Err(format!("'{w}': too many '/' in a face corner"));
            };
            let out_of_range = || {
                let corner = if part == w {
                    String::new()
                } else {
                    format!(" in '{w}'")
                };
                format!(
                    "face index out of range: '{part}'{corner}, but there are {count} '{}' \
                     lines before it (indices start at 1 and must refer to an earlier line)",
                    KINDS[k]
                )
            };
            // Digits that do not fit an i64 are an index far beyond any count.
            let idx: i64 = match part.parse() {
                Ok(v) => v,
                Err(e) => {
                    use std::num::IntErrorKind::{NegOverflow, PosOverflow};
                    return Err(match e.kind() {
                        PosOverflow | NegOverflow => out_of_range(),
                        _ => format!("'{w}': expected face indices 'f a b c' (whole numbers)"),
                    });
                }
            };
            let count = i64::try_from(count).unwrap_or(i64::MAX);
            // -1 is the last line so far: count + idx + 1, which cannot overflow for
            // count >= 0 and idx < 0.
            let resolved = if idx < 0 {
                count.checked_add(idx).and_then(|v| v.checked_add(1))
            } else {
                Some(idx)
            };
            match resolved {
                Some(r) if (1..=count).contains(&r) => {}
                _ => return Err(out_of_range()),
            }
        }
    }
    if corners < 3 {
        return Err(format!(
            "a face with {corners} corner{}: expected at least three (faces of one or two \
             vertices are refused, not dropped)",
            if corners == 1 { "" } else { "s" }
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_shapes_are_valid_and_wound_outward() {
        let shapes = [
            MeshData::cube(),
            MeshData::plane(1.0),
            MeshData::sphere(24, 12),
            MeshData::terrain(16),
        ];
        for mesh in shapes {
            mesh.validate().unwrap();
            for (t, tri) in mesh.triangles().enumerate() {
                let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize();
                let i = mesh.indices[3 * t] as usize;
                let stored = Vec3::from(mesh.normals[i]);
                assert!(
                    n.dot(stored) > 0.9,
                    "{} triangle {t} winds inward (face normal against the stored one)",
                    mesh.name
                );
            }
        }
        let (lo, hi) = MeshData::cube().bounds();
        assert_eq!((lo, hi), (Vec3::splat(-1.0), Vec3::splat(1.0)));
    }

    #[test]
    fn obj_quad_is_triangulated_and_gets_normals() {
        let obj = "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3 4\n";
        let m = MeshData::parse_obj(Path::new("quad.obj"), obj).unwrap();
        assert_eq!(m.indices.len(), 6);
        assert!(m.normals.iter().all(|n| (n[1] - 1.0).abs() < 1e-6));
    }

    #[test]
    fn obj_errors_name_file_and_line() {
        let e = MeshData::parse_obj(Path::new("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("bad.obj: "), "{e}");
        assert!(e.contains("line 4"), "{e}");
    }

    #[test]
    fn obj_short_faces_and_wrapping_indices_are_refused() {
        let err = |obj: &str| {
            MeshData::parse_obj(Path::new("m.obj"), obj)
                .unwrap_err()
                .to_string()
        };
        let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        assert_eq!(
            err(&format!("{tri}f 1 2\n")),
            "m.obj: not a valid OBJ model at line 4: a face with 2 corners: expected at least \
             three (faces of one or two vertices are refused, not dropped)"
        );
        assert!(err(&format!("{tri}f 3\n")).contains("a face with 1 corner: "));
        // 2^32 + 1 (wraps to 1 in u32), 2^64 + 1 (does not fit i64), a huge negative one.
        for index in ["4294967297", "18446744073709551617", "-9223372036854775808"] {
            let e = err(&format!("{tri}f 1 2 {index}\n"));
            assert!(
                e.contains(&format!(
                    "line 4: face index out of range: '{index}', but there are 3 'v' lines"
                )),
                "{e}"
            );
        }
        let e = err(&format!("{tri}vt 0 0\nf 1/1 2/1 3/9\n"));
        assert!(
            e.contains("line 5: face index out of range: '9' in '3/9', but there are 1 'vt' lines"),
            "{e}"
        );
        // Relative indices that stay in range are fine.
        let m = MeshData::parse_obj(Path::new("m.obj"), &format!("{tri}f -3 -2 -1\n")).unwrap();
        assert_eq!(m.indices.len(), 3);
    }

    #[test]
    fn welded_positions_keep_every_triangle_with_each_corner_once() {
        let cube = MeshData::cube();
        let (positions, indices) = cube.welded_positions();
        assert_eq!((cube.positions.len(), positions.len()), (24, 8));
        assert_eq!(indices.len(), cube.indices.len());
        for (&w, &i) in indices.iter().zip(&cube.indices) {
            assert_eq!(positions[w as usize], cube.positions[i as usize]);
        }
        let plane = MeshData::plane(1.0);
        assert_eq!(plane.welded_positions().0.len(), plane.positions.len());
    }
}
