//! Scene files: TOML with a camera, lights, shadow settings and items. The format is
//! documented in the README ("Scene files"); this module is its one implementation.
//!
//! Reading goes in three steps. The text is first parsed into a [`Raw`] tree that remembers
//! where every value sits, so any later error can name its line and its field as the file
//! spells it (`item[2] ("cube").scale`). That tree is checked for numbers no field may hold
//! (NaN, infinities, values beyond f32). Then serde fills the typed tables below and
//! [`build`] turns them into a [`Scene`], checking what serde cannot (ranges, relations
//! between fields, files on disk).

use std::collections::HashMap;
use std::fmt;
use std::marker::PhantomData;
use std::path::{Path, PathBuf};

use glam::{Vec3, Vec4};
use serde::de::{self, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;
use toml::Spanned;

use super::refusals;
use super::{
    Camera, DirectionalLight, GameItem, Light, Material, OrthoCoords, PointLight, Scene,
    ShadingModel, SpotLight, StepContext, StepList, MAX_LIGHTS,
};
use crate::error::{Error, Result};
use crate::geometry::MeshData;
use crate::image_data::ImageData;
use crate::input::{read_text_file, SCENE_LIMIT};
use crate::settings::{ShadowPatch, ShadowSettings, Wrap};
use crate::transformation::Transformation;

// ---------------------------------------------------------------------------------------
// The typed tables

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    name: Option<String>,
    #[serde(default = "default_size")]
    size: Fixed<u32, 2>,
    #[serde(default)]
    clear_colour: Fixed<f32, 3>,
    #[serde(default = "default_ambient")]
    ambient: Fixed<f32, 3>,
    #[serde(default = "default_specular_power")]
    specular_power: f32,
    #[serde(default)]
    shading: ShadingModel,
    #[serde(default)]
    camera: CameraFile,
    /// One light (`[light]`), or several (`[[lights]]`); not both. Kept as tables here and
    /// read by kind in [`read_light`], where the light's name (`lights[1]`) is known.
    light: Option<toml::Table>,
    #[serde(default)]
    lights: Vec<toml::Table>,
    #[serde(default)]
    shadow: ShadowSettings,
    #[serde(default)]
    steps: StepsFile,
    #[serde(default, rename = "item")]
    items: Vec<ItemFile>,
}

/// The `[camera]` table. Not `Camera` itself: glam's `Vec3` takes the first three numbers
/// of a longer array without a word.
#[derive(Debug, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct CameraFile {
    position: Fixed<f32, 3>,
    /// The book's angles; default 0, 0, 0. Not with `target`.
    rotation: Option<Fixed<f32, 3>>,
    /// A look-at camera: the point it looks at, turned into the book's pitch and yaw.
    target: Option<Fixed<f32, 3>>,
    fov: f32,
    near: f32,
    far: f32,
}

impl Default for CameraFile {
    fn default() -> Self {
        let c = Camera::default();
        CameraFile {
            position: Fixed(c.position.to_array()),
            rotation: None,
            target: None,
            fov: c.fov,
            near: c.near,
            far: c.far,
        }
    }
}

/// What the chapter steps need from the tutorial behind the scene.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct StepsFile {
    /// The tutorial's constant bias (the book 0.05, LearnOpenGL 0.005).
    bias: f32,
    /// The wrap mode the chapter starts with (LearnOpenGL starts with REPEAT).
    start_wrap: Wrap,
    /// The camera the steps are shown from, where the tutorial's own does not show what
    /// they change; fields it leaves out are the scene's `[camera]`'s.
    camera: Option<StepsCameraFile>,
    /// Which tutorial's steps: "chapters" (the default) or "playground".
    list: StepList,
    /// The lights' size while the steps are shown (a step like PCSS needs one).
    light_size: Option<f32>,
}

impl Default for StepsFile {
    fn default() -> Self {
        StepsFile {
            bias: 0.05,
            start_wrap: Wrap::ClampToEdge,
            camera: None,
            list: StepList::Chapters,
            light_size: None,
        }
    }
}

/// `[steps] camera`: a `[camera]` table whose every field is optional.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct StepsCameraFile {
    position: Option<Fixed<f32, 3>>,
    rotation: Option<Fixed<f32, 3>>,
    target: Option<Fixed<f32, 3>>,
    fov: Option<f32>,
    near: Option<f32>,
    far: Option<f32>,
}

impl StepsCameraFile {
    /// The whole camera: these fields over `scene`'s.
    fn over(&self, scene: &CameraFile) -> CameraFile {
        // Angles or a target given here replace the scene's way of aiming.
        let (rotation, target) = match (self.rotation, self.target) {
            (None, None) => (scene.rotation, scene.target),
            aim => aim,
        };
        CameraFile {
            position: self.position.unwrap_or(scene.position),
            rotation,
            target,
            fov: self.fov.unwrap_or(scene.fov),
            near: self.near.unwrap_or(scene.near),
            far: self.far.unwrap_or(scene.far),
        }
    }
}

fn default_size() -> Fixed<u32, 2> {
    Fixed([1280, 720])
}
fn default_ambient() -> Fixed<f32, 3> {
    Fixed([0.3; 3])
}
fn default_specular_power() -> f32 {
    10.0
}
fn one() -> f32 {
    1.0
}
fn one3() -> Fixed<f32, 3> {
    Fixed([1.0; 3])
}
fn white() -> Fixed<f32, 4> {
    Fixed([1.0; 4])
}
fn yes() -> bool {
    true
}

/// A light table read by its `kind`; each kind is its own struct, so serde itself refuses
/// what a kind does not take. Not serde's `#[serde(tag = "kind")]`: that cannot default a
/// missing tag to "directional", and it buffers the table in a way that loses the name of
/// a field that fails.
#[derive(Debug)]
enum LightFile {
    Directional(DirectionalFile),
    Spot(SpotFile),
    Point(PointFile),
}

/// The values `kind` takes, in the order messages list them.
const LIGHT_KINDS: [&str; 3] = ["directional", "spot", "point"];

/// The book's light (an angle or a direction) or LearnOpenGL's (a position, towards the
/// origin), with an orthographic shadow box.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct DirectionalFile {
    #[serde(default = "one3")]
    colour: Fixed<f32, 3>,
    #[serde(default = "one")]
    intensity: f32,
    /// The DummyGame's angle in degrees: direction (0, sin a, cos a).
    angle: Option<f32>,
    /// Towards the light; need not be normalised.
    direction: Option<Fixed<f32, 3>>,
    /// Shade from this point and put the shadow camera there, looking at the origin.
    position: Option<Fixed<f32, 3>>,
    shadow_pos_mult: Option<f32>,
    ortho: Option<OrthoCoords>,
    /// Whether it gets a shadow map (a light that does not cast lights all it faces).
    #[serde(default = "yes")]
    casts_shadows: bool,
    /// Its size: a directional light's angular diameter in degrees, a spot or point
    /// light's radius (0 = a point).
    #[serde(default)]
    size: f32,
    /// Its own shadow settings over the scene's `[shadow]`.
    #[serde(default)]
    shadow: ShadowPatch,
}

/// A positional light with a perspective shadow map.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SpotFile {
    #[serde(default = "one3")]
    colour: Fixed<f32, 3>,
    #[serde(default = "one")]
    intensity: f32,
    position: Fixed<f32, 3>,
    target: Fixed<f32, 3>,
    /// The shadow camera's up vector; `None` is +Y.
    up: Option<Fixed<f32, 3>>,
    fov: f32,
    /// The frustum's width over height.
    #[serde(default = "one")]
    aspect: f32,
    /// Whether a cone of `fov` limits the light (false: the whole frustum is lit).
    #[serde(default = "yes")]
    cone: bool,
    near: f32,
    far: f32,
    #[serde(default = "yes")]
    casts_shadows: bool,
    /// Its size: a directional light's angular diameter in degrees, a spot or point
    /// light's radius (0 = a point).
    #[serde(default)]
    size: f32,
    /// Its own shadow settings over the scene's `[shadow]`.
    #[serde(default)]
    shadow: ShadowPatch,
}

/// A light shining every way from a point (a depth cube map).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PointFile {
    #[serde(default = "one3")]
    colour: Fixed<f32, 3>,
    #[serde(default = "one")]
    intensity: f32,
    position: Fixed<f32, 3>,
    #[serde(default = "one")]
    near: f32,
    #[serde(default = "default_point_far")]
    far: f32,
    /// The light moves to position + oscillate * sin(0.5 t) (LearnOpenGL's moving light).
    #[serde(default)]
    oscillate: Fixed<f32, 3>,
    #[serde(default = "yes")]
    casts_shadows: bool,
    /// Its size: a directional light's angular diameter in degrees, a spot or point
    /// light's radius (0 = a point).
    #[serde(default)]
    size: f32,
    /// Its own shadow settings over the scene's `[shadow]`.
    #[serde(default)]
    shadow: ShadowPatch,
}

fn default_point_far() -> f32 {
    25.0
}

#[derive(Debug, Deserialize, Default, Clone, Copy, PartialEq, Eq, Hash)]
#[serde(rename_all = "kebab-case")]
enum Winding {
    #[default]
    Ccw,
    Cw,
}

/// A uniform scale or one per axis.
#[derive(Debug, Clone, Copy)]
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

/// By hand rather than `#[serde(untagged)]`, whose only complaint is "data did not match
/// any variant": this one says what `scale` takes.
impl<'de> Deserialize<'de> for ScaleFile {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct ScaleVisitor;
        impl<'de> Visitor<'de> for ScaleVisitor {
            type Value = ScaleFile;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number > 0 or three of them, [x, y, z]")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> std::result::Result<ScaleFile, E> {
                Ok(ScaleFile::Uniform(v as f32))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> std::result::Result<ScaleFile, E> {
                Ok(ScaleFile::Uniform(v as f32))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> std::result::Result<ScaleFile, E> {
                Ok(ScaleFile::Uniform(v as f32))
            }
            fn visit_seq<A: SeqAccess<'de>>(
                self,
                seq: A,
            ) -> std::result::Result<ScaleFile, A::Error> {
                read_exactly::<f32, 3, A>(seq).map(ScaleFile::Axes)
            }
        }
        d.deserialize_any(ScaleVisitor)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ItemFile {
    name: Option<String>,
    /// A built-in mesh (`cube`, `plane`, `sphere`, `terrain`) or a path to an OBJ file,
    /// relative to the scene file.
    mesh: String,
    #[serde(default)]
    position: Fixed<f32, 3>,
    #[serde(default)]
    rotation: Fixed<f32, 3>,
    /// Instead of `rotation`: turn `rotation_angle` degrees about this axis (LearnOpenGL's
    /// third cube), converted to the book's angles.
    rotation_axis: Option<Fixed<f32, 3>>,
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
    colour: Fixed<f32, 4>,
    /// A PNG, relative to the scene file; replaces the colour.
    texture: Option<String>,
    /// How many times the texture repeats across a built-in plane.
    #[serde(default = "one")]
    tiles: f32,
    #[serde(default = "one")]
    reflectance: f32,
    #[serde(default)]
    spin: Fixed<f32, 3>,
    #[serde(default = "yes")]
    casts_shadows: bool,
    /// Instead of one item, `count` copies strewn over an area (the `large` scene's
    /// forest of pillars), each turned and scaled at random from a fixed seed.
    scatter: Option<ScatterFile>,
    /// Tessellation of a built-in sphere ([segments, rings], default [48, 24]) or terrain
    /// ([cells, cells], default [64, 64]): many copies of a mesh want fewer triangles.
    detail: Option<Fixed<u32, 2>>,
}

fn unit_scale() -> ScaleFile {
    ScaleFile::Uniform(1.0)
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
    area: Fixed<f32, 4>,
    #[serde(default = "one3")]
    scale_min: Fixed<f32, 3>,
    #[serde(default = "one3")]
    scale_max: Fixed<f32, 3>,
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
        let [x0, x1, z0, z1] = self.area.0;
        (0..self.count)
            .map(|_| {
                let (x, z, turn) = (lerp(x0, x1, next()), lerp(z0, z1, next()), next() * 360.0);
                let scale = Vec3::from_array(std::array::from_fn(|k| {
                    lerp(self.scale_min.0[k], self.scale_max.0[k], next())
                }));
                ([x, z], turn, scale)
            })
            .collect()
    }
}

/// The built-in meshes, in the order messages list them.
const BUILTIN_MESHES: &str = "cube, plane, sphere, terrain";

// ---------------------------------------------------------------------------------------
// Arrays of exactly N

/// `[T; N]` that refuses an array of any other length. serde's own arrays read the first
/// N elements and the toml crate never says that more were left over, so `size = [64, 48,
/// 7]` would load as [64, 48].
#[derive(Debug, Clone, Copy, PartialEq)]
struct Fixed<T, const N: usize>([T; N]);

impl<T: Default + Copy, const N: usize> Default for Fixed<T, N> {
    fn default() -> Self {
        Fixed([T::default(); N])
    }
}

impl<'de, T: Deserialize<'de> + Default + Copy, const N: usize> Deserialize<'de> for Fixed<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct FixedVisitor<T, const N: usize>(PhantomData<T>);
        impl<'de, T: Deserialize<'de> + Default + Copy, const N: usize> Visitor<'de>
            for FixedVisitor<T, N>
        {
            type Value = Fixed<T, N>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "an array of {N} numbers")
            }
            fn visit_seq<A: SeqAccess<'de>>(
                self,
                seq: A,
            ) -> std::result::Result<Self::Value, A::Error> {
                read_exactly::<T, N, A>(seq).map(Fixed)
            }
        }
        d.deserialize_seq(FixedVisitor(PhantomData))
    }
}

/// Reads a sequence that must hold exactly N values, counting any beyond N to say how many
/// there were.
fn read_exactly<'de, T, const N: usize, A>(mut seq: A) -> std::result::Result<[T; N], A::Error>
where
    T: Deserialize<'de> + Default + Copy,
    A: SeqAccess<'de>,
{
    let mut out = [T::default(); N];
    let mut n = 0;
    while n < N {
        match seq.next_element::<T>()? {
            Some(v) => out[n] = v,
            None => break,
        }
        n += 1;
    }
    if n == N {
        while seq.next_element::<IgnoredAny>()?.is_some() {
            n += 1;
        }
    }
    if n != N {
        let s = if n == 1 { "" } else { "s" };
        return Err(de::Error::custom(format!(
            "{n} value{s} given: expected exactly {N} numbers"
        )));
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------
// The raw tree: every value with where it is

/// A parsed TOML value and the byte range it came from (via `toml::Spanned`), for line
/// numbers and field names in messages.
#[derive(Debug)]
enum Raw {
    Table(RawTable),
    Array(Vec<Spanned<Raw>>),
    Float(f64),
    String(String),
    /// Integers, booleans and dates: nothing here needs to look into them.
    Other,
}

type RawTable = Vec<(String, Spanned<Raw>)>;
/// A table's entries, borrowed.
type RawEntries = [(String, Spanned<Raw>)];

impl<'de> Deserialize<'de> for Raw {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct RawVisitor;
        impl<'de> Visitor<'de> for RawVisitor {
            type Value = Raw;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a TOML value")
            }
            fn visit_f64<E>(self, v: f64) -> std::result::Result<Raw, E> {
                Ok(Raw::Float(v))
            }
            fn visit_i64<E>(self, _: i64) -> std::result::Result<Raw, E> {
                Ok(Raw::Other)
            }
            fn visit_u64<E>(self, _: u64) -> std::result::Result<Raw, E> {
                Ok(Raw::Other)
            }
            fn visit_bool<E>(self, _: bool) -> std::result::Result<Raw, E> {
                Ok(Raw::Other)
            }
            fn visit_str<E>(self, v: &str) -> std::result::Result<Raw, E> {
                Ok(Raw::String(v.to_string()))
            }
            fn visit_seq<A: SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> std::result::Result<Raw, A::Error> {
                let mut values = Vec::new();
                while let Some(v) = seq.next_element()? {
                    values.push(v);
                }
                Ok(Raw::Array(values))
            }
            fn visit_map<A: MapAccess<'de>>(
                self,
                mut map: A,
            ) -> std::result::Result<Raw, A::Error> {
                let mut entries = Vec::new();
                while let Some(key) = map.next_key::<String>()? {
                    entries.push((key, map.next_value()?));
                }
                Ok(Raw::Table(entries))
            }
        }
        d.deserialize_any(RawVisitor)
    }
}

/// `[i]`, with the element's `name` when it has one: `[2] ("cube")`.
fn element_label(index: usize, name: Option<&str>) -> String {
    match name {
        Some(n) => format!("[{index}] ({n:?})"),
        None => format!("[{index}]"),
    }
}

fn raw_name(table: &RawTable) -> Option<&str> {
    table
        .iter()
        .find_map(|(k, v)| match (k.as_str(), v.get_ref()) {
            ("name", Raw::String(s)) => Some(s.as_str()),
            _ => None,
        })
}

/// The field the byte `offset` lies in, named as messages name it (`item[2] ("cube").scale`),
/// down to the innermost table or array that holds it.
fn field_at(root: &RawTable, offset: usize) -> Option<String> {
    let mut field = String::new();
    let mut table = root;
    while let Some((key, value)) = table.iter().find(|(_, v)| v.span().contains(&offset)) {
        if !field.is_empty() {
            field.push('.');
        }
        field.push_str(key);
        match value.get_ref() {
            Raw::Table(t) => table = t,
            Raw::Array(elements) => {
                let inner = elements
                    .iter()
                    .enumerate()
                    .find_map(|(i, e)| match e.get_ref() {
                        Raw::Table(t) if e.span().contains(&offset) => Some((i, t)),
                        _ => None,
                    });
                match inner {
                    Some((i, t)) => {
                        field.push_str(&element_label(i, raw_name(t)));
                        table = t;
                    }
                    None => break,
                }
            }
            _ => break,
        }
    }
    (!field.is_empty()).then_some(field)
}

/// Arrays of a fixed length in tables this module does not type itself (`[shadow]` is
/// `ShadowSettings`, whose `[f32; 2]` would take a longer array): (field, length, meaning).
const FOREIGN_ARRAYS: &[(&str, usize, &str)] = &[("shadow.polygon_offset", 2, "[factor, units]")];

/// Refuses numbers no field of a scene takes, wherever they are: NaN, infinities, and
/// values too large for the f32 every field is read into. Also checks `FOREIGN_ARRAYS`.
fn check_raw(
    table: &RawTable,
    prefix: &str,
    text: &str,
) -> std::result::Result<(), (String, String)> {
    for (key, value) in table {
        let field = if prefix.is_empty() {
            key.clone()
        } else {
            format!("{prefix}.{key}")
        };
        check_raw_value(value, &field, text)?;
    }
    Ok(())
}

fn check_raw_value(
    value: &Spanned<Raw>,
    field: &str,
    text: &str,
) -> std::result::Result<(), (String, String)> {
    let at = || {
        let (line, _) = line_col(text, value.span().start);
        format!("line {line}")
    };
    match value.get_ref() {
        Raw::Float(v) => {
            let f = *v as f32;
            if v.is_nan() || v.is_infinite() {
                return Err((
                    field.into(),
                    format!("{v} is not a finite number ({})", at()),
                ));
            }
            if f.is_infinite() {
                return Err((
                    field.into(),
                    format!(
                        "{v:e} is too large: expected a number within +-{:e} (32-bit floats; {})",
                        f32::MAX,
                        at()
                    ),
                ));
            }
            Ok(())
        }
        Raw::Table(t) => check_raw(t, field, text),
        Raw::Array(elements) => {
            // `shadow.polygon_offset`, also in a light's own `shadow` table.
            let foreign = FOREIGN_ARRAYS
                .iter()
                .find(|(f, _, _)| field == *f || field.ends_with(&format!(".{f}")));
            if let Some((_, len, meaning)) = foreign {
                if elements.len() != *len {
                    let n = elements.len();
                    let s = if n == 1 { "" } else { "s" };
                    return Err((
                        field.into(),
                        format!(
                            "{n} value{s} given: expected exactly {len} numbers {meaning} ({})",
                            at()
                        ),
                    ));
                }
            }
            for (i, e) in elements.iter().enumerate() {
                match e.get_ref() {
                    Raw::Table(t) => {
                        let label = format!("{field}{}", element_label(i, raw_name(t)));
                        check_raw(t, &label, text)?;
                    }
                    _ => check_raw_value(e, field, text)?,
                }
            }
            Ok(())
        }
        Raw::String(_) | Raw::Other => Ok(()),
    }
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before[before.rfind('\n').map_or(0, |i| i + 1)..]
        .chars()
        .count()
        + 1;
    (line, col)
}

/// The name inside the first backticks after `prefix` in a serde message
/// ("unknown field `shininess`, expected ...").
fn backticked<'m>(message: &'m str, prefix: &str) -> Option<&'m str> {
    let rest = &message[message.find(prefix)? + prefix.len()..];
    rest.split('`').next()
}

/// serde names Rust types ("expected f32"); say what to write instead.
fn friendly(message: &str) -> String {
    [
        ("expected f32", "expected a number"),
        ("expected f64", "expected a number"),
        (
            "expected u32",
            "expected a whole number from 0 to 4294967295",
        ),
        ("expected u64", "expected a whole number >= 0"),
        ("expected a boolean", "expected true or false"),
        ("expected a map", "expected a table"),
        ("expected a sequence", "expected an array"),
        (
            "expected struct OrthoCoords",
            "expected a table { left, right, bottom, top, near, far }",
        ),
    ]
    .iter()
    .fold(message.to_string(), |m, (from, to)| m.replace(from, to))
}

// ---------------------------------------------------------------------------------------
// Parsing

/// Reads a scene file; relative mesh and texture paths resolve from its folder.
pub fn load_file(path: &Path) -> Result<Scene> {
    let text = read_text_file(path, SCENE_LIMIT, "scene file")?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    parse(&text, path, Some(&base))
}

/// Parses scene TOML. `source` names it in errors; `base` is where relative paths start
/// (`None` for built-in scenes, which may only use built-in meshes).
pub fn parse(text: &str, source: &Path, base: Option<&Path>) -> Result<Scene> {
    let raw = match toml::from_str::<Raw>(text) {
        Ok(Raw::Table(t)) => t,
        Ok(_) => return Err(Error::Internal("a TOML document is not a table".into())),
        Err(e) => return Err(toml_error(&e, text, None, source)),
    };
    check_raw(&raw, "", text)
        .map_err(|(field, message)| Error::in_field(source, field, message))?;
    let file: SceneFile =
        toml::from_str(text).map_err(|e| toml_error(&e, text, Some(&raw), source))?;
    let cx = Context {
        source,
        base,
        raw: &raw,
        text,
    };
    build(file, &cx)
}

/// A parse error with its line and column, and its field when the raw tree can tell.
fn toml_error(e: &toml::de::Error, text: &str, raw: Option<&RawTable>, source: &Path) -> Error {
    let message = friendly(e.message());
    let Some(span) = e.span() else {
        return Error::file(source, message);
    };
    let (line, col) = line_col(text, span.start);
    let message = format!("line {line}, column {col}: {message}");
    let mut field = raw.and_then(|r| field_at(r, span.start));
    // An unknown or missing key is not a value in the tree: add it to its table's name.
    let key = backticked(e.message(), "unknown field `")
        .or_else(|| backticked(e.message(), "missing field `"));
    if let Some(key) = key {
        field = Some(match field {
            Some(f) => format!("{f}.{key}"),
            None => key.to_string(),
        });
    }
    match field {
        Some(field) => Error::in_field(source, field, message),
        None => Error::file(source, message),
    }
}

/// What building needs besides the typed file: where it came from, for messages and
/// relative paths.
struct Context<'a> {
    source: &'a Path,
    base: Option<&'a Path>,
    raw: &'a RawTable,
    text: &'a str,
}

impl Context<'_> {
    fn bad(&self, field: impl Into<String>, message: impl Into<String>) -> Error {
        Error::in_field(self.source, field, message)
    }

    /// `values` must all be finite (the raw check refuses NaN in the file; this guards
    /// what is computed from it).
    fn finite(&self, field: &str, values: &[f32]) -> Result<()> {
        match values.iter().find(|v| !v.is_finite()) {
            Some(v) => Err(self.bad(field, format!("{v} is not a finite number"))),
            None => Ok(()),
        }
    }

    /// `values` must all be >= 0 (colours, intensities, ambient light).
    fn non_negative(&self, field: &str, values: &[f32]) -> Result<()> {
        if values.iter().any(|v| *v < 0.0) {
            let shown = match values {
                [v] => v.to_string(),
                _ => format!("{values:?}"),
            };
            let what = if values.len() == 1 {
                "a number"
            } else {
                "numbers"
            };
            return Err(self.bad(field, format!("{shown}: expected {what} >= 0")));
        }
        Ok(())
    }

    /// The raw table of `light` (index `None`) or `lights[i]`, and where it starts.
    fn raw_light(&self, index: Option<usize>) -> Option<(usize, &RawEntries)> {
        let key = if index.is_some() { "lights" } else { "light" };
        let value = &self.raw.iter().find(|(k, _)| k == key)?.1;
        let value = match (value.get_ref(), index) {
            (Raw::Array(a), Some(i)) => a.get(i)?,
            (_, None) => value,
            _ => return None,
        };
        match value.get_ref() {
            Raw::Table(t) => Some((value.span().start, t)),
            _ => None,
        }
    }

    /// "line L, column C" of the value at `keys` (dotted) inside `table`, or of the
    /// innermost value on the way that is not a table.
    fn where_in(&self, table: Option<&RawEntries>, keys: &str) -> Option<String> {
        let mut table = table?;
        let mut start = None;
        for key in keys.split('.') {
            let value = &table.iter().find(|(k, _)| k == key)?.1;
            start = Some(value.span().start);
            match value.get_ref() {
                Raw::Table(t) => table = t,
                _ => break,
            }
        }
        let (line, col) = line_col(self.text, start?);
        Some(format!("line {line}, column {col}"))
    }
}

// ---------------------------------------------------------------------------------------
// Building the scene

fn build(file: SceneFile, cx: &Context) -> Result<Scene> {
    check_globals(&file, cx)?;
    let camera = build_camera(&file.camera, "camera", cx)?;
    let lights = build_lights(file.light, file.lights, cx)?;
    // map_size is checked against the driver's maximum once there is a driver.
    file.shadow
        .validate_values()
        .map_err(|e| Error::file(cx.source, e.to_string()))?;
    // Each light's own table, over the scene's.
    for (i, light) in lights.iter().enumerate() {
        if !light.shadow_patch().given().is_empty() {
            let field = match lights.len() {
                1 => "light.shadow".to_string(),
                _ => format!("lights[{i}].shadow"),
            };
            refusals::own_settings(light, &file.shadow)
                .validate_values()
                .map_err(|e| cx.bad(field, e.to_string()))?;
        }
    }
    // What a light cannot be drawn with (the book's angle view off the YZ plane, which
    // would say nothing; a non-square map for a cube map or cascades): the setting named.
    let prefix = |i: usize| match lights.len() {
        1 => "light".to_string(),
        _ => format!("lights[{i}]"),
    };
    if let Err(refused) = refusals::check(&lights, &file.shadow, prefix) {
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
    let steps = build_steps(&file.steps, &file.camera, cx)?;
    if let Some(size) = steps.light_size {
        if let Some(problem) = lights.iter().find_map(|l| l.size_problem(size)) {
            return Err(cx.bad("steps.light_size", problem));
        }
    }
    let mut items = Items::default();
    for (i, item) in file.items.into_iter().enumerate() {
        items.add(i, item, cx)?;
    }
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
        time: 0.0,
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

/// The top-level numbers: frame size, colours, the specular power.
fn check_globals(file: &SceneFile, cx: &Context) -> Result<()> {
    let size = file.size.0;
    if size[0] == 0 || size[1] == 0 {
        return Err(cx.bad("size", format!("{size:?}: expected both sides at least 1")));
    }
    cx.finite("clear_colour", &file.clear_colour.0)?;
    cx.non_negative("clear_colour", &file.clear_colour.0)?;
    cx.finite("ambient", &file.ambient.0)?;
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
    cx.finite(&format!("{table}.position"), &c.position.0)?;
    let position = Vec3::from(c.position.0);
    let rotation = match (&c.rotation, &c.target) {
        (Some(_), Some(_)) => {
            return Err(cx.bad(
                table,
                "rotation and target are both given: a camera takes one (rotation = angles, \
                 target = a point to look at)",
            ))
        }
        (Some(r), None) => {
            cx.finite(&format!("{table}.rotation"), &r.0)?;
            Vec3::from(r.0)
        }
        (None, Some(t)) => {
            cx.finite(&format!("{table}.target"), &t.0)?;
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
    cx.finite(&format!("{table}.fov"), &[c.fov])?;
    cx.finite(&format!("{table}.near"), &[c.near])?;
    cx.finite(&format!("{table}.far"), &[c.far])?;
    if !(c.near > 0.0 && c.near < c.far) {
        return Err(cx.bad(
            table,
            format!(
                "near = {}, far = {}: expected 0 < near < far",
                c.near, c.far
            ),
        ));
    }
    if !(c.fov > 0.0 && c.fov < 180.0) {
        return Err(cx.bad(
            format!("{table}.fov"),
            format!("{}: expected degrees between 0 and 180", c.fov),
        ));
    }
    Ok(Camera {
        position,
        rotation,
        fov: c.fov,
        near: c.near,
        far: c.far,
    })
}

fn build_steps(s: &StepsFile, scene_camera: &CameraFile, cx: &Context) -> Result<StepContext> {
    if !(s.bias.is_finite() && s.bias >= 0.0) {
        return Err(cx.bad(
            "steps.bias",
            format!("{}: expected a finite number >= 0", s.bias),
        ));
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

fn build_lights(
    light: Option<toml::Table>,
    lights: Vec<toml::Table>,
    cx: &Context,
) -> Result<Vec<Light>> {
    match (light, lights.len()) {
        (Some(l), 0) => Ok(vec![build_light(read_light(l, None, cx)?, "light", cx)?]),
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
        (None, _) => lights
            .into_iter()
            .enumerate()
            .map(|(i, l)| build_light(read_light(l, Some(i), cx)?, &format!("lights[{i}]"), cx))
            .collect(),
        (Some(_), _) => Err(cx.bad(
            "light",
            "give either one [light] table or [[lights]] tables, not both",
        )),
    }
}

/// The field names serde derives for the struct `T`: it is asked to deserialize itself
/// from a deserializer that only records the names it is given.
fn fields_of<'de, T: Deserialize<'de>>() -> &'static [&'static str] {
    struct Probe<'a>(&'a mut &'static [&'static str]);
    impl<'de> Deserializer<'de> for Probe<'_> {
        type Error = de::value::Error;
        fn deserialize_any<V: Visitor<'de>>(
            self,
            _: V,
        ) -> std::result::Result<V::Value, Self::Error> {
            Err(de::Error::custom("not a struct"))
        }
        fn deserialize_struct<V: Visitor<'de>>(
            self,
            _: &'static str,
            fields: &'static [&'static str],
            _: V,
        ) -> std::result::Result<V::Value, Self::Error> {
            *self.0 = fields;
            Err(de::Error::custom("probed"))
        }
        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes
            byte_buf option unit unit_struct newtype_struct seq tuple tuple_struct map enum
            identifier ignored_any
        }
    }
    let mut fields: &'static [&'static str] = &[];
    let _ = T::deserialize(Probe(&mut fields));
    fields
}

/// The fields a light kind takes, `kind` first.
fn light_fields(kind: &str) -> Vec<&'static str> {
    let fields = match kind {
        "spot" => fields_of::<SpotFile>(),
        "point" => fields_of::<PointFile>(),
        _ => fields_of::<DirectionalFile>(),
    };
    std::iter::once("kind")
        .chain(fields.iter().copied())
        .collect()
}

/// Reads one light table by its kind. `index` is None for `[light]`, i for `lights[i]`.
fn read_light(mut table: toml::Table, index: Option<usize>, cx: &Context) -> Result<LightFile> {
    let at = LightAt::new(index, cx);
    let kind = match table.remove("kind") {
        None => "directional".to_string(),
        Some(toml::Value::String(k)) if LIGHT_KINDS.contains(&k.as_str()) => k,
        Some(other) => {
            return Err(cx.bad(
                format!("{}.kind", at.prefix),
                format!(
                    "{other}: expected \"directional\" (the default), \"spot\" or \"point\"{}",
                    at.key("kind")
                ),
            ))
        }
    };
    refuse_other_fields(&table, &kind, &at, cx)?;
    let value = toml::Value::Table(table);
    let read = match kind.as_str() {
        "spot" => SpotFile::deserialize(value).map(LightFile::Spot),
        "point" => PointFile::deserialize(value).map(LightFile::Point),
        _ => DirectionalFile::deserialize(value).map(LightFile::Directional),
    };
    read.map_err(|e| light_error(&e, &kind, &at, cx))
}

/// Where a light is, for its messages: its name and its raw table.
struct LightAt<'a> {
    /// `light` or `lights[i]`.
    prefix: String,
    raw: Option<&'a RawEntries>,
    cx: &'a Context<'a>,
    /// " (the table at line L)", to find a light whose table lacks something.
    table: String,
}

impl<'a> LightAt<'a> {
    fn new(index: Option<usize>, cx: &'a Context<'a>) -> Self {
        let found = cx.raw_light(index);
        LightAt {
            prefix: index.map_or("light".to_string(), |i| format!("lights[{i}]")),
            raw: found.map(|(_, t)| t),
            cx,
            table: found.map_or(String::new(), |(start, _)| {
                format!(" (the table at line {})", line_col(cx.text, start).0)
            }),
        }
    }

    /// " (line L, column C)" of the value of `keys` (dotted) in this light, if found.
    fn key(&self, keys: &str) -> String {
        self.cx
            .where_in(self.raw, keys)
            .map_or(String::new(), |w| format!(" ({w})"))
    }
}

/// A field of another kind: "not used by a point light"; one of no kind: "unknown field".
/// Both list what this kind takes (the names serde derives, so the list cannot go stale).
fn refuse_other_fields(table: &toml::Table, kind: &str, at: &LightAt, cx: &Context) -> Result<()> {
    let takes = light_fields(kind);
    let Some(key) = table.keys().find(|k| !takes.contains(&k.as_str())) else {
        return Ok(());
    };
    let takes = takes.join(", ");
    let elsewhere = LIGHT_KINDS
        .iter()
        .any(|k| light_fields(k).contains(&key.as_str()));
    let message = if elsewhere {
        format!(
            "not used by a {kind} light{}; it takes {takes}",
            at.key(key)
        )
    } else {
        format!("unknown field{}; a {kind} light takes {takes}", at.key(key))
    };
    Err(cx.bad(format!("{}.{key}", at.prefix), message))
}

/// A serde error reading a light's table, with its field and line.
fn light_error(e: &toml::de::Error, kind: &str, at: &LightAt, cx: &Context) -> Error {
    // Read from a `toml::Value` there is no span, and the message ends with "in `keys`".
    let shown = e.to_string();
    let keys = shown
        .lines()
        .find_map(|l| l.strip_prefix("in `")?.strip_suffix('`'))
        .unwrap_or("");
    let missing = backticked(e.message(), "missing field `");
    if let (Some(missing), "") = (missing, keys) {
        return cx.bad(
            format!("{}.{missing}", at.prefix),
            format!("a {kind} light needs it{}", at.table),
        );
    }
    let mut field = match keys {
        "" => at.prefix.clone(),
        k => format!("{}.{k}", at.prefix),
    };
    // A table inside the light (`ortho`) lacking a key: name the key.
    if let Some(missing) = missing {
        field = format!("{field}.{missing}");
    }
    let located = cx
        .where_in(at.raw, keys)
        .map_or(String::new(), |w| format!("{w}: "));
    cx.bad(field, format!("{located}{}", friendly(e.message())))
}

fn build_light(light: LightFile, prefix: &str, cx: &Context) -> Result<Light> {
    match light {
        LightFile::Directional(d) => directional(d, prefix, cx),
        LightFile::Spot(s) => spot(s, prefix, cx),
        LightFile::Point(p) => point(p, prefix, cx),
    }
}

/// Colour and intensity, checked alike for every kind.
fn light_colour(
    colour: &Fixed<f32, 3>,
    intensity: f32,
    prefix: &str,
    cx: &Context,
) -> Result<Vec3> {
    cx.finite(&format!("{prefix}.colour"), &colour.0)?;
    cx.non_negative(&format!("{prefix}.colour"), &colour.0)?;
    cx.finite(&format!("{prefix}.intensity"), &[intensity])?;
    cx.non_negative(&format!("{prefix}.intensity"), &[intensity])?;
    Ok(Vec3::from(colour.0))
}

fn near_far(near: f32, far: f32, prefix: &str, cx: &Context) -> Result<()> {
    cx.finite(&format!("{prefix}.near"), &[near])?;
    cx.finite(&format!("{prefix}.far"), &[far])?;
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
        cx.finite(&field(name), &v.to_array())?;
        v.try_normalize()
            .ok_or_else(|| cx.bad(field(name), format!("{v}: expected a non-zero vector")))
    };
    let position = l.position.map(|p| Vec3::from(p.0));
    let direction = match (l.angle, l.direction, position) {
        (Some(a), None, None) => {
            cx.finite(&field("angle"), &[a])?;
            DirectionalLight::direction_from_angle(a)
        }
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
    cx.finite(&field("shadow_pos_mult"), &[shadow_pos_mult])?;
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

/// An ortho box must be finite, ordered, and not so wide that its width overflows f32
/// (left = -3e38, right = 3e38 is ordered, but the projection divides by an infinity).
fn check_ortho(o: &OrthoCoords, field: &str, cx: &Context) -> Result<()> {
    cx.finite(field, &[o.left, o.right, o.bottom, o.top, o.near, o.far])?;
    if !(o.left < o.right && o.bottom < o.top && o.near < o.far) {
        return Err(cx.bad(
            field,
            format!("{o:?}: expected left < right, bottom < top and near < far"),
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
                    "{o:?}: {name} overflows 32-bit floats: expected a box less than {:e} across",
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
    cx.finite(&format!("{prefix}.position"), &l.position.0)?;
    cx.finite(&format!("{prefix}.oscillate"), &l.oscillate.0)?;
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
    cx.finite(&field("position"), &l.position.0)?;
    cx.finite(&field("target"), &l.target.0)?;
    if let Some(up) = &l.up {
        cx.finite(&field("up"), &up.0)?;
        if Vec3::from(up.0).length() < 1e-6 {
            return Err(cx.bad(
                field("up"),
                format!("{:?}: expected a non-zero vector", up.0),
            ));
        }
    }
    cx.finite(&field("fov"), &[l.fov])?;
    cx.finite(&field("aspect"), &[l.aspect])?;
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

// ---------------------------------------------------------------------------------------
// Items, meshes and textures

/// Meshes and textures are shared between items: one upload for many copies.
type MeshKey = (String, u32, Winding, bool, Option<[u32; 2]>);

#[derive(Default)]
struct Items {
    items: Vec<GameItem>,
    meshes: Vec<MeshData>,
    mesh_ids: HashMap<MeshKey, usize>,
    textures: Vec<ImageData>,
    texture_ids: HashMap<PathBuf, usize>,
}

/// `item[2] ("cube")`, or `item[2]` for an item without a name.
fn item_label(index: usize, name: Option<&str>) -> String {
    format!("item{}", element_label(index, name))
}

impl Items {
    fn add(&mut self, i: usize, item: ItemFile, cx: &Context) -> Result<()> {
        let label = item_label(i, item.name.as_deref());
        let field = |f: &str| format!("{label}.{f}");
        for (name, values) in [
            ("position", &item.position.0[..]),
            ("rotation", &item.rotation.0[..]),
            ("colour", &item.colour.0[..]),
            ("spin", &item.spin.0[..]),
            ("reflectance", &[item.reflectance][..]),
        ] {
            cx.finite(&field(name), values)?;
        }
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
            casts_shadows: item.casts_shadows,
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
            cx.finite(&field("rotation_axis"), &axis.0)?;
            cx.finite(&field("rotation_angle"), &[angle])?;
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
    cx.finite(&field("scatter.area"), &sc.area.0)?;
    cx.finite(&field("scatter.scale_min"), &sc.scale_min.0)?;
    cx.finite(&field("scatter.scale_max"), &sc.scale_max.0)?;
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
        .map(|(k, ([x, z], turn, factor))| GameItem {
            name: format!("{}{k}", one.name),
            position: one.position + Vec3::new(x, 0.0, z),
            rotation: one.rotation + Vec3::new(0.0, turn, 0.0),
            scale: one.scale * factor,
            ..one.clone()
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIGHT: &str = "[light]\nangle = 45.0\n";

    /// The error for `text` as a scene file in /tmp: (its field, its whole message).
    fn fails(text: &str) -> (Option<String>, String) {
        match parse(text, Path::new("s.toml"), Some(Path::new("/tmp"))) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => (e.field().map(String::from), e.to_string()),
        }
    }

    /// Asserts the error names `field` and its message contains `fragment`.
    fn refuses(text: &str, field: &str, fragment: &str) {
        let (f, message) = fails(text);
        assert_eq!(f.as_deref(), Some(field), "{message}");
        assert!(
            message.starts_with(&format!("s.toml: {field}: ")),
            "{message}"
        );
        assert!(message.contains(fragment), "{message}\n  lacks: {fragment}");
    }

    #[test]
    fn a_lights_size_is_read_and_checked_for_its_kind() {
        let sun = parse(
            "[light]\nangle = 45.0\nsize = 0.53\n",
            Path::new("s.toml"),
            None,
        )
        .unwrap();
        assert_eq!(sun.lights[0].size(), 0.53);
        refuses(
            "[light]\nangle = 45.0\nsize = 90.0\n",
            "light.size",
            "90: expected an angular diameter in degrees (the sun: 0.53) under 90",
        );
        refuses(
            "[light]\nkind = \"point\"\nposition = [0.0, 1.0, 0.0]\nsize = -0.5\n",
            "light.size",
            "-0.5: expected a radius in world units >= 0 (0 = a point)",
        );
        refuses(
            "[light]\nangle = 45.0\n[steps]\nlight_size = 120.0\n",
            "steps.light_size",
            "120: expected an angular diameter in degrees",
        );
        refuses(
            "[light]\nangle = 45.0\n[steps]\nlist = \"book\"\n",
            "steps.list",
            "unknown variant `book`, expected `chapters` or `playground`",
        );
    }

    #[test]
    fn every_built_in_scene_loads() {
        for name in Scene::builtin_names() {
            let scene = Scene::load(name).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(
                !scene.lights.is_empty() && !scene.items.is_empty(),
                "{name}"
            );
        }
        let three = Scene::load("three-lights").unwrap();
        let kinds: Vec<&str> = three
            .lights
            .iter()
            .map(|l| match l {
                Light::Directional(_) => "directional",
                Light::Spot(_) => "spot",
                Light::Point(_) => "point",
            })
            .collect();
        assert_eq!(kinds, ["directional", "spot", "point", "point"]);
        // No `kind` is a directional light, in [light] and in [[lights]] alike.
        for text in [LIGHT, "[[lights]]\nangle = 45.0\n"] {
            let s = parse(text, Path::new("s.toml"), None).unwrap();
            assert!(matches!(s.lights[..], [Light::Directional(_)]), "{text}");
        }
    }

    #[test]
    fn a_camera_target_becomes_the_books_angles() {
        let text =
            format!("{LIGHT}[camera]\nposition = [0.0, 4.0, 9.0]\ntarget = [0.0, 0.0, 0.0]\n");
        let s = parse(&text, Path::new("s.toml"), None).unwrap();
        let want = Camera::look_at(Vec3::new(0.0, 4.0, 9.0), Vec3::ZERO).unwrap();
        assert_eq!(s.camera.rotation, want.rotation);
        // Looking down at the origin from above and behind: pitch down, no yaw, no roll.
        assert!((s.camera.rotation.x - (4.0f32 / 9.0).atan().to_degrees()).abs() < 1e-4);
        assert_eq!((s.camera.rotation.y, s.camera.rotation.z), (0.0, 0.0));
        refuses(
            &format!("{LIGHT}[camera]\nrotation = [10.0, 0.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n"),
            "camera",
            "rotation and target are both given",
        );
        refuses(
            &format!("{LIGHT}[camera]\nposition = [1.0, 2.0, 3.0]\ntarget = [1.0, 2.0, 3.0]\n"),
            "camera.target",
            "the camera's own position",
        );
        refuses(
            &format!("{LIGHT}[camera]\ntarget = [1.0, 2.0]\n"),
            "camera.target",
            "expected exactly 3 numbers",
        );
    }

    #[test]
    fn arrays_of_the_wrong_length_are_refused() {
        let exactly =
            |n: usize, k: usize| format!("{n} values given: expected exactly {k} numbers");
        refuses(
            &format!("size = [64, 48, 7]\n{LIGHT}"),
            "size",
            &exactly(3, 2),
        );
        refuses(
            &format!("{LIGHT}[camera]\nposition = [1.0, 2.0, 3.0, 4.0]\n"),
            "camera.position",
            &format!("line 4, column 12: {}", exactly(4, 3)),
        );
        refuses(
            &format!("clear_colour = [0.0, 0.0, 0.0, 0.0, 1.0]\n{LIGHT}"),
            "clear_colour",
            &exactly(5, 3),
        );
        refuses(
            &format!("{LIGHT}colour = [1.0, 1.0, 1.0, 1.0]\n"),
            "light.colour",
            &exactly(4, 3),
        );
        refuses(
            &format!("{LIGHT}[shadow]\npolygon_offset = [1.0, 2.0, 3.0]\n"),
            "shadow.polygon_offset",
            &format!("{} [factor, units] (line 4)", exactly(3, 2)),
        );
        refuses(
            &format!("{LIGHT}[[item]]\nname = \"ball\"\nmesh = \"sphere\"\ndetail = [8, 8, 8]\n"),
            "item[0] (\"ball\").detail",
            &exactly(3, 2),
        );
        refuses(
            &format!(
                "{LIGHT}[[item]]\nmesh = \"cube\"\n\
                 scatter = {{ count = 2, area = [0.0, 1.0, 0.0, 1.0, 5.0] }}\n"
            ),
            "item[0].scatter.area",
            &exactly(5, 4),
        );
        refuses(
            &format!("{LIGHT}[[item]]\nmesh = \"cube\"\ncolour = [1.0, 1.0, 1.0, 1.0, 1.0]\n"),
            "item[0].colour",
            &exactly(5, 4),
        );
        refuses(
            &format!("{LIGHT}[[item]]\nmesh = \"cube\"\nscale = [1.0, 2.0, 3.0, 4.0]\n"),
            "item[0].scale",
            &exactly(4, 3),
        );
        refuses(
            &format!("{LIGHT}[[item]]\nmesh = \"cube\"\nposition = [1.0]\n"),
            "item[0].position",
            "1 value given: expected exactly 3 numbers",
        );
    }

    #[test]
    fn numbers_no_field_takes_are_refused_anywhere() {
        refuses(
            &format!("{LIGHT}[steps]\nbias = nan\n"),
            "steps.bias",
            "NaN is not a finite number (line 4)",
        );
        refuses(
            &format!("{LIGHT}[shadow]\nperspective_fov = -nan\n"),
            "shadow.perspective_fov",
            "NaN is not a finite number",
        );
        refuses(
            &format!("{LIGHT}[[item]]\nmesh = \"cube\"\nspin = [0.0, inf, 0.0]\n"),
            "item[0].spin",
            "inf is not a finite number",
        );
        refuses(
            &format!("{LIGHT}[camera]\nfar = 1e39\n"),
            "camera.far",
            "1e39 is too large: expected a number within +-3.4028235e38",
        );
        refuses(
            &format!("{LIGHT}[steps]\nbias = -0.5\n"),
            "steps.bias",
            "-0.5: expected a finite number >= 0",
        );
    }

    #[test]
    fn negative_light_and_overflowing_boxes_are_refused() {
        refuses(
            &format!("ambient = [-0.1, 0.0, 0.0]\n{LIGHT}"),
            "ambient",
            "[-0.1, 0.0, 0.0]: expected numbers >= 0",
        );
        refuses(
            &format!("specular_power = -2.0\n{LIGHT}"),
            "specular_power",
            "-2: expected a number > 0",
        );
        refuses(
            &format!("{LIGHT}intensity = -1.0\n"),
            "light.intensity",
            "-1: expected a number >= 0",
        );
        refuses(
            "[[lights]]\nangle = 1.0\n[[lights]]\nkind = \"point\"\nposition = [0.0, 1.0, 0.0]\n\
             colour = [1.0, -1.0, 1.0]\n",
            "lights[1].colour",
            "[1.0, -1.0, 1.0]: expected numbers >= 0",
        );
        refuses(
            "[light]\nangle = 45.0\northo = { left = -3e38, right = 3e38, bottom = -1.0, \
             top = 1.0, near = 0.0, far = 1.0 }\n",
            "light.ortho",
            "right - left overflows 32-bit floats",
        );
        refuses(
            &format!(
                "{LIGHT}[[item]]\nmesh = \"cube\"\n\
                 scatter = {{ count = 2, area = [-3e38, 3e38, 0.0, 1.0] }}\n"
            ),
            "item[0].scatter.area",
            "the area's width overflows 32-bit floats",
        );
    }

    #[test]
    fn messages_say_what_a_field_takes() {
        let cube = format!(
            "{LIGHT}[[item]]\nmesh = \"cube\"\n[[item]]\nname = \"cube\"\nmesh = \"cube\"\n"
        );
        refuses(
            &format!("{cube}scale = \"big\"\n"),
            "item[1] (\"cube\").scale",
            "line 8, column 9: invalid type: string \"big\", expected a number > 0 or three \
             of them, [x, y, z]",
        );
        refuses(
            &format!("{cube}scale = -1.0\n"),
            "item[1] (\"cube\").scale",
            "-1: expected a finite number > 0",
        );
        refuses(
            &format!("{cube}reflectance = \"x\"\n"),
            "item[1] (\"cube\").reflectance",
            "invalid type: string \"x\", expected a number",
        );
        refuses(
            &format!("size = [1.5, 2]\n{LIGHT}"),
            "size",
            "expected a whole number from 0 to 4294967295",
        );
        refuses(
            &format!("{LIGHT}[[item]]\nmesh = \"cueb\"\n"),
            "item[0].mesh",
            "'cueb' is not a built-in mesh (cube, plane, sphere, terrain), and there is no \
             OBJ file at /tmp/cueb",
        );
        refuses(
            &format!("{LIGHT}[[item]]\nname = \"x\"\nposition = [0.0, 0.0, 0.0]\n"),
            "item[0] (\"x\").mesh",
            "line 3, column 1: missing field `mesh`",
        );
    }

    #[test]
    fn each_light_kind_takes_its_own_fields() {
        refuses(
            "[[lights]]\nangle = 45.0\n[[lights]]\nkind = \"point\"\nposition = [0.0, 1.0, 0.0]\n\
             fov = 30.0\n",
            "lights[1].fov",
            "not used by a point light (line 6, column 7); it takes kind, colour, intensity, \
             position, near, far, oscillate, casts_shadows, size, shadow",
        );
        refuses(
            "[light]\nangle = 45.0\nshadow_pos_multi = 5.0\n",
            "light.shadow_pos_multi",
            "unknown field (line 3, column 20); a directional light takes kind, colour",
        );
        refuses(
            "[light]\nkind = \"spot\"\nposition = [0.0, 1.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n\
             fov = 30.0\nfar = 5.0\n",
            "light.near",
            "a spot light needs it (the table at line 1)",
        );
        refuses(
            "[light]\nkind = \"spott\"\n",
            "light.kind",
            "\"spott\": expected \"directional\" (the default), \"spot\" or \"point\"",
        );
        refuses(
            "[light]\nangle = \"high\"\n",
            "light.angle",
            "line 2, column 9: invalid type: string \"high\", expected a number",
        );
        refuses(
            "[light]\nangle = 45.0\northo = { right = 1.0, bottom = -1.0, top = 1.0, near = 0.0, \
             far = 1.0 }\n",
            "light.ortho.left",
            "missing field `left`",
        );
        refuses(
            "[light]\nangle = 45.0\ndirection = [0.0, 1.0, 0.0]\n",
            "light",
            "expected exactly one of `angle`",
        );
    }

    #[test]
    fn fields_of_reads_what_serde_derives() {
        assert_eq!(
            fields_of::<PointFile>(),
            [
                "colour",
                "intensity",
                "position",
                "near",
                "far",
                "oscillate",
                "casts_shadows",
                "size",
                "shadow"
            ]
        );
        assert!(fields_of::<Fixed<f32, 3>>().is_empty());
    }

    #[test]
    fn field_at_names_items_by_index_and_name() {
        let text = "a = 1.0\n[[item]]\nmesh = \"x\"\n[[item]]\nname = \"b\"\ncolour = [1.0]\n";
        let Ok(Raw::Table(raw)) = toml::from_str::<Raw>(text) else {
            panic!("parses")
        };
        let at = |needle: &str| field_at(&raw, text.find(needle).unwrap());
        assert_eq!(at("1.0]").as_deref(), Some("item[1] (\"b\").colour"));
        assert_eq!(at("\"x\"").as_deref(), Some("item[0].mesh"));
        assert_eq!(at("1.0\n").as_deref(), Some("a"));
    }
}
