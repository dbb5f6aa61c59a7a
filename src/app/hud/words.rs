//! A light's shadow and the shadow cache's counters in plain words, for the HUD: what a
//! student reads beside the chapters ("24-bit depth", not "24").

use shadowmap::renderer::{DepthPasses, MaskUses};
use shadowmap::settings::{BiasMode, Cull, DepthFormat, Filter, MapSize, PointPass};
use shadowmap::shadows::plan::LightPlan;
use shadowmap::shadows::ShadowKind;

/// The light's technique, its filter and its bias, a line each (one line without a map).
pub fn shadow(light: &LightPlan) -> Vec<String> {
    let s = &light.settings;
    let size = size(s.map_size);
    let depth = depth(s.depth_format);
    let technique = match light.kind {
        ShadowKind::None if !s.shadows => return vec!["Shadows: off".to_string()],
        ShadowKind::None => return vec!["Shadow: none (this light casts no shadow)".to_string()],
        ShadowKind::Volume => {
            return vec!["Shadow: stencil shadow volumes (z-fail), no map".to_string()];
        }
        ShadowKind::Map => format!("Shadow: one {size} depth map, {depth}"),
        ShadowKind::Moments => format!(
            "Shadow: one {size} moment map, {}",
            match s.blur.taps() {
                0 => "not blurred".to_string(),
                n => format!("blurred {n} x {n}"),
            }
        ),
        ShadowKind::Cube => format!(
            "Shadow: a cube map, 6 faces of {size}, {depth}, {}",
            match s.point_pass {
                PointPass::Layered => "drawn in one pass",
                PointPass::SixPasses => "drawn in six passes",
            }
        ),
        ShadowKind::Cascades => format!("Shadow: {} cascades of {size}, {depth}", s.cascades),
        ShadowKind::Groups => format!(
            "Shadow: {} caster groups, a {size} map each, {depth}",
            s.caster_groups
        ),
    };
    let bias = match s.bias_mode {
        BiasMode::None => "Bias: none".to_string(),
        BiasMode::Constant => format!("Bias: {}", s.bias),
        BiasMode::Slope => format!("Bias: {} to {}, growing with the slope", s.bias_min, s.bias),
    };
    let mut bias = vec![bias];
    if s.normal_offset != 0.0 {
        bias.push(format!("normal offset {} texels", s.normal_offset));
    }
    match s.cull {
        Cull::None => {}
        Cull::Back => bias.push("back faces culled in the map".to_string()),
        Cull::Front => bias.push("front faces culled in the map".to_string()),
    }
    vec![
        technique,
        format!("Filter: {}", filter(s.filter)),
        bias.join(", "),
    ]
}

/// "2048 x 2048".
fn size(m: MapSize) -> String {
    format!("{} x {}", m.width, m.height)
}

fn depth(f: DepthFormat) -> &'static str {
    match f {
        DepthFormat::D16 => "16-bit depth",
        DepthFormat::D24 => "24-bit depth",
        DepthFormat::D32F => "32-bit float depth",
    }
}

/// What the filter does to each shaded pixel's test.
fn filter(f: Filter) -> &'static str {
    f.facts().words
}

/// The shadow cache's counters, each said with what it counts.
pub fn cache(passes: DepthPasses, mask: MaskUses) -> Vec<String> {
    vec![
        format!(
            "Shadow maps: {} drawn whole, {} patched (redrawn only where casters moved), {} \
             reused (nothing changed)",
            passes.drawn, passes.patched, passes.skipped
        ),
        format!(
            "Frames whose shadow tests were read from the saved mask (camera and lights \
             still): {}",
            mask.read
        ),
    ]
}
