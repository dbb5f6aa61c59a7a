//! Stencil shadow volumes, the slides' closing technique: exact hard shadows from the stencil
//! buffer, with no map and no bias.
//!
//! 1. A shadow volume is the region an object hides from the light: its light-facing
//!    triangles (the near cap), their silhouette edges pulled away from the light to
//!    infinity (the sides) and, for a positional light, those triangles projected to
//!    infinity (the far cap). `shaders/volume.geom` builds them per triangle from
//!    `GL_TRIANGLES_ADJACENCY` input, made here at load ([`Adjacency`]).
//! 2. A pixel is in shadow when its surface lies inside some volume. Z-fail (Carmack's
//!    reverse) counts the volume faces *behind* the pixel, back faces up and front faces
//!    down, in one pass with two-sided stencil: a pixel inside has one more back face behind
//!    it than front faces, outside as many of each. Counting behind rather than in front
//!    keeps it right when the camera itself is inside a volume, and `GL_DEPTH_CLAMP` keeps
//!    the caps at infinity (clamped to the far plane) instead of clipping them away.
//! 3. Each light's light is then added where its count is 0 (`renderer::volume_pass`):
//!    an ambient pass first, then per light: clear the stencil, count, add.
//!
//! Open and non-manifold edges: an edge is shared only when exactly two triangles meet on
//! it, running along it in opposite directions (a closed, consistently wound surface).
//! Every other edge (open, met by three or more triangles, or by two wound the same way)
//! gets, as its neighbour, the triangle's own third vertex: the geometry shader then sees
//! the triangle turned around across that edge, which always faces the other way, so the
//! edge is always a silhouette and every triangle's volume is closed whatever its
//! neighbours. The sides of shared edges cancel, so the count at a point is the number of
//! casting triangles between it and the light: never negative, nonzero exactly where one
//! hides it. A closed mesh casts from its light-facing triangles only (its back is behind
//! its front: the same shadow, half the fill). A mesh that is not closed casts from both
//! sides of every triangle, a triangle lit from behind taken turned around, as the exact
//! reference's ray cast sees it: LearnOpenGL's floor (a single-sided plane) shadows from
//! below as from above, and a box without a lid casts its whole shape.

use std::collections::HashMap;

use glam::{DMat4, Vec4};

use super::kind::{self, Family, IdleRules, KindFacts};
use super::{Rays, ShadowKind};
use crate::engine::{AdjacencyMesh, Gl, ShaderProgram};
use crate::error::Result;
use crate::geometry::MeshData;
use crate::scene::{Light, Scene};
use crate::settings::ShadowSettings;
use crate::shaders;

/// A mesh's triangles with adjacency, and what welding found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Adjacency {
    /// Six indices per triangle: `a, across a-b, b, across b-c, c, across c-a`.
    pub indices: Vec<u32>,
    /// Edges with one triangle.
    pub open_edges: usize,
    /// Edges with three or more triangles, or two wound the same way.
    pub non_manifold_edges: usize,
    /// Triangles left out because welding made two of their corners one (no area).
    pub degenerate: usize,
}

impl Adjacency {
    /// Welds `mesh`'s positions (points within [`WELD`] of the mesh's size are one vertex,
    /// whatever their normals and texture coordinates: a UV sphere's seam and poles, whose
    /// sines and cosines of 0 and 2 pi differ in the last bits) and finds each triangle's
    /// neighbours. Every index it gives is a welded vertex's, so each geometry shader
    /// invocation that meets a vertex sees the same position.
    pub fn of(mesh: &MeshData) -> Adjacency {
        let weld = weld(&mesh.positions);
        let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(mesh.indices.len() / 3);
        let mut degenerate = 0;
        for t in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| weld[i as usize]);
            if a == b || b == c || c == a {
                degenerate += 1;
            } else {
                triangles.push([a, b, c]);
            }
        }
        // Every undirected edge: the triangles on it, with the edge's slot and direction.
        let mut edges: HashMap<(u32, u32), Vec<EdgeUse>> = HashMap::new();
        for (t, tri) in triangles.iter().enumerate() {
            for e in 0..3 {
                let (a, b) = (tri[e], tri[(e + 1) % 3]);
                edges
                    .entry((a.min(b), a.max(b)))
                    .or_default()
                    .push((t, e, a < b));
            }
        }
        // By default every edge's neighbour is the triangle's own third vertex (see the
        // module's notes); shared edges get the neighbour's.
        let mut indices = Vec::with_capacity(triangles.len() * 6);
        for tri in &triangles {
            for e in 0..3 {
                indices.push(tri[e]);
                indices.push(tri[(e + 2) % 3]);
            }
        }
        let (mut open_edges, mut non_manifold_edges) = (0, 0);
        for on in edges.values() {
            match on.as_slice() {
                [_] => open_edges += 1,
                [(t, e, forward), (u, f, backward)] if forward != backward => {
                    indices[t * 6 + e * 2 + 1] = triangles[*u][(f + 2) % 3];
                    indices[u * 6 + f * 2 + 1] = triangles[*t][(e + 2) % 3];
                }
                _ => non_manifold_edges += 1,
            }
        }
        Adjacency {
            indices,
            open_edges,
            non_manifold_edges,
            degenerate,
        }
    }

    /// Whether every edge is shared by two triangles wound oppositely.
    pub fn is_closed(&self) -> bool {
        self.open_edges == 0 && self.non_manifold_edges == 0
    }
}

/// A triangle on an edge: the triangle, the edge's slot in it (0: a-b, 1: b-c, 2: c-a) and
/// whether it runs from the lower vertex number to the higher.
type EdgeUse = (usize, usize, bool);

/// How close two positions must be to weld, as a fraction of the mesh's largest extent.
pub const WELD: f32 = 1e-6;

/// For each position, the first position within [`WELD`] of it (itself if none): a grid of
/// cells one tolerance wide, each point checked against the 27 cells around it.
fn weld(positions: &[[f32; 3]]) -> Vec<u32> {
    let (lo, hi) = positions
        .iter()
        .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
            )
        });
    let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f32, f32::max);
    let tolerance = (extent * WELD).max(f32::MIN_POSITIVE);
    let cell = |p: &[f32; 3]| p.map(|c| (f64::from(c) / f64::from(tolerance)).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let mut out = Vec::with_capacity(positions.len());
    for (i, p) in positions.iter().enumerate() {
        let c = cell(p);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(there) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else {
                        continue;
                    };
                    if let Some(&j) = there.iter().find(|&&j| {
                        let q = positions[j as usize];
                        (0..3).all(|k| (q[k] - p[k]).abs() <= tolerance)
                    }) {
                        found = Some(j);
                        break 'search;
                    }
                }
            }
        }
        out.push(found.unwrap_or_else(|| {
            grid.entry(c).or_default().push(i as u32);
            i as u32
        }));
    }
    out
}

/// The scene shader's call for light `i` with volumes: no test of its own, lit in its
/// own pass (the stencil has already hidden its shadows) and nowhere else.
pub fn call(i: usize, positional: bool, cone: bool) -> String {
    format!("addLight({i}, toLightOf({i}, {positional}), {cone}, float(passLight == {i}), f);")
}

/// The rays light `index`'s volumes follow: the ones its map would stand for
/// ([`super::light_camera`]), so volumes and maps shadow the same light and the exact
/// reference traces the same rays for both (a directional light shaded from a point, as
/// LearnOpenGL's, casts parallel rays from its direction).
pub fn rays(scene: &Scene, index: usize, settings: &ShadowSettings) -> Rays {
    match (&scene.lights[index], settings.light_projection) {
        // Parallel whatever its box (fitting one per frame would only give this back).
        (Light::Directional(l), crate::settings::LightProjection::Ortho) => Rays::Parallel {
            to_light: l.direction.normalize(),
        },
        (Light::Directional(_), crate::settings::LightProjection::Perspective)
        | (Light::Spot(_) | Light::Point(_), _) => super::light_camera(scene, index, settings).rays,
    }
}

/// The meshes with adjacency (and whether each casts from both sides: not closed) and the
/// program that extrudes them, made on first use.
pub struct Volumes {
    meshes: Vec<(AdjacencyMesh, bool)>,
    program: ShaderProgram,
}

/// How far the near cap moves back, in NDC depth (times w): about 32 steps of a 24-bit
/// depth buffer, so a caster's lit pixels always count their own cap as behind them.
pub const CAP_NUDGE: f32 = 1.0 / 262_144.0;

impl Volumes {
    pub fn new(gl: &Gl, scene: &Scene) -> Result<Volumes> {
        let meshes = scene
            .meshes
            .iter()
            .map(|m| {
                let a = Adjacency::of(m);
                let mesh = AdjacencyMesh::new(gl, &m.name, &m.positions, &a.indices)?;
                Ok((mesh, !a.is_closed()))
            })
            .collect::<Result<Vec<_>>>()?;
        let program = ShaderProgram::from_stages(
            gl,
            &[
                (glow::VERTEX_SHADER, &shaders::volume_vert()),
                (glow::GEOMETRY_SHADER, &shaders::volume_geom()),
                (glow::FRAGMENT_SHADER, &shaders::volume_frag()),
            ],
            &[],
        )?;
        // A constant of the program: set once.
        program.bind();
        program.set_f32("capNudge", CAP_NUDGE);
        program.unbind();
        Ok(Volumes { meshes, program })
    }

    /// Whether these were made for `scene`'s meshes (same count).
    pub fn fits(&self, scene: &Scene) -> bool {
        self.meshes.len() == scene.meshes.len()
    }

    /// Draws light `index`'s volumes for every caster with the bound target and state
    /// (the stencil pass, or the debug view in `colour`); `settings` are the light's own.
    pub fn draw(
        &self,
        scene: &Scene,
        settings: &ShadowSettings,
        index: usize,
        (width, height): (u32, u32),
        colour: Vec4,
    ) {
        if index >= scene.lights.len() {
            return;
        }
        let source = rays(scene, index, settings);
        let p = &self.program;
        let view64 = scene.camera.view_matrix64();
        p.bind();
        p.set_mat4(
            "projectionMatrix",
            &scene.camera.projection_matrix(width, height),
        );
        let light = match source {
            Rays::Parallel { to_light } => view64.as_mat4().transform_vector3(to_light).extend(0.0),
            Rays::FromPoint { position } => view64
                .transform_point3(position.as_dvec3())
                .as_vec3()
                .extend(1.0),
        };
        p.set_vec4("lightVector", light);
        p.set_vec4("volumeColour", colour);
        for (mesh_id, (mesh, two_sided)) in self.meshes.iter().enumerate() {
            p.set_i32("twoSided", i32::from(*two_sided));
            let casters = scene
                .items
                .iter()
                .filter(|i| i.mesh == mesh_id && i.casts_shadows);
            mesh.render_list(casters, |item| {
                let model_view: DMat4 = view64 * item.model_matrix64();
                p.set_mat4("modelViewMatrix", &model_view.as_mat4());
            });
        }
        p.unbind();
    }
}

/// The shadow volumes' row of the kind table: no map, no technique behind
/// [`super::Technique`] (the renderer draws them per light: `renderer::volume_pass`).
pub const KIND: KindFacts = KindFacts {
    technique: None,
    words: |_| "Shadow: stencil shadow volumes (z-fail), no map".to_string(),
    storage: |_| None,
    follows_camera: |_, _| false,
    layers: None,
    per_vertex: |_| false,
    family: |_| Family::Volumes,
    idle: IdleRules {
        no_map: Some(|_| "the light has shadow volumes, which have no map"),
        depth_lookup: |_| Some(kind::LAYERS_READ_NEAREST),
        light: |v, idle| {
            if v.kind != ShadowKind::Volume {
                idle.push("show_volumes", "the light has no shadow volumes");
            }
        },
        scene: |v, idle| {
            let volumes = v.has(ShadowKind::Volume);
            let maps = (v.lights.iter()).any(|l| l.kind.has_map());
            if volumes && !maps {
                for name in kind::MAP_SETTINGS {
                    idle.push(
                        name,
                        "every casting light has shadow volumes (technique = volumes): there is \
                         no map to size, test or draw",
                    );
                }
            }
            if !volumes {
                idle.push(
                    "show_volumes",
                    "no light has shadow volumes (--technique volumes): there are none to show",
                );
            }
        },
    },
};

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(positions: Vec<[f32; 3]>, indices: Vec<u32>) -> MeshData {
        let n = positions.len();
        MeshData {
            name: "test".into(),
            positions,
            tex_coords: vec![[0.0; 2]; n],
            normals: vec![[0.0, 1.0, 0.0]; n],
            indices,
        }
    }

    #[test]
    fn the_built_in_cube_and_sphere_weld_closed() {
        for m in [MeshData::cube(), MeshData::sphere(16, 8)] {
            let a = Adjacency::of(&m);
            assert!(a.is_closed(), "{}: {a:?}", m.name);
            assert_eq!(a.indices.len(), (m.indices.len() / 3 - a.degenerate) * 6);
        }
    }

    #[test]
    fn a_plane_has_four_open_edges_and_a_shared_diagonal() {
        // Two triangles of a quad; the diagonal 0-2 is shared.
        let m = mesh(
            vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [1.0, 0.0, -1.0],
                [0.0, 0.0, -1.0],
            ],
            vec![0, 1, 2, 0, 2, 3],
        );
        let a = Adjacency::of(&m);
        assert_eq!((a.open_edges, a.non_manifold_edges), (4, 0));
        // Triangle 0 = 0 1 2: across 0-1 (open) its own 2, across 1-2 (open) its own 0,
        // across 2-0 the other triangle's 3.
        assert_eq!(a.indices[..6], [0, 2, 1, 0, 2, 3]);
        assert_eq!(a.indices[6..], [0, 1, 2, 0, 3, 2]);
    }

    #[test]
    fn an_edge_of_three_triangles_is_non_manifold_and_one_wound_wrong_too() {
        let fan = mesh(
            vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, -1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            vec![0, 1, 2, 1, 0, 3, 0, 1, 4],
        );
        assert_eq!(Adjacency::of(&fan).non_manifold_edges, 1);
        let same_way = mesh(
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]],
            vec![0, 1, 2, 0, 1, 3],
        );
        let a = Adjacency::of(&same_way);
        assert_eq!((a.open_edges, a.non_manifold_edges), (4, 1));
    }

    #[test]
    fn a_box_without_its_top_has_four_open_edges() {
        let mut m = MeshData::cube();
        let closed = Adjacency::of(&m);
        // Drop the two triangles whose corners all have the top's y.
        let top = m.positions.iter().map(|p| p[1]).fold(f32::MIN, f32::max);
        let keep: Vec<u32> = m
            .indices
            .chunks_exact(3)
            .filter(|t| !t.iter().all(|&i| m.positions[i as usize][1] == top))
            .flatten()
            .copied()
            .collect();
        assert_eq!(keep.len(), m.indices.len() - 6);
        m.indices = keep;
        let open = Adjacency::of(&m);
        assert!(closed.is_closed());
        assert_eq!((open.open_edges, open.non_manifold_edges), (4, 0));
    }
}
