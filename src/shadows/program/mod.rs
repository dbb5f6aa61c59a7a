//! What the scene program is compiled for, as a typed key, and the one place that key turns
//! into `#define`s. Branches on these would run for every pixel on a software rasteriser,
//! so they are compile-time constants; the key is a small `Copy` value compared every frame
//! without allocating, and its text is made only when a program is compiled.

pub mod slots;
pub mod vertex;

use super::kind::LayerLayout;
use super::plan::ShadowPlan;
use super::volumetric::VolumetricKey;
use super::{ShadowKind, ShadowTest};
use crate::engine::{gl_limits, Gl, Outputs, ShaderProgram, ShaderSource};
use crate::error::{Error, Result};
use crate::scene::{Scene, Shading, ShadingModel, MAX_LIGHTS};
use crate::settings::glsl_float;
use crate::shaders;
use slots::{LightSlot, MaskMode};

/// Everything a scene program is compiled for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ProgramKey {
    /// The scene's lights in order (the first `light_count`).
    lights: [Option<LightSlot>; MAX_LIGHTS],
    light_count: usize,
    /// The layers of the light with cascades or caster groups, if one has them.
    cascades: Option<LayerLayout>,
    blinn: bool,
    specular_power_bits: u32,
    visibility_light: usize,
    /// The outputs the target has: the others are not computed.
    outputs: Outputs,
    /// A light has shadow volumes: the frame is drawn in passes, one light each
    /// (`MULTIPASS`, the uniform `passLight`).
    multipass: bool,
    /// Whether it writes or reads the cached shadow mask.
    mask: MaskMode,
}

impl ProgramKey {
    /// The program for `scene`'s lights as `plan` draws them.
    pub fn of(
        scene: &Scene,
        plan: &ShadowPlan,
        visibility_light: usize,
        outputs: Outputs,
    ) -> Result<ProgramKey> {
        let n = scene.lights.len();
        if n == 0 || n > MAX_LIGHTS || plan.lights.len() != n {
            return Err(Error::Invalid(format!(
                "{}: {n} lights: expected 1 to {MAX_LIGHTS}",
                scene.source.display()
            )));
        }
        let mut lights = [None; MAX_LIGHTS];
        let mut cascades = None;
        for ((slot, light), planned) in lights.iter_mut().zip(&scene.lights).zip(&plan.lights) {
            let (shadow, own) = (planned.kind, &planned.settings);
            let (positional, cone) = match light.shading() {
                Shading::Direction(_) => (false, false),
                Shading::Position { cone, .. } => (true, cone.is_some()),
            };
            if let Some(layout) = shadow.facts().layers {
                cascades = Some(layout(own));
            }
            *slot = Some(LightSlot {
                shadow,
                positional,
                cone,
                // Volumes have no test in the shader: the stencil decides.
                test: shadow.has_map().then(|| ShadowTest {
                    volumetric: planned.volumetric.and_then(|_| VolumetricKey::of(own)),
                    ..ShadowTest::for_light(light, own)
                }),
            });
        }
        Ok(ProgramKey {
            lights,
            light_count: n,
            cascades,
            blinn: scene.shading == ShadingModel::BlinnPhong,
            specular_power_bits: scene.specular_power.to_bits(),
            visibility_light,
            outputs,
            multipass: plan.has(ShadowKind::Volume),
            mask: MaskMode::Off,
        })
    }

    /// Whether it writes or reads the cached shadow mask, or takes its own tests.
    pub fn mask(&self) -> MaskMode {
        self.mask
    }

    /// The same program writing or reading the cached shadow mask.
    pub fn with_mask(self, mask: MaskMode) -> ProgramKey {
        ProgramKey { mask, ..self }
    }

    /// Whether the shadow mask can stand for these lights' tests: not with shadow volumes
    /// (their test is the stencil, per pass) nor with cascades tinted (the tint needs the
    /// cascade the test chose).
    pub fn maskable(&self) -> bool {
        !self.multipass && !self.cascades.is_some_and(|c| c.show)
    }

    /// Whether a light's test runs per vertex in this key's translucent program
    /// ([`slots::per_vertex`]).
    pub fn tests_per_vertex(&self) -> bool {
        self.lights.iter().flatten().any(slots::per_vertex)
    }

    /// Whether the translucent items take a program of their own ([`MaskMode::Vertex`]):
    /// a light tests them per vertex, or the opaque receivers read a resolved map
    /// ([`crate::shadows::volumetric::resolved`]) where they need the curve.
    pub fn translucent_apart(&self) -> bool {
        let resolved = |s: &LightSlot| {
            s.test
                .and_then(|t| t.volumetric)
                .is_some_and(|v| v.resolved)
        };
        self.tests_per_vertex() || self.lights.iter().flatten().any(resolved)
    }

    /// The lights' slots, in the scene's order.
    pub fn slots(&self) -> Vec<LightSlot> {
        self.lights[..self.light_count]
            .iter()
            .flatten()
            .copied()
            .collect()
    }

    /// The `#define`s for shaders/scene.{vert,frag}; each exists only when a light uses it.
    /// (Each light's test takes its settings as arguments, in the generated snippet.)
    pub fn defines(&self) -> Vec<(String, String)> {
        let mut d: Vec<(String, String)> = Vec::new();
        let mut set = |k: &str, v: String| d.push((k.to_string(), v));
        let bit = |b: bool| u32::from(b).to_string();
        let slots = self.slots();
        let mapped = slots::map_slots(slots.iter().map(|s| s.shadow))
            .iter()
            .flatten()
            .count();
        set("LIGHT_COUNT", slots.len().max(1).to_string());
        set("MAP_COUNT", mapped.to_string());
        set("MAP_SLOTS", mapped.max(1).to_string());
        set("VISIBILITY_LIGHT", self.visibility_light.to_string());
        set("BLINN", bit(self.blinn));
        set(
            "SPECULAR_POWER",
            glsl_float(f32::from_bits(self.specular_power_bits)),
        );
        set("OUTPUT_VISIBILITY", bit(self.outputs.visibility));
        set("OUTPUT_GBUFFER", bit(self.outputs.gbuffer));
        // The shadow tests' settings are each light's own: see `slots::snippets`. The
        // vertex shader offsets along the normal for every mapped light when one asks
        // (the others get an offset of 0).
        if slots
            .iter()
            .any(|s| s.test.is_some_and(|t| t.normal_offset))
        {
            set("NORMAL_OFFSET", "1".into());
        }
        if self.multipass {
            set("MULTIPASS", "1".into());
        }
        match self.mask {
            MaskMode::Off => {}
            MaskMode::Write => set("SHADOW_MASK_WRITE", "1".into()),
            MaskMode::Read => set("SHADOW_MASK_READ", "1".into()),
            MaskMode::Vertex if self.tests_per_vertex() => set("VERTEX_TESTS", "1".into()),
            MaskMode::Vertex => {}
        }
        if let Some(c) = &self.cascades {
            set("USES_CASCADES", "1".into());
            set("CASCADES", c.count.to_string());
            set("CASCADE_BLEND", glsl_float(f32::from_bits(c.blend_bits)));
            if c.show {
                set("SHOW_CASCADES", "1".into());
            }
        }
        d
    }

    /// Compiles the scene program for this key, first checking that its vertex outputs fit
    /// the driver's limit (GL 3.3 guarantees 64 components).
    pub fn compile(&self, gl: &Gl) -> Result<ShaderProgram> {
        let slots = self.slots();
        let cascades = self.cascades.map_or(1, |c| c.count);
        let per_vertex = if self.tests_per_vertex() { 4 } else { 0 };
        let needed = slots::vertex_outputs(&slots, cascades) + per_vertex;
        let allowed = gl_limits(gl).max_vertex_output_components as usize;
        if needed > allowed {
            return Err(Error::Invalid(format!(
                "{} lights with {cascades} cascades or caster groups need {needed} vertex shader \
                 outputs and this driver allows {allowed}: use fewer lights, cascades or caster \
                 groups",
                slots.len()
            )));
        }
        let [vertex, fragment] = self.sources()?;
        ShaderProgram::new(gl, &vertex, &fragment, &[])
    }

    /// The scene program's vertex and fragment shaders exactly as [`ProgramKey::compile`]
    /// hands them to the driver: includes resolved, the defines after `#version`.
    pub fn sources(&self) -> Result<[ShaderSource; 2]> {
        let fragment = shaders::scene_frag(&slots::snippets(&self.slots(), self.mask))?;
        // The per-vertex tests are compiled into the capture program alone.
        let none = "// The per-vertex tests: in the capture program only (VERTEX_CAPTURE).\n";
        let plain = shaders::scene_vert();
        let vertex = shaders::resolve(
            &plain.files[0],
            &plain.text,
            &[(vertex::VERTEX_SNIPPET, none.into())],
        )?;
        let defines = self.defines();
        Ok([vertex, fragment].map(|s| ShaderSource {
            text: s.with_defines(&defines),
            ..s
        }))
    }

    /// The vertex shader that computes the translucent items' per-vertex tests for this
    /// key's lights (`VERTEX_CAPTURE`, [`vertex`]), for a transform feedback pass.
    pub fn capture_source(&self) -> Result<ShaderSource> {
        let key = self.with_mask(MaskMode::Vertex);
        let generated = [vertex::vertex_snippet(&key.slots())];
        let plain = shaders::scene_vert();
        let vertex = shaders::resolve(&plain.files[0], &plain.text, &generated)?;
        let mut defines = key.defines();
        defines.push(("VERTEX_CAPTURE".into(), "1".into()));
        Ok(ShaderSource {
            text: vertex.with_defines(&defines),
            ..vertex
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::ShadowSettings;

    #[test]
    fn defines_exist_only_for_what_the_lights_use() {
        let scene = Scene::load("point-shadows").unwrap();
        let s = ShadowSettings {
            cascades: 4,
            ..scene.shadow
        };
        let plan = ShadowPlan::decide(&scene.lights, &s);
        let key = ProgramKey::of(&scene, &plan, 0, Outputs::default()).unwrap();
        let names: Vec<String> = key.defines().into_iter().map(|(k, _)| k).collect();
        for absent in [
            "USES_CASCADES",
            "CASCADES",
            "CASCADE_BLEND",
            "NORMAL_OFFSET",
        ] {
            assert!(
                !names.contains(&absent.to_string()),
                "{absent} in {names:?}"
            );
        }
        // A light that does not cast: no shadow test at all.
        let mut dark = scene.clone();
        if let crate::scene::Light::Point(p) = &mut dark.lights[0] {
            p.casts_shadows = false;
        }
        let plan = ShadowPlan::decide(&dark.lights, &s);
        let key = ProgramKey::of(&dark, &plan, 0, Outputs::default()).unwrap();
        let names: Vec<String> = key.defines().into_iter().map(|(k, _)| k).collect();
        for absent in ["USES_SHADOWS", "PCF_RADIUS", "BIAS", "USES_CUBE"] {
            assert!(
                !names.contains(&absent.to_string()),
                "{absent} in {names:?}"
            );
        }
    }

    #[test]
    fn keys_differ_exactly_when_the_program_would() {
        let scene = Scene::load("dummy").unwrap();
        let key = |s: &ShadowSettings| {
            let plan = ShadowPlan::decide(&scene.lights, s);
            ProgramKey::of(&scene, &plan, 0, Outputs::default())
        };
        let base = key(&scene.shadow).unwrap();
        assert_eq!(base, key(&scene.shadow).unwrap());
        let biased = ShadowSettings {
            bias: 0.01,
            ..scene.shadow
        };
        assert_ne!(base, key(&biased).unwrap());
        // Cascade settings do not touch a program without cascades.
        let blended = ShadowSettings {
            cascade_blend: 0.3,
            ..scene.shadow
        };
        assert_eq!(base, key(&blended).unwrap());
        // The moment maps' knobs: nothing for a depth map, a new program for a moment one.
        let less_bleeding = ShadowSettings {
            bleed_reduction: 0.3,
            ..scene.shadow
        };
        assert_eq!(base, key(&less_bleeding).unwrap());
        let vsm = ShadowSettings {
            filter: crate::settings::Filter::Vsm,
            ..scene.shadow
        };
        assert_eq!(
            ShadowPlan::decide(&scene.lights, &vsm).kinds(),
            [ShadowKind::Moments]
        );
        assert_ne!(
            key(&vsm).unwrap(),
            key(&ShadowSettings {
                bleed_reduction: 0.3,
                ..vsm
            })
            .unwrap()
        );
    }

    /// The cells are part of a soft filter's test, so of the program's key, and of no
    /// other filter's.
    #[test]
    fn the_cells_change_a_soft_filters_test_only() {
        use crate::settings::Filter;
        let cells = |filter, search, each| {
            ShadowTest::of(&ShadowSettings {
                filter,
                soft_search_cells: search,
                soft_filter_cells: each,
                ..ShadowSettings::default()
            })
        };
        for filter in Filter::SOFT_MOMENTS {
            assert_ne!(cells(filter, 4, 4), cells(filter, 2, 4), "{filter:?}");
            assert_ne!(cells(filter, 4, 4), cells(filter, 4, 3), "{filter:?}");
        }
        assert_eq!(cells(Filter::Pcss, 4, 4), cells(Filter::Pcss, 1, 1));
        assert_eq!(cells(Filter::Vsm, 4, 4), cells(Filter::Vsm, 1, 1));
    }
}

#[cfg(test)]
mod snippet_tests;
