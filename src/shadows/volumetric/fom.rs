//! Fourier opacity maps (Jansen and Bavoil 2010, "Fourier Opacity Mapping"): the optical
//! depth's density along the light's depth t (0 to 1 over the translucent casters), a sum
//! of spikes -ln(1 - a) at the crossings, kept as the first terms of its Fourier series:
//! the mean and, for k = 1 to N, a cosine and a sine coefficient, each crossing adding
//! its share (additive blending, any order). A receiver at t integrates the series from 0
//! to t, each term damped by Lanczos' sigma factor against ringing, and takes exp(-it),
//! clamped to [0, 1]. At t = 1 every term but the mean integrates to 0: exact behind the
//! medium. `shaders/fom_map.frag`, `shaders/lib/fom.glsl`; 1 + 2N floats in RGBA32F layers.

use super::{Draw, Method, VolumetricMap};
use crate::engine::{Gl, ShaderProgram, TranslucentMap};
use crate::error::Result;
use crate::settings::{MapSize, ShadowSettings};
use crate::shaders;

/// The technique (`volumetric = "fom"`, `fom_coefficients` N).
pub struct Fom;

/// RGBA layers for the mean and `terms` cosine and sine pairs.
fn layers(terms: u32) -> u32 {
    (1 + 2 * terms).div_ceil(4)
}

impl Method for Fom {
    fn create(&self, gl: &Gl, settings: &ShadowSettings) -> Result<Box<dyn VolumetricMap>> {
        let terms = settings.fom_coefficients;
        Ok(Box::new(FomMap::new(gl, settings.map_size, terms)?))
    }

    fn parameter(&self, settings: &ShadowSettings) -> u32 {
        settings.fom_coefficients
    }

    fn lookup(&self, i: usize, terms: u32) -> (&'static str, String) {
        (
            "lib/fom.glsl",
            format!(
                "fomTransmittance({}, volumetricCoords({i}), {terms})",
                super::SAMPLERS[i]
            ),
        )
    }

    fn cost(&self, settings: &ShadowSettings) -> (u32, u32) {
        (16 * layers(settings.fom_coefficients), 1)
    }
}

/// A light's coefficients and the program that adds into them.
pub struct FomMap {
    map: TranslucentMap,
    program: ShaderProgram,
    terms: u32,
}

impl FomMap {
    pub fn new(gl: &Gl, size: MapSize, terms: u32) -> Result<FomMap> {
        let layers = layers(terms);
        let defines = [
            ("LAYERS".to_string(), layers.to_string()),
            ("TERMS".to_string(), terms.to_string()),
        ];
        Ok(FomMap {
            map: TranslucentMap::new(gl, size, layers)?,
            program: ShaderProgram::new(
                gl,
                &shaders::translucent_map_vert(),
                &shaders::fom_map_frag(),
                &defines,
            )?,
            terms,
        })
    }
}

impl VolumetricMap for FomMap {
    fn fits(&self, settings: &ShadowSettings) -> bool {
        self.terms == settings.fom_coefficients && self.map.size() == settings.map_size
    }

    fn render(&mut self, draw: &Draw) -> Result<()> {
        let _pass = self.map.begin_additive(draw.region);
        self.program.bind();
        draw.casters(&self.program);
        Ok(())
    }

    fn map(&self) -> &TranslucentMap {
        &self.map
    }
}
