//! A directional light's depth array with an orthographic box per layer: the storage, the
//! depth pass and the scene pass' uniforms that [`super::cascades`] (a box per slice of
//! the view) and [`super::groups`] (a box per group of casters) share. The scene shader's
//! side is `shaders/lib/shadow_layers.glsl` (one layer's test); each technique's own
//! snippet says which layers a fragment reads.
//!
//! One light per scene is layered: its positions in every layer are worked out per vertex
//! (`cascadePos` in scene.vert), and four layers of one light already fill GL 3.3's 64
//! vertex outputs with four lights ([`super::program::slots::vertex_outputs`]).

use glam::{DMat4, Mat4, Vec3};

use super::camera::fitted::FittedBox;
use super::casters::{depth_state, draw_casters};
use super::kind::{self, Idles, LightIdle, SceneIdle, Storage};
use super::{
    DepthPass, DepthViewKind, LightGlsl, ShadowKind, ShadowTest, ShadowView, SlotTransform,
    Technique,
};
use crate::engine::{
    state, CascadeShadowMap, DepthPassGuard, Gl, Sampling, ShaderProgram, Texture,
};
use crate::error::{Error, Result};
use crate::scene::{DirectionalLight, Light, Scene};
use crate::settings::{LightProjection, ShadowSettings, ShadowTechnique, Wrap};

/// How a layered technique lays out its layers: what tells cascades (a layer per slice of
/// the view) from caster groups (a layer per group of casters). [`Layered`] runs it over
/// the shared storage as a [`Technique`].
pub trait Layout {
    /// The kind it is, and its name in errors ("cascades").
    const KIND: ShadowKind;
    const NAME: &'static str;
    /// The setting that counts its layers, as the scene file names it.
    const SETTING: &'static str;
    /// Its layers under `settings`.
    fn count(settings: &ShadowSettings) -> u32;
    /// Fits the layers for directional light `light` of `scene` (the depth pass' item
    /// boxes and settings in `pass`): their boxes, by layer.
    fn fit(&mut self, pass: &DepthPass, scene: &Scene, light: &DirectionalLight) -> Vec<FittedBox>;
    /// Whether item `item` (world box `bounds`) is drawn into layer `layer`.
    fn keeps(&self, layer: usize, item: usize, bounds: &(glam::DVec3, glam::DVec3)) -> bool;
    /// The casters offered to the depth pass (of which [`Layout::keeps`] draws some).
    fn offered(&self, scene: &Scene) -> u64;
    /// Scene-pass uniforms of its own, beside the layers' matrices and offsets.
    fn set_uniforms(&self, _program: &ShaderProgram) {}
}

/// A layered technique: the depth array, the box each layer was last drawn with and a
/// [`Layout`] of its layers.
pub struct Layered<L: Layout> {
    array: CascadeShadowMap,
    boxes: Vec<FittedBox>,
    layout: L,
}

impl<L: Layout + Default> Layered<L> {
    /// `L::count` square layers of the settings' map size and format (a non-square size
    /// is an error naming the technique).
    pub fn new(gl: &Gl, s: &ShadowSettings) -> Result<Layered<L>> {
        let side = s.map_size.square_side(L::NAME)?;
        Ok(Layered {
            array: CascadeShadowMap::new(gl, side, L::count(s), s.depth_format)?,
            boxes: Vec::new(),
            layout: L::default(),
        })
    }
}

impl<L: Layout> Technique for Layered<L> {
    fn kind(&self) -> ShadowKind {
        L::KIND
    }

    fn fits(&self, s: &ShadowSettings) -> bool {
        self.array.size() == s.map_size
            && self.array.format() == s.depth_format
            && self.array.layers() == L::count(s)
    }

    /// The layers fitted, then one depth pass per layer: cleared and drawn from its box
    /// with the casters the layout keeps in it.
    fn render_depth(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
    ) -> Result<ShadowView> {
        let Light::Directional(l) = &scene.lights[index] else {
            return Err(Error::Invalid(format!(
                "light {index} has {} but is not a directional light",
                L::NAME
            )));
        };
        self.boxes = self.layout.fit(pass, scene, l);
        pass.casters.total += self.layout.offered(scene);
        let program = pass.programs.flat(pass.gl)?;
        let _state = DepthPassGuard::begin(pass.gl, depth_state(pass.settings), &program);
        for (layer, b) in self.boxes.iter().enumerate() {
            self.array.bind_layer(layer as u32);
            state::clear_depth(pass.gl);
            let [l, r, bottom, t, n, f] = b.bounds;
            let projection = DMat4::orthographic_rh_gl(l, r, bottom, t, n, f).as_mat4();
            program.set_mat4("orthoProjectionMatrix", &projection);
            let keep = |i: usize| self.layout.keeps(layer, i, &pass.boxes[i]);
            pass.casters.drawn += draw_casters(pass.gpu(), scene, &program, b.view, keep) as u64;
        }
        // The first layer stands for the light's camera (reports, the depth view's near
        // and far, the reference's rays).
        match self.boxes.first() {
            Some(first) => Ok(first.shadow_view(l.direction)),
            None => Err(Error::Internal(format!(
                "light {index}: {} were fitted but there are none",
                L::NAME
            ))),
        }
    }

    fn texture(&self) -> &Texture {
        self.array.texture()
    }

    /// A layer covers exactly its box: outside it is lit (a border of depth 1), whatever
    /// the settings' wrap.
    fn sampling(&self, settings: &ShadowSettings) -> Sampling {
        let hardware = settings.filter.hardware();
        Sampling {
            compare: hardware,
            linear: hardware,
            wrap: Wrap::ClampToBorder,
            border_in_shader: false,
            interpolate_in_shader: false,
        }
    }

    /// None: the layers' positions come from their own matrices (`cascadeMatrix`).
    fn slot_transform(
        &self,
        _: &Light,
        _: &ShadowView,
        _: &ShadowSettings,
    ) -> Option<SlotTransform> {
        None
    }

    /// Camera-relative world to each layer's clip space (`cascadeMatrix`), each layer's
    /// normal offset in world units, the settings' texels of its own
    /// (`cascadeNormalOffset`), and the layout's own.
    fn set_scene_uniforms(&self, p: &ShaderProgram, scene: &Scene, s: &ShadowSettings) {
        let boxes = &self.boxes;
        let matrices: Vec<Mat4> = boxes
            .iter()
            .map(|b| camera_relative_matrix(b, scene.camera.position).as_mat4())
            .collect();
        let offsets: Vec<f32> = boxes
            .iter()
            .map(|b| s.normal_offset * b.texel as f32)
            .collect();
        p.set_mat4_array("cascadeMatrix", &matrices);
        p.set_f32_array("cascadeNormalOffset", &offsets);
        p.set_f32_array("cascadeBiasScale", &bias_scales(boxes));
        self.layout.set_uniforms(p);
    }

    fn bytes(&self) -> u64 {
        u64::from(self.array.layers()) * u64::from(self.array.size()).pow(2) * 4
    }

    fn depth_view(&self) -> DepthViewKind {
        DepthViewKind::Array {
            layers: self.array.layers(),
        }
    }
}

/// What each layer's depth bias is multiplied by (`cascadeBiasScale`): the deepest layer's
/// depth range over its own, so a bias (a fraction of the deepest layer's range, where its
/// world length is needed against acne on the coarsest texels) spans the same world
/// distance in every layer, as the normal offset does per layer. On `large` with four
/// cascades (85 to 452 units deep) the first layer's range as the measure left the far
/// layers acne (docs/techniques/cascades.md).
pub fn bias_scales(boxes: &[FittedBox]) -> Vec<f32> {
    let depth = |b: &FittedBox| b.bounds[5] - b.bounds[4];
    let deepest = boxes.iter().map(depth).fold(0.0, f64::max);
    boxes
        .iter()
        .map(|b| (deepest / depth(b).max(f64::MIN_POSITIVE)) as f32)
        .collect()
}

/// A layered technique's shader snippet: its file (which includes shadow_layers.glsl), its
/// test function, whether that takes the fragment (to note the cascade it chose), and its
/// sampler's name per light.
pub struct Snippet {
    pub files: &'static [&'static str],
    pub function: &'static str,
    pub takes_fragment: bool,
    pub samplers: [&'static str; crate::scene::MAX_LIGHTS],
}

/// Camera-relative world position to a layer's light clip space (the scene shader's
/// `worldPos` is relative to the camera, which keeps its digits far from the origin).
pub fn camera_relative_matrix(b: &FittedBox, camera_position: Vec3) -> DMat4 {
    let [l, r, bottom, t, n, f] = b.bounds;
    DMat4::orthographic_rh_gl(l, r, bottom, t, n, f)
        * b.view
        * DMat4::from_translation(camera_position.as_dvec3())
}
/// Light `i`'s part of the generated snippets: the file, its array sampler, its call,
/// and its filter as the defines of shadow_layers.glsl (one light is layered; a depth
/// map's test only).
pub fn glsl(snippet: &Snippet, i: usize, test: &ShadowTest) -> Option<LightGlsl> {
    let depth = test.depth()?;
    let sampler_type = match depth.hardware {
        true => "sampler2DArrayShadow",
        false => "sampler2DArray",
    };
    let fragment = if snippet.takes_fragment { ", f" } else { "" };
    Some(LightGlsl {
        snippets: snippet.files.to_vec(),
        sampler_type,
        test: format!(
            "{}({}, {}{fragment})",
            snippet.function,
            snippet.samplers[i],
            test.bias_glsl(i)
        ),
        // A kernel with no layered form is refused before (`FilterFacts::on_layers`);
        // without its define shadow_layers.glsl stops at its #error.
        defines: [
            ("LAYER_SAMPLER", sampler_type.to_string()),
            ("LAYER_TEXEL", test.texel_glsl()),
            ("LAYER_RADIUS", depth.pcf_radius.to_string()),
        ]
        .into_iter()
        .chain(
            depth
                .kernel
                .glsl()
                .layer_define
                .map(|d| (d, "1".to_string())),
        )
        .collect(),
    })
}

/// What a layout's layers of `s.map_size` hold, naming the setting that counts them.
pub fn storage<L: Layout>(s: &ShadowSettings) -> Option<Storage> {
    let count = L::count(s);
    let sides = kind::sides(s.map_size);
    Some(Storage {
        what: format!("shadow.{} = {count} layers of {sides}", L::SETTING),
        bytes: u64::from(count) * s.map_size.texels() * kind::DEPTH_TEXEL_BYTES,
    })
}

/// A layout's count, idle for light `v` when it is set but the light is not of its kind.
pub fn idle_for_light<L: Layout>(v: &LightIdle, idle: &mut Idles) {
    if L::count(v.settings) > 1 && v.kind != L::KIND {
        idle.push(L::SETTING, not_for_light(v, L::NAME));
    }
}

/// A layout's count, idle in scene `v` when it is set but no light is of its kind.
pub fn idle_in_scene<L: Layout>(v: &SceneIdle, idle: &mut Idles) {
    if L::count(v.settings) > 1 && !v.has(L::KIND) {
        idle.push(L::SETTING, not_in_scene(v, L::NAME));
    }
}

/// Why a light (`v`) does not get the layers `what` (cascades, caster groups) it is set to.
fn not_for_light(v: &LightIdle, what: &str) -> String {
    if !matches!(v.light, Light::Directional(_)) {
        format!("only a directional light has {what}")
    } else if v.settings.light_projection == LightProjection::Perspective {
        format!("{what} need an orthographic light projection")
    } else {
        format!("only the first casting directional light gets {what}; this one keeps one map")
    }
}

/// Why no light of a scene (`v`) draws the layers `what` the scene's settings ask for.
fn not_in_scene(v: &SceneIdle, what: &str) -> String {
    let settings = v.settings;
    if !settings.shadows {
        "shadows are off (--shadows off)".to_string()
    } else if settings.technique == ShadowTechnique::Volumes {
        "the lights have shadow volumes (--technique volumes), which have no map".to_string()
    } else if v.suns().next().is_none() {
        format!(
            "no directional light casts shadows in this scene, and only one gets {what}; each \
             light keeps one map"
        )
    } else if settings.light_projection == LightProjection::Perspective {
        format!(
            "{what} need an orthographic light projection (--light-projection perspective is \
             set); the light keeps one map"
        )
    } else if what != "cascades" && settings.cascades > 1 {
        "cascades are set (--cascades), and a light has cascades or caster groups, not both"
            .to_string()
    } else {
        format!("the directional light's own shadow table gives it no {what}")
    }
}
