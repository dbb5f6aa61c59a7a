//! Soft shadows at a constant cost: summed-area tables of a moment map (`vssm`, two
//! moments; `msm-soft`, four), for directional and spot lights with a sized light.
//!
//! PCSS (`shaders/lib/pcss.glsl`) finds the penumbra per pixel but pays a tap per
//! point of its kernel; a blurred moment map costs one lookup but its blur is one width for
//! every edge. A summed-area table of the moments gives the mean over any box in a handful
//! of reads, so both PCSS stages cost the same at any width: the blockers' mean depth from
//! the moments of the search box's cells (Yang et al. 2010, variance soft shadow mapping;
//! Peters et al. 2016, moment soft shadow mapping), then the moments over a box as wide as
//! their penumbra, each cell against the receiver's plane; each stage's cells a side are a
//! setting ([`SoftCells`], 4 x 4 by default).
//! The table is built after the depth pass ([`crate::engine::SummedAreaTable`],
//! `shaders/summed_area.frag`) in unsigned fixed point; the test is
//! `shaders/lib/soft_moments.glsl`.

use super::{LightGlsl, ShadowTest};
use crate::engine::summed_area::{SAT_RADIX, SAT_SCALE};
use crate::engine::{FullScreenTriangle, Gl, ShaderProgram, SummedAreaTable, Texture};
use crate::error::Result;
use crate::settings::{Filter, MapSize, ShadowSettings};
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

/// A soft moment filter's cells a side, the blocker search's and the filter's: each stage
/// reads (n + 1)^2 corners of the table a pixel. Literal arguments of the light's call, so
/// the compiler sizes each lattice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SoftCells {
    pub search: u32,
    pub filter: u32,
}

impl SoftCells {
    /// The cells under `s`, if its filter reads a table (others' keys ignore the counts).
    pub fn of(s: &ShadowSettings) -> Option<SoftCells> {
        reads_table(s.filter).then_some(SoftCells {
            search: s.soft_search_cells,
            filter: s.soft_filter_cells,
        })
    }
}

/// A soft moment filter's test (src/shadows/summed.rs), light `i`, map slot `p`:
/// `vssm` or `msmSoft` (shaders/lib/soft_moments.glsl) on its table, through a
/// `usampler2D`, with PCSS's light constants (`lightPenumbra`) and each stage's cells.
pub fn glsl(i: usize, p: usize, test: &ShadowTest) -> Option<LightGlsl> {
    let moments = test.moments()?;
    let most = crate::settings::MAX_SOFT_CELLS;
    let cells = moments.soft_cells.unwrap_or(SoftCells {
        search: most,
        filter: most,
    });
    let head = format!(
        "{}, mlightviewVertexPos[{p}], {}, {}, lightPenumbra[{i}], {}, {}",
        super::map2d::SAMPLERS[i],
        test.bias_glsl(i),
        test.texel_glsl(),
        cells.search.clamp(1, most),
        cells.filter.clamp(1, most)
    );
    let tail = format!(
        "{}, {}, {}",
        test.pcss_perspective, moments.border_lit, test.beyond_far_lit
    );
    let call = moments.call(&head, &tail);
    Some(LightGlsl {
        snippets: vec![
            "lib/shadow_depth.glsl",
            "lib/pcss.glsl",
            "lib/shadow_moments.glsl",
            "lib/soft_moments.glsl",
        ],
        sampler_type: "usampler2D",
        test: call,
        defines: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::summed_area::SAT_MAX_BOX;
    use crate::settings::MAX_SOFT_CELLS;

    #[test]
    fn the_snippets_constants_are_the_tables() {
        let text = include_str!("../../shaders/lib/soft_moments.glsl");
        let scale = format!("const float SAT_SCALE_F = {}.0;", SAT_SCALE);
        assert!(text.contains(&scale), "{scale}");
        // The widest box read: twice the largest half width and a texel each way.
        assert!(text.contains("const float SOFT_MAX_TEXELS = 64.0;"));
        let cells = format!("const int SOFT_MAX_CELLS = {MAX_SOFT_CELLS};");
        assert!(text.contains(&cells), "{cells}");
        assert_eq!(SAT_MAX_BOX, 2 * 64 + 2);
    }
}
