//! Opacity shadow maps (Kim and Neumann 2001, "Opacity Shadow Maps"): the light's depth
//! between the nearest and farthest translucent caster cut into K slices; each crossing
//! adds its optical depth, -ln(1 - a), to the slice it falls in (additive blending, so the
//! order of the casters does not matter). A receiver's transmittance is exp(-(the slices
//! before its own, and the part of its own it is past)): exact behind the medium, a ramp
//! across a slice within it. Four slices to an RGBA32F layer (`shaders/osm_map.frag`,
//! `shaders/lib/osm.glsl`).

use super::{Draw, Method, VolumetricMap};
use crate::engine::{Gl, ShaderProgram, TranslucentMap};
use crate::error::Result;
use crate::settings::{MapSize, ShadowSettings};
use crate::shaders;

/// The technique (`volumetric = "osm"`, `osm_slices` K).
pub struct Osm;

/// RGBA layers for `slices`.
fn layers(slices: u32) -> u32 {
    slices.div_ceil(4)
}

impl Method for Osm {
    fn create(&self, gl: &Gl, settings: &ShadowSettings) -> Result<Box<dyn VolumetricMap>> {
        Ok(Box::new(OsmMap::new(
            gl,
            settings.map_size,
            settings.osm_slices,
        )?))
    }

    fn parameter(&self, settings: &ShadowSettings) -> u32 {
        settings.osm_slices
    }

    fn lookup(&self, i: usize, slices: u32) -> (&'static str, String) {
        (
            "lib/osm.glsl",
            format!(
                "osmTransmittance({}, volumetricCoords({i}), {slices})",
                super::SAMPLERS[i]
            ),
        )
    }

    fn cost(&self, settings: &ShadowSettings) -> (u32, u32) {
        (16 * layers(settings.osm_slices), 1)
    }
}

/// A light's slices and the program that adds into them.
pub struct OsmMap {
    map: TranslucentMap,
    program: ShaderProgram,
    slices: u32,
}

impl OsmMap {
    pub fn new(gl: &Gl, size: MapSize, slices: u32) -> Result<OsmMap> {
        let layers = layers(slices);
        let defines = [
            ("LAYERS".to_string(), layers.to_string()),
            ("SLICES".to_string(), slices.to_string()),
        ];
        Ok(OsmMap {
            map: TranslucentMap::new(gl, size, layers)?,
            program: ShaderProgram::new(
                gl,
                &shaders::translucent_map_vert(),
                &shaders::osm_map_frag(),
                &defines,
            )?,
            slices,
        })
    }
}

impl VolumetricMap for OsmMap {
    fn fits(&self, settings: &ShadowSettings) -> bool {
        self.slices == settings.osm_slices && self.map.size() == settings.map_size
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
