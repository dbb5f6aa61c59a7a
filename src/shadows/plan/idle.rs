//! Settings that are legal but do nothing: for one light ([`of_light`]), and for every
//! light of a scene ([`of_scene`], what the commands warn about when a flag gives one).

use crate::scene::Light;
use crate::settings::{
    Filter, Fit, LightProjection, MomentKnob, ShadowSettings, ShadowTechnique, Volumetric,
};
use crate::shadows::volumetric::method;
use crate::shadows::ShadowKind;
use crate::shadows::ShadowTest;

use super::LightPlan;

/// A setting that does nothing, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Idle {
    /// As the scene file names it (`cascades`, `point_pass`, ...).
    pub setting: &'static str,
    pub why: String,
}

impl Idle {
    fn new(setting: &'static str, why: impl Into<String>) -> Idle {
        Idle {
            setting,
            why: why.into(),
        }
    }
}

/// The settings a map's storage, test and pass read: nothing when there is no map.
const MAP_SETTINGS: [&str; 17] = [
    "map_size",
    "depth_format",
    "cascades",
    "caster_groups",
    "filter",
    "depth_lookup",
    "bias_mode",
    "bias",
    "bias_min",
    "normal_offset",
    "wrap",
    "beyond_far",
    "cull",
    "polygon_offset",
    "point_pass",
    "shadow_cache",
    "show_depth_map",
];

/// Why `depth_lookup` does nothing for a light whose shadow is `kind` under `filter`, if
/// it does nothing: only a single 2D depth map read by a shader's own lookups takes it.
fn depth_lookup_idle(kind: ShadowKind, filter: Filter) -> Option<&'static str> {
    match kind {
        ShadowKind::Map if filter.hardware() => Some(
            "the hardware filters compare in the sampler, which filters LINEAR whatever it says",
        ),
        ShadowKind::Map => None,
        ShadowKind::Moments => {
            Some("a moment map is always read LINEAR (its filtering is the filter)")
        }
        ShadowKind::Cube => {
            Some("it is for a 2D depth map; a point light's cube map is read NEAREST")
        }
        // (No map at all: `of_light` says so first.)
        ShadowKind::Cascades | ShadowKind::Groups | ShadowKind::None | ShadowKind::Volume => {
            Some("it is for one 2D depth map; cascades and caster groups are read NEAREST")
        }
    }
}

/// Whether a light's box is snapped to texels: an orthographic one fitted or layered.
fn snapped(s: &ShadowSettings) -> bool {
    s.light_projection == LightProjection::Ortho
        && (s.fit == Fit::Scene || s.cascades > 1 || s.caster_groups > 1)
}

/// The settings that do nothing for `light`, whose shadow is `kind` under `s`.
pub(super) fn of_light(light: &Light, kind: ShadowKind, s: &ShadowSettings) -> Vec<Idle> {
    let mut idle = Vec::new();
    let none = match kind {
        ShadowKind::None if !light.casts_shadows() => Some("the light casts no shadow"),
        ShadowKind::None => Some("shadows are off"),
        ShadowKind::Volume => Some("the light has shadow volumes, which have no map"),
        ShadowKind::Map | ShadowKind::Moments | ShadowKind::Cube => None,
        ShadowKind::Cascades | ShadowKind::Groups => None,
    };
    if let Some(why) = none {
        idle.extend(MAP_SETTINGS.iter().map(|n| Idle::new(n, why)));
    }
    let directional = matches!(light, Light::Directional(_));
    let layers = |what: &str| {
        if !directional {
            format!("only a directional light has {what}")
        } else if s.light_projection == LightProjection::Perspective {
            format!("{what} need an orthographic light projection")
        } else {
            format!("only the first casting directional light gets {what}; this one keeps one map")
        }
    };
    let mut push = |name: &'static str, why: String| push_once(&mut idle, name, why);
    if s.cascades > 1 && kind != ShadowKind::Cascades {
        push("cascades", layers("cascades"));
    }
    if s.caster_groups > 1 && kind != ShadowKind::Groups {
        push("caster_groups", layers("caster groups"));
    }
    if kind != ShadowKind::Cube {
        push(
            "point_pass",
            "only a point light's cube map has faces to draw".into(),
        );
    }
    if !(directional && s.light_projection == LightProjection::Perspective) {
        push(
            "perspective_fov",
            "only a directional light with a perspective projection uses it".into(),
        );
    }
    if !linear_depth_can_apply(light, kind, s) {
        push(
            "perspective_depth",
            "only a perspective depth map stores it (a spot light's, a directional light's \
             perspective one), and not with pcss"
                .into(),
        );
    }
    if !(directional && snapped(s)) || none.is_some() {
        push("snap", "the light's box is not fitted or cascaded".into());
    }
    if none.is_none() {
        if let Some(why) = depth_lookup_idle(kind, s.filter) {
            push("depth_lookup", why.into());
        }
    }
    let filter = (none.is_none()).then_some(s.filter);
    if filter != Some(Filter::Pcss) {
        for name in ["pcss_blocker_taps", "pcss_filter_taps"] {
            push(name, "only the pcss filter takes its counts".into());
        }
    }
    for knob in MomentKnob::ALL {
        let reads = kind == ShadowKind::Moments && filter.is_some_and(|f| knob.read_by(f));
        if !reads {
            let which = knob.readers();
            for name in knob.settings() {
                push(name, format!("it is for {which}, on a 2D map"));
            }
        }
    }
    volumetric_idle(kind, s, &mut idle);
    idle
}

/// The light's idle settings of shadow volumes and translucent casters.
fn volumetric_idle(kind: ShadowKind, s: &ShadowSettings, idle: &mut Vec<Idle>) {
    if kind != ShadowKind::Volume {
        push_once(
            idle,
            "show_volumes",
            "the light has no shadow volumes".into(),
        );
    }
    if !(kind == ShadowKind::Map && method(s.volumetric).is_some()) {
        push_once(
            idle,
            "volumetric_size",
            "only a 2D depth map with volumetric = \"osm\", \"fom\" or \"avsm\" keeps a \
             translucent map"
                .into(),
        );
        push_once(idle, "opaque_receivers", NO_MAP_TO_RESOLVE.into());
    }
    if !vertex_capable(kind, s) {
        push_once(idle, "translucent_receivers", no_vertex_test());
    }
    for (name, technique) in VOLUMETRIC_KNOBS {
        if !(kind == ShadowKind::Map && s.volumetric == technique) {
            let value = technique.name();
            push_once(
                idle,
                name,
                format!("only a 2D depth map with volumetric = \"{value}\" reads it"),
            );
        }
    }
}

/// Adds `name` as idle for `why` unless it already is.
fn push_once(idle: &mut Vec<Idle>, name: &'static str, why: String) {
    if !idle.iter().any(|i| i.setting == name) {
        idle.push(Idle::new(name, why));
    }
}

/// The translucent maps' counts, each with the technique that reads it.
const VOLUMETRIC_KNOBS: [(&str, Volumetric); 4] = [
    ("osm_slices", Volumetric::Osm),
    ("fom_coefficients", Volumetric::Fom),
    ("avsm_nodes", Volumetric::Avsm),
    ("peel_layers", Volumetric::Avsm),
];

/// Whether `perspective_depth` decides what light's map stores: a perspective depth map
/// (not with PCSS: [`crate::shadows::map2d::stores_linear_depth`]).
fn linear_depth_can_apply(light: &Light, kind: ShadowKind, s: &ShadowSettings) -> bool {
    let perspective = match light {
        Light::Spot(_) => true,
        Light::Directional(_) => s.light_projection == LightProjection::Perspective,
        Light::Point(_) => false,
    };
    kind == ShadowKind::Map && perspective && s.filter != Filter::Pcss
}

/// The settings that do nothing for any of `lights` (planned as `plans`) under the scene's
/// `settings`, each with the reason as a command's warning gives it.
pub(super) fn of_scene(
    lights: &[Light],
    settings: &ShadowSettings,
    plans: &[LightPlan],
) -> Vec<Idle> {
    let has = |k: ShadowKind| plans.iter().any(|p| p.kind == k);
    // The casting directional lights, each under its own settings.
    let suns: Vec<&ShadowSettings> = lights
        .iter()
        .zip(plans)
        .filter(|(l, _)| l.casts_shadows() && matches!(l, Light::Directional(_)))
        .map(|(_, p)| &p.settings)
        .collect();
    let mut idle = Vec::new();
    if settings.cascades > 1 && !has(ShadowKind::Cascades) {
        idle.push(Idle::new(
            "cascades",
            no_layers(settings, !suns.is_empty(), "cascades"),
        ));
    }
    if settings.caster_groups > 1 && !has(ShadowKind::Groups) {
        let why = no_layers(settings, !suns.is_empty(), "caster groups");
        idle.push(Idle::new("caster_groups", why));
    }
    if !has(ShadowKind::Cube) {
        idle.push(Idle::new(
            "point_pass",
            "no point light casts shadows in this scene; it says how a cube map's faces are \
             drawn",
        ));
    }
    if !suns
        .iter()
        .any(|s| s.light_projection == LightProjection::Perspective)
    {
        idle.push(Idle::new(
            "perspective_fov",
            "no directional light has a perspective projection (--light-projection \
             perspective); spot lights use their own fov",
        ));
    }
    let pcss = lights
        .iter()
        .zip(plans)
        .any(|(l, p)| l.casts_shadows() && p.settings.filter == Filter::Pcss);
    if !pcss {
        for name in ["pcss_blocker_taps", "pcss_filter_taps"] {
            idle.push(Idle::new(
                name,
                "no light's filter is pcss (--filter pcss); only PCSS takes its counts",
            ));
        }
    }
    let perspective_maps = lights
        .iter()
        .zip(plans)
        .any(|(l, p)| linear_depth_can_apply(l, p.kind, &p.settings));
    if !perspective_maps {
        idle.push(Idle::new(
            "perspective_depth",
            "no light has a perspective depth map (a spot light, or --light-projection \
             perspective) without pcss; it says what such a map stores",
        ));
    }
    if !suns.iter().any(|s| snapped(s)) {
        idle.push(Idle::new(
            "snap",
            "no light's box is fitted (--fit scene) or cascaded, so there is nothing to snap",
        ));
    }
    let lookups = plans
        .iter()
        .any(|p| depth_lookup_idle(p.kind, p.settings.filter).is_none());
    if !lookups {
        idle.push(Idle::new(
            "depth_lookup",
            "no light has a 2D depth map read by the shader's own lookups (hardware and moment \
             filters, cube maps, cascades and caster groups filter on their own)",
        ));
    }
    of_scene_volumetric(settings, plans, &mut idle);
    of_scene_maps(plans, &mut idle);
    idle
}

/// The scene's idle settings of translucent casters: no light keeps such a map, or none
/// can test translucent receivers per vertex.
fn of_scene_volumetric(settings: &ShadowSettings, plans: &[LightPlan], idle: &mut Vec<Idle>) {
    for (name, technique) in VOLUMETRIC_KNOBS {
        if !plans.iter().any(|p| p.volumetric == Some(technique)) {
            let value = technique.name();
            let why = format!(
                "no light keeps a translucent map with volumetric = \"{value}\" (--volumetric \
                 {value}, on a directional or spot light's 2D map)"
            );
            idle.push(Idle::new(name, why));
        }
    }
    if !plans.iter().any(|p| p.volumetric.is_some()) {
        idle.push(Idle::new("volumetric_size", no_translucent_map(settings)));
        let why = format!("no light's translucent map to resolve: {NO_MAP_TO_RESOLVE}");
        idle.push(Idle::new("opaque_receivers", why));
    }
    if !plans.iter().any(|p| vertex_capable(p.kind, &p.settings)) {
        let why = format!("no light's test can run per vertex: {}", no_vertex_test());
        idle.push(Idle::new("translucent_receivers", why));
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

/// Why `opaque_receivers` does nothing for a light.
const NO_MAP_TO_RESOLVE: &str = "only a 2D depth map with volumetric = \"osm\", \"fom\" or \
     \"avsm\" keeps a translucent map (--volumetric osm, fom or avsm, on a directional or spot \
     light)";

/// Why `translucent_receivers` does nothing for a light, naming the filters whose test
/// reads the pixel itself (their kernel's `per_pixel`, or a summed-area table's box).
fn no_vertex_test() -> String {
    use clap::ValueEnum;
    let per_pixel = |f: &&Filter| {
        let facts = f.facts();
        facts.kernel.glsl().per_pixel || facts.moments.is_some_and(|m| m.reads_table())
    };
    let names: Vec<&str> = (Filter::value_variants().iter())
        .filter(per_pixel)
        .map(|f| f.name())
        .collect();
    format!(
        "only a 2D depth or moment map's test runs per vertex, and not one that reads the \
         pixel itself ({}: its screen derivatives or its position)",
        names.join(", ")
    )
}

/// Whether a light whose shadow is `kind` under `s` can take its test per vertex.
fn vertex_capable(kind: ShadowKind, s: &ShadowSettings) -> bool {
    ShadowTest::of(s).runs_per_vertex(kind)
}

/// Why `translucent_receivers` does nothing in a scene with no translucent item.
pub const NO_TRANSLUCENT_RECEIVER: &str =
    "the scene has no translucent item (opacity below 1): every receiver is opaque and \
     tested per pixel";

/// Why `volumetric_size` does nothing in a scene with no translucent caster.
pub const NO_TRANSLUCENT_CASTER: &str =
    "the scene has no translucent caster (an item with opacity below 1): the translucent map \
     stays empty";

impl super::ShadowPlan {
    /// The scene's idle settings ([`super::ShadowPlan::idle`]) and those its items make
    /// idle: `volumetric_size` without a translucent caster, `translucent_receivers`
    /// without a translucent item (the plan sees the lights alone).
    pub fn idle_in(&self, scene: &crate::scene::Scene) -> Vec<Idle> {
        let mut idle = self.idle.clone();
        let casters = crate::shadows::volumetric::translucent_casters(scene).next();
        if casters.is_none() && !idle.iter().any(|i| i.setting == "volumetric_size") {
            idle.push(Idle::new("volumetric_size", NO_TRANSLUCENT_CASTER));
            idle.push(Idle::new("opaque_receivers", NO_TRANSLUCENT_CASTER));
        }
        if !scene.items.iter().any(|i| i.is_translucent()) {
            idle.retain(|i| i.setting != "translucent_receivers");
            idle.push(Idle::new("translucent_receivers", NO_TRANSLUCENT_RECEIVER));
        }
        idle
    }
}

/// Why a directional light's layers (`what`: cascades, caster groups) are not drawn under
/// the scene's `settings`; `suns`: some directional light casts.
fn no_layers(settings: &ShadowSettings, suns: bool, what: &str) -> String {
    if !settings.shadows {
        "shadows are off (--shadows off)".to_string()
    } else if settings.technique == ShadowTechnique::Volumes {
        "the lights have shadow volumes (--technique volumes), which have no map".to_string()
    } else if !suns {
        format!(
            "no directional light casts shadows in this scene, and only one gets {what}; each \
             light keeps one map"
        )
    } else if settings.light_projection == LightProjection::Perspective {
        format!(
            "{what} need an orthographic light projection (--light-projection perspective is \
             set); the light keeps one map"
        )
    } else if what != "cascades" && settings.cascades > 1 {
        "cascades are set (--cascades), and a light has cascades or caster groups, not both"
            .to_string()
    } else {
        format!("the directional light's own shadow table gives it no {what}")
    }
}

/// The scene's idle settings that depend on its maps: every map setting without a map,
/// the moment maps' knobs without a filter that reads them, `show_volumes` without volumes.
fn of_scene_maps(plans: &[LightPlan], idle: &mut Vec<Idle>) {
    let has = |k: ShadowKind| plans.iter().any(|p| p.kind == k);
    let volumes = has(ShadowKind::Volume);
    let maps = plans
        .iter()
        .any(|p| !matches!(p.kind, ShadowKind::None | ShadowKind::Volume));
    if volumes && !maps {
        for name in MAP_SETTINGS {
            if !idle.iter().any(|i| i.setting == name) {
                idle.push(Idle::new(
                    name,
                    "every casting light has shadow volumes (technique = volumes): there is no \
                     map to size, test or draw",
                ));
            }
        }
    }
    let moment_filters: Vec<Filter> = plans
        .iter()
        .filter(|p| p.kind == ShadowKind::Moments)
        .map(|p| p.settings.filter)
        .collect();
    for knob in MomentKnob::ALL {
        if !moment_filters.iter().any(|f| knob.read_by(*f)) {
            let which = knob.readers();
            for name in knob.settings() {
                idle.push(Idle::new(
                    name,
                    format!("no light's filter reads it (it is for {which}, on a 2D map)"),
                ));
            }
        }
    }
    if !volumes {
        idle.push(Idle::new(
            "show_volumes",
            "no light has shadow volumes (--technique volumes): there are none to show",
        ));
    }
}

/// `settings` with each of `idle` set back to its default.
pub(super) fn defaults_for(settings: &ShadowSettings, idle: &[Idle]) -> ShadowSettings {
    let (Ok(serde_json::Value::Object(mut used)), Ok(serde_json::Value::Object(base))) = (
        serde_json::to_value(settings),
        serde_json::to_value(ShadowSettings::default()),
    ) else {
        return *settings;
    };
    for i in idle {
        if let Some(v) = base.get(i.setting) {
            used.insert(i.setting.to_string(), v.clone());
        }
    }
    serde_json::from_value(serde_json::Value::Object(used)).unwrap_or(*settings)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use crate::shadows::plan::ShadowPlan;

    fn why(idle: &[Idle], setting: &str) -> Option<String> {
        idle.iter()
            .find(|i| i.setting == setting)
            .map(|i| i.why.clone())
    }

    #[test]
    fn volumetric_size_is_idle_without_a_translucent_map_or_caster() {
        let smoke = Scene::load("smoke").unwrap();
        let with = |v: Volumetric| ShadowSettings {
            volumetric: v,
            ..smoke.shadow
        };
        // The smoke's own `off`, and `solid`: no translucent map.
        for v in [Volumetric::Off, Volumetric::Solid] {
            let plan = ShadowPlan::decide(&smoke.lights, &with(v));
            let expected = format!(
                "volumetric = \"{}\" keeps no translucent map to size (--volumetric osm, fom \
                 or avsm keep one)",
                v.name()
            );
            assert_eq!(
                why(&plan.idle_in(&smoke), "volumetric_size"),
                Some(expected)
            );
            assert_eq!(
                why(&plan.lights[0].idle, "volumetric_size").as_deref(),
                Some(
                    "only a 2D depth map with volumetric = \"osm\", \"fom\" or \"avsm\" \
                     keeps a translucent map"
                )
            );
        }
        // A map over translucent casters: it acts.
        for v in [Volumetric::Osm, Volumetric::Fom, Volumetric::Avsm] {
            let plan = ShadowPlan::decide(&smoke.lights, &with(v));
            assert_eq!(why(&plan.idle_in(&smoke), "volumetric_size"), None, "{v:?}");
            assert_eq!(why(&plan.lights[0].idle, "volumetric_size"), None, "{v:?}");
        }
        // A map with nothing translucent to cast: the DummyGame.
        let dummy = Scene::load("dummy").unwrap();
        let osm = ShadowSettings {
            volumetric: Volumetric::Osm,
            ..dummy.shadow
        };
        let plan = ShadowPlan::decide(&dummy.lights, &osm);
        assert_eq!(why(&plan.idle, "volumetric_size"), None);
        assert_eq!(
            why(&plan.idle_in(&dummy), "volumetric_size").as_deref(),
            Some(
                "the scene has no translucent caster (an item with opacity below 1): the \
                 translucent map stays empty"
            )
        );
        // Shadows off: no map at all.
        let off = ShadowSettings {
            shadows: false,
            ..osm
        };
        let plan = ShadowPlan::decide(&smoke.lights, &off);
        assert_eq!(
            why(&plan.idle, "volumetric_size").as_deref(),
            Some("no light keeps a translucent map (one beside a directional or spot light's 2D map)")
        );
    }
}
