//! The one place that decides each light's shadow: which kind it gets ([`ShadowKind`]),
//! under which settings (its own `shadow` table over the scene's), which settings do
//! nothing for it, and whether it can be drawn at all. Resolved once, before any frame
//! (when a renderer is made, when the settings or the lights change); the renderer, the
//! commands' warnings, the HUD, the bench and the steps read the plan rather than asking
//! again.

mod idle;

use crate::error::{Error, Result};
use crate::scene::light::BOOK_ANGLES_MAX_X;
use crate::scene::{DirectionalLight, Light};
use crate::settings::{
    DirectionalLayers, Filter, Fit, LightProjection, LightView, ShadowSettings, ShadowTechnique,
};

use super::ShadowKind;

pub use idle::Idle;

/// One light's part of the plan.
#[derive(Debug, Clone, PartialEq)]
pub struct LightPlan {
    pub kind: ShadowKind,
    /// The settings its shadow uses: the scene's with the light's own table on top.
    pub settings: ShadowSettings,
    /// Settings that do nothing for this light, each with the reason.
    pub idle: Vec<Idle>,
}

impl LightPlan {
    /// Whether `setting` (as the scene file names it) does nothing for this light.
    pub fn is_idle(&self, setting: &str) -> bool {
        self.idle.iter().any(|i| i.setting == setting)
    }
}

/// Why a light cannot be drawn with its settings: the setting, and the message (which
/// starts `shadow.NAME = VALUE: `).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refusal {
    pub light: usize,
    /// The setting refused, as the scene file names it (`filter`, `map_size`, ...).
    pub setting: &'static str,
    pub message: String,
}

/// What the plan was resolved for, light by light: what a light's shadow depends on
/// besides the settings, compared each frame without formatting or allocating.
#[derive(Debug, Clone, Copy, PartialEq)]
struct LightShape {
    kind: std::mem::Discriminant<Light>,
    casts: bool,
    own: crate::settings::ShadowPatch,
    /// A directional light off the YZ plane (the book's angles cannot build its view).
    off_yz: bool,
}

impl LightShape {
    fn of(light: &Light) -> LightShape {
        LightShape {
            kind: std::mem::discriminant(light),
            casts: light.casts_shadows(),
            own: *light.shadow_patch(),
            off_yz: light
                .as_directional()
                .is_some_and(|l| l.direction.normalize().x.abs() > BOOK_ANGLES_MAX_X),
        }
    }
}

/// Every light's shadow, decided.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ShadowPlan {
    /// One per scene light, in the scene's order.
    pub lights: Vec<LightPlan>,
    /// The settings that do nothing for any light of the scene, with the reason (what the
    /// commands warn about).
    pub idle: Vec<Idle>,
    /// The scene's settings it was resolved for.
    scene: ShadowSettings,
    shapes: Vec<LightShape>,
}

impl ShadowPlan {
    /// Decides and checks every light's shadow under the scene's `settings`; refuses what
    /// cannot be drawn, naming light `i` "light i". With `max_texture_size` (a driver is
    /// there), a light's own table is checked against it too.
    pub fn resolve(
        lights: &[Light],
        settings: &ShadowSettings,
        max_texture_size: Option<u32>,
    ) -> Result<ShadowPlan> {
        let plan = ShadowPlan::resolve_named(lights, settings, |i| format!("light {i}"))
            .map_err(|r| Error::Invalid(r.message))?;
        if let Some(max) = max_texture_size {
            for (i, (light, own)) in lights.iter().zip(&plan.lights).enumerate() {
                if !light.shadow_patch().given().is_empty() {
                    own.settings.validate(max).map_err(|e| {
                        Error::Invalid(format!("light {i}'s own shadow table: {e}"))
                    })?;
                }
            }
        }
        Ok(plan)
    }

    /// [`ShadowPlan::resolve`] without the driver, naming light `i` as `name(i)` in a
    /// refusal (a scene file says `lights[1]`).
    pub fn resolve_named(
        lights: &[Light],
        settings: &ShadowSettings,
        name: impl Fn(usize) -> String,
    ) -> std::result::Result<ShadowPlan, Refusal> {
        let plan = ShadowPlan::decide(lights, settings);
        for (i, (light, own)) in lights.iter().zip(&plan.lights).enumerate() {
            if let Some((setting, message)) = refusal(light, &name(i), own) {
                return Err(Refusal {
                    light: i,
                    setting,
                    message,
                });
            }
        }
        Ok(plan)
    }

    /// The decisions alone, without refusing anything: each light's kind and settings
    /// (what a light that is refused would get, were it drawn).
    pub fn decide(lights: &[Light], settings: &ShadowSettings) -> ShadowPlan {
        let own: Vec<ShadowSettings> = lights.iter().map(|l| own_settings(l, settings)).collect();
        // One light's positions in every layer fit among GL 3.3's vertex outputs: only the
        // first that asks gets its layers, the others keep one map.
        let layered = lights
            .iter()
            .zip(&own)
            .position(|(l, s)| layers_asked(l, s).is_some());
        let kinds = lights
            .iter()
            .zip(&own)
            .enumerate()
            .map(|(i, (l, s))| match kind_alone(l, s) {
                kind if kind.layered() && layered != Some(i) => one_map(s),
                kind => kind,
            });
        let lights_plan: Vec<LightPlan> = kinds
            .zip(&own)
            .zip(lights)
            .map(|((kind, s), light)| LightPlan {
                kind,
                settings: *s,
                idle: idle::of_light(light, kind, s),
            })
            .collect();
        ShadowPlan {
            idle: idle::of_scene(lights, settings, &lights_plan),
            lights: lights_plan,
            scene: *settings,
            shapes: lights.iter().map(LightShape::of).collect(),
        }
    }

    /// Whether the plan still stands for `lights` under `settings` (cheap: compares, no
    /// formatting, no allocation; a light that moves keeps its plan).
    pub fn fits(&self, lights: &[Light], settings: &ShadowSettings) -> bool {
        self.scene == *settings
            && self.shapes.len() == lights.len()
            && self
                .shapes
                .iter()
                .zip(lights)
                .all(|(s, l)| *s == LightShape::of(l))
    }

    /// The scene's settings it was resolved for.
    pub fn scene_settings(&self) -> &ShadowSettings {
        &self.scene
    }

    /// Each light's kind, in the scene's order.
    pub fn kinds(&self) -> Vec<ShadowKind> {
        self.lights.iter().map(|l| l.kind).collect()
    }

    /// Whether some light's shadow is of `kind`.
    pub fn has(&self, kind: ShadowKind) -> bool {
        self.lights.iter().any(|l| l.kind == kind)
    }

    /// The scene's settings as they act on its lights: those that do nothing set back to
    /// their defaults, so a summary says what is used (no "4 cascades" for a point light).
    pub fn in_use(&self) -> ShadowSettings {
        idle::defaults_for(&self.scene, &self.idle)
    }
}

/// The settings `light`'s shadow uses: `scene`'s with its own table on top.
pub fn own_settings(light: &Light, scene: &ShadowSettings) -> ShadowSettings {
    let mut s = *scene;
    light.shadow_patch().apply_to(&mut s);
    s
}

/// The layers (cascades, caster groups) a light asks for under its own `settings`: a
/// casting directional light with shadow maps.
fn layers_asked(light: &Light, settings: &ShadowSettings) -> Option<DirectionalLayers> {
    match light {
        Light::Directional(_)
            if light.casts_shadows()
                && settings.shadows
                && settings.technique == ShadowTechnique::Maps =>
        {
            settings.directional_layers()
        }
        _ => None,
    }
}

/// The kind a light gets under its own `settings`, alone in its scene.
fn kind_alone(light: &Light, settings: &ShadowSettings) -> ShadowKind {
    match light {
        l if !l.casts_shadows() || !settings.shadows => ShadowKind::None,
        _ if settings.technique == ShadowTechnique::Volumes => ShadowKind::Volume,
        Light::Point(_) => ShadowKind::Cube,
        Light::Directional(_) => match settings.directional_layers() {
            Some(DirectionalLayers::Cascades) => ShadowKind::Cascades,
            Some(DirectionalLayers::CasterGroups) => ShadowKind::Groups,
            None => one_map(settings),
        },
        Light::Spot(_) => one_map(settings),
    }
}

/// The kind of one 2D map under `settings`: a depth map, or with a moment filter a moment
/// map.
fn one_map(settings: &ShadowSettings) -> ShadowKind {
    match settings.filter.moments() {
        true => ShadowKind::Moments,
        false => ShadowKind::Map,
    }
}

/// What is wrong with drawing `light` (named `name`) as `plan` says, if anything: the
/// setting and the message, which starts with it (`shadow.NAME = VALUE: ...`).
fn refusal(light: &Light, name: &str, plan: &LightPlan) -> Option<(&'static str, String)> {
    if !light.casts_shadows() {
        return None;
    }
    let settings = &plan.settings;
    let layers = match plan.kind {
        ShadowKind::Cascades => Some(DirectionalLayers::Cascades),
        ShadowKind::Groups => Some(DirectionalLayers::CasterGroups),
        _ => None,
    };
    if let Light::Directional(l) = light {
        if let Some(problem) = book_angles_problem(l, name, settings, layers.is_some()) {
            return Some(("light_view", format!("shadow.light_view = {problem}")));
        }
    }
    let cube = matches!(light, Light::Point(_));
    if let Some(why) = filter_refusal(settings.filter, cube, layers.is_some()) {
        return Some((
            "filter",
            format!(
                "shadow.filter = {}: {name} cannot use it: {why}",
                settings.filter.name()
            ),
        ));
    }
    let what = match light {
        Light::Point(_) => "a point light's cube map",
        _ => match layers? {
            DirectionalLayers::Cascades => "cascades",
            DirectionalLayers::CasterGroups => "caster groups",
        },
    };
    let size = settings.map_size;
    (!size.is_square()).then(|| {
        let message = format!(
            "shadow.map_size = {size}: {name} has {what}, which needs a square map; expected \
             one number, like {}",
            size.max_side()
        );
        ("map_size", message)
    })
}

/// Why the book's angle view cannot stand for `light` (`name` names it), if `settings`
/// would build its view that way ("Shadows": rotation x = acos(dir.z), y = asin(dir.x)):
/// its direction has an x component, and the angles would turn the map away from the
/// light without a word. `layered`: its map is split into layers, whose boxes build their
/// own views.
fn book_angles_problem(
    light: &DirectionalLight,
    name: &str,
    settings: &ShadowSettings,
    layered: bool,
) -> Option<String> {
    let uses_angles = settings.light_view == LightView::BookAngles
        && settings.light_projection == LightProjection::Ortho
        && settings.fit == Fit::Manual
        && !layered
        && light.casts_shadows;
    let d = light.direction.normalize();
    (uses_angles && d.x.abs() > BOOK_ANGLES_MAX_X).then(|| {
        format!(
            "\"book-angles\" cannot build the view of {name} (direction [{:.3}, {:.3}, {:.3}]): \
             the book's angles (acos z, asin x) are right only for directions in the YZ \
             plane (|x| <= {BOOK_ANGLES_MAX_X:e}); expected \"look-at\" for this light",
            d.x, d.y, d.z
        )
    })
}

/// Why a light whose shadow is a cube map (`cube`) or layers (`layered`: cascades, caster
/// groups) cannot use `filter`, if it cannot: the soft filters read a 2D texel grid, which
/// a cube map has not; PCSS needs one light camera per map, which layers have not (each
/// has its own box); the moment maps need one 2D map.
pub fn filter_refusal(filter: Filter, cube: bool, layered: bool) -> Option<&'static str> {
    match filter {
        Filter::Pcf4x4Weighted | Filter::SoftPcf | Filter::Pcss if cube => Some(
            "a point light's cube map takes single, pcf3x3, pcf5x5, hw2x2 or hw3x3 (the soft \
             filters read a 2D map's texel grid)",
        ),
        Filter::Pcss if layered => Some(
            "cascades and caster groups take every filter but pcss (its penumbra is measured \
             in one light camera's units, and each layer has its own box)",
        ),
        Filter::Vsm | Filter::Evsm2 | Filter::Evsm4 | Filter::Msm if cube => Some(
            "the moment maps (vsm, evsm2, evsm4, msm) need one 2D map and a point light's \
             shadow is a cube map; give the light a depth filter of its own (shadow = { \
             filter = \"pcf3x3\" }) or use one for the scene",
        ),
        Filter::Vsm | Filter::Evsm2 | Filter::Evsm4 | Filter::Msm if layered => Some(
            "the moment maps (vsm, evsm2, evsm4, msm) need one 2D map and cascades and caster \
             groups have a layer each; use cascades = 1 and caster_groups = 1, or a depth \
             filter (pcf3x3) for the light",
        ),
        _ => None,
    }
}

#[cfg(test)]
mod tests;
