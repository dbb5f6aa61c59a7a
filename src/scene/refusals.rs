//! What a light cannot be drawn with, as plain rules over the lights and the settings: the
//! scene loader refuses a file by them, naming the field, and the shadow plan
//! (`shadows::plan`, which decides each light's shadow) refuses settings by them before
//! any frame. Here, below the shadows, so that loading a scene can use them.

use super::light::{DirectionalLight, Light, BOOK_ANGLES_MAX_X};
use crate::settings::{
    filter_names, DirectionalLayers, Filter, Fit, LightProjection, LightView, ShadowSettings,
    ShadowTechnique, Volumetric,
};

/// Why a light cannot be drawn with its settings: the setting, and the message (which
/// starts `shadow.NAME = VALUE: `).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refusal {
    pub light: usize,
    /// The setting refused, as the scene file names it (`filter`, `map_size`, ...).
    pub setting: &'static str,
    pub message: String,
}

/// The settings `light`'s shadow uses: `scene`'s with its own table on top.
pub fn own_settings(light: &Light, scene: &ShadowSettings) -> ShadowSettings {
    let mut s = *scene;
    light.shadow_patch().apply_to(&mut s);
    s
}

/// The layers (cascades, caster groups) a light asks for under its own `settings`: a
/// casting directional light with shadow maps.
pub fn layers_asked(light: &Light, settings: &ShadowSettings) -> Option<DirectionalLayers> {
    match light {
        Light::Directional(_)
            if light.casts_shadows()
                && settings.shadows
                && settings.technique == ShadowTechnique::Maps =>
        {
            settings.directional_layers()
        }
        Light::Directional(_) | Light::Spot(_) | Light::Point(_) => None,
    }
}

/// Which of `lights` gets its map split into layers under the scene's `settings` (each
/// light's own table on top): the first that asks for them. One light's positions in
/// every layer fit among GL 3.3's vertex outputs; the others keep one map.
pub fn layered_light(lights: &[Light], settings: &ShadowSettings) -> Option<usize> {
    lights
        .iter()
        .position(|l| layers_asked(l, &own_settings(l, settings)).is_some())
}

/// The first light of `lights` (light `i` named `name(i)`) that cannot be drawn under the
/// scene's `settings` with its own table on top, and why.
pub fn check(
    lights: &[Light],
    settings: &ShadowSettings,
    name: impl Fn(usize) -> String,
) -> Result<(), Refusal> {
    let layered = layered_light(lights, settings);
    for (i, light) in lights.iter().enumerate() {
        let own = own_settings(light, settings);
        let layers = layers_asked(light, &own).filter(|_| layered == Some(i));
        if let Some((setting, message)) = refusal(light, &name(i), &own, layers) {
            return Err(Refusal {
                light: i,
                setting,
                message,
            });
        }
    }
    Ok(())
}

/// What is wrong with drawing `light` (named `name`) under its own `settings`, if
/// anything: the setting and the message, which starts with it (`shadow.NAME = VALUE:
/// ...`). `layers`: the layers its map is split into ([`layered_light`]).
fn refusal(
    light: &Light,
    name: &str,
    settings: &ShadowSettings,
    layers: Option<DirectionalLayers>,
) -> Option<(&'static str, String)> {
    if !light.casts_shadows() {
        return None;
    }
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
    if let Some(why) = volumetric_refusal(settings, cube, layers.is_some()) {
        let value = settings.volumetric.name();
        let message = format!("shadow.volumetric = {value}: {name} cannot use it: {why}");
        return Some(("volumetric", message));
    }
    let what = match light {
        Light::Point(_) => "a point light's cube map",
        Light::Directional(_) | Light::Spot(_) => match layers? {
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

/// Why a light cannot cast its translucent items by `settings.volumetric`, if it cannot:
/// the techniques draw into one 2D depth map, with the box given by hand.
pub fn volumetric_refusal(settings: &ShadowSettings, cube: bool, layered: bool) -> Option<String> {
    if settings.volumetric == Volumetric::Off {
        return None;
    }
    if settings.technique == ShadowTechnique::Volumes {
        return Some(
            "shadow volumes cast opaque silhouettes only; expected technique = \"maps\""
                .to_string(),
        );
    }
    if cube {
        return Some("a point light's cube map takes volumetric = \"off\" only".to_string());
    }
    if layered {
        return Some(
            "cascades and caster groups take volumetric = \"off\" only; use cascades = 1 and \
             caster_groups = 1"
                .to_string(),
        );
    }
    if settings.filter.moments() {
        return Some(moments_without_volumetric(settings.filter));
    }
    if settings.fit != Fit::Manual {
        return Some(
            "a fitted box is fitted to the opaque casters only; expected fit = \"manual\""
                .to_string(),
        );
    }
    None
}

/// Why a light whose maps are moments cannot keep a translucent map beside them.
fn moments_without_volumetric(filter: Filter) -> String {
    match filter.facts().moments.is_some_and(|m| m.reads_table()) {
        true => format!(
            "the soft moment filters ({}) take volumetric = \"off\" only",
            filter_names(&Filter::SOFT_MOMENTS, false)
        ),
        false => format!(
            "the moment maps ({}) take volumetric = \"off\" only",
            filter_names(&Filter::MOMENTS, false)
        ),
    }
}

/// Why a light whose shadow is a cube map (`cube`) or layers (`layered`: cascades, caster
/// groups) cannot use `filter`, if it cannot: the soft filters read a 2D texel grid, which
/// a cube map has not; PCSS needs one light camera per map, which layers have not (each
/// has its own box); the moment maps need one 2D map.
pub fn filter_refusal(filter: Filter, cube: bool, layered: bool) -> Option<String> {
    let facts = filter.facts();
    let why = match (cube, layered) {
        (true, _) => facts.on_cube,
        (false, true) => facts.on_layers,
        (false, false) => None,
    };
    why.map(|why| why())
}
