//! The translucent maps' idle settings: a map's size and its resolve do nothing without a
//! technique that keeps one beside a 2D depth map, and each technique's counts
//! ([`super::Method::settings`]) without that technique.

use clap::ValueEnum;

use super::method;
use crate::settings::{ShadowSettings, Volumetric};
use crate::shadows::kind::{Idles, LightIdle, SceneIdle};
use crate::shadows::ShadowKind;

/// Why `opaque_receivers` does nothing for a light.
const NO_MAP_TO_RESOLVE: &str = "only a 2D depth map with volumetric = \"osm\", \"fom\" or \
     \"avsm\" keeps a translucent map (--volumetric osm, fom or avsm, on a directional or spot \
     light)";

/// The techniques that keep a map, each with its own settings.
fn kept() -> impl Iterator<Item = (Volumetric, &'static [&'static str])> {
    (Volumetric::value_variants().iter()).filter_map(|v| method(*v).map(|m| (*v, m.settings())))
}

/// The settings of translucent maps that do nothing for light `v`.
pub fn of_light(v: &LightIdle, idle: &mut Idles) {
    let s = v.settings;
    let map = v.kind == ShadowKind::Map;
    if !(map && method(s.volumetric).is_some()) {
        idle.push(
            "volumetric_size",
            "only a 2D depth map with volumetric = \"osm\", \"fom\" or \"avsm\" keeps a \
             translucent map",
        );
        idle.push("opaque_receivers", NO_MAP_TO_RESOLVE);
    }
    for (technique, names) in kept() {
        if !(map && s.volumetric == technique) {
            let value = technique.name();
            for name in names {
                idle.push(
                    name,
                    format!("only a 2D depth map with volumetric = \"{value}\" reads it"),
                );
            }
        }
    }
}

/// The settings of translucent maps that do nothing for every light of scene `v`.
pub fn of_scene(v: &SceneIdle, idle: &mut Idles) {
    for (technique, names) in kept() {
        if !v.lights.iter().any(|l| l.volumetric == Some(technique)) {
            let value = technique.name();
            let why = format!(
                "no light keeps a translucent map with volumetric = \"{value}\" (--volumetric \
                 {value}, on a directional or spot light's 2D map)"
            );
            for name in names {
                idle.push(name, why.clone());
            }
        }
    }
    if !v.lights.iter().any(|l| l.volumetric.is_some()) {
        idle.push("volumetric_size", no_translucent_map(v.settings));
        let why = format!("no light's translucent map to resolve: {NO_MAP_TO_RESOLVE}");
        idle.push("opaque_receivers", why);
    }
}

/// Why no light keeps a translucent map under the scene's `settings`.
fn no_translucent_map(settings: &ShadowSettings) -> String {
    match method(settings.volumetric) {
        None => format!(
            "volumetric = \"{}\" keeps no translucent map to size (--volumetric osm, fom or \
             avsm keep one)",
            settings.volumetric.name()
        ),
        Some(_) => "no light keeps a translucent map (one beside a directional or spot light's \
                    2D map)"
            .to_string(),
    }
}
