//! Items, their meshes and textures: built-in meshes or OBJ files, PNG textures, each
//! loaded once however many items use it.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{Vec3, Vec4};

use super::read::{element_label, Context};
use super::{ItemFile, ScaleFile, ScatterFile, Winding, BUILTIN_MESHES, MAX_SCATTER};
use crate::error::Result;
use crate::geometry::MeshData;
use crate::image_data::ImageData;
use crate::scene::{GameItem, Material};
use crate::transformation::Transformation;

/// Meshes and textures are shared between items: one upload for many copies.
type MeshKey = (String, u32, Winding, bool, Option<[u32; 2]>);

#[derive(Default)]
pub(super) struct Items {
    pub(super) items: Vec<GameItem>,
    pub(super) meshes: Vec<MeshData>,
    mesh_ids: HashMap<MeshKey, usize>,
    pub(super) textures: Vec<ImageData>,
    texture_ids: HashMap<PathBuf, usize>,
}

/// `item[2] ("cube")`, or `item[2]` for an item without a name.
fn item_label(index: usize, name: Option<&str>) -> String {
    format!("item{}", element_label(index, name))
}

impl Items {
    pub(super) fn add(&mut self, i: usize, item: ItemFile, cx: &Context) -> Result<()> {
        let label = item_label(i, item.name.as_deref());
        let field = |f: &str| format!("{label}.{f}");
        cx.non_negative(&field("colour"), &item.colour.0)?;
        cx.non_negative(&field("reflectance"), &[item.reflectance])?;
        let rotation = item_rotation(&item, &field, cx)?;
        let scale = item.scale.vec();
        if !scale.is_finite() || scale.min_element() <= 0.0 {
            let shown = match item.scale {
                ScaleFile::Uniform(s) => s.to_string(),
                ScaleFile::Axes(a) => format!("{a:?}"),
            };
            return Err(cx.bad(
                field("scale"),
                format!("{shown}: expected a finite number > 0 (or three of them)"),
            ));
        }
        if !(item.tiles.is_finite() && item.tiles > 0.0) {
            return Err(cx.bad(
                field("tiles"),
                format!("{}: expected a finite number > 0", item.tiles),
            ));
        }
        let opacity = item.opacity;
        if !(opacity > 0.0 && opacity <= 1.0) {
            return Err(cx.bad(
                field("opacity"),
                format!("{opacity}: expected a number above 0 and at most 1 (1 = opaque)"),
            ));
        }
        let mesh = self.mesh(&item, &field, cx)?;
        let texture = self.texture(item.texture.as_deref(), &field, cx)?;
        let one = GameItem {
            name: item.name.clone().unwrap_or_else(|| format!("item{i}")),
            mesh,
            position: Vec3::from(item.position.0),
            rotation,
            scale,
            material: Material {
                colour: Vec4::from(item.colour.0),
                texture,
                reflectance: item.reflectance,
            },
            spin: Vec3::from(item.spin.0),
            // A translucent item stays out of the depth map: its technique casts it.
            casts_shadows: item.casts_shadows && opacity >= 1.0,
            opacity,
            casts_translucent: item.casts_shadows && opacity < 1.0,
        };
        match &item.scatter {
            None => self.items.push(one),
            Some(sc) => self.items.extend(scatter(sc, &one, &field, cx)?),
        }
        Ok(())
    }

    /// The item's mesh, loaded once per (mesh, tiles, winding, inside out, detail).
    fn mesh(
        &mut self,
        item: &ItemFile,
        field: &dyn Fn(&str) -> String,
        cx: &Context,
    ) -> Result<usize> {
        let detail = mesh_detail(&item.mesh, item.detail.map(|d| d.0), field, cx)?;
        let key = (
            item.mesh.clone(),
            item.tiles.to_bits(),
            item.winding,
            item.inside_out,
            detail,
        );
        if let Some(&id) = self.mesh_ids.get(&key) {
            return Ok(id);
        }
        let data = load_mesh(&item.mesh, item.tiles, detail, field, cx)?;
        let data = match item.winding {
            Winding::Ccw => data,
            Winding::Cw => data.flip_winding(),
        };
        self.meshes.push(if item.inside_out {
            data.inside_out()
        } else {
            data
        });
        self.mesh_ids.insert(key, self.meshes.len() - 1);
        Ok(self.meshes.len() - 1)
    }

    /// The item's texture, loaded once per path; "wood" is the built-in one.
    fn texture(
        &mut self,
        texture: Option<&str>,
        field: &dyn Fn(&str) -> String,
        cx: &Context,
    ) -> Result<Option<usize>> {
        let t = match texture {
            None => return Ok(None),
            Some(t) => t,
        };
        if t.trim().is_empty() {
            return Err(cx.bad(
                field("texture"),
                "empty: expected a path to a PNG file (or the built-in \"wood\")",
            ));
        }
        let key = if t == "wood" {
            PathBuf::from("<wood>")
        } else {
            let base = cx.base.ok_or_else(|| {
                cx.bad(
                    field("texture"),
                    "built-in scenes have no texture files (the built-in texture is \"wood\")",
                )
            })?;
            base.join(t)
        };
        if let Some(&id) = self.texture_ids.get(&key) {
            return Ok(Some(id));
        }
        let image = if t == "wood" {
            ImageData::wood(256)
        } else {
            ImageData::load_png(&key).map_err(|e| cx.bad(field("texture"), e.to_string()))?
        };
        self.textures.push(image);
        self.texture_ids.insert(key, self.textures.len() - 1);
        Ok(Some(self.textures.len() - 1))
    }
}

/// `rotation`, or `rotation_axis` with `rotation_angle` turned into the book's angles.
fn item_rotation(item: &ItemFile, field: &dyn Fn(&str) -> String, cx: &Context) -> Result<Vec3> {
    match (item.rotation_axis, item.rotation_angle) {
        (None, None) => Ok(Vec3::from(item.rotation.0)),
        (Some(axis), Some(angle)) => {
            if item.rotation.0 != [0.0; 3] {
                return Err(cx.bad(
                    field("rotation"),
                    "give either `rotation` or `rotation_axis` with `rotation_angle`",
                ));
            }
            let axis = Vec3::from(axis.0).try_normalize().ok_or_else(|| {
                cx.bad(
                    field("rotation_axis"),
                    format!("{:?}: expected a non-zero vector", axis.0),
                )
            })?;
            Ok(Transformation::book_angles(glam::Quat::from_axis_angle(
                axis,
                angle.to_radians(),
            )))
        }
        _ => Err(cx.bad(
            field("rotation_axis"),
            "`rotation_axis` and `rotation_angle` go together",
        )),
    }
}

/// `detail`, which only a sphere or a terrain takes.
fn mesh_detail(
    mesh: &str,
    detail: Option<[u32; 2]>,
    field: &dyn Fn(&str) -> String,
    cx: &Context,
) -> Result<Option<[u32; 2]>> {
    match (mesh, detail) {
        (_, None) => Ok(None),
        ("sphere", Some([s, r])) if (3..=512).contains(&s) && (2..=256).contains(&r) => {
            Ok(Some([s, r]))
        }
        ("terrain", Some([c, r])) if c == r && (1..=1024).contains(&c) => Ok(Some([c, r])),
        (mesh, Some(d)) => Err(cx.bad(
            field("detail"),
            format!(
                "{d:?} for mesh '{mesh}': expected [segments 3..512, rings 2..256] for \
                 a sphere or [cells, cells] (1..1024) for a terrain"
            ),
        )),
    }
}

/// A built-in mesh by name, or an OBJ file relative to the scene.
fn load_mesh(
    mesh: &str,
    tiles: f32,
    detail: Option<[u32; 2]>,
    field: &dyn Fn(&str) -> String,
    cx: &Context,
) -> Result<MeshData> {
    match mesh {
        "" => Err(cx.bad(
            field("mesh"),
            format!("empty: expected a built-in mesh ({BUILTIN_MESHES}) or a path to an OBJ file"),
        )),
        "cube" => Ok(MeshData::cube()),
        "plane" => Ok(MeshData::plane(tiles)),
        "sphere" => {
            let [segments, rings] = detail.unwrap_or([48, 24]);
            Ok(MeshData::sphere(segments, rings))
        }
        "terrain" => Ok(MeshData::terrain(detail.map_or(64, |d| d[0]))),
        path => {
            let base = cx.base.ok_or_else(|| {
                cx.bad(
                    field("mesh"),
                    format!(
                        "'{path}': built-in scenes only use the built-in meshes ({BUILTIN_MESHES})"
                    ),
                )
            })?;
            let full = base.join(path);
            // A bare word that is no file is most likely a misspelt built-in ("cueb").
            if Path::new(path).extension().is_none() && !full.exists() {
                return Err(cx.bad(
                    field("mesh"),
                    format!(
                        "'{path}' is not a built-in mesh ({BUILTIN_MESHES}), and there is no \
                         OBJ file at {}",
                        full.display()
                    ),
                ));
            }
            MeshData::load_obj(&full).map_err(|e| cx.bad(field("mesh"), e.to_string()))
        }
    }
}

/// The copies of `one` a scatter makes.
fn scatter(
    sc: &ScatterFile,
    one: &GameItem,
    field: &dyn Fn(&str) -> String,
    cx: &Context,
) -> Result<Vec<GameItem>> {
    if sc.count == 0 || sc.count > MAX_SCATTER {
        return Err(cx.bad(
            field("scatter.count"),
            format!("{}: expected 1 to {MAX_SCATTER}", sc.count),
        ));
    }
    let [x0, x1, z0, z1] = sc.area.0;
    if !(x0 <= x1 && z0 <= z1) {
        return Err(cx.bad(
            field("scatter.area"),
            format!("{:?}: expected [x_min, x_max, z_min, z_max]", sc.area.0),
        ));
    }
    if !((x1 - x0).is_finite() && (z1 - z0).is_finite()) {
        return Err(cx.bad(
            field("scatter.area"),
            format!(
                "{:?}: the area's width overflows 32-bit floats: expected less than {:e} across",
                sc.area.0,
                f32::MAX
            ),
        ));
    }
    if let Some(h) = sc.height {
        let [y0, y1] = h.0;
        if !(y0 <= y1 && (y1 - y0).is_finite()) {
            return Err(cx.bad(
                field("scatter.height"),
                format!("{:?}: expected [y_min, y_max] with y_min <= y_max", h.0),
            ));
        }
    }
    let scales = sc.scale_min.0.iter().chain(&sc.scale_max.0);
    if scales.clone().any(|v| *v <= 0.0) {
        return Err(cx.bad(
            field("scatter"),
            "scale_min and scale_max: expected numbers > 0",
        ));
    }
    Ok(sc
        .placements()
        .into_iter()
        .enumerate()
        .map(|(k, (offset, turn, factor))| GameItem {
            name: format!("{}{k}", one.name),
            position: one.position + offset,
            rotation: one.rotation + Vec3::new(0.0, turn, 0.0),
            scale: one.scale * factor,
            ..one.clone()
        })
        .collect())
}
