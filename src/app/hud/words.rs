//! A light's shadow and the shadow cache's counters in plain words, for the HUD: what a
//! student reads beside the chapters ("24-bit depth", not "24").

use shadowmap::renderer::{DepthPasses, MaskUses};
use shadowmap::settings::{BiasMode, Cull, Filter};
use shadowmap::shadows::plan::LightPlan;

/// The light's technique, its filter and its bias, a line each (one line without a map).
pub fn shadow(light: &LightPlan) -> Vec<String> {
    let s = &light.settings;
    let technique = (light.kind.facts().words)(s);
    if !light.kind.has_map() {
        return vec![technique];
    }
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
