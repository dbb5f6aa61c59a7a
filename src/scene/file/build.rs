//! Building the scene from the typed tables: what serde cannot check (ranges, relations
//! between fields, the lights' settings against their kind), each refusal naming its field.

use glam::Vec3;
use serde::de::value::MapDeserializer;
use serde::de::{self, Deserialize};
use toml::de::DeValue;
use toml::Spanned;

use super::items::Items;
use super::read::Context;
use super::{
    CameraFile, DirectionalFile, Fixed, LightKind, PointFile, SceneFile, SpotFile, StepsFile,
};
use crate::error::{Error, Result};
use crate::scene::refusals;
use crate::scene::{
    Camera, DirectionalLight, Light, OrthoCoords, PointLight, Scene, SpotLight, StepContext,
    MAX_LIGHTS,
};
use crate::settings::ShadowSettings;

pub(super) fn build(file: SceneFile, cx: &Context) -> Result<Scene> {
    check_globals(&file, cx)?;
    let camera = build_camera(&file.camera, "camera", cx)?;
    let lights = build_lights(&file, cx)?;
    check_light_settings(&lights, &file.shadow, cx)?;
    let steps = build_steps(&file.steps, &file.camera, cx)?;
    let (views, opening_view) = build_views(&file, cx)?;
    if let Some(size) = steps.light_size {
        if let Some(problem) = lights.iter().find_map(|l| l.size_problem(size)) {
            return Err(cx.bad("steps.light_size", problem));
        }
    }
    let mut items = Items::default();
    for (i, item) in file.items.into_iter().enumerate() {
        items.add(i, item, cx)?;
    }
    let motion = file.motion.keyframes;
    crate::scene::motion::check_keyframes(&motion).map_err(|(f, m)| cx.bad(f, m))?;
    let name = file.name.unwrap_or_else(|| {
        cx.source
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into())
    });
    Ok(Scene {
        source: cx.source.to_path_buf(),
        name,
        camera,
        lights,
        shading: file.shading,
        steps,
        fit_camera: None,
        views,
        opening_view,
        time: 0.0,
        motion_keyframes: motion,
        motion: None,
        ambient: Vec3::from(file.ambient.0),
        specular_power: file.specular_power,
        clear_colour: Vec3::from(file.clear_colour.0).extend(1.0),
        size: file.size.0,
        items: items.items,
        meshes: items.meshes,
        textures: items.textures,
        shadow: file.shadow,
    })
}

/// Each light's own shadow table over the scene's, then what a light cannot be drawn with
/// (the book's angle view off the YZ plane, which would say nothing; a non-square map for
/// a cube map or cascades): the setting named.
fn check_light_settings(lights: &[Light], shadow: &ShadowSettings, cx: &Context) -> Result<()> {
    // map_size is checked against the driver's maximum once there is a driver.
    shadow
        .validate_values()
        .map_err(|e| Error::file(cx.source, e.to_string()))?;
    let prefix = |i: usize| match lights.len() {
        1 => "light".to_string(),
        _ => format!("lights[{i}]"),
    };
    for (i, light) in lights.iter().enumerate() {
        if !light.shadow_patch().given().is_empty() {
            refusals::own_settings(light, shadow)
                .validate_values()
                .map_err(|e| cx.bad(format!("{}.shadow", prefix(i)), e.to_string()))?;
        }
    }
    if let Err(refused) = refusals::check(lights, shadow, prefix) {
        let own = lights[refused.light].shadow_patch();
        let given_by_light = match refused.setting {
            "light_view" => own.light_view.is_some(),
            "map_size" => own.map_size.is_some(),
            "filter" => own.filter.is_some(),
            _ => false,
        };
        let field = format!("{}.shadow.{}", prefix(refused.light), refused.setting);
        return Err(match given_by_light {
            true => cx.bad(field, refused.message),
            false => Error::file(cx.source, refused.message),
        });
    }
    Ok(())
}

/// The top-level numbers: frame size, colours, the specular power.
fn check_globals(file: &SceneFile, cx: &Context) -> Result<()> {
    let size = file.size.0;
    if size[0] == 0 || size[1] == 0 {
        return Err(cx.bad("size", format!("{size:?}: expected both sides at least 1")));
    }
    cx.non_negative("clear_colour", &file.clear_colour.0)?;
    cx.non_negative("ambient", &file.ambient.0)?;
    let p = file.specular_power;
    // GLSL's pow(0, p) is undefined for p <= 0, and a highlight needs p > 0 anyway.
    if !(p.is_finite() && p > 0.0) {
        return Err(cx.bad("specular_power", format!("{p}: expected a number > 0")));
    }
    Ok(())
}

/// A camera table (`table`: `camera`, or `steps.camera`), checked: angles or a target.
fn build_camera(c: &CameraFile, table: &str, cx: &Context) -> Result<Camera> {
    let d = Camera::default();
    let position = c.position.map_or(d.position, |p| Vec3::from(p.0));
    let (fov, near, far) = (
        c.fov.unwrap_or(d.fov),
        c.near.unwrap_or(d.near),
        c.far.unwrap_or(d.far),
    );
    let rotation = match (&c.rotation, &c.target) {
        (Some(_), Some(_)) => {
            return Err(cx.bad(
                table,
                "rotation and target are both given: a camera takes one (rotation = angles, \
                 target = a point to look at)",
            ))
        }
        (Some(r), None) => Vec3::from(r.0),
        (None, Some(t)) => {
            let target = Vec3::from(t.0);
            Camera::look_at(position, target)
                .ok_or_else(|| {
                    cx.bad(
                        format!("{table}.target"),
                        format!("{target}: the camera's own position; it must look somewhere else"),
                    )
                })?
                .rotation
        }
        (None, None) => Vec3::ZERO,
    };
    if !(near > 0.0 && near < far) {
        return Err(cx.bad(
            table,
            format!("near = {near}, far = {far}: expected 0 < near < far"),
        ));
    }
    if !(fov > 0.0 && fov < 180.0) {
        return Err(cx.bad(
            format!("{table}.fov"),
            format!("{fov}: expected degrees between 0 and 180"),
        ));
    }
    Ok(Camera {
        position,
        rotation,
        fov,
        near,
        far,
    })
}

/// Named cameras, in the file's order of names.
type Views = Vec<(String, Camera)>;

/// The named views (`[views]`, each over `[camera]`) and the one the commands open on
/// (`view`), which must be one of them.
fn build_views(file: &SceneFile, cx: &Context) -> Result<(Views, Option<String>)> {
    let mut views = Vec::new();
    for (name, c) in &file.views {
        let camera = build_camera(&c.over(&file.camera), &format!("views.{name}"), cx)?;
        views.push((name.clone(), camera));
    }
    if let Some(view) = &file.view {
        if !file.views.contains_key(view) {
            let names: Vec<&str> = file.views.keys().map(String::as_str).collect();
            return Err(cx.bad(
                "view",
                match names.is_empty() {
                    true => format!("\"{view}\": the file has no [views] table to name one of"),
                    false => format!("\"{view}\": expected one of [views]: {}", names.join(", ")),
                },
            ));
        }
    }
    Ok((views, file.view.clone()))
}

fn build_steps(s: &StepsFile, scene_camera: &CameraFile, cx: &Context) -> Result<StepContext> {
    // The steps' bias becomes `shadow.bias`: the same range.
    if let Some(problem) = crate::settings::bias_problem(s.bias) {
        return Err(cx.bad("steps.bias", problem));
    }
    let camera = match &s.camera {
        Some(c) => Some(build_camera(&c.over(scene_camera), "steps.camera", cx)?),
        None => None,
    };
    Ok(StepContext {
        bias: s.bias,
        start_wrap: s.start_wrap,
        camera,
        list: s.list,
        light_size: s.light_size,
    })
}

// ---------------------------------------------------------------------------------------
// Lights

fn build_lights(file: &SceneFile, cx: &Context) -> Result<Vec<Light>> {
    let root = cx.root.get_ref();
    match (&file.light, file.lights.len()) {
        (Some(_), 0) => Ok(vec![read_light(root.get("light"), "light", cx)?]),
        (None, 0) => Err(cx.bad(
            "light",
            format!("missing: expected a [light] table or one to {MAX_LIGHTS} [[lights]] tables"),
        )),
        (None, n) if n > MAX_LIGHTS => Err(cx.bad(
            "lights",
            format!(
                "{n} lights: expected at most {MAX_LIGHTS} (each has a texture unit and a \
                 block of the scene shader)"
            ),
        )),
        (None, n) => (0..n)
            .map(|i| {
                let value = root.get("lights").and_then(|l| l.get_ref().get(i));
                read_light(value, &format!("lights[{i}]"), cx)
            })
            .collect(),
        (Some(_), _) => Err(cx.bad(
            "light",
            "give either one [light] table or [[lights]] tables, not both",
        )),
    }
}

/// Reads the light `prefix` (`light` or `lights[i]`) from its table by its kind: each kind
/// is its own struct, so serde itself refuses what a kind does not take. Not serde's
/// `#[serde(tag = "kind")]`, which cannot default a missing tag to "directional" and
/// buffers the table, losing the positions and names of what it refuses.
fn read_light(value: Option<&Spanned<DeValue>>, prefix: &str, cx: &Context) -> Result<Light> {
    let value = value.ok_or_else(|| Error::Internal(format!("{prefix} is not in the document")))?;
    let kind = match value.get_ref().get("kind") {
        None => LightKind::Directional,
        Some(k) => match k.get_ref().as_str().and_then(LightKind::parse) {
            Some(kind) => kind,
            None => {
                let written = &cx.text[k.span()];
                return Err(cx.bad(
                    format!("{prefix}.kind"),
                    format!(
                        "{}: {written}: expected \"directional\" (the default), \"spot\" or \
                         \"point\"",
                        cx.at(k.span().start)
                    ),
                ));
            }
        },
    };
    let refused = |r| light_error(r, kind, prefix, cx);
    match kind {
        LightKind::Spot => spot(cx.read(value, prefix).map_err(refused)?, prefix, cx),
        LightKind::Point => point(cx.read(value, prefix).map_err(refused)?, prefix, cx),
        LightKind::Directional => {
            let l: DirectionalFile = cx.read(value, prefix).map_err(refused)?;
            if let (Some(angle), Some(at)) = (l.angle, value.get_ref().get("angle")) {
                check_angle(angle, at.span().start, prefix, cx)?;
            }
            directional(l, prefix, cx)
        }
    }
}

/// A key of the light's own table that its kind does not take, or lacks: said for the
/// kind, with what it takes; anything else as serde says it.
fn light_error(r: super::read::Refusal, kind: LightKind, prefix: &str, cx: &Context) -> Error {
    let name = kind.name();
    use super::read::backticked;
    let own =
        |problem| backticked(&r.message, problem).filter(|k| r.field == format!("{prefix}.{k}"));
    let at = r
        .span
        .as_ref()
        .map_or(String::new(), |s| format!("{}: ", cx.at(s.start)));
    if let Some(key) = own("unknown field `") {
        let fields = light_fields(kind);
        let takes = fields.join(", ");
        let guess = crate::settings::suggest::did_you_mean(key, fields.iter().map(String::as_str));
        let message = match LightKind::ALL
            .into_iter()
            .any(|k| light_fields(k).iter().any(|f| f == key))
        {
            true => format!("{at}not used by a {name} light; it takes {takes}"),
            false => match guess {
                Some(g) => format!("{at}unknown field `{key}`: did you mean `{g}`?"),
                None => format!("{at}unknown field; a {name} light takes {takes}"),
            },
        };
        return cx.bad(r.field.clone(), message);
    }
    if own("missing field `").is_some() {
        let line = r.span.as_ref().map_or(String::new(), |s| {
            format!(
                " (the table at line {})",
                super::read::line_col(cx.text, s.start).0
            )
        });
        return cx.bad(r.field.clone(), format!("a {name} light needs it{line}"));
    }
    r.error(cx)
}

/// The fields a light kind takes (`kind` first), as serde lists them when it refuses a key
/// none of them has: the list cannot go stale.
pub(super) fn light_fields(kind: LightKind) -> Vec<String> {
    let probe = || MapDeserializer::<_, de::value::Error>::new(std::iter::once(("", ())));
    let refused = match kind {
        LightKind::Spot => SpotFile::deserialize(probe()).err(),
        LightKind::Point => PointFile::deserialize(probe()).err(),
        LightKind::Directional => DirectionalFile::deserialize(probe()).err(),
    };
    let message = refused.map(|e| e.to_string()).unwrap_or_default();
    let list = message.split_once("expected one of").map_or("", |(_, l)| l);
    list.split('`')
        .skip(1)
        .step_by(2)
        .map(String::from)
        .collect()
}

/// A directional light's `angle` (at byte `at` of the file), refused by the rule and in
/// the words of `--light-angle`: 450 is not silently 90.
fn check_angle(angle: f32, at: usize, prefix: &str, cx: &Context) -> Result<()> {
    match DirectionalLight::angle_problem(angle) {
        Some(problem) => Err(cx.bad(
            format!("{prefix}.angle"),
            format!("{}: {problem}", cx.at(at)),
        )),
        None => Ok(()),
    }
}

/// Colour and intensity, checked alike for every kind.
fn light_colour(
    colour: &Fixed<f32, 3>,
    intensity: f32,
    prefix: &str,
    cx: &Context,
) -> Result<Vec3> {
    cx.non_negative(&format!("{prefix}.colour"), &colour.0)?;
    cx.non_negative(&format!("{prefix}.intensity"), &[intensity])?;
    Ok(Vec3::from(colour.0))
}

fn near_far(near: f32, far: f32, prefix: &str, cx: &Context) -> Result<()> {
    if !(near > 0.0 && near < far) {
        return Err(cx.bad(
            prefix,
            format!("near = {near}, far = {far}: expected 0 < near < far"),
        ));
    }
    Ok(())
}

fn directional(l: DirectionalFile, prefix: &str, cx: &Context) -> Result<Light> {
    let colour = light_colour(&l.colour, l.intensity, prefix, cx)?;
    let field = |name: &str| format!("{prefix}.{name}");
    let non_zero = |name: &str, v: Vec3| {
        v.try_normalize()
            .ok_or_else(|| cx.bad(field(name), format!("{v}: expected a non-zero vector")))
    };
    let position = l.position.map(|p| Vec3::from(p.0));
    let direction = match (l.angle, l.direction, position) {
        (Some(a), None, None) => DirectionalLight::direction_from_angle(a),
        (None, Some(d), None) => non_zero("direction", Vec3::from(d.0))?,
        (None, None, Some(p)) => non_zero("position", p)?,
        _ => {
            return Err(cx.bad(
                prefix,
                "expected exactly one of `angle` (degrees), `direction` ([x, y, z] towards \
                 the light) or `position` (a point the light shines from, towards the origin)",
            ))
        }
    };
    let shadow_pos_mult = match (l.shadow_pos_mult, position) {
        (Some(_), Some(_)) => {
            return Err(cx.bad(
                field("shadow_pos_mult"),
                "not used with `position` (the shadow camera sits at the position)",
            ))
        }
        (Some(m), None) => m,
        (None, Some(p)) => p.length(),
        (None, None) => 5.0,
    };
    // The distance to a far `position` can overflow f32.
    if !shadow_pos_mult.is_finite() {
        return Err(cx.bad(
            field("shadow_pos_mult"),
            format!("{shadow_pos_mult} is not a finite number"),
        ));
    }
    let ortho = l.ortho.unwrap_or_default();
    check_ortho(&ortho, &field("ortho"), cx)?;
    Ok(Light::Directional(DirectionalLight {
        colour,
        direction,
        intensity: l.intensity,
        ortho,
        shadow_pos_mult,
        shading_position: position,
        casts_shadows: l.casts_shadows,
        shadow: l.shadow,
        size: 0.0,
    }))
    .and_then(|light| sized(light, l.size, prefix, cx))
}

/// An ortho box must be ordered, and not so wide that its width overflows f32
/// (left = -3e38, right = 3e38 is ordered, but the projection divides by an infinity).
fn check_ortho(o: &OrthoCoords, field: &str, cx: &Context) -> Result<()> {
    let pairs = [
        ("left", o.left, "right", o.right),
        ("bottom", o.bottom, "top", o.top),
        ("near", o.near, "far", o.far),
    ];
    if let Some((a, va, b, vb)) = pairs
        .iter()
        .find(|(_, va, _, vb)| va.partial_cmp(vb) != Some(std::cmp::Ordering::Less))
    {
        return Err(cx.bad(
            field,
            format!(
                "{o}: {a} = {va} is not below {b} = {vb} (expected left < right, bottom < top \
                 and near < far)"
            ),
        ));
    }
    for (name, a, b) in [
        ("right - left", o.left, o.right),
        ("top - bottom", o.bottom, o.top),
        ("far - near", o.near, o.far),
    ] {
        if !(b - a).is_finite() {
            return Err(cx.bad(
                field,
                format!(
                    "{o}: {name} overflows 32-bit floats: expected a box less than {:e} across",
                    f32::MAX
                ),
            ));
        }
    }
    Ok(())
}

/// The light with its `size`, checked for its kind.
fn sized(mut light: Light, size: f32, prefix: &str, cx: &Context) -> Result<Light> {
    if let Some(problem) = light.size_problem(size) {
        return Err(cx.bad(format!("{prefix}.size"), problem));
    }
    light.set_size(size);
    Ok(light)
}

fn point(l: PointFile, prefix: &str, cx: &Context) -> Result<Light> {
    let colour = light_colour(&l.colour, l.intensity, prefix, cx)?;
    near_far(l.near, l.far, prefix, cx)?;
    let position = Vec3::from(l.position.0);
    Ok(Light::Point(PointLight {
        colour,
        intensity: l.intensity,
        position,
        near: l.near,
        far: l.far,
        oscillate: Vec3::from(l.oscillate.0),
        centre: position,
        casts_shadows: l.casts_shadows,
        shadow: l.shadow,
        size: 0.0,
    }))
    .and_then(|light| sized(light, l.size, prefix, cx))
}

fn spot(l: SpotFile, prefix: &str, cx: &Context) -> Result<Light> {
    let colour = light_colour(&l.colour, l.intensity, prefix, cx)?;
    let field = |name: &str| format!("{prefix}.{name}");
    if let Some(up) = &l.up {
        if Vec3::from(up.0).length() < 1e-6 {
            return Err(cx.bad(
                field("up"),
                format!("{:?}: expected a non-zero vector", up.0),
            ));
        }
    }
    if !(l.aspect > 0.0 && l.aspect <= 1e3) {
        return Err(cx.bad(
            field("aspect"),
            format!(
                "{}: expected a width over height between 0 and 1000 (1 = square, 4:3 = 1.3333)",
                l.aspect
            ),
        ));
    }
    let (position, target) = (Vec3::from(l.position.0), Vec3::from(l.target.0));
    if (target - position).length() < 1e-6 {
        return Err(cx.bad(
            field("target"),
            format!("must differ from {prefix}.position"),
        ));
    }
    if !(l.fov > 0.0 && l.fov < 180.0) {
        return Err(cx.bad(
            field("fov"),
            format!("{}: expected degrees between 0 and 180", l.fov),
        ));
    }
    near_far(l.near, l.far, prefix, cx)?;
    Ok(Light::Spot(SpotLight {
        colour,
        intensity: l.intensity,
        position,
        target,
        up: l.up.map(|u| Vec3::from(u.0)),
        fov: l.fov,
        aspect: l.aspect,
        cone: l.cone,
        near: l.near,
        far: l.far,
        casts_shadows: l.casts_shadows,
        shadow: l.shadow,
        size: 0.0,
    }))
    .and_then(|light| sized(light, l.size, prefix, cx))
}
