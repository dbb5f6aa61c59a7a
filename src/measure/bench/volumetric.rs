//! The bench's rows for translucent casters: on a scene with translucent items, every
//! `--volumetric` choice on the scene's own settings, timed as the sweep's rows are
//! ([`super::run`]) and scored against the transmittance truth, with the translucent
//! map's bytes a texel and passes a frame.

use clap::ValueEnum;

use super::{BenchConfig, BenchRow, BiasPreset, Family};
use crate::scene::Scene;
use crate::settings::{ShadowSettings, Volumetric};
use crate::shadows::plan::ShadowPlan;
use crate::shadows::volumetric::{method, translucent_casters};

/// Every `--volumetric` choice the scene's lights can take, on `base`; none for a scene
/// without translucent casters.
pub fn configs(scene: &Scene, base: &ShadowSettings) -> Vec<BenchConfig> {
    if translucent_casters(scene).next().is_none() {
        return Vec::new();
    }
    Volumetric::value_variants()
        .iter()
        .map(|&volumetric| ShadowSettings {
            volumetric,
            ..*base
        })
        .filter(|s| ShadowPlan::resolve(&scene.lights, s, None).is_ok())
        .map(|settings| BenchConfig {
            settings,
            bias_preset: BiasPreset::None,
            tutorial: None,
            family: Family::OneMap,
        })
        .collect()
}

/// The translucent map's count (slices, terms, nodes), bytes a texel and passes a frame
/// under `settings`: zeros for `off` and `solid`, which keep none.
pub fn map_cost(settings: &ShadowSettings) -> (u32, u32, u32) {
    match method(settings.volumetric) {
        Some(m) => {
            let (bytes, passes) = m.cost(settings);
            (m.parameter(settings), bytes, passes)
        }
        None => (0, 0, 0),
    }
}

/// The rows as a Markdown table, with each row's shadow overhead against `off`'s (the
/// scene's opaque shadow map alone).
pub fn to_markdown(rows: &[BenchRow]) -> String {
    let mut out = String::from(
        "| volumetric | count | map bytes / texel | map passes | wall ms (median) | shadow \
         overhead ms | overhead / off's | transmittance MAE | within the translucent shadow \
         | max error |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let off = rows
        .iter()
        .find(|r| r.config.settings.volumetric == Volumetric::Off)
        .map(|r| r.overhead_ms);
    for r in rows {
        let s = &r.config.settings;
        let (count, bytes, passes) = map_cost(s);
        let ratio = off
            .filter(|o| *o > 0.0)
            .map_or("n/a".into(), |o| format!("{:.2}", r.overhead_ms / o));
        let t = r.transmittance;
        let f = |v: Option<f64>| v.map_or("n/a".into(), |v| format!("{v:.4}"));
        out.push_str(&format!(
            "| {} | {} | {bytes} | {passes} | {:.2} | {:.2} | {ratio} | {} | {} | {} |\n",
            s.volumetric.name(),
            if count == 0 {
                "-".into()
            } else {
                count.to_string()
            },
            r.wall_ms.median,
            r.overhead_ms,
            f(t.map(|t| t.mae)),
            f(t.map(|t| t.mae_in_shadow)),
            f(t.map(|t| t.max_error)),
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_smoke_scene_benches_every_choice_and_a_scene_without_translucent_items_none() {
        let smoke = Scene::load("smoke").unwrap();
        let names: Vec<&str> = configs(&smoke, &smoke.shadow)
            .iter()
            .map(|c| c.settings.volumetric.name())
            .collect();
        let all: Vec<&str> = Volumetric::value_variants()
            .iter()
            .map(|v| v.name())
            .collect();
        assert_eq!(names, all);
        let dummy = Scene::load("dummy").unwrap();
        assert!(configs(&dummy, &dummy.shadow).is_empty());
        let osm = ShadowSettings {
            volumetric: Volumetric::Osm,
            ..smoke.shadow
        };
        assert_eq!(map_cost(&osm), (16, 64, 1));
        assert_eq!(map_cost(&smoke.shadow), (0, 0, 0));
    }
}
