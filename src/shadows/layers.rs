//! A directional light's depth array with an orthographic box per layer: the storage, the
//! depth pass and the scene pass' uniforms that [`super::cascades`] (a box per slice of
//! the view) and [`super::groups`] (a box per group of casters) share. The scene shader's
//! side is `shaders/lib/shadow_layers.glsl` (one layer's test); each technique's own
//! snippet says which layers a fragment reads.
//!
//! One light per scene is layered: its positions in every layer are worked out per vertex
//! (`cascadePos` in scene.vert), and four layers of one light already fill GL 3.3's 64
//! vertex outputs with four lights ([`super::slots::vertex_outputs`]).

use glam::{DMat4, Mat4, Vec3};

use super::casters::{depth_state, draw_casters};
use super::fitted::FittedBox;
use super::{DepthPass, DepthViewKind, LightGlsl};
use crate::engine::{
    state, CascadeShadowMap, DepthPassGuard, Gl, Sampling, ShaderProgram, Texture,
};
use crate::error::Result;
use crate::scene::Scene;
use crate::settings::{ShadowSettings, Wrap};

/// A layered technique's shader snippet: its file (which includes shadow_layers.glsl), the
/// functions it defines with the layer test's (renamed per light), its `addLight...`
/// function and its sampler's name per light.
pub struct Snippet {
    pub file: &'static str,
    pub functions: &'static [&'static str],
    pub add: &'static str,
    pub samplers: [&'static str; crate::scene::MAX_LIGHTS],
}

impl Snippet {
    /// Light `i`'s part of the generated snippets: the file, its array sampler and its call.
    pub fn glsl(&self, i: usize, positional: bool, cone: bool, hardware: bool) -> LightGlsl {
        LightGlsl {
            snippet: self.file,
            functions: self.functions,
            sampler_type: if hardware {
                "sampler2DArrayShadow"
            } else {
                "sampler2DArray"
            },
            call: format!(
                "{}_{i}({i}, {}, {positional}, {cone}, f);",
                self.add, self.samplers[i]
            ),
        }
    }
}

/// The depth array and the box each layer was last drawn with.
pub struct Layers {
    array: CascadeShadowMap,
    boxes: Vec<FittedBox>,
}

impl Layers {
    /// `count` square layers of `settings`' map size and format; `what` names the technique
    /// in the error a non-square size gets.
    pub fn new(gl: &Gl, s: &ShadowSettings, count: u32, what: &str) -> Result<Layers> {
        Ok(Layers {
            array: CascadeShadowMap::new(gl, s.map_size.square_side(what)?, count, s.depth_format)?,
            boxes: Vec::new(),
        })
    }

    /// Whether the array still has `count` layers of `s`' size and format.
    pub fn fits(&self, s: &ShadowSettings, count: u32) -> bool {
        self.array.size() == s.map_size
            && self.array.format() == s.depth_format
            && self.array.layers() == count
    }

    /// The boxes of the last depth pass, by layer.
    pub fn boxes(&self) -> &[FittedBox] {
        &self.boxes
    }

    /// The depth pass: layer `k` cleared and drawn from `boxes[k]` with the casters
    /// `keep(k, item)` lets in (counted as drawn; the technique counts those offered).
    pub fn draw(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        boxes: Vec<FittedBox>,
        keep: impl Fn(usize, usize) -> bool,
    ) -> Result<()> {
        self.boxes = boxes;
        let program = pass.programs.flat(pass.gl)?;
        let _state = DepthPassGuard::begin(pass.gl, depth_state(pass.settings), &program);
        for (layer, b) in self.boxes.iter().enumerate() {
            self.array.bind_layer(layer as u32);
            state::clear_depth(pass.gl);
            let [l, r, bottom, t, n, f] = b.bounds;
            let projection = DMat4::orthographic_rh_gl(l, r, bottom, t, n, f).as_mat4();
            program.set_mat4("orthoProjectionMatrix", &projection);
            pass.casters.drawn += draw_casters(
                pass.meshes,
                scene,
                &program,
                "modelLightViewMatrix",
                b.view,
                |i| keep(layer, i),
            ) as u64;
        }
        Ok(())
    }

    pub fn texture(&self) -> &Texture {
        self.array.texture()
    }

    /// A layer covers exactly its box: outside it is lit (a border of depth 1), whatever the
    /// settings' wrap.
    pub fn sampling(settings: &ShadowSettings) -> Sampling {
        let hardware = settings.filter.hardware();
        Sampling {
            compare: hardware,
            linear: hardware,
            wrap: Wrap::ClampToBorder,
        }
    }

    /// Camera-relative world to each layer's clip space (`cascadeMatrix`) and each layer's
    /// normal offset in world units, `normal_offset` texels of its own
    /// (`cascadeNormalOffset`).
    pub fn set_uniforms(&self, p: &ShaderProgram, camera_position: Vec3, normal_offset: f32) {
        let matrices: Vec<Mat4> = self
            .boxes
            .iter()
            .map(|b| camera_relative_matrix(b, camera_position).as_mat4())
            .collect();
        let offsets: Vec<f32> = self
            .boxes
            .iter()
            .map(|b| normal_offset * b.texel as f32)
            .collect();
        p.set_mat4_array("cascadeMatrix", &matrices);
        p.set_f32_array("cascadeNormalOffset", &offsets);
    }

    pub fn bytes(&self) -> u64 {
        u64::from(self.array.layers()) * u64::from(self.array.size()).pow(2) * 4
    }

    pub fn depth_view(&self) -> DepthViewKind {
        DepthViewKind::Array {
            layers: self.array.layers(),
        }
    }
}

/// Camera-relative world position to a layer's light clip space (the scene shader's
/// `worldPos` is relative to the camera, which keeps its digits far from the origin).
pub fn camera_relative_matrix(b: &FittedBox, camera_position: Vec3) -> DMat4 {
    let [l, r, bottom, t, n, f] = b.bounds;
    DMat4::orthographic_rh_gl(l, r, bottom, t, n, f)
        * b.view
        * DMat4::from_translation(camera_position.as_dvec3())
}
