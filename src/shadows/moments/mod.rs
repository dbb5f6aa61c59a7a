//! Filterable shadow maps: variance (VSM), exponential variance (EVSM, 2 or 4 components)
//! and moment shadow maps (MSM), for directional and spot lights with one 2D map. The
//! shadow-playground's "variance" and "moment" demos, and the engines' EVSM.
//!
//! A depth map cannot be averaged: the mean of depths says nothing about how many of them
//! a receiver is behind. Moments of depth can: the depth pass writes (z, z^2) (or four
//! moments) into a float colour map, a separable Gaussian blur averages them
//! ([`crate::engine::MomentMap::blur`], `shaders/moments_blur.frag`), and the scene pass
//! reads one bilinear lookup and bounds the lit fraction from it
//! (`shaders/lib/shadow_moments.glsl`). The price is light bleeding where occluders
//! overlap, which the bleeding reduction, EVSM's warp and MSM's four moments each cut.
//!
//! Cube maps and cascades have no moment form here: the shadow plan ([`super::plan`]) refuses
//! those combinations, naming the light and the filter.

mod kind;

pub use kind::KIND;

use glam::{DVec2, DVec3};

use super::camera::culling::may_land;
use super::camera::fitted;
use super::casters::depth_state;
use super::map2d::{camera, draw_map_casters};
pub use super::moment_mode::MomentMode;
use super::summed::{self, Summed};
use super::{
    DepthPass, DepthViewKind, LightGlsl, ShadowKind, ShadowTest, ShadowView, SlotTransform,
    Technique,
};
use crate::engine::{
    DepthPassGuard, FullScreenTriangle, Gl, MomentMap, PixelRect, Sampling, ShaderProgram, Texture,
};
use crate::error::{Error, Result};
use crate::scene::{Light, Scene};
use crate::settings::{
    glsl_float, Blur, MapSize, MomentDepth, MomentKnob, ShadowSettings, Wrap, ESM_MAX_EXPONENT,
    EVSM_MAX_EXPONENT,
};
use crate::shaders;

/// EVSM's exponents as the shaders use them: clamped so exp(2c) fits a 32-bit float.
pub fn evsm_exponents(settings: &ShadowSettings) -> [f32; 2] {
    settings.evsm_exponents.map(|c| c.min(EVSM_MAX_EXPONENT))
}

/// ESM's exponent as the shaders use it: clamped so exp(c) fits a 32-bit float.
pub fn esm_exponent(settings: &ShadowSettings) -> f32 {
    settings.esm_exponent.min(ESM_MAX_EXPONENT)
}

/// The moments of depth 1 (where no caster was drawn), which the map is cleared to.
pub fn far_moments(settings: &ShadowSettings) -> [f32; 4] {
    let Some(mode) = MomentMode::of(settings.filter) else {
        return [1.0; 4];
    };
    match mode.facts().depth {
        MomentDepth::Evsm => {
            let [p, n] = evsm_exponents(settings);
            let (pos, neg) = (p.exp(), -(-n).exp());
            [pos, pos * pos, neg, neg * neg]
        }
        MomentDepth::Vsm => [1.0, 1.0, 0.0, 0.0],
        MomentDepth::Msm => [1.0; 4],
        MomentDepth::Esm => [esm_exponent(settings).exp(), 0.0, 0.0, 0.0],
    }
}

/// How the depth view reads back what the depth pass under `settings` stores.
fn view_kind(settings: &ShadowSettings) -> DepthViewKind {
    let Some(mode) = MomentMode::of(settings.filter) else {
        return DepthViewKind::Flat;
    };
    match mode.facts().depth {
        MomentDepth::Evsm => DepthViewKind::Exponential {
            exponent_bits: evsm_exponents(settings)[0].to_bits(),
            warped: true,
        },
        MomentDepth::Esm => DepthViewKind::Exponential {
            exponent_bits: esm_exponent(settings).to_bits(),
            warped: false,
        },
        MomentDepth::Vsm | MomentDepth::Msm => DepthViewKind::Flat,
    }
}

/// A group of the test's constants as its function's arguments, if it takes them.
fn knob_args(knob: MomentKnob, t: &MomentTest) -> Option<String> {
    let f = |bits: u32| glsl_float(f32::from_bits(bits));
    Some(match knob {
        MomentKnob::Blur | MomentKnob::Cells => return None,
        MomentKnob::Variance => {
            format!("{}, {}", f(t.min_variance_bits), f(t.bleed_reduction_bits))
        }
        MomentKnob::EvsmExponents => format!(
            "vec2({}, {}), {}",
            f(t.evsm_bits[0]),
            f(t.evsm_bits[1]),
            // The 4-component map stores the negative warp too.
            t.mode == MomentMode::Evsm4
        ),
        MomentKnob::Msm => {
            let [x, y, z, w] = t.msm_toward_bits.map(f);
            format!("{}, vec4({x}, {y}, {z}, {w})", f(t.msm_bias_bits))
        }
        MomentKnob::EsmExponent => f(t.esm_bits),
    })
}

/// The constants of shaders/lib/shadow_moments.glsl for one light (with bias.glsl's, from
/// [`super::ShadowTest`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MomentTest {
    pub mode: MomentMode,
    pub min_variance_bits: u32,
    pub bleed_reduction_bits: u32,
    pub evsm_bits: [u32; 2],
    pub msm_bias_bits: u32,
    pub msm_toward_bits: [u32; 4],
    pub esm_bits: u32,
    pub border_lit: bool,
    /// A soft moment filter's lattices ([`summed::SoftCells`]).
    pub soft_cells: Option<summed::SoftCells>,
}

impl MomentTest {
    /// The test under `settings` (as [`ShadowSettings::effective`] made them), if its filter
    /// is a moment one.
    pub fn of(s: &ShadowSettings) -> Option<MomentTest> {
        MomentMode::of(s.filter).map(|mode| MomentTest {
            mode,
            min_variance_bits: s.min_variance.to_bits(),
            bleed_reduction_bits: s.bleed_reduction.to_bits(),
            evsm_bits: evsm_exponents(s).map(f32::to_bits),
            msm_bias_bits: s.msm_bias.to_bits(),
            msm_toward_bits: s.msm_toward.vector().map(f32::to_bits),
            esm_bits: esm_exponent(s).to_bits(),
            border_lit: s.wrap == Wrap::ClampToBorder,
            soft_cells: summed::SoftCells::of(s),
        })
    }

    /// The call of its filter's function (its row's), its own constants group by group
    /// between `head` (map, position, bias; a table's: [`summed::glsl`]'s) and `tail`
    /// (borderLit, beyondFarLit).
    pub fn call(&self, head: &str, tail: &str) -> String {
        let facts = self.mode.facts();
        let mut args = vec![head.to_string()];
        args.extend(facts.knobs.iter().filter_map(|&k| knob_args(k, self)));
        args.push(tail.to_string());
        format!("{}({})", facts.function, args.join(", "))
    }
}

/// The texels of a `size` map that light `index`'s casters (those its depth pass draws)
/// can cover, seen through `view`: their world boxes' corners projected, clamped to the
/// map. `None` when a corner is behind a perspective light's eye (the whole map, then).
pub fn caster_footprint(
    scene: &Scene,
    boxes: &[(DVec3, DVec3)],
    index: usize,
    view: &ShadowView,
    size: MapSize,
) -> Option<PixelRect> {
    let clip = view.projection.as_dmat4() * view.view64;
    let light = &scene.lights[index];
    let (mut lo, mut hi) = (DVec2::splat(1.0), DVec2::splat(-1.0));
    for (k, item) in scene.items.iter().enumerate() {
        let (a, b) = boxes[k];
        if !item.casts_shadows || !may_land(light, view, a, b) {
            continue;
        }
        for c in fitted::corners(a, b) {
            let p = clip * c.extend(1.0);
            if p.w <= 1e-9 {
                return None;
            }
            let ndc = (p.truncate().truncate() / p.w).clamp(DVec2::splat(-1.0), DVec2::ONE);
            lo = lo.min(ndc);
            hi = hi.max(ndc);
        }
    }
    if lo.x > hi.x || lo.y > hi.y {
        return Some(PixelRect {
            x: 0,
            y: 0,
            width: 0,
            height: 0,
        });
    }
    let texels = DVec2::new(f64::from(size.width), f64::from(size.height));
    let a = ((lo + 1.0) * 0.5 * texels).floor();
    let b = ((hi + 1.0) * 0.5 * texels).ceil().min(texels);
    Some(PixelRect {
        x: a.x as u32,
        y: a.y as u32,
        width: (b.x - a.x).max(0.0) as u32,
        height: (b.y - a.y).max(0.0) as u32,
    })
}

/// A light's filterable map, with the programs that draw and blur it.
pub struct Moments {
    map: MomentMap,
    /// The depth program and the (mode, EVSM's and ESM's exponents) it was compiled for.
    depth: Option<((&'static str, [u32; 3]), ShaderProgram)>,
    /// The blur program and its kernel.
    blur: Option<(Blur, ShaderProgram)>,
    /// The summed-area table of a soft filter (vssm, msm-soft), which the scene pass reads.
    summed: Option<Summed>,
    triangle: FullScreenTriangle,
    /// How the depth view reads what the last depth pass stored.
    view: DepthViewKind,
}

impl Moments {
    pub fn new(gl: &Gl, settings: &ShadowSettings) -> Result<Moments> {
        let components = settings.filter.moment_components();
        if components == 0 {
            return Err(Error::Invalid(format!(
                "filter {} has no moment map",
                settings.filter.name()
            )));
        }
        Ok(Moments {
            map: MomentMap::new(gl, settings.map_size, components)?,
            depth: None,
            blur: None,
            summed: summed::reads_table(settings.filter)
                .then(|| Summed::new(gl, settings.map_size, components))
                .transpose()?,
            triangle: FullScreenTriangle::new(gl)?,
            view: view_kind(settings),
        })
    }

    /// Compiles the depth program for `s`' filter and exponents unless it is the one there.
    fn prepare_depth(&mut self, gl: &Gl, s: &ShadowSettings) -> Result<()> {
        let [p, n] = evsm_exponents(s);
        let exponents = [p, n, esm_exponent(s)];
        let Some(mode) = MomentMode::of(s.filter) else {
            return Err(Error::Invalid(format!(
                "filter {} has no moment map",
                s.filter.name()
            )));
        };
        let key = (mode.depth_define(), exponents.map(f32::to_bits));
        if self.depth.as_ref().map(|(k, _)| *k) != Some(key) {
            let defines = vec![
                (key.0.to_string(), "1".to_string()),
                ("EVSM_POS".to_string(), glsl_float(exponents[0])),
                ("EVSM_NEG".to_string(), glsl_float(exponents[1])),
                ("ESM_EXPONENT".to_string(), glsl_float(exponents[2])),
            ];
            let program = ShaderProgram::new(
                gl,
                &shaders::depth_vert(),
                &shaders::moments_depth_frag(),
                &defines,
            )?;
            self.depth = Some((key, program));
        }
        Ok(())
    }

    /// Compiles the blur program for `blur` unless it is the one there.
    fn prepare_blur(&mut self, gl: &Gl, blur: Blur) -> Result<()> {
        if self.blur.as_ref().map(|(b, _)| *b) != Some(blur) {
            let weights = blur.weights();
            let list: Vec<String> = weights.iter().map(|w| glsl_float(*w)).collect();
            let defines = vec![
                ("BLUR_RADIUS".to_string(), (weights.len() - 1).to_string()),
                ("BLUR_WEIGHTS".to_string(), list.join(", ")),
            ];
            let program = ShaderProgram::new(
                gl,
                &shaders::depth_view_vert(),
                &shaders::moments_blur_frag(),
                &defines,
            )?;
            self.blur = Some((blur, program));
        }
        Ok(())
    }
}

impl Technique for Moments {
    fn kind(&self) -> ShadowKind {
        ShadowKind::Moments
    }

    fn fits(&self, s: &ShadowSettings) -> bool {
        self.map.size() == s.map_size
            && self.map.components() == s.filter.moment_components()
            && self.summed.is_some() == summed::reads_table(s.filter)
    }

    /// The chapter's depth pass with moments for depth, then the blur.
    fn render_depth(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
    ) -> Result<ShadowView> {
        let settings = pass.settings;
        let view = camera(scene, index, settings);
        self.view = view_kind(settings);
        let gl = pass.gl.clone();
        self.prepare_depth(&gl, settings)?;
        if let Some((_, program)) = &self.depth {
            let _state = DepthPassGuard::begin(&gl, depth_state(settings), program);
            self.map.begin_depth_pass(far_moments(settings));
            draw_map_casters(pass, scene, index, &view, program, None);
        }
        if let Some(table) = &mut self.summed {
            // The table is the filter: no blur.
            table.build(self.map.texture(), &self.triangle);
        } else if settings.blur != Blur::None {
            self.prepare_blur(&gl, settings.blur)?;
            let footprint = caster_footprint(scene, pass.boxes, index, &view, self.map.size());
            let radius = settings.blur.taps() / 2;
            match (&self.blur, footprint) {
                // No caster lands: the map is all far moments, which a blur keeps.
                (_, Some(f)) if f.width == 0 || f.height == 0 => {}
                (Some((_, program)), f) => self.map.blur(program, &self.triangle, radius, f),
                (None, _) => {}
            }
        }
        Ok(view)
    }

    /// The summed-area table for a soft filter, else the (blurred) moments.
    fn texture(&self) -> &Texture {
        match &self.summed {
            Some(table) => table.table().texture(),
            None => self.map.texture(),
        }
    }

    fn view_texture(&self) -> &Texture {
        self.map.texture()
    }

    /// Filtered, never compared: the blur and the bilinear lookup are the filter. Outside
    /// the map the shader decides (`BORDER_LIT`): a border colour of depth 1 is not the
    /// moments of depth 1 for every filter.
    /// A summed-area table is read texel by texel (integer textures do not filter).
    fn sampling(&self, _settings: &ShadowSettings) -> Sampling {
        Sampling {
            compare: false,
            linear: self.summed.is_none(),
            wrap: Wrap::ClampToEdge,
            border_in_shader: false,
            interpolate_in_shader: false,
        }
    }

    fn slot_transform(
        &self,
        _light: &Light,
        view: &ShadowView,
        settings: &ShadowSettings,
    ) -> Option<SlotTransform> {
        Some(super::map2d::slot_transform(view, settings))
    }

    fn bytes(&self) -> u64 {
        self.map.bytes() + self.summed.as_ref().map_or(0, |t| t.table().bytes())
    }

    fn depth_view(&self) -> DepthViewKind {
        self.view
    }
}

/// Light `i`'s part of the generated snippets, its light-space position in map slot `p`:
/// its filter's function in shaders/lib/shadow_moments.glsl, read through a plain
/// `sampler2D` (the moments are filtered, not compared).
pub fn glsl(i: usize, p: usize, test: &ShadowTest) -> Option<LightGlsl> {
    let moments = test.moments()?;
    if moments.mode.reads_table() {
        return summed::glsl(i, p, test);
    }
    let head = format!(
        "{}, mlightviewVertexPos[{p}], {}",
        super::map2d::SAMPLERS[i],
        test.bias_glsl(i)
    );
    let tail = format!("{}, {}", moments.border_lit, test.beyond_far_lit);
    Some(LightGlsl {
        snippets: vec!["lib/shadow_moments.glsl"],
        sampler_type: "sampler2D",
        test: moments.call(&head, &tail),
        defines: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::{Filter, MsmToward};

    #[test]
    fn kernels_sum_to_one_and_the_playgrounds_is_its_3x3() {
        for blur in Blur::ALL {
            let w = blur.weights();
            assert_eq!(w.len() as u32, blur.taps() / 2 + 1, "{}", blur.name());
            let sum = w[0] + 2.0 * w[1..].iter().sum::<f32>();
            assert!((sum - 1.0).abs() < 1e-6, "{}: {sum}", blur.name());
            assert!(w.windows(2).all(|p| p[0] >= p[1]), "{}: {w:?}", blur.name());
        }
        // The outer product of the 1D kernel is the playground's 2D one.
        let w = Blur::Playground3x3.weights();
        for (got, want) in [
            (w[1] * w[1], 0.045),
            (w[0] * w[1], 0.122),
            (w[0] * w[0], 0.332),
        ] {
            assert!((got - want).abs() < 1e-3, "{got} vs {want}");
        }
    }

    #[test]
    fn evsm_exponents_are_clamped_so_the_cleared_map_is_finite() {
        let s = ShadowSettings {
            filter: Filter::Evsm4,
            evsm_exponents: [500.0, 90.0],
            ..ShadowSettings::default()
        };
        assert_eq!(evsm_exponents(&s), [EVSM_MAX_EXPONENT, EVSM_MAX_EXPONENT]);
        assert!(far_moments(&s).iter().all(|m| m.is_finite()));
        let [pos, pos2, neg, neg2] = far_moments(&ShadowSettings {
            evsm_exponents: [40.0, 5.0],
            ..s
        });
        assert_eq!((pos, pos2), (40f32.exp(), 40f32.exp() * 40f32.exp()));
        assert_eq!((neg, neg2), (-(-5f32).exp(), (-5f32).exp() * (-5f32).exp()));
    }

    #[test]
    fn the_esm_exponent_keeps_the_cleared_map_finite_up_to_its_limit() {
        let at = |c: f32| {
            far_moments(&ShadowSettings {
                filter: Filter::Esm,
                esm_exponent: c,
                ..ShadowSettings::default()
            })[0]
        };
        assert!(at(ESM_MAX_EXPONENT).is_finite() && at(ESM_MAX_EXPONENT) > 1e38);
        assert_eq!(at(500.0), at(ESM_MAX_EXPONENT));
        // The limit is the last whole exponent whose exp(c) is a 32-bit float.
        assert!(f32::MAX.ln() < ESM_MAX_EXPONENT + 1.0);
        assert!(!(ESM_MAX_EXPONENT + 1.0).exp().is_finite());
    }

    #[test]
    fn moment_constants_reach_only_moment_programs() {
        let pcf = ShadowSettings::default();
        assert_eq!(MomentTest::of(&pcf), None);
        let vsm = ShadowSettings {
            filter: Filter::Vsm,
            ..pcf
        };
        let test = MomentTest::of(&vsm).unwrap();
        assert_eq!(
            test.call("m", "false, false"),
            format!(
                "calcShadowVsm(m, {}, 0.15, false, false)",
                glsl_float(vsm.min_variance)
            )
        );
        let playground = ShadowSettings {
            filter: Filter::Msm,
            msm_bias: 9e-4,
            msm_toward: MsmToward::Playground,
            ..pcf
        };
        assert_eq!(
            MomentTest::of(&playground)
                .unwrap()
                .call("m", "true, false"),
            "calcShadowMsm(m, 0.0009, vec4(0.0, 0.63, 0.0, 0.63), true, false)"
        );
        let evsm4 = ShadowSettings {
            filter: Filter::Evsm4,
            evsm_exponents: [40.0, 5.0],
            ..pcf
        };
        let call = MomentTest::of(&evsm4).unwrap().call("m", "t");
        assert!(call.ends_with(", vec2(40.0, 5.0), true, t)"), "{call}");
        // A border of depth 1 is lit through the shader, not the sampler.
        let fitted = ShadowSettings {
            fit: crate::settings::Fit::Scene,
            ..vsm
        };
        assert!(MomentTest::of(&fitted.effective()).unwrap().border_lit);
        assert!(!test.border_lit);
    }
}

#[cfg(test)]
mod footprint_tests {
    use super::*;

    #[test]
    fn the_blur_covers_the_casters_footprint_and_no_more() {
        let scene = Scene::load("dummy").unwrap();
        let s = scene.shadow;
        let view = camera(&scene, 0, &s);
        let size = s.map_size;
        let f =
            caster_footprint(&scene, &fitted::item_world_boxes(&scene), 0, &view, size).unwrap();
        // The 5 x 5 plane and the cube in a 20 x 20 box: about a quarter of the map's side.
        assert!(
            f.x + f.width <= size.width && f.y + f.height <= size.height,
            "{f:?}"
        );
        assert!(
            f.width < size.width / 2 && f.height < size.height / 2,
            "{f:?}"
        );
        // Every caster's centre projects inside it.
        let clip = view.projection.as_dmat4() * view.view64;
        for item in scene.items.iter().filter(|i| i.casts_shadows) {
            let p = clip * item.position.as_dvec3().extend(1.0);
            let t = (p.truncate().truncate() / p.w + 1.0) * 0.5 * f64::from(size.width);
            assert!(
                t.x >= f64::from(f.x)
                    && t.x <= f64::from(f.x + f.width)
                    && t.y >= f64::from(f.y)
                    && t.y <= f64::from(f.y + f.height),
                "{} at {t:?} outside {f:?}",
                item.name
            );
        }
        // No casters: nothing to blur.
        let mut empty = scene.clone();
        for item in &mut empty.items {
            item.casts_shadows = false;
        }
        let none =
            caster_footprint(&empty, &fitted::item_world_boxes(&empty), 0, &view, size).unwrap();
        assert_eq!((none.width, none.height), (0, 0));
    }
}
