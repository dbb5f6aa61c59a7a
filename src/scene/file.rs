//! Scene files: TOML with a camera, a light, shadow settings and items. The format is
//! documented in the README ("Scene files"); this module is its one implementation.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{Vec3, Vec4};
use serde::Deserialize;

use super::{Camera, DirectionalLight, GameItem, Material, OrthoCoords, Scene};
use crate::error::{Error, Result};
use crate::geometry::MeshData;
use crate::image_data::ImageData;
use crate::settings::ShadowSettings;

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
    camera: Camera,
    light: LightFile,
    #[serde(default)]
    shadow: ShadowSettings,
    #[serde(default, rename = "item")]
    items: Vec<ItemFile>,
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

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LightFile {
    #[serde(default = "one3")]
    colour: [f32; 3],
    #[serde(default = "one")]
    intensity: f32,
    /// The DummyGame's angle in degrees: direction (0, sin a, cos a).
    angle: Option<f32>,
    /// Towards the light; need not be normalised.
    direction: Option<[f32; 3]>,
    #[serde(default = "default_pos_mult")]
    shadow_pos_mult: f32,
    #[serde(default)]
    ortho: OrthoCoords,
}

fn one() -> f32 {
    1.0
}
fn one3() -> [f32; 3] {
    [1.0; 3]
}
fn default_pos_mult() -> f32 {
    5.0
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
    #[serde(default = "one")]
    scale: f32,
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
    finite(
        "camera",
        &[
            c.position.x,
            c.position.y,
            c.position.z,
            c.rotation.x,
            c.rotation.y,
            c.fov,
            c.near,
            c.far,
        ],
    )?;
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

    let l = &file.light;
    let direction = match (l.angle, l.direction) {
        (Some(a), None) => {
            finite("light.angle", &[a])?;
            DirectionalLight::direction_from_angle(a)
        }
        (None, Some(d)) => {
            finite("light.direction", &d)?;
            Vec3::from(d).try_normalize().ok_or_else(|| {
                bad(
                    "light.direction",
                    format!("{d:?}: expected a non-zero vector pointing towards the light"),
                )
            })?
        }
        (Some(_), Some(_)) => {
            return Err(bad(
                "light",
                "both `angle` and `direction` given: expected one of them".into(),
            ))
        }
        (None, None) => {
            return Err(bad(
                "light",
                "expected `angle` (degrees) or `direction` ([x, y, z] towards the light)".into(),
            ))
        }
    };
    finite("light.colour", &l.colour)?;
    finite("light.intensity", &[l.intensity])?;
    finite("light.shadow_pos_mult", &[l.shadow_pos_mult])?;
    let o = &l.ortho;
    finite(
        "light.ortho",
        &[o.left, o.right, o.bottom, o.top, o.near, o.far],
    )?;
    if !(o.left < o.right && o.bottom < o.top && o.near < o.far) {
        return Err(bad(
            "light.ortho",
            format!("{o:?}: expected left < right, bottom < top and near < far"),
        ));
    }

    let s = &file.shadow;
    finite("shadow", &[s.bias, s.bias_min])?;
    // The driver's maximum is checked when the renderer is made; 65536 bounds a sane file.
    s.validate(65536)
        .map_err(|e| Error::file(source, e.to_string()))?;

    let mut meshes: Vec<MeshData> = Vec::new();
    let mut mesh_ids: HashMap<(String, u32), usize> = HashMap::new();
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
        if !(item.scale.is_finite() && item.scale > 0.0) {
            return Err(bad(
                &field("scale"),
                format!("{}: expected a finite number > 0", item.scale),
            ));
        }
        if !(item.tiles.is_finite() && item.tiles > 0.0) {
            return Err(bad(
                &field("tiles"),
                format!("{}: expected a finite number > 0", item.tiles),
            ));
        }
        let key = (item.mesh.clone(), item.tiles.to_bits());
        let mesh = match mesh_ids.get(&key) {
            Some(&id) => id,
            None => {
                let data = match item.mesh.as_str() {
                    "cube" => MeshData::cube(),
                    "plane" => MeshData::plane(item.tiles),
                    path => {
                        let base = base.ok_or_else(|| {
                            bad(
                                &field("mesh"),
                                format!(
                                    "'{path}': built-in scenes only use the meshes cube and plane"
                                ),
                            )
                        })?;
                        MeshData::load_obj(&base.join(path))
                            .map_err(|e| bad(&field("mesh"), e.to_string()))?
                    }
                };
                meshes.push(data);
                mesh_ids.insert(key, meshes.len() - 1);
                meshes.len() - 1
            }
        };
        let texture = match &item.texture {
            None => None,
            Some(t) => {
                let base = base.ok_or_else(|| {
                    bad(
                        &field("texture"),
                        "built-in scenes have no texture files".into(),
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
        items.push(GameItem {
            name: item.name.unwrap_or_else(|| format!("item{i}")),
            mesh,
            position: Vec3::from(item.position),
            rotation: Vec3::from(item.rotation),
            scale: item.scale,
            material: Material {
                colour: Vec4::from(item.colour),
                texture,
                reflectance: item.reflectance,
            },
            spin: Vec3::from(item.spin),
            casts_shadows: item.casts_shadows,
        });
    }

    let name = file.name.unwrap_or_else(|| {
        source
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into())
    });
    Ok(Scene {
        name,
        camera: file.camera,
        light: DirectionalLight {
            colour: Vec3::from(l.colour),
            direction,
            intensity: l.intensity,
            ortho: l.ortho,
            shadow_pos_mult: l.shadow_pos_mult,
        },
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
