//! A point light's omnidirectional shadow: a depth cube map of distances (LearnOpenGL's
//! "Point Shadows"). The depth pass draws six 90-degree faces from the light, storing each
//! fragment's distance over the far plane; the test (`shaders/lib/shadow_cube.glsl`)
//! compares distances in world units.

use glam::{DMat4, DVec3, Mat4, Vec3, Vec4};

use super::camera::culling::{beyond_a_plane, may_land};
use super::camera::point_camera;
use super::casters::{casters, depth_state, draw_casters, draw_casters_with};
use super::kind::{self, Family, IdleRules, KindFacts, Storage, TechniqueFacts};
use super::{
    DepthPass, DepthViewKind, LightGlsl, ShadowKind, ShadowTest, ShadowView, SlotTransform,
    Technique,
};
use crate::engine::{state, CubeShadowMap, DepthPassGuard, Gl, Sampling, Texture};
use crate::error::Result;
use crate::scene::{Light, PointLight, Scene};
use crate::settings::{PointPass, ShadowSettings};

/// Its sampler in the scene shader, per light.
pub const SAMPLERS: [&str; crate::scene::MAX_LIGHTS] =
    ["shadowCube0", "shadowCube1", "shadowCube2", "shadowCube3"];

/// The six views of the cube map's faces (+X, -X, +Y, -Y, +Z, -Z), relative to the light,
/// with GL's cube-map orientation.
pub fn face_views() -> [Mat4; 6] {
    let faces = [
        (Vec3::X, -Vec3::Y),
        (-Vec3::X, -Vec3::Y),
        (Vec3::Y, Vec3::Z),
        (-Vec3::Y, -Vec3::Z),
        (Vec3::Z, -Vec3::Y),
        (-Vec3::Z, -Vec3::Y),
    ];
    faces.map(|(d, up)| Mat4::look_at_rh(Vec3::ZERO, d, up))
}

/// The faces (bit f for face f of `faces`, each a face's projection x view relative to the
/// light) that a box `lo..hi`, relative to the light, may enter.
pub fn face_mask(faces: &[Mat4; 6], lo: DVec3, hi: DVec3) -> u32 {
    (0..6)
        .filter(|&f| !beyond_a_plane(faces[f].as_dmat4(), lo, hi))
        .fold(0, |mask, f| mask | 1 << f)
}

/// World to the light's position: the faces and the scene pass' lookups are relative to it.
fn from_light(p: &PointLight) -> DMat4 {
    DMat4::from_translation(-p.position.as_dvec3())
}

pub struct Cube {
    cube: CubeShadowMap,
}

impl Cube {
    pub fn new(gl: &Gl, settings: &ShadowSettings) -> Result<Cube> {
        Ok(Cube {
            cube: CubeShadowMap::new(
                gl,
                settings.map_size.square_side("a point light's cube map")?,
                settings.depth_format,
            )?,
        })
    }
}

impl Technique for Cube {
    fn kind(&self) -> ShadowKind {
        ShadowKind::Cube
    }

    fn fits(&self, s: &ShadowSettings) -> bool {
        self.cube.size() == s.map_size && self.cube.format() == s.depth_format
    }

    fn render_depth(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
    ) -> Result<ShadowView> {
        let Light::Point(light) = &scene.lights[index] else {
            return Err(crate::Error::Invalid(format!(
                "light {index} has a cube map but is not a point light"
            )));
        };
        // OpenGL ES (WebGL2) has no geometry shader: there the six faces are drawn in turn.
        let point_pass = match crate::engine::Dialect::of(pass.gl) {
            crate::engine::Dialect::Desktop => pass.settings.point_pass,
            crate::engine::Dialect::Es => PointPass::SixPasses,
        };
        let gpu = pass.gpu();
        let program = pass.programs.point(pass.gl, point_pass)?;
        let projection = Mat4::perspective_rh_gl(90f32.to_radians(), 1.0, light.near, light.far);
        let to_light = from_light(light);
        let _state = DepthPassGuard::begin(pass.gl, depth_state(pass.settings), program);
        program.set_f32("farPlane", light.far);
        // Per caster, the faces it can land in (bit f for face f): none beyond the light's
        // reach (`far`), and of the rest only the faces whose frustum its box may enter.
        let boxes = pass.boxes;
        let camera = point_camera(light, pass.settings);
        let faces = face_views().map(|v| projection * v);
        let origin = light.position.as_dvec3();
        let masks: Vec<u32> = boxes
            .iter()
            .map(
                |&(lo, hi)| match may_land(&scene.lights[index], &camera, lo, hi) {
                    false => 0,
                    true => face_mask(&faces, lo - origin, hi - origin),
                },
            )
            .collect();
        match point_pass {
            PointPass::Layered => {
                // One pass: the geometry shader draws each triangle into its caster's faces.
                self.cube.bind_layered()?;
                state::clear_depth(pass.gl);
                program.set_mat4_array("faceProjections", &faces);
                let keep = |k: usize| masks[k] != 0;
                let faces = |k: usize| Vec4::new(masks[k] as f32, 0.0, 0.0, 0.0);
                draw_casters_with(gpu, scene, program, to_light, keep, Some(&faces), false);
            }
            PointPass::SixPasses => {
                for (face, clip) in faces.iter().enumerate() {
                    self.cube.bind_face(face as u32);
                    state::clear_depth(pass.gl);
                    program.set_mat4("faceProjection", clip);
                    let keep = |k: usize| masks[k] & (1 << face) != 0;
                    draw_casters(gpu, scene, program, to_light, keep);
                }
            }
        }
        // Counted per face: a caster in two faces is two of the six offered.
        let drawn: u32 = scene
            .items
            .iter()
            .zip(&masks)
            .filter(|(item, _)| item.casts_shadows)
            .map(|(_, m)| m.count_ones())
            .sum();
        pass.casters.drawn += drawn as u64;
        pass.casters.total += 6 * casters(scene);
        Ok(camera)
    }

    fn texture(&self) -> &Texture {
        self.cube.texture()
    }

    /// Plain NEAREST reads of distances: there is no shadow cube sampler path, so the
    /// hardware filters fall back to one lookup.
    fn sampling(&self, _settings: &ShadowSettings) -> Sampling {
        Sampling::PLAIN
    }

    fn slot_transform(
        &self,
        light: &Light,
        view: &ShadowView,
        settings: &ShadowSettings,
    ) -> Option<SlotTransform> {
        let Light::Point(p) = light else {
            return None;
        };
        Some(SlotTransform {
            from: from_light(p),
            projection: Mat4::IDENTITY,
            normal_offset: settings.normal_offset * view.texel_world,
        })
    }

    fn bytes(&self) -> u64 {
        6 * u64::from(self.cube.size()).pow(2) * 4
    }

    fn depth_view(&self) -> DepthViewKind {
        DepthViewKind::Cube
    }
}
/// Light `i`'s part of the generated snippets, its position relative to the fragment in
/// map slot `p`: `calcShadowCube` (shaders/lib/shadow_cube.glsl), one lookup, or with a
/// PCF filter `calcShadowCubeSoft`, LearnOpenGL's 20 (a depth map's test only).
pub fn glsl(i: usize, p: usize, test: &ShadowTest) -> Option<LightGlsl> {
    let function = match test.depth()?.pcf_radius {
        0 => "calcShadowCube",
        _ => "calcShadowCubeSoft",
    };
    Some(LightGlsl {
        snippets: vec!["lib/shadow_cube.glsl"],
        sampler_type: "samplerCube",
        test: format!(
            "{function}({}, mlightviewVertexPos[{p}].xyz, lightFar[{i}], {}, {})",
            SAMPLERS[i],
            test.bias_glsl(i),
            test.beyond_far_lit
        ),
        defines: Vec::new(),
    })
}

/// The cube map's row of the kind table.
pub const KIND: KindFacts = KindFacts {
    technique: Some(TechniqueFacts {
        create: |gl, s| Ok(Box::new(Cube::new(gl, s)?)),
        glsl,
        samplers: &SAMPLERS,
        map_slot: true,
    }),
    words: |s| {
        let pass = match s.point_pass {
            PointPass::Layered => "drawn in one pass",
            PointPass::SixPasses => "drawn in six passes",
        };
        let (size, depth) = (kind::sides(s.map_size), kind::depth_words(s.depth_format));
        format!("Shadow: a cube map, 6 faces of {size}, {depth}, {pass}")
    },
    storage: |s| {
        Some(Storage {
            what: format!("a cube of six {} faces", kind::sides(s.map_size)),
            bytes: 6 * s.map_size.texels() * kind::DEPTH_TEXEL_BYTES,
        })
    },
    follows_camera: |_, _| false,
    layers: None,
    // LearnOpenGL's 20 taps read per pixel.
    per_vertex: |_| false,
    family: |s| match s.point_pass {
        PointPass::Layered => Family::PointLayered,
        PointPass::SixPasses => Family::PointSixPasses,
    },
    idle: IdleRules {
        no_map: None,
        depth_lookup: |_| {
            Some("it is for a 2D depth map; a point light's cube map is read NEAREST")
        },
        light: |v, idle| {
            if v.kind != ShadowKind::Cube {
                idle.push(
                    "point_pass",
                    "only a point light's cube map has faces to draw",
                );
            }
        },
        scene: |v, idle| {
            if !v.has(ShadowKind::Cube) {
                idle.push(
                    "point_pass",
                    "no point light casts shadows in this scene; it says how a cube map's faces \
                     are drawn",
                );
            }
        },
    },
};
