//! The chapter's map in the scene program: light `i`'s sampler and its call of
//! `calcShadow` (shaders/lib/shadow_2d.glsl, "Shadows": `calcShadow`), or of its filter's
//! function, with the light's settings as literal arguments.

use super::MapDepth;
use crate::settings::KernelArgs;
use crate::shadows::{LightGlsl, ShadowTest};

/// Light `i`'s part of the generated snippets, its light-space position in map slot `p`:
/// the book's `calcShadow` (shaders/lib/shadow_2d.glsl), or the function of its filter
/// (hardware comparisons, the playground's soft filters, PCSS); a depth map's test only.
pub fn glsl(i: usize, p: usize, test: &ShadowTest) -> Option<LightGlsl> {
    let map = super::SAMPLERS[i];
    let own = test.depth()?;
    let test_depth = own.map_depth;
    let (position, bias) = match own.map_depth {
        MapDepth::Projected => (format!("mlightviewVertexPos[{p}]"), test.bias_glsl(i)),
        MapDepth::Linear => (
            format!("linearDepthPosition(mlightviewVertexPos[{p}])"),
            test.bias_glsl(i),
        ),
        MapDepth::LinearBias => (
            format!(
                "projectedBiasedPosition(mlightviewVertexPos[{p}], {}, lightDepthRange[{i}])",
                test.bias_glsl(i)
            ),
            "0.0".into(),
        ),
    };
    let head = format!("{map}, {position}, {bias}, {}", test.texel_glsl());
    let (r, far) = (own.pcf_radius, test.beyond_far_lit);
    let kernel = own.kernel.glsl();
    let args = match kernel.args {
        KernelArgs::Plain => String::new(),
        KernelArgs::Radius => format!(", {r}"),
        KernelArgs::Pcss => format!(
            ", lightPenumbra[{i}], {}, {}, {}",
            own.pcss_blocker_taps, own.pcss_filter_taps, test.pcss_perspective
        ),
        KernelArgs::Pixel => ", gl_FragCoord.xy".into(),
    };
    let test = format!("{}({head}{args}, {far})", kernel.function);
    let linear = match test_depth {
        MapDepth::Projected => None,
        MapDepth::Linear | MapDepth::LinearBias => Some("lib/linear_depth.glsl"),
    };
    // The map's lit border, and its interpolated depths, in the shader where the sampler
    // has neither (lib/shadow_border.glsl, lib/shadow_depth.glsl).
    let test = format!("SHADOW_BORDER({i}, mlightviewVertexPos[{p}], {far}, {test})");
    let test = format!("SHADOW_DEPTH_OF({i}, {test})");
    Some(LightGlsl {
        snippets: ["lib/shadow_border.glsl", "lib/shadow_depth.glsl"]
            .into_iter()
            .chain(linear)
            .chain([kernel.library])
            .collect(),
        sampler_type: kernel.sampler_type,
        test,
        defines: Vec::new(),
    })
}
