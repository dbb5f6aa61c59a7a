//! The one place that decides each light's shadow: which kind it gets ([`ShadowKind`]),
//! under which settings (its own `shadow` table over the scene's), which settings do
//! nothing for it, and whether it can be drawn at all. Resolved once, before any frame
//! (when a renderer is made, when the settings or the lights change); the renderer, the
//! commands' warnings, the HUD, the bench and the steps read the plan rather than asking
//! again. What is refused follows the rules of `scene::refusals`, which the scene loader
//! also reads (it sits below the shadows).

mod idle;

use crate::error::{Error, Result};
use crate::scene::light::BOOK_ANGLES_MAX_X;
use crate::scene::refusals::{self, layered_light};
use crate::scene::Light;
use crate::settings::{DirectionalLayers, ShadowSettings, ShadowTechnique, Volumetric};

use super::ShadowKind;

pub use crate::scene::refusals::{filter_refusal, own_settings, Refusal};
pub use idle::Idle;

/// One light's part of the plan.
#[derive(Debug, Clone, PartialEq)]
pub struct LightPlan {
    pub kind: ShadowKind,
    /// The settings its shadow uses: the scene's with the light's own table on top.
    pub settings: ShadowSettings,
    /// Settings that do nothing for this light, each with the reason.
    pub idle: Vec<Idle>,
    /// The technique of its translucent map beside its depth map, if it keeps one
    /// (`volumetric = "osm"` or `"fom"` on a light with one 2D depth map; the map's depth
    /// is fitted to the translucent casters each frame: `shadows::volumetric::DepthFit`).
    pub volumetric: Option<Volumetric>,
}

impl LightPlan {
    /// Whether `setting` (as the scene file names it) does nothing for this light.
    pub fn is_idle(&self, setting: &str) -> bool {
        self.idle.iter().any(|i| i.setting == setting)
    }
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
        refusals::check(lights, settings, name)?;
        Ok(ShadowPlan::decide(lights, settings))
    }

    /// The decisions alone, without refusing anything: each light's kind and settings
    /// (what a light that is refused would get, were it drawn).
    pub fn decide(lights: &[Light], settings: &ShadowSettings) -> ShadowPlan {
        let own: Vec<ShadowSettings> = lights.iter().map(|l| own_settings(l, settings)).collect();
        // Only the first light that asks gets its layers; the others keep one map.
        let layered = layered_light(lights, settings);
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
                volumetric: translucent_map(kind, s),
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

/// The technique of the translucent map a light of `kind` keeps under its `settings`, if
/// any: one beside a 2D depth map (the refusals turn the others down by name).
fn translucent_map(kind: ShadowKind, settings: &ShadowSettings) -> Option<Volumetric> {
    let keeps = kind == ShadowKind::Map && super::volumetric::method(settings.volumetric).is_some();
    keeps.then_some(settings.volumetric)
}

/// The kind of one 2D map under `settings`: a depth map, or with a moment filter a moment
/// map.
fn one_map(settings: &ShadowSettings) -> ShadowKind {
    match settings.filter.moments() {
        true => ShadowKind::Moments,
        false => ShadowKind::Map,
    }
}

#[cfg(test)]
mod tests;
