//! Scene files: TOML with a camera, lights, shadow settings and items. The format is
//! documented in docs/scene-format.md (every field: docs/reference-scene.toml); this module
//! is its one implementation.
//!
//! toml parses the text into its own tree of spans ([`DeTable`]), and serde reads the typed
//! tables below from that tree through `serde_path_to_error`, so whatever serde refuses
//! comes with toml's line and column and serde's path to the field, named as the file
//! spells it (`item[2] ("cube").scale`). One pass before that refuses numbers no field
//! may hold (NaN, infinities, values beyond f32); [`build`] then turns the tables into a
//! [`Scene`], checking what serde cannot (ranges, relations between fields, files on disk).

mod build;
mod items;
mod read;
#[cfg(test)]
mod tests;

use std::fmt;
use std::marker::PhantomData;
use std::path::Path;

use glam::Vec3;
use serde::de::{self, Deserializer, IgnoredAny, SeqAccess, Visitor};
use serde::Deserialize;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

use super::{OrthoCoords, Scene, ShadingModel, StepList};
use crate::error::Result;
use crate::input::{read_text_file, SCENE_LIMIT};
use crate::settings::{ShadowPatch, ShadowSettings, Wrap};
use read::Context;

/// Reads a scene file; relative mesh and texture paths resolve from its folder.
pub fn load_file(path: &Path) -> Result<Scene> {
    let text = read_text_file(path, SCENE_LIMIT, "scene file")?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    parse(&text, path, Some(&base))
}

/// Parses scene TOML. `source` names it in errors; `base` is where relative paths start
/// (`None` for built-in scenes, which may only use built-in meshes).
pub fn parse(text: &str, source: &Path, base: Option<&Path>) -> Result<Scene> {
    let doc = DeTable::parse(text).map_err(|e| read::syntax_error(&e, text, source))?;
    let root = Spanned::new(doc.span(), DeValue::Table(doc.into_inner()));
    let cx = Context {
        source,
        base,
        text,
        root: &root,
    };
    cx.read::<read::Numbers>(&root, "")
        .map_err(|r| r.error(&cx))?;
    let file: SceneFile = cx.read(&root, "").map_err(|r| r.error(&cx))?;
    build::build(file, &cx)
}

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
    /// The view the commands open on (a name in `[views]`); left out: `[camera]`.
    view: Option<String>,
    /// Named cameras (`--view NAME`), each over `[camera]`: fields left out are its.
    #[serde(default)]
    views: std::collections::BTreeMap<String, CameraFile>,
    /// One light (`[light]`), or several (`[[lights]]`); not both. Only counted here: each
    /// is read by its `kind` in [`build`], from the document.
    light: Option<LightTable>,
    #[serde(default)]
    lights: Vec<LightTable>,
    #[serde(default)]
    shadow: ShadowSettings,
    #[serde(default)]
    steps: StepsFile,
    #[serde(default, rename = "item")]
    items: Vec<ItemFile>,
    /// A scripted path by keyframes (`--motion keyframes`).
    #[serde(default)]
    motion: MotionFile,
}

/// `[motion]`: keyframes of the camera and the first light's angle.
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct MotionFile {
    keyframes: Vec<super::motion::Keyframe>,
}

/// A camera table: `[camera]`, and `[steps] camera` over it. Not `Camera` itself: glam's
/// `Vec3` takes the first three numbers of a longer array without a word. Fields left out
/// are `Camera::default()`'s.
#[derive(Debug, Default, Clone, Copy, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct CameraFile {
    position: Option<Fixed<f32, 3>>,
    /// The book's angles; default 0, 0, 0. Not with `target`.
    rotation: Option<Fixed<f32, 3>>,
    /// A look-at camera: the point it looks at, turned into the book's pitch and yaw.
    target: Option<Fixed<f32, 3>>,
    fov: Option<f32>,
    near: Option<f32>,
    far: Option<f32>,
}

impl CameraFile {
    /// These fields over `under`'s (`[steps] camera` over the scene's).
    fn over(&self, under: &CameraFile) -> CameraFile {
        // Angles or a target given here replace the other's way of aiming.
        let (rotation, target) = match (self.rotation, self.target) {
            (None, None) => (under.rotation, under.target),
            aim => aim,
        };
        CameraFile {
            position: self.position.or(under.position),
            rotation,
            target,
            fov: self.fov.or(under.fov),
            near: self.near.or(under.near),
            far: self.far.or(under.far),
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
    camera: Option<CameraFile>,
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

/// A light's table, seen as a table: serde refuses `light = 5` here, the kind's own struct
/// reads it later.
type LightTable = std::collections::BTreeMap<String, IgnoredAny>;

/// The values a light's `kind` takes: each is its own struct of fields.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum LightKind {
    Directional,
    Spot,
    Point,
}

impl LightKind {
    /// Every kind, in the order messages list them.
    const ALL: [LightKind; 3] = [LightKind::Directional, LightKind::Spot, LightKind::Point];

    /// The kind's name in a scene file.
    pub(super) fn name(self) -> &'static str {
        match self {
            LightKind::Directional => "directional",
            LightKind::Spot => "spot",
            LightKind::Point => "point",
        }
    }

    /// The kind written `text`, if it is one.
    fn parse(text: &str) -> Option<LightKind> {
        LightKind::ALL.into_iter().find(|k| k.name() == text)
    }
}

/// The book's light (an angle or a direction) or LearnOpenGL's (a position, towards the
/// origin), with an orthographic shadow box.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct DirectionalFile {
    /// Read before the table (it picks this struct); here so serde lists it.
    #[serde(default, rename = "kind")]
    _kind: IgnoredAny,
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

/// A positional light with a perspective shadow map (the shared fields as in
/// [`DirectionalFile`]).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SpotFile {
    #[serde(default, rename = "kind")]
    _kind: IgnoredAny,
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
    #[serde(default)]
    size: f32,
    #[serde(default)]
    shadow: ShadowPatch,
}

/// A light shining every way from a point (a depth cube map; the shared fields as in
/// [`DirectionalFile`]).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PointFile {
    #[serde(default, rename = "kind")]
    _kind: IgnoredAny,
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
    #[serde(default)]
    size: f32,
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
    /// How much light a crossing of its surface stops, 0 < opacity <= 1: each crossing
    /// multiplies the light left by (1 - opacity). Below 1 the item is translucent: drawn
    /// blended, and cast by the volumetric technique instead of the depth map.
    #[serde(default = "one")]
    opacity: f32,
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
/// from the item's position (plus a height uniform over `height`, when given: a cloud in a
/// volume, such as smoke), a turn about y, and the item's scale times a factor per axis
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
    /// [y_min, y_max] added to the item's y; `None`: every copy at the item's y.
    height: Option<Fixed<f32, 2>>,
}

/// The most copies one scatter makes (a typo of a few zeros should not hang the loader).
const MAX_SCATTER: u32 = 10_000;

impl ScatterFile {
    /// (position offset in x, y and z, turn in degrees, scale factor) for each copy:
    /// SplitMix64, so a seed gives the same scene on every machine. Heights come from a
    /// stream of their own, so giving a scatter a `height` moves no copy across.
    fn placements(&self) -> Vec<(Vec3, f32, Vec3)> {
        let mut next = splitmix(self.seed);
        let mut next_height = splitmix(self.seed ^ 0xD1B5_4A32_D192_ED03);
        let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
        let [x0, x1, z0, z1] = self.area.0;
        (0..self.count)
            .map(|_| {
                let (x, z, turn) = (lerp(x0, x1, next()), lerp(z0, z1, next()), next() * 360.0);
                let scale = Vec3::from_array(std::array::from_fn(|k| {
                    lerp(self.scale_min.0[k], self.scale_max.0[k], next())
                }));
                let y = (self.height).map_or(0.0, |Fixed([y0, y1])| lerp(y0, y1, next_height()));
                (Vec3::new(x, y, z), turn, scale)
            })
            .collect()
    }
}

/// SplitMix64 from `seed`: numbers in [0, 1) with 24 bits.
fn splitmix(seed: u64) -> impl FnMut() -> f32 {
    let mut state = seed;
    move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The built-in meshes, in the order messages list them.
const BUILTIN_MESHES: &str = "cube, plane, sphere, terrain";

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

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Fixed<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct FixedVisitor<T, const N: usize>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>, const N: usize> Visitor<'de> for FixedVisitor<T, N> {
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

/// Reads a sequence that must hold exactly N values.
fn read_exactly<'de, T, const N: usize, A>(mut seq: A) -> std::result::Result<[T; N], A::Error>
where
    T: Deserialize<'de>,
    A: SeqAccess<'de>,
{
    let mut values = Vec::with_capacity(N);
    while let Some(v) = seq.next_element()? {
        values.push(v);
    }
    let n = values.len();
    values
        .try_into()
        .map_err(|_| de::Error::custom(format!("{}: expected exactly {N} numbers", read::given(n))))
}
