//! What the two additive translucent maps share ([`super::osm`], [`super::fom`]): every
//! crossing adds into RGBA32F layers with additive blending, so the order of the casters
//! does not matter, in one pass over the casters' footprint. A technique differs only in
//! what it counts (slices, terms), how many layers that takes, its map shader and its
//! lookup: an [`Additive`] value.

use super::{Draw, Method, VolumetricMap};
use crate::engine::{Gl, ShaderProgram, ShaderSource, TranslucentMap};
use crate::error::Result;
use crate::settings::ShadowSettings;
use crate::shaders;

/// One additive technique, as data.
pub struct Additive {
    /// The setting it counts (slices, terms).
    pub count: fn(&ShadowSettings) -> u32,
    /// That setting's name in the scene file, the one only it reads.
    pub settings: &'static [&'static str],
    /// RGBA layers for a count.
    pub layers: fn(u32) -> u32,
    /// The map shader's define for the count (`SLICES`, `TERMS`).
    pub define: &'static str,
    /// The fragment shader adding a crossing into the layers.
    pub fragment: fn() -> ShaderSource,
    /// The lookup's library file and its function `f(sampler, coords, count)`.
    pub library: &'static str,
    pub function: &'static str,
}

impl Method for Additive {
    fn create(&self, gl: &Gl, settings: &ShadowSettings) -> Result<Box<dyn VolumetricMap>> {
        let count = (self.count)(settings);
        let layers = (self.layers)(count);
        let defines = [
            ("LAYERS".to_string(), layers.to_string()),
            (self.define.to_string(), count.to_string()),
        ];
        Ok(Box::new(AdditiveMap {
            map: TranslucentMap::new(gl, settings.volumetric_size, layers)?,
            program: ShaderProgram::new(
                gl,
                &shaders::translucent_map_vert(),
                &(self.fragment)(),
                &defines,
            )?,
            count,
            technique: self.count,
        }))
    }

    fn parameter(&self, settings: &ShadowSettings) -> u32 {
        (self.count)(settings)
    }

    fn lookup(&self, i: usize, count: u32) -> (&'static str, String) {
        let call = format!(
            "{}({}, volumetricCoords({i}), {count})",
            self.function,
            super::SAMPLERS[i]
        );
        (self.library, call)
    }

    fn texel_call(&self, count: u32) -> (&'static str, String) {
        // The texel's centre: the filter reads that texel alone.
        let call = format!(
            "{}(translucentMap, vec4(uv, depth, 1.0), {count})",
            self.function
        );
        (self.library, call)
    }

    fn cost(&self, settings: &ShadowSettings) -> (u32, u32) {
        (16 * (self.layers)((self.count)(settings)), 1)
    }

    fn settings(&self) -> &'static [&'static str] {
        self.settings
    }
}

/// A light's layers and the program that adds into them.
struct AdditiveMap {
    map: TranslucentMap,
    program: ShaderProgram,
    count: u32,
    technique: fn(&ShadowSettings) -> u32,
}

impl VolumetricMap for AdditiveMap {
    fn fits(&self, settings: &ShadowSettings) -> bool {
        self.count == (self.technique)(settings) && self.map.size() == settings.volumetric_size
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
