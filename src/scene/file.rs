//! Scene files: TOML with a camera, a light, shadow settings and items. The format is
//! documented in the README ("Scene files"); this module is its one implementation.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{Vec3, Vec4};
use serde::Deserialize;

use super::MAX_LIGHTS;
use super::{
    Camera, DirectionalLight, GameItem, Light, Material, OrthoCoords, PointLight, Scene,
    ShadingModel, SpotLight, StepContext,
};
use crate::error::{Error, Result};
use crate::geometry::MeshData;
use crate::image_data::ImageData;
use crate::settings::{ShadowPatch, ShadowSettings, Wrap};
use crate::transformation::Transformation;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    name: Option<String>,
    #[serde(default = "default_size")]
    size: [u32; 2],
    #[serde(default)]
    clear_colour: [f32; 3],
    #[serde(default = "default_ambient")]
    ambient: [f32; 3],
    #[serde(default = "default_specular_power")]
    specular_power: f32,
    #[serde(default)]
    shading: ShadingModel,
    #[serde(default)]
    camera: Camera,
    /// One light (`[light]`), or several (`[[lights]]`); not both.
    light: Option<LightFile>,
    #[serde(default)]
    lights: Vec<LightFile>,
    #[serde(default)]
    shadow: ShadowSettings,
    #[serde(default)]
    steps: StepsFile,
    #[serde(default, rename = "item")]
    items: Vec<ItemFile>,
}

/// What the chapter steps need from the tutorial behind the scene.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct StepsFile {
    /// The tutorial's constant bias (the book 0.05, LearnOpenGL 0.005).
    bias: f32,
    /// The wrap mode the chapter starts with (LearnOpenGL starts with REPEAT).
    start_wrap: Wrap,
}

impl Default for StepsFile {
    fn default() -> Self {
        StepsFile {
            bias: 0.05,
            start_wrap: Wrap::ClampToEdge,
        }
    }
}

fn default_size() -> [u32; 2] {
    [1280, 720]
}
fn default_ambient() -> [f32; 3] {
    [0.3; 3]
}
fn default_specular_power() -> f32 {
    10.0
}

#[derive(Debug, Deserialize, Default, PartialEq)]
#[serde(rename_all = "kebab-case")]
enum LightKindFile {
    #[default]
    Directional,
    Spot,
    Point,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LightFile {
    #[serde(default)]
    kind: LightKindFile,
    #[serde(default = "one3")]
    colour: [f32; 3],
    #[serde(default = "one")]
    intensity: f32,
    /// Directional: the DummyGame's angle in degrees, direction (0, sin a, cos a).
    angle: Option<f32>,
    /// Directional: towards the light; need not be normalised.
    direction: Option<[f32; 3]>,
    /// Directional: shade from this point and put the shadow camera there, looking at the
    /// origin (LearnOpenGL). Spot: where the light is.
    position: Option<[f32; 3]>,
    shadow_pos_mult: Option<f32>,
    ortho: Option<OrthoCoords>,
    /// Spot: what it points at, the shadow camera's up vector, cone/frustum angle, depth range.
    target: Option<[f32; 3]>,
    up: Option<[f32; 3]>,
    fov: Option<f32>,
    near: Option<f32>,
    far: Option<f32>,
    /// Point: the light moves to position + oscillate * sin(0.5 t) (LearnOpenGL's moving light).
    oscillate: Option<[f32; 3]>,
    /// Whether it gets a shadow map (a light that does not cast lights all it faces).
    #[serde(default = "yes")]
    casts_shadows: bool,
    /// Its own shadow settings over the scene's `[shadow]`.
    #[serde(default)]
    shadow: ShadowPatch,
}

#[derive(Debug, Deserialize, Default, Clone, Copy, PartialEq, Eq, Hash)]
#[serde(rename_all = "kebab-case")]
enum Winding {
    #[default]
    Ccw,
    Cw,
}

/// A uniform scale or one per axis.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum ScaleFile {
    Uniform(f32),
    Axes([f32; 3]),
}

impl ScaleFile {
    fn vec(&self) -> Vec3 {
        match self {
            ScaleFile::Uniform(s) => Vec3::splat(*s),
            ScaleFile::Axes(a) => Vec3::from(*a),
        }
    }
}

fn one() -> f32 {
    1.0
}
fn one3() -> [f32; 3] {
    [1.0; 3]
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ItemFile {
    name: Option<String>,
    /// A built-in mesh (`cube`, `plane`) or a path to an OBJ file, relative to the scene file.
    mesh: String,
    #[serde(default)]
    position: [f32; 3],
    #[serde(default)]
    rotation: [f32; 3],
    /// Instead of `rotation`: turn `rotation_angle` degrees about this axis (LearnOpenGL's
    /// third cube), converted to the book's angles.
    rotation_axis: Option<[f32; 3]>,
    rotation_angle: Option<f32>,
    /// "ccw" (default) or "cw": LearnOpenGL's floor is wound clockwise on purpose.
    #[serde(default)]
    winding: Winding,
    /// Seen from inside (LearnOpenGL's room): faces and normals turned inwards.
    #[serde(default)]
    inside_out: bool,
    #[serde(default = "unit_scale")]
    scale: ScaleFile,
    #[serde(default = "white")]
    colour: [f32; 4],
    /// A PNG, relative to the scene file; replaces the colour.
    texture: Option<String>,
    /// How many times the texture repeats across a built-in plane.
    #[serde(default = "one")]
    tiles: f32,
    #[serde(default = "one")]
    reflectance: f32,
    #[serde(default)]
    spin: [f32; 3],
    #[serde(default = "yes")]
    casts_shadows: bool,
    /// Instead of one item, `count` copies strewn over an area (the `large` scene's
    /// forest of pillars), each turned and scaled at random from a fixed seed.
    scatter: Option<ScatterFile>,
    /// Tessellation of a built-in sphere ([segments, rings], default [48, 24]) or terrain
    /// ([cells, cells], default [64, 64]): many copies of a mesh want fewer triangles.
    detail: Option<[u32; 2]>,
}

/// Copies of an item at random (but repeatable) places: x and z uniform over `area`, y
/// from the item's position, a turn about y, and the item's scale times a factor per axis
/// between `scale_min` and `scale_max`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ScatterFile {
    count: u32,
    #[serde(default)]
    seed: u64,
    /// [x_min, x_max, z_min, z_max]
    area: [f32; 4],
    #[serde(default = "one3")]
    scale_min: [f32; 3],
    #[serde(default = "one3")]
    scale_max: [f32; 3],
}

/// The most copies one scatter makes (a typo of a few zeros should not hang the loader).
const MAX_SCATTER: u32 = 10_000;

impl ScatterFile {
    /// (position offset in x and z, turn in degrees, scale factor) for each copy: SplitMix64,
    /// so a seed gives the same scene on every machine.
    fn placements(&self) -> Vec<([f32; 2], f32, Vec3)> {
        let mut state = self.seed;
        let mut next = move || {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
        };
        let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
        let [x0, x1, z0, z1] = self.area;
        (0..self.count)
            .map(|_| {
                let (x, z, turn) = (lerp(x0, x1, next()), lerp(z0, z1, next()), next() * 360.0);
                let scale = Vec3::from_array(std::array::from_fn(|k| {
                    lerp(self.scale_min[k], self.scale_max[k], next())
                }));
                ([x, z], turn, scale)
            })
            .collect()
    }
}

fn unit_scale() -> ScaleFile {
    ScaleFile::Uniform(1.0)
}
fn white() -> [f32; 4] {
    [1.0; 4]
}
fn yes() -> bool {
    true
}

/// Reads a scene file; relative mesh and texture paths resolve from its folder.
pub fn load_file(path: &Path) -> Result<Scene> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::file(path, format!("cannot read scene file: {e}")))?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    parse(&text, path, Some(&base))
}

/// Parses scene TOML. `source` names it in errors; `base` is where relative paths start
/// (`None` for built-in scenes, which may only use built-in meshes).
pub fn parse(text: &str, source: &Path, base: Option<&Path>) -> Result<Scene> {
    let file: SceneFile = toml::from_str(text).map_err(|e| {
        let (line, col) = e.span().map(|s| line_col(text, s.start)).unwrap_or((0, 0));
        Error::file(
            source,
            format!("line {line}, column {col}: {}", e.message()),
        )
    })?;
    build(file, source, base)
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.len() - before.rfind('\n').map(|i| i + 1).unwrap_or(0) + 1;
    (line, col)
}

fn build(file: SceneFile, source: &Path, base: Option<&Path>) -> Result<Scene> {
    let bad = |field: &str, msg: String| Error::file(source, format!("{field}: {msg}"));
    let finite = |field: &str, values: &[f32]| -> Result<()> {
        match values.iter().find(|v| !v.is_finite()) {
            Some(v) => Err(bad(field, format!("{v} is not a finite number"))),
            None => Ok(()),
        }
    };

    if file.size[0] == 0 || file.size[1] == 0 {
        return Err(bad(
            "size",
            format!("{:?}: expected both sides at least 1", file.size),
        ));
    }
    finite("clear_colour", &file.clear_colour)?;
    finite("ambient", &file.ambient)?;
    finite("specular_power", &[file.specular_power])?;

    let c = &file.camera;
    finite("camera.position", &c.position.to_array())?;
    finite("camera.rotation", &c.rotation.to_array())?;
    finite("camera.fov", &[c.fov])?;
    finite("camera.near", &[c.near])?;
    finite("camera.far", &[c.far])?;
    if !(c.near > 0.0 && c.near < c.far) {
        return Err(bad(
            "camera",
            format!(
                "near = {}, far = {}: expected 0 < near < far",
                c.near, c.far
            ),
        ));
    }
    if !(c.fov > 0.0 && c.fov < 180.0) {
        return Err(bad(
            "camera.fov",
            format!("{}: expected degrees between 0 and 180", c.fov),
        ));
    }

    let lights = match (&file.light, file.lights.len()) {
        (Some(l), 0) => vec![build_light(l, "light", &bad, &finite)?],
        (None, 0) => {
            return Err(bad(
                "light",
                "missing: expected a [light] table or one to 4 [[lights]] tables".into(),
            ))
        }
        (None, n) if n > MAX_LIGHTS => {
            return Err(bad(
                "lights",
                format!(
                    "{n} lights: expected at most {MAX_LIGHTS} (each has a texture unit and a \
                     block of the scene shader)"
                ),
            ))
        }
        (None, _) => file
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| build_light(l, &format!("lights[{i}]"), &bad, &finite))
            .collect::<Result<Vec<_>>>()?,
        (Some(_), _) => {
            return Err(bad(
                "light",
                "give either one [light] table or [[lights]] tables, not both".into(),
            ))
        }
    };

    let s = &file.shadow;
    finite("shadow", &[s.bias, s.bias_min])?;
    // map_size is checked against the driver's maximum once there is a driver.
    s.validate_values()
        .map_err(|e| Error::file(source, e.to_string()))?;
    for (i, light) in lights.iter().enumerate() {
        if !light.shadow_patch().given().is_empty() {
            light
                .settings(s)
                .validate_values()
                .map_err(|e| bad(&format!("lights[{i}].shadow"), e.to_string()))?;
        }
    }

    let mut meshes: Vec<MeshData> = Vec::new();
    type MeshKey = (String, u32, Winding, bool, Option<[u32; 2]>);
    let mut mesh_ids: HashMap<MeshKey, usize> = HashMap::new();
    let mut textures: Vec<ImageData> = Vec::new();
    let mut texture_ids: HashMap<PathBuf, usize> = HashMap::new();
    let mut items = Vec::new();
    for (i, item) in file.items.into_iter().enumerate() {
        let field = |f: &str| format!("item[{i}].{f}");
        finite(&field("position"), &item.position)?;
        finite(&field("rotation"), &item.rotation)?;
        finite(&field("colour"), &item.colour)?;
        finite(&field("spin"), &item.spin)?;
        finite(&field("reflectance"), &[item.reflectance])?;
        let rotation = match (item.rotation_axis, item.rotation_angle) {
            (None, None) => Vec3::from(item.rotation),
            (Some(axis), Some(angle)) => {
                finite(&field("rotation_axis"), &axis)?;
                finite(&field("rotation_angle"), &[angle])?;
                if item.rotation != [0.0; 3] {
                    return Err(bad(
                        &field("rotation"),
                        "give either `rotation` or `rotation_axis` with `rotation_angle`".into(),
                    ));
                }
                let axis = Vec3::from(axis).try_normalize().ok_or_else(|| {
                    bad(
                        &field("rotation_axis"),
                        format!("{axis:?}: expected a non-zero vector"),
                    )
                })?;
                Transformation::book_angles(glam::Quat::from_axis_angle(axis, angle.to_radians()))
            }
            _ => {
                return Err(bad(
                    &field("rotation_axis"),
                    "`rotation_axis` and `rotation_angle` go together".into(),
                ))
            }
        };
        let scale = item.scale.vec();
        if !scale.is_finite() || scale.min_element() <= 0.0 {
            let shown = match item.scale {
                ScaleFile::Uniform(s) => s.to_string(),
                ScaleFile::Axes(a) => format!("{a:?}"),
            };
            return Err(bad(
                &field("scale"),
                format!("{shown}: expected a finite number > 0 (or three of them)"),
            ));
        }
        if !(item.tiles.is_finite() && item.tiles > 0.0) {
            return Err(bad(
                &field("tiles"),
                format!("{}: expected a finite number > 0", item.tiles),
            ));
        }
        let detail = match (item.mesh.as_str(), item.detail) {
            (_, None) => None,
            ("sphere", Some([s, r])) if (3..=512).contains(&s) && (2..=256).contains(&r) => {
                Some([s, r])
            }
            ("terrain", Some([c, r])) if c == r && (1..=1024).contains(&c) => Some([c, r]),
            (mesh, Some(d)) => {
                return Err(bad(
                    &field("detail"),
                    format!(
                        "{d:?} for mesh '{mesh}': expected [segments 3..512, rings 2..256] for \
                         a sphere or [cells, cells] (1..1024) for a terrain"
                    ),
                ))
            }
        };
        let key = (
            item.mesh.clone(),
            item.tiles.to_bits(),
            item.winding,
            item.inside_out,
            detail,
        );
        let mesh = match mesh_ids.get(&key) {
            Some(&id) => id,
            None => {
                let data = match item.mesh.as_str() {
                    "" => return Err(bad(
                        &field("mesh"),
                        "empty: expected a built-in mesh (cube, plane, sphere, terrain) or a path \
                             to an OBJ file"
                            .into(),
                    )),
                    "cube" => MeshData::cube(),
                    "plane" => MeshData::plane(item.tiles),
                    "sphere" => {
                        let [segments, rings] = detail.unwrap_or([48, 24]);
                        MeshData::sphere(segments, rings)
                    }
                    "terrain" => MeshData::terrain(detail.map_or(64, |d| d[0])),
                    path => {
                        let base = base.ok_or_else(|| {
                            bad(
                                &field("mesh"),
                                format!(
                                    "'{path}': built-in scenes only use the built-in meshes (cube, plane, sphere, terrain)"
                                ),
                            )
                        })?;
                        MeshData::load_obj(&base.join(path))
                            .map_err(|e| bad(&field("mesh"), e.to_string()))?
                    }
                };
                let data = match item.winding {
                    Winding::Ccw => data,
                    Winding::Cw => data.flip_winding(),
                };
                meshes.push(if item.inside_out {
                    data.inside_out()
                } else {
                    data
                });
                mesh_ids.insert(key, meshes.len() - 1);
                meshes.len() - 1
            }
        };
        let texture = match &item.texture {
            None => None,
            Some(t) if t.trim().is_empty() => {
                return Err(bad(
                    &field("texture"),
                    "empty: expected a path to a PNG file (or the built-in \"wood\")".into(),
                ))
            }
            Some(t) if t == "wood" => Some(match texture_ids.get(Path::new("<wood>")) {
                Some(&id) => id,
                None => {
                    textures.push(ImageData::wood(256));
                    texture_ids.insert(PathBuf::from("<wood>"), textures.len() - 1);
                    textures.len() - 1
                }
            }),
            Some(t) => {
                let base = base.ok_or_else(|| {
                    bad(
                        &field("texture"),
                        "built-in scenes have no texture files (the built-in texture is \"wood\")"
                            .into(),
                    )
                })?;
                let path = base.join(t);
                Some(match texture_ids.get(&path) {
                    Some(&id) => id,
                    None => {
                        textures.push(
                            ImageData::load_png(&path)
                                .map_err(|e| bad(&field("texture"), e.to_string()))?,
                        );
                        texture_ids.insert(path, textures.len() - 1);
                        textures.len() - 1
                    }
                })
            }
        };
        let one = GameItem {
            name: item.name.unwrap_or_else(|| format!("item{i}")),
            mesh,
            position: Vec3::from(item.position),
            rotation,
            scale,
            material: Material {
                colour: Vec4::from(item.colour),
                texture,
                reflectance: item.reflectance,
            },
            spin: Vec3::from(item.spin),
            casts_shadows: item.casts_shadows,
        };
        match &item.scatter {
            None => items.push(one),
            Some(sc) => {
                finite(&field("scatter.area"), &sc.area)?;
                finite(&field("scatter.scale_min"), &sc.scale_min)?;
                finite(&field("scatter.scale_max"), &sc.scale_max)?;
                if sc.count == 0 || sc.count > MAX_SCATTER {
                    return Err(bad(
                        &field("scatter.count"),
                        format!("{}: expected 1 to {MAX_SCATTER}", sc.count),
                    ));
                }
                let [x0, x1, z0, z1] = sc.area;
                if !(x0 <= x1 && z0 <= z1) {
                    return Err(bad(
                        &field("scatter.area"),
                        format!("{:?}: expected [x_min, x_max, z_min, z_max]", sc.area),
                    ));
                }
                let scales = sc.scale_min.iter().chain(&sc.scale_max);
                if scales.clone().any(|v| *v <= 0.0) {
                    return Err(bad(
                        &field("scatter"),
                        "scale_min and scale_max: expected numbers > 0".into(),
                    ));
                }
                for (k, ([x, z], turn, factor)) in sc.placements().into_iter().enumerate() {
                    items.push(GameItem {
                        name: format!("{}{k}", one.name),
                        position: one.position + Vec3::new(x, 0.0, z),
                        rotation: one.rotation + Vec3::new(0.0, turn, 0.0),
                        scale: one.scale * factor,
                        ..one.clone()
                    });
                }
            }
        }
    }

    let name = file.name.unwrap_or_else(|| {
        source
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into())
    });
    Ok(Scene {
        source: source.to_path_buf(),
        name,
        camera: file.camera,
        lights,
        shading: file.shading,
        steps: StepContext {
            bias: file.steps.bias,
            start_wrap: file.steps.start_wrap,
        },
        fit_camera: None,
        time: 0.0,
        ambient: Vec3::from(file.ambient),
        specular_power: file.specular_power,
        clear_colour: Vec3::from(file.clear_colour).extend(1.0),
        size: file.size,
        items,
        meshes,
        textures,
        shadow: file.shadow,
    })
}

type Bad<'a> = &'a dyn Fn(&str, String) -> Error;
type Finite<'a> = &'a dyn Fn(&str, &[f32]) -> Result<()>;

/// The `[light]` table: a directional light (the book's, or LearnOpenGL's positioned one)
/// or a spot light.
fn build_light(l: &LightFile, prefix: &str, bad: Bad, finite: Finite) -> Result<Light> {
    finite(&format!("{prefix}.colour"), &l.colour)?;
    finite(&format!("{prefix}.intensity"), &[l.intensity])?;
    let vec = |name: &str, v: Option<[f32; 3]>| -> Result<Option<Vec3>> {
        match v {
            Some(v) => {
                finite(&format!("{prefix}.{name}"), &v)?;
                Ok(Some(Vec3::from(v)))
            }
            None => Ok(None),
        }
    };
    let position = vec("position", l.position)?;
    let target = vec("target", l.target)?;
    let up = vec("up", l.up)?;
    let only = |kind: &str, fields: &[(&str, bool)]| -> Result<()> {
        match fields.iter().find(|(_, given)| *given) {
            Some((name, _)) => Err(bad(
                &format!("{prefix}.{name}"),
                format!("not used by a {kind} light"),
            )),
            None => Ok(()),
        }
    };
    match l.kind {
        LightKindFile::Directional => {
            only(
                "directional",
                &[
                    ("target", l.target.is_some()),
                    ("up", l.up.is_some()),
                    ("fov", l.fov.is_some()),
                    ("near", l.near.is_some()),
                    ("far", l.far.is_some()),
                    ("oscillate", l.oscillate.is_some()),
                ],
            )?;
            let given = [l.angle.is_some(), l.direction.is_some(), position.is_some()];
            if given.iter().filter(|g| **g).count() != 1 {
                return Err(bad(
                    prefix,
                    "expected exactly one of `angle` (degrees), `direction` ([x, y, z] towards \
                     the light) or `position` (a point the light shines from, towards the origin)"
                        .into(),
                ));
            }
            let non_zero = |name: &str, v: Vec3| {
                v.try_normalize().ok_or_else(|| {
                    bad(
                        &format!("{prefix}.{name}"),
                        format!("{v}: expected a non-zero vector"),
                    )
                })
            };
            let direction = match (l.angle, vec("direction", l.direction)?, position) {
                (Some(a), _, _) => {
                    finite(&format!("{prefix}.angle"), &[a])?;
                    DirectionalLight::direction_from_angle(a)
                }
                (_, Some(d), _) => non_zero("direction", d)?,
                (_, _, Some(p)) => non_zero("position", p)?,
                _ => unreachable!("exactly one was checked above"),
            };
            let shadow_pos_mult = match (l.shadow_pos_mult, position) {
                (Some(_), Some(_)) => {
                    return Err(bad(
                        &format!("{prefix}.shadow_pos_mult"),
                        "not used with `position` (the shadow camera sits at the position)".into(),
                    ))
                }
                (Some(m), None) => m,
                (None, Some(p)) => p.length(),
                (None, None) => 5.0,
            };
            finite(&format!("{prefix}.shadow_pos_mult"), &[shadow_pos_mult])?;
            let ortho = l.ortho.unwrap_or_default();
            let o = &ortho;
            finite(
                &format!("{prefix}.ortho"),
                &[o.left, o.right, o.bottom, o.top, o.near, o.far],
            )?;
            if !(o.left < o.right && o.bottom < o.top && o.near < o.far) {
                return Err(bad(
                    &format!("{prefix}.ortho"),
                    format!("{o:?}: expected left < right, bottom < top and near < far"),
                ));
            }
            Ok(Light::Directional(DirectionalLight {
                colour: Vec3::from(l.colour),
                direction,
                intensity: l.intensity,
                ortho,
                shadow_pos_mult,
                shading_position: position,
                casts_shadows: l.casts_shadows,
                shadow: l.shadow,
            }))
        }
        LightKindFile::Point => {
            only(
                "point",
                &[
                    ("angle", l.angle.is_some()),
                    ("direction", l.direction.is_some()),
                    ("shadow_pos_mult", l.shadow_pos_mult.is_some()),
                    ("ortho", l.ortho.is_some()),
                    ("target", l.target.is_some()),
                    ("up", l.up.is_some()),
                    ("fov", l.fov.is_some()),
                ],
            )?;
            let position = position.ok_or_else(|| {
                bad(
                    &format!("{prefix}.position"),
                    "a point light needs it".into(),
                )
            })?;
            let (near, far) = (l.near.unwrap_or(1.0), l.far.unwrap_or(25.0));
            finite(&format!("{prefix}.near"), &[near, far])?;
            if !(near > 0.0 && near < far) {
                return Err(bad(
                    prefix,
                    format!("near = {near}, far = {far}: expected 0 < near < far"),
                ));
            }
            let oscillate = vec("oscillate", l.oscillate)?.unwrap_or(Vec3::ZERO);
            Ok(Light::Point(PointLight {
                colour: Vec3::from(l.colour),
                intensity: l.intensity,
                position,
                near,
                far,
                oscillate,
                centre: position,
                casts_shadows: l.casts_shadows,
                shadow: l.shadow,
            }))
        }
        LightKindFile::Spot => {
            only(
                "spot",
                &[
                    ("angle", l.angle.is_some()),
                    ("direction", l.direction.is_some()),
                    ("shadow_pos_mult", l.shadow_pos_mult.is_some()),
                    ("ortho", l.ortho.is_some()),
                    ("oscillate", l.oscillate.is_some()),
                ],
            )?;
            let need =
                |name: &str| bad(&format!("{prefix}.{name}"), "a spot light needs it".into());
            let position = position.ok_or_else(|| need("position"))?;
            let target = target.ok_or_else(|| need("target"))?;
            let (fov, near, far) = (
                l.fov.ok_or_else(|| need("fov"))?,
                l.near.ok_or_else(|| need("near"))?,
                l.far.ok_or_else(|| need("far"))?,
            );
            finite(&format!("{prefix}.fov"), &[fov, near, far])?;
            if (target - position).length() < 1e-6 {
                return Err(bad(
                    &format!("{prefix}.target"),
                    "must differ from light.position".into(),
                ));
            }
            if !(fov > 0.0 && fov < 180.0) {
                return Err(bad(
                    &format!("{prefix}.fov"),
                    format!("{fov}: expected degrees between 0 and 180"),
                ));
            }
            if !(near > 0.0 && near < far) {
                return Err(bad(
                    prefix,
                    format!("near = {near}, far = {far}: expected 0 < near < far"),
                ));
            }
            Ok(Light::Spot(SpotLight {
                colour: Vec3::from(l.colour),
                intensity: l.intensity,
                position,
                target,
                up,
                fov,
                near,
                far,
                casts_shadows: l.casts_shadows,
                shadow: l.shadow,
            }))
        }
    }
}
