//! Soft shadows at a constant cost: summed-area tables of a moment map (`vssm`, two
//! moments; `msm-soft`, four), for directional and spot lights with a sized light.
//!
//! PCSS (`shaders/lib/soft_filters.glsl`) finds the penumbra per pixel but pays a tap per
//! point of its kernel; a blurred moment map costs one lookup but its blur is one width for
//! every edge. A summed-area table of the moments gives the mean over any box in a handful
//! of reads, so both PCSS stages become one box each: the blockers' mean depth from the
//! search box's moments (Yang et al. 2010, variance soft shadow mapping; Peters et al. 2016,
//! moment soft shadow mapping), then the moments over a box as wide as their penumbra.
//! The table is built after the depth pass ([`crate::engine::SummedAreaTable`],
//! `shaders/summed_area.frag`) in unsigned fixed point; the test is
//! `shaders/lib/soft_moments.glsl`.

use super::moments::MomentTest;
use super::slots::ShadowTest;
use super::LightGlsl;
use crate::engine::summed_area::{SAT_RADIX, SAT_SCALE};
use crate::engine::{FullScreenTriangle, Gl, ShaderProgram, SummedAreaTable, Texture};
use crate::error::Result;
use crate::settings::{glsl_float, Filter, MapSize};
use crate::shaders;

/// Whether `filter` reads a summed-area table ([`Filter::SOFT_MOMENTS`]).
pub fn reads_table(filter: Filter) -> bool {
    Filter::SOFT_MOMENTS.contains(&filter)
}

/// A light's summed-area table and the two programs that build it.
pub struct Summed {
    table: SummedAreaTable,
    convert: ShaderProgram,
    add: ShaderProgram,
}

impl Summed {
    /// A table for a `size` map of `components` moments.
    pub fn new(gl: &Gl, size: MapSize, components: u32) -> Result<Summed> {
        let program = |first: bool| {
            let mut defines = vec![
                ("SAT_RADIX".to_string(), SAT_RADIX.to_string()),
                ("SAT_SCALE".to_string(), format!("{SAT_SCALE}u")),
            ];
            if first {
                defines.push(("SOURCE_FLOAT".to_string(), "1".to_string()));
            }
            ShaderProgram::new(
                gl,
                &shaders::depth_view_vert(),
                &shaders::summed_area_frag(),
                &defines,
            )
        };
        Ok(Summed {
            table: SummedAreaTable::new(gl, size, components)?,
            convert: program(true)?,
            add: program(false)?,
        })
    }

    /// Builds the table of `moments` (the depth pass' float moments, the table's size).
    pub fn build(&mut self, moments: &Texture, triangle: &FullScreenTriangle) {
        self.table
            .build(&self.convert, &self.add, moments, triangle);
    }

    pub fn table(&self) -> &SummedAreaTable {
        &self.table
    }

    pub fn fits(&self, size: MapSize, components: u32) -> bool {
        self.table.size() == size && self.table.components() == components
    }
}

/// Light `i`'s part of the generated snippets, its light-space position in map slot `p`:
/// `vssm` or `msmSoft` (shaders/lib/soft_moments.glsl) on its table, through a
/// `usampler2D` read with `texelFetch`, with PCSS's light constants (`lightPenumbra`).
pub fn glsl(i: usize, p: usize, test: &ShadowTest, moments: &MomentTest) -> LightGlsl {
    let f = |bits: u32| glsl_float(f32::from_bits(bits));
    let head = format!(
        "{}, mlightviewVertexPos[{p}], {}, {}, lightPenumbra[{i}]",
        super::map2d::SAMPLERS[i],
        test.bias_glsl(i),
        test.texel_glsl()
    );
    let tail = format!(
        "{}, {}, {}",
        test.pcss_perspective, moments.border_lit, test.beyond_far_lit
    );
    let call = match moments.mode {
        MODE_MSM_SOFT => {
            let t = moments.msm_toward_bits.map(f);
            format!(
                "msmSoft({head}, {}, vec4({}, {}, {}, {}), {tail})",
                f(moments.msm_bias_bits),
                t[0],
                t[1],
                t[2],
                t[3]
            )
        }
        _ => format!(
            "vssm({head}, {}, {}, {tail})",
            f(moments.min_variance_bits),
            f(moments.bleed_reduction_bits)
        ),
    };
    LightGlsl {
        snippets: &[
            "lib/soft_filters.glsl",
            "lib/shadow_moments.glsl",
            "lib/soft_moments.glsl",
        ],
        sampler_type: "usampler2D",
        test: call,
        defines: Vec::new(),
    }
}

/// Whether a moment test's mode ([`super::moments::mode`]) reads a table.
pub fn reads_table_mode(mode: u32) -> bool {
    mode == MODE_VSSM || mode == MODE_MSM_SOFT
}

/// The moment shader's number for `vssm` ([`super::moments::mode`]).
pub const MODE_VSSM: u32 = 5;
/// The moment shader's number for `msm-soft`.
pub const MODE_MSM_SOFT: u32 = 6;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::summed_area::SAT_MAX_BOX;
    use crate::settings::ShadowSettings;

    #[test]
    fn the_snippets_constants_are_the_tables() {
        let text = include_str!("../../shaders/lib/soft_moments.glsl");
        let scale = format!("const float SAT_SCALE_F = {}.0;", SAT_SCALE);
        assert!(text.contains(&scale), "{scale}");
        // The widest box read: twice the largest half width and a texel each way.
        assert!(text.contains("const float SOFT_MAX_TEXELS = 64.0;"));
        assert_eq!(SAT_MAX_BOX, 2 * 64 + 2);
    }

    #[test]
    fn each_filter_calls_its_function_with_its_constants() {
        let vssm = ShadowSettings {
            filter: Filter::Vssm,
            ..ShadowSettings::default()
        };
        let test = ShadowTest::of(&vssm);
        let m = test.moments.expect("vssm is a moment filter");
        let g = glsl(1, 0, &test, &m);
        assert_eq!(g.sampler_type, "usampler2D");
        assert!(
            g.test
                .starts_with("vssm(shadowMap1, mlightviewVertexPos[0], "),
            "{}",
            g.test
        );
        assert!(g.test.contains(", lightPenumbra[1], "), "{}", g.test);
        let msm = ShadowSettings {
            filter: Filter::MsmSoft,
            ..vssm
        };
        let test = ShadowTest::of(&msm);
        let g = glsl(0, 0, &test, &test.moments.unwrap());
        assert!(g.test.starts_with("msmSoft("), "{}", g.test);
    }
}
