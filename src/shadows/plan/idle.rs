//! Settings that are legal but do nothing: for one light ([`of_light`]), and for every
//! light of a scene ([`of_scene`], what the commands warn about when a flag gives one).

use clap::ValueEnum;

use crate::scene::Light;
use crate::settings::{Exclusive, Filter, Fit, LightProjection, ShadowSettings};
pub use crate::shadows::kind::Idle;
use crate::shadows::kind::{Idles, LightIdle, PlannedLight, SceneIdle, MAP_SETTINGS};
use crate::shadows::ShadowKind;
use crate::shadows::ShadowTest;

use super::LightPlan;

/// Whether a light's box is snapped to texels: an orthographic one fitted or layered.
fn snapped(s: &ShadowSettings) -> bool {
    s.light_projection == LightProjection::Ortho
        && (s.fit == Fit::Scene || s.cascades > 1 || s.caster_groups > 1)
}

/// The settings that do nothing for `light`, whose shadow is `kind` under `s`: those every
/// light's filter and camera read, then each kind's own ([`crate::shadows::kind::IdleRules`]).
pub(super) fn of_light(light: &Light, kind: ShadowKind, s: &ShadowSettings) -> Vec<Idle> {
    let mut idle = Idles::default();
    let rules = &kind.facts().idle;
    let none = rules.no_map.map(|why| why(light));
    if let Some(why) = none {
        MAP_SETTINGS.iter().for_each(|n| idle.push(n, why));
    }
    let directional = matches!(light, Light::Directional(_));
    if !(directional && s.light_projection == LightProjection::Perspective) {
        idle.push(
            "perspective_fov",
            "only a directional light with a perspective projection uses it",
        );
    }
    if !(directional && snapped(s)) || none.is_some() {
        idle.push("snap", "the light's box is not fitted or cascaded");
    }
    if let Some(why) = (rules.depth_lookup)(s.filter).filter(|_| none.is_none()) {
        idle.push("depth_lookup", why);
    }
    for f in Filter::value_variants() {
        let Exclusive { names, what } = f.facts().exclusive;
        if !names.is_empty() && (none.is_some() || s.filter != *f) {
            let why = format!("only the {} filter takes {what}", f.name());
            names.iter().for_each(|n| idle.push(n, why.clone()));
        }
    }
    if !vertex_capable(kind, s) {
        idle.push("translucent_receivers", no_vertex_test());
    }
    let view = LightIdle {
        light,
        kind,
        settings: s,
    };
    for k in ShadowKind::ALL {
        (k.facts().idle.light)(&view, &mut idle);
    }
    idle.0
}

/// The settings that do nothing for any of `lights` (planned as `plans`) under the scene's
/// `settings`, each with the reason as a command's warning gives it.
pub(super) fn of_scene(
    lights: &[Light],
    settings: &ShadowSettings,
    plans: &[LightPlan],
) -> Vec<Idle> {
    let view = SceneIdle {
        settings,
        lights: (lights.iter().zip(plans))
            .map(|(light, p)| PlannedLight {
                light,
                kind: p.kind,
                settings: &p.settings,
                volumetric: p.volumetric,
            })
            .collect(),
    };
    let mut idle = Idles::default();
    if !view
        .suns()
        .any(|s| s.light_projection == LightProjection::Perspective)
    {
        idle.push(
            "perspective_fov",
            "no directional light has a perspective projection (--light-projection \
             perspective); spot lights use their own fov",
        );
    }
    for f in Filter::value_variants() {
        let Exclusive { names, what } = f.facts().exclusive;
        let used = (view.lights.iter()).any(|l| l.light.casts_shadows() && l.settings.filter == *f);
        if !used && !names.is_empty() {
            let name = f.name();
            let why = format!(
                "no light's filter is {name} (--filter {name}), the only one that takes {what}"
            );
            names.iter().for_each(|n| idle.push(n, why.clone()));
        }
    }
    if !view.suns().any(snapped) {
        idle.push(
            "snap",
            "no light's box is fitted (--fit scene) or cascaded, so there is nothing to snap",
        );
    }
    let lookups = (view.lights.iter())
        .any(|l| (l.kind.facts().idle.depth_lookup)(l.settings.filter).is_none());
    if !lookups {
        idle.push(
            "depth_lookup",
            "no light has a 2D depth map read by the shader's own lookups (hardware and moment \
             filters, cube maps, cascades and caster groups filter on their own)",
        );
    }
    if !(view.lights.iter()).any(|l| vertex_capable(l.kind, l.settings)) {
        let why = format!("no light's test can run per vertex: {}", no_vertex_test());
        idle.push("translucent_receivers", why);
    }
    for k in ShadowKind::ALL {
        (k.facts().idle.scene)(&view, &mut idle);
    }
    idle.0
}

/// Why `translucent_receivers` does nothing for a light, naming the filters whose test
/// reads the pixel itself (their kernel's `per_pixel`, or a summed-area table's box).
fn no_vertex_test() -> String {
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
        let mut idle = Idles(self.idle.clone());
        if crate::shadows::volumetric::translucent_casters(scene)
            .next()
            .is_none()
        {
            idle.push("volumetric_size", NO_TRANSLUCENT_CASTER);
            idle.push("opaque_receivers", NO_TRANSLUCENT_CASTER);
        }
        if !scene.items.iter().any(|i| i.is_translucent()) {
            idle.0.retain(|i| i.setting != "translucent_receivers");
            idle.push("translucent_receivers", NO_TRANSLUCENT_RECEIVER);
        }
        idle.0
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
    use crate::settings::Volumetric;
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
