//! The plan's decisions on the built-in scenes and on lights built to hit each rule.

use super::*;
use crate::scene::Scene;
use crate::settings::{Filter, LightView, MapSize};

fn scene(name: &str) -> Scene {
    Scene::load(name).unwrap()
}

fn with(s: &ShadowSettings, change: impl Fn(&mut ShadowSettings)) -> ShadowSettings {
    let mut s = *s;
    change(&mut s);
    s
}

fn idle_why<'a>(idle: &'a [Idle], setting: &str) -> Option<&'a str> {
    idle.iter()
        .find(|i| i.setting == setting)
        .map(|i| i.why.as_str())
}

#[test]
fn a_point_light_refuses_a_moment_filter_naming_the_setting_and_the_light() {
    let point = scene("point-shadows");
    let vsm = with(&point.shadow, |s| s.filter = Filter::Vsm);
    let e = ShadowPlan::resolve(&point.lights, &vsm, None).unwrap_err();
    assert_eq!(
        e.to_string(),
        "shadow.filter = vsm: light 0 cannot use it: the moment maps (vsm, evsm2, evsm4, msm, esm) \
         need one 2D map and a point light's shadow is a cube map; give the light a depth \
         filter of its own (shadow = { filter = \"pcf3x3\" }) or use one for the scene"
    );
    let named = ShadowPlan::resolve_named(&point.lights, &vsm, |_| "lights[0]".into());
    let refused = named.unwrap_err();
    assert_eq!((refused.light, refused.setting), (0, "filter"));
    assert!(refused.message.contains("lights[0] cannot use it"));
    // The decision alone still says what it would be: a cube map.
    assert_eq!(
        ShadowPlan::decide(&point.lights, &vsm).kinds(),
        [ShadowKind::Cube]
    );
}

#[test]
fn only_the_first_casting_directional_light_gets_cascades() {
    let mut three = scene("three-lights");
    let sun = three.lights[0];
    let mut quiet = sun;
    if let Light::Directional(l) = &mut quiet {
        l.casts_shadows = false;
    }
    three.lights = vec![quiet, sun, sun, three.lights[1], three.lights[2]];
    let s = with(&three.shadow, |s| s.cascades = 4);
    let plan = ShadowPlan::resolve(&three.lights, &s, None).unwrap();
    let k = |i: usize| plan.lights[i].kind;
    assert_eq!(
        [k(0), k(1), k(2), k(3), k(4)],
        [
            ShadowKind::None,
            ShadowKind::Cascades,
            ShadowKind::Map,
            ShadowKind::Map,
            ShadowKind::Cube
        ]
    );
    assert!(!plan.lights[1].is_idle("cascades"));
    assert_eq!(
        idle_why(&plan.lights[2].idle, "cascades"),
        Some("only the first casting directional light gets cascades; this one keeps one map")
    );
    for spot_and_point in [3, 4] {
        assert_eq!(
            idle_why(&plan.lights[spot_and_point].idle, "cascades"),
            Some("only a directional light has cascades")
        );
    }
    assert_eq!(
        idle_why(&plan.lights[0].idle, "map_size"),
        Some("the light casts no shadow")
    );
    // Cascades are drawn by a light: not idle for the scene.
    assert_eq!(idle_why(&plan.idle, "cascades"), None);
    // PCSS is refused for the cascaded sun, yet the second sun keeps one map and takes it.
    let pcss = with(&s, |s| s.filter = Filter::Pcss);
    let e = ShadowPlan::resolve(&three.lights[1..3], &pcss, None).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("shadow.filter = pcss: light 0 cannot use it: cascades and caster"),
        "{e}"
    );
    let mut second_pcss = three.lights[1..3].to_vec();
    second_pcss[1].shadow_patch_mut().filter = Some(Filter::Pcss);
    assert!(ShadowPlan::resolve(&second_pcss, &s, None).is_ok());
}

#[test]
fn each_light_gets_its_own_table_over_the_scenes() {
    let mut three = scene("three-lights");
    three.lights[2].shadow_patch_mut().filter = Some(Filter::Pcf3x3);
    let vsm = with(&three.shadow, |s| s.filter = Filter::Vsm);
    let plan = ShadowPlan::resolve(&three.lights, &vsm, None).unwrap();
    let filters: Vec<Filter> = plan.lights.iter().map(|l| l.settings.filter).collect();
    assert_eq!(filters[..3], [Filter::Vsm, Filter::Vsm, Filter::Pcf3x3]);
    assert_eq!(plan.lights[2].kind, ShadowKind::Cube);
    assert_eq!(plan.lights[0].kind, ShadowKind::Moments);
    // The moment knobs are read by the moment maps, not by the cube map.
    assert!(!plan.lights[0].is_idle("blur"));
    assert_eq!(
        idle_why(&plan.lights[2].idle, "blur"),
        Some("it is for vsm, evsm2, evsm4, msm or esm, on a 2D map")
    );
    assert_eq!(idle_why(&plan.idle, "blur"), None);
}

#[test]
fn the_scene_idle_settings_give_the_commands_reasons_and_in_use_drops_them() {
    let point = scene("point-shadows");
    let s = with(&point.shadow, |s| {
        s.cascades = 4;
        s.pcss_filter_taps = 9;
    });
    let plan = ShadowPlan::resolve(&point.lights, &s, None).unwrap();
    assert_eq!(
        idle_why(&plan.idle, "cascades"),
        Some(
            "no directional light casts shadows in this scene, and only one gets cascades; \
             each light keeps one map"
        )
    );
    assert_eq!(
        idle_why(&plan.idle, "pcss_filter_taps"),
        Some("no light's filter is pcss (--filter pcss), the only one that takes its counts")
    );
    assert_eq!(idle_why(&plan.idle, "point_pass"), None);
    let used = plan.in_use();
    let defaults = ShadowSettings::default();
    assert_eq!(used.cascades, defaults.cascades);
    assert_eq!(used.pcss_filter_taps, defaults.pcss_filter_taps);
    assert_eq!(used.map_size, s.map_size);
    // Shadows off: every map setting idle for the light, with the reason.
    let off = with(&s, |s| s.shadows = false);
    let plan = ShadowPlan::resolve(&point.lights, &off, None).unwrap();
    assert_eq!(plan.kinds(), [ShadowKind::None]);
    assert_eq!(
        idle_why(&plan.lights[0].idle, "filter"),
        Some("shadows are off")
    );
    assert_eq!(
        idle_why(&plan.idle, "cascades"),
        Some("shadows are off (--shadows off)")
    );
}

#[test]
fn book_angles_are_refused_off_the_yz_plane_unless_layers_build_the_views() {
    let lo = scene("learnopengl");
    let angles = with(&lo.shadow, |s| s.light_view = LightView::BookAngles);
    let e = ShadowPlan::resolve(&lo.lights, &angles, None).unwrap_err();
    assert!(
        e.to_string().starts_with(
            "shadow.light_view = \"book-angles\" cannot build the view of light 0 (direction \
             [-0.436, 0.873, -0.218])"
        ),
        "{e}"
    );
    let cascaded = with(&angles, |s| s.cascades = 2);
    assert!(ShadowPlan::resolve(&lo.lights, &cascaded, None).is_ok());
    // The DummyGame's light turns in the YZ plane: the book's view is right for it.
    let dummy = scene("dummy");
    let book = with(&dummy.shadow, |s| s.light_view = LightView::BookAngles);
    assert!(ShadowPlan::resolve(&dummy.lights, &book, None).is_ok());
}

#[test]
fn square_maps_and_the_drivers_limit_are_checked_per_light() {
    let mut point = scene("point-shadows");
    let wide = with(&point.shadow, |s| {
        s.map_size = MapSize {
            width: 512,
            height: 256,
        }
    });
    let e = ShadowPlan::resolve(&point.lights, &wide, None).unwrap_err();
    assert_eq!(
        e.to_string(),
        "shadow.map_size = 512x256: light 0 has a point light's cube map, which needs a square \
         map; expected one number, like 512"
    );
    point.lights[0].shadow_patch_mut().map_size = Some(MapSize::square(8192));
    assert!(ShadowPlan::resolve(&point.lights, &point.shadow, None).is_ok());
    let e = ShadowPlan::resolve(&point.lights, &point.shadow, Some(4096)).unwrap_err();
    assert!(
        e.to_string().starts_with("light 0's own shadow table: "),
        "{e}"
    );
}

#[test]
fn the_plan_stands_until_the_settings_or_the_lights_shadows_change() {
    let mut dummy = scene("dummy");
    let plan = ShadowPlan::resolve(&dummy.lights, &dummy.shadow, None).unwrap();
    assert!(plan.fits(&dummy.lights, &dummy.shadow));
    // The light turning in its plane keeps the plan.
    assert!(dummy.set_light_angle(30.0));
    assert!(plan.fits(&dummy.lights, &dummy.shadow));
    let pcf = with(&dummy.shadow, |s| s.filter = Filter::Pcf5x5);
    assert!(!plan.fits(&dummy.lights, &pcf));
    let mut own = dummy.clone();
    own.lights[0].shadow_patch_mut().filter = Some(Filter::Pcf5x5);
    assert!(!plan.fits(&own.lights, &dummy.shadow));
    let mut off_plane = dummy.clone();
    if let Light::Directional(l) = &mut off_plane.lights[0] {
        l.direction.x = 0.5;
    }
    assert!(!plan.fits(&off_plane.lights, &dummy.shadow));
    let mut more = dummy.clone();
    more.lights.push(dummy.lights[0]);
    assert!(!plan.fits(&more.lights, &dummy.shadow));
}

#[test]
fn the_plan_gives_a_translucent_map_to_a_2d_depth_map_only() {
    let scene = Scene::load("smoke").unwrap();
    let with = |volumetric| ShadowSettings {
        volumetric,
        ..scene.shadow
    };
    let plan = |v| ShadowPlan::decide(&scene.lights, &with(v));
    assert_eq!(
        plan(Volumetric::Osm).lights[0].volumetric,
        Some(Volumetric::Osm)
    );
    assert_eq!(
        plan(Volumetric::Fom).lights[0].volumetric,
        Some(Volumetric::Fom)
    );
    assert_eq!(plan(Volumetric::Solid).lights[0].volumetric, None);
    assert_eq!(plan(Volumetric::Off).lights[0].volumetric, None);
    let cost = |v| {
        crate::shadows::volumetric::method(v)
            .unwrap()
            .cost(&with(v))
    };
    // 16 slices and 1 + 2 x 7 coefficients: four RGBA32F layers each, 64 bytes.
    assert_eq!(cost(Volumetric::Osm), (64, 1));
    assert_eq!(cost(Volumetric::Fom), (64, 1));
}
