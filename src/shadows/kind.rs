//! What a kind of shadow is, beside its technique's code: one row per kind
//! ([`KindFacts`]), kept in the technique's own file and gathered by
//! [`super::ShadowKind::facts`]. The plan's idle rules, the HUD, the memory check, the
//! cache, the vertex test and the bench read the rows; none of them matches on a kind.

use crate::engine::Gl;
use crate::error::Result;
use crate::scene::Light;
use crate::settings::{DepthFormat, Filter, MapSize, ShadowSettings, Volumetric};

use super::{LightGlsl, ShadowKind, ShadowTest, Technique};

/// One kind's row: the one table a new technique joins.
pub struct KindFacts {
    /// The technique that stores and tests it (none: a light without a map).
    pub technique: Option<TechniqueFacts>,
    /// What the HUD says of the light's shadow ("Shadow: one 2048 x 2048 depth map, ...").
    pub words: fn(&ShadowSettings) -> String,
    /// The storage its map needs, sized before it is made (none: no map).
    pub storage: fn(&ShadowSettings) -> Option<Storage>,
    /// Whether its light camera moves with the view camera (a box fitted to what the
    /// camera sees: the cache keys such a map on the camera too).
    pub follows_camera: fn(&Light, &ShadowSettings) -> bool,
    /// A layered light's layers, as the scene program is compiled for them (none: one map).
    pub layers: Option<fn(&ShadowSettings) -> LayerLayout>,
    /// Whether its test can run in a vertex shader (translucent receivers per vertex).
    pub per_vertex: fn(&ShadowTest) -> bool,
    /// The bench's family of configurations it falls in.
    pub family: fn(&ShadowSettings) -> Family,
    /// Which settings do nothing for it, and why.
    pub idle: IdleRules,
}

/// A layered light's constants in the scene program (shaders/lib/shadow_layers.glsl).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct LayerLayout {
    pub count: u32,
    /// The blend between layers (cascades').
    pub blend_bits: u32,
    /// Whether each layer is tinted (`show_cascades`).
    pub show: bool,
}

/// A technique's entries in its kind's row.
pub struct TechniqueFacts {
    pub create: fn(&Gl, &ShadowSettings) -> Result<Box<dyn Technique>>,
    pub glsl: fn(usize, usize, &ShadowTest) -> Option<LightGlsl>,
    pub samplers: &'static [&'static str; crate::scene::MAX_LIGHTS],
    /// Whether the vertex shader gives the light a light-space position.
    pub map_slot: bool,
}

/// A kind's idle rules: the settings that do nothing for a light of it, and those only it
/// reads (which do nothing for a light of any other kind, or in a scene without it).
pub struct IdleRules {
    /// Why a light of this kind keeps no map, if it keeps none: then every one of
    /// [`MAP_SETTINGS`] does nothing.
    pub no_map: Option<fn(&Light) -> &'static str>,
    /// Why `depth_lookup` does nothing for a light of this kind under a filter.
    pub depth_lookup: fn(Filter) -> Option<&'static str>,
    /// Its own settings that do nothing for one light (of any kind: [`LightIdle::kind`]).
    pub light: fn(&LightIdle, &mut Idles),
    /// Its own settings that do nothing for every light of a scene.
    pub scene: fn(&SceneIdle, &mut Idles),
}

/// A setting that does nothing, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Idle {
    /// As the scene file names it (`cascades`, `point_pass`, ...).
    pub setting: &'static str,
    pub why: String,
}

/// The idle settings found so far, each once.
#[derive(Debug, Default)]
pub struct Idles(pub Vec<Idle>);

impl Idles {
    /// Adds `setting` as idle for `why` unless it already is.
    pub fn push(&mut self, setting: &'static str, why: impl Into<String>) {
        if !self.has(setting) {
            self.0.push(Idle {
                setting,
                why: why.into(),
            });
        }
    }

    pub fn has(&self, setting: &str) -> bool {
        self.0.iter().any(|i| i.setting == setting)
    }
}

/// One light, as a kind's idle rules see it.
pub struct LightIdle<'a> {
    pub light: &'a Light,
    /// The light's own kind (a rule asks whether it is the rule's).
    pub kind: ShadowKind,
    pub settings: &'a ShadowSettings,
}

/// One light of a scene, planned.
pub struct PlannedLight<'a> {
    pub light: &'a Light,
    pub kind: ShadowKind,
    pub settings: &'a ShadowSettings,
    /// The translucent map it keeps beside its 2D map, if any.
    pub volumetric: Option<Volumetric>,
}

/// Every light of a scene, as a kind's idle rules see them.
pub struct SceneIdle<'a> {
    /// The scene's settings, before each light's own.
    pub settings: &'a ShadowSettings,
    pub lights: Vec<PlannedLight<'a>>,
}

impl SceneIdle<'_> {
    /// Whether some light's shadow is of `kind`.
    pub fn has(&self, kind: ShadowKind) -> bool {
        self.lights.iter().any(|l| l.kind == kind)
    }

    /// The casting directional lights' settings.
    pub fn suns(&self) -> impl Iterator<Item = &ShadowSettings> {
        (self.lights.iter())
            .filter(|l| l.light.casts_shadows() && matches!(l.light, Light::Directional(_)))
            .map(|l| l.settings)
    }
}

/// The settings a map's storage, test and pass read: nothing when there is no map.
pub const MAP_SETTINGS: [&str; 17] = [
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

/// One light's shadow storage, sized before it is made.
#[derive(Debug, Clone, PartialEq)]
pub struct Storage {
    /// What it is, naming the settings that size it ("shadow.cascades = 4 layers of
    /// 16384 x 16384").
    pub what: String,
    /// Its bytes: its depth texels, or its moment maps and their depth buffer.
    pub bytes: u64,
}

/// A depth texel's bytes on the drivers this runs on, whatever the format asks (see
/// [`Technique::bytes`]).
pub const DEPTH_TEXEL_BYTES: u64 = 4;

/// A map's sides as the HUD and the messages say them: "2048 x 2048".
pub fn sides(m: MapSize) -> String {
    format!("{} x {}", m.width, m.height)
}

/// A depth format as the HUD says it.
pub fn depth_words(f: DepthFormat) -> &'static str {
    match f {
        DepthFormat::D16 => "16-bit depth",
        DepthFormat::D24 => "24-bit depth",
        DepthFormat::D32F => "32-bit float depth",
    }
}

/// What kind of shadow a bench configuration draws, for the plot's series and the tables
/// (each kind's row says which is its).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Family {
    /// One 2D map (the chapters).
    OneMap,
    /// A directional light's cascades.
    Cascades,
    /// A directional light's box per group of casters (`caster_groups`).
    Groups,
    /// A point light's cube map drawn in one layered pass.
    PointLayered,
    /// A point light's cube map drawn face by face.
    PointSixPasses,
    /// Stencil shadow volumes (no map).
    Volumes,
    /// One 2D map read through a soft filter (the playground's, PCSS).
    Soft,
}

/// The row of a light that casts no shadow (or of any light with shadows off).
pub const NO_SHADOW: KindFacts = KindFacts {
    technique: None,
    words: |s| match s.shadows {
        false => "Shadows: off".to_string(),
        true => "Shadow: none (this light casts no shadow)".to_string(),
    },
    storage: |_| None,
    follows_camera: |_, _| false,
    layers: None,
    per_vertex: |_| false,
    family: |_| Family::OneMap,
    idle: IdleRules {
        no_map: Some(|light| match light.casts_shadows() {
            false => "the light casts no shadow",
            true => "shadows are off",
        }),
        depth_lookup: |_| Some(LAYERS_READ_NEAREST),
        light: |_, _| {},
        scene: |_, _| {},
    },
};

/// Why `depth_lookup` does nothing for cascades and caster groups. The rows without a map
/// give it too, though a light without a map never shows it: its map settings are all idle
/// for having no map first.
pub const LAYERS_READ_NEAREST: &str =
    "it is for one 2D depth map; cascades and caster groups are read NEAREST";

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// How many variants src/shadows/mod.rs declares `ShadowKind` with.
    fn declared_kinds() -> usize {
        let source = include_str!("mod.rs");
        let body = source.split("pub enum ShadowKind {").nth(1).unwrap();
        let body = body.split("\n}").next().unwrap();
        (body.lines().map(str::trim))
            .filter(|l| !l.is_empty() && !l.starts_with("//"))
            .count()
    }

    #[test]
    fn every_kind_is_in_the_list_once_and_its_row_agrees_with_itself() {
        assert_eq!(ShadowKind::ALL.len(), declared_kinds(), "ShadowKind::ALL");
        let s = Scene::load("dummy").unwrap().shadow;
        let test = ShadowTest::of(&s);
        for (i, kind) in ShadowKind::ALL.into_iter().enumerate() {
            assert!(!ShadowKind::ALL[..i].contains(&kind), "{kind:?} twice");
            let facts = kind.facts();
            let map = kind.has_map();
            // A kind keeps a map exactly when it has storage and no reason for having none.
            assert_eq!((facts.storage)(&s).is_some(), map, "{kind:?}");
            assert_eq!(facts.idle.no_map.is_none(), map, "{kind:?}");
            // Layers, a vertex test and a depth-map lookup need a map.
            assert!(map || facts.layers.is_none(), "{kind:?}");
            assert!(map || !(facts.per_vertex)(&test), "{kind:?}");
            assert!(
                map || (facts.idle.depth_lookup)(s.filter).is_some(),
                "{kind:?}"
            );
            assert_eq!(kind.layered(), facts.layers.is_some(), "{kind:?}");
        }
    }

    #[test]
    fn a_setting_only_one_kind_reads_is_idle_for_the_others() {
        let scene = Scene::load("dummy").unwrap();
        let light = &scene.lights[0];
        let s = ShadowSettings {
            cascades: 4,
            caster_groups: 3,
            filter: Filter::Vsm,
            volumetric: Volumetric::Osm,
            ..scene.shadow
        };
        let idle_for = |kind: ShadowKind| {
            let view = LightIdle {
                light,
                kind,
                settings: &s,
            };
            let mut idle = Idles::default();
            for k in ShadowKind::ALL {
                (k.facts().idle.light)(&view, &mut idle);
            }
            idle
        };
        let owners = [
            ("cascades", ShadowKind::Cascades),
            ("caster_groups", ShadowKind::Groups),
            ("point_pass", ShadowKind::Cube),
            ("show_volumes", ShadowKind::Volume),
            ("blur", ShadowKind::Moments),
            ("min_variance", ShadowKind::Moments),
            ("osm_slices", ShadowKind::Map),
            ("volumetric_size", ShadowKind::Map),
        ];
        for kind in ShadowKind::ALL {
            let idle = idle_for(kind);
            for (setting, owner) in owners {
                assert_eq!(idle.has(setting), kind != owner, "{setting} for {kind:?}");
            }
        }
        let why = |setting: &str| {
            let idle = idle_for(ShadowKind::Map);
            idle.0
                .into_iter()
                .find(|i| i.setting == setting)
                .unwrap()
                .why
        };
        assert_eq!(
            why("point_pass"),
            "only a point light's cube map has faces to draw"
        );
        assert_eq!(
            why("cascades"),
            "only the first casting directional light gets cascades; this one keeps one map"
        );
    }
}
