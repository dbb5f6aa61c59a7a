//! Lights and their shadow cameras. `DirectionalLight` and `OrthoCoords` are the book's
//! ("Shadows": the light's ortho box and `shadowPosMult`); `SpotLight` is the positional
//! light with a perspective shadow map of the slides, the blog and LearnOpenGL's
//! "orthographic vs perspective" section.

use glam::{Mat4, Vec3};
use serde::{Deserialize, Serialize};

use crate::settings::{LightView, ShadowPatch};
use crate::transformation::Transformation;

/// The box the orthographic light projection keeps, in light-view units (the book's
/// `OrthoCoords`). `near` and `far` are distances along the light's view direction from the
/// light's position, so a negative near reaches behind it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrthoCoords {
    pub left: f32,
    pub right: f32,
    pub bottom: f32,
    pub top: f32,
    pub near: f32,
    pub far: f32,
}

/// As a scene file writes it (`{ left = -10, right = 10, ... }`), for messages.
impl std::fmt::Display for OrthoCoords {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let OrthoCoords {
            left,
            right,
            bottom,
            top,
            near,
            far,
        } = self;
        write!(
            f,
            "{{ left = {left}, right = {right}, bottom = {bottom}, top = {top}, near = {near}, \
             far = {far} }}"
        )
    }
}

impl Default for OrthoCoords {
    /// The DummyGame's box: +-10 across, near -1, far 20.
    fn default() -> Self {
        OrthoCoords {
            left: -10.0,
            right: 10.0,
            bottom: -10.0,
            top: 10.0,
            near: -1.0,
            far: 20.0,
        }
    }
}

/// A directional light's angular diameter stays under this many degrees (its cone's half
/// angle under 45).
pub const MAX_ANGULAR_DIAMETER: f32 = 90.0;

/// A spot or point light's radius stays under this many world units: the built-in scenes
/// are tens of units across, and a bulb far larger than its scene lights every receiver
/// from inside itself.
pub const MAX_LIGHT_RADIUS: f32 = 1000.0;

/// The largest |x| of a (unit) direction the book's angle view represents: its two angles,
/// x = acos(dir.z) and y = asin(dir.x), compose to the right orientation only in the YZ plane
/// (`shadows::plan` refuses the view for other directions).
pub const BOOK_ANGLES_MAX_X: f32 = 1e-6;

/// A light infinitely far away. `direction` points from the scene TOWARDS the light (the
/// book's convention), so (0, 1, 0) is the sun straight overhead.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectionalLight {
    pub colour: Vec3,
    pub direction: Vec3,
    pub intensity: f32,
    pub ortho: OrthoCoords,
    /// Where the shadow "camera" sits: `direction * shadow_pos_mult`.
    pub shadow_pos_mult: f32,
    /// LearnOpenGL shades with a light *position* while its shadow map is orthographic;
    /// when set, shading uses the direction from each fragment to this point.
    pub shading_position: Option<Vec3>,
    /// Only a light that casts gets a shadow map ("render a separate depth map for each
    /// light"); the others light everything they face.
    pub casts_shadows: bool,
    /// This light's own shadow settings over the scene's `[shadow]` (its `shadow` table).
    pub shadow: ShadowPatch,
    /// Its angular diameter in degrees (the sun: 0.53); 0 = a point at infinity, whose
    /// shadows are hard. Soft filters (PCSS) and the area-light reference read it.
    pub size: f32,
}

impl DirectionalLight {
    /// Why `angle_deg` cannot be a light's angle, if it cannot: degrees from 0 to 180 (90
    /// overhead). The scene file's `angle` and the `--light-angle` flag share this rule
    /// and its words, so neither turns a light the other refuses (450 is not silently 90).
    pub fn angle_problem(angle_deg: f32) -> Option<String> {
        (!(0.0..=180.0).contains(&angle_deg))
            .then(|| format!("{angle_deg}: expected degrees from 0 to 180 (90 = overhead)"))
    }

    /// The DummyGame's direction for a light angle in degrees: (0, sin a, cos a), so 90 is
    /// overhead, 0 and 180 are at the horizon along +Z and -Z. The book's light turns
    /// about the X axis; this is [`Self::direction_about`] with the azimuth +Z.
    pub fn direction_from_angle(angle_deg: f32) -> Vec3 {
        Self::direction_about(Vec3::Z, angle_deg)
    }

    /// The direction at `angle_deg` in the vertical plane through `azimuth` (a horizontal
    /// unit vector): 0 is the horizon towards `azimuth`, 90 overhead, 180 the opposite
    /// horizon. The book's angle keys generalised: the light turns about the horizontal
    /// axis across its azimuth, so the azimuth stays and only the elevation changes.
    pub fn direction_about(azimuth: Vec3, angle_deg: f32) -> Vec3 {
        let a = angle_deg.to_radians();
        // With azimuth +Z every product below is exact: (0, sin a, cos a), the book's.
        (azimuth * a.cos() + Vec3::Y * a.sin()).normalize()
    }

    /// The horizontal unit vector this light's angle is measured from. A direction in the
    /// YZ plane (x = 0) is the DummyGame's: +Z, so its angle is the book's `atan2(y, z)`
    /// from 0 to 180 through the overhead. Any other direction's azimuth is its own
    /// horizontal part (LearnOpenGL's light at (-2, 4, -1) has the azimuth (-2, 0, -1)).
    pub fn azimuth(&self) -> Vec3 {
        let d = self.direction;
        match d.x == 0.0 {
            true => Vec3::Z,
            // Straight overhead (no horizontal part to speak of): the book's azimuth.
            false => Vec3::new(d.x, 0.0, d.z).try_normalize().unwrap_or(Vec3::Z),
        }
    }

    /// The light's angle in degrees measured from `azimuth` (see [`Self::direction_about`]),
    /// from -90 to 270: a light just below the opposite horizon reads a little over 180, not
    /// near -180. (In f32, sin 180 degrees is -8.7e-8: the book's light at 180 sits a hair
    /// below the horizon, and read as -180 the keys' clamp would throw it back to 0.)
    pub fn angle_about(&self, azimuth: Vec3) -> f32 {
        let d = self.direction;
        let a = d.y.atan2(d.dot(azimuth)).to_degrees();
        match a < -90.0 {
            true => a + 360.0,
            false => a,
        }
    }

    /// The light's angle from its own azimuth ([`Self::azimuth`]); for the DummyGame's
    /// light the book's angle (the inverse of [`Self::direction_from_angle`]).
    pub fn angle_deg(&self) -> f32 {
        self.angle_about(self.azimuth())
    }

    /// Turns the light to `angle_deg` about `azimuth`. A light given by a position
    /// (LearnOpenGL's) keeps its distance from the origin: the point it shades from moves
    /// with the shadow camera, so shading and shadow still agree.
    pub fn set_angle_about(&mut self, azimuth: Vec3, angle_deg: f32) {
        self.direction = Self::direction_about(azimuth, angle_deg);
        if let Some(p) = &mut self.shading_position {
            *p = self.direction * p.length();
        }
    }

    /// The shadow camera's position.
    pub fn position(&self) -> Vec3 {
        self.direction * self.shadow_pos_mult
    }

    /// The light's view matrix, built the book's way or with a look-at.
    pub fn view_matrix(&self, mode: LightView) -> Mat4 {
        let d = self.direction.normalize();
        match mode {
            LightView::BookAngles => {
                // The book: rotation x = acos(dir.z), y = asin(dir.x). This maps the direction
                // onto +Z only while dir.x == 0 (as in the DummyGame, whose light turns in the
                // YZ plane). With an x component the two rotations no longer compose to the
                // right orientation and the shadow map looks at the scene askew: use LookAt.
                let rotation = Vec3::new(
                    d.z.clamp(-1.0, 1.0).acos().to_degrees(),
                    d.x.clamp(-1.0, 1.0).asin().to_degrees(),
                    0.0,
                );
                Transformation::light_view(self.position(), rotation)
            }
            // A basis that stays finite and smooth for every direction, poles included.
            LightView::LookAt => {
                Transformation::light_look_at(self.position().as_dvec3(), d.as_dvec3()).as_mat4()
            }
        }
    }

    /// The orthographic projection of the ortho box.
    pub fn projection_matrix(&self) -> Mat4 {
        let o = &self.ortho;
        Transformation::ortho(o.left, o.right, o.bottom, o.top, o.near, o.far)
    }
}

/// A light at a point shining towards a target, with a perspective shadow map whose field of
/// view is the cone (the slides' and the blog's light "camera").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpotLight {
    pub colour: Vec3,
    pub intensity: f32,
    pub position: Vec3,
    pub target: Vec3,
    /// The up vector of the shadow camera (the slides use +Z); `None` is +Y.
    pub up: Option<Vec3>,
    /// The shadow frustum's vertical field of view, degrees (and the full cone angle).
    pub fov: f32,
    /// The shadow frustum's width over height (the shadow-playground's 4:3 canvas).
    pub aspect: f32,
    /// Whether a cone of `fov` limits the light; without one (the shadow-playground's bulb)
    /// it lights its whole frustum (and beyond, unshadowed).
    pub cone: bool,
    pub near: f32,
    pub far: f32,
    pub casts_shadows: bool,
    /// This light's own shadow settings over the scene's `[shadow]` (its `shadow` table).
    pub shadow: ShadowPatch,
    /// Its radius in world units (a disc facing what it lights); 0 = a point.
    pub size: f32,
}

/// A light shining every way from a point, with an omnidirectional shadow in a depth cube
/// map (LearnOpenGL's "Point Shadows": 90-degree faces, linear distance stored).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLight {
    pub colour: Vec3,
    pub intensity: f32,
    pub position: Vec3,
    pub near: f32,
    pub far: f32,
    /// The light moves to `position + oscillate * sin(0.5 t)` (t in seconds), as
    /// LearnOpenGL's does along z.
    pub oscillate: Vec3,
    /// The resting position the oscillation is about.
    pub centre: Vec3,
    pub casts_shadows: bool,
    /// This light's own shadow settings over the scene's `[shadow]` (its `shadow` table).
    pub shadow: ShadowPatch,
    /// Its radius in world units (a sphere); 0 = a point.
    pub size: f32,
}

/// A scene's light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Light {
    Directional(DirectionalLight),
    Spot(SpotLight),
    Point(PointLight),
}

/// How the shading sees the light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shading {
    /// The same direction (towards the light) everywhere.
    Direction(Vec3),
    /// From each fragment to this point; `cone` = (cos of the half angle, axis) for spots.
    Position {
        position: Vec3,
        cone: Option<(f32, Vec3)>,
    },
}

impl Light {
    pub fn colour(&self) -> Vec3 {
        match self {
            Light::Directional(l) => l.colour,
            Light::Spot(l) => l.colour,
            Light::Point(l) => l.colour,
        }
    }

    pub fn intensity(&self) -> f32 {
        match self {
            Light::Directional(l) => l.intensity,
            Light::Spot(l) => l.intensity,
            Light::Point(l) => l.intensity,
        }
    }

    /// This light's own settings over the scene's.
    pub fn shadow_patch(&self) -> &ShadowPatch {
        match self {
            Light::Directional(l) => &l.shadow,
            Light::Spot(l) => &l.shadow,
            Light::Point(l) => &l.shadow,
        }
    }

    pub fn shadow_patch_mut(&mut self) -> &mut ShadowPatch {
        match self {
            Light::Directional(l) => &mut l.shadow,
            Light::Spot(l) => &mut l.shadow,
            Light::Point(l) => &mut l.shadow,
        }
    }

    /// Its size: a directional light's angular diameter in degrees, a spot or point
    /// light's radius in world units (0 = a point: hard shadows).
    pub fn size(&self) -> f32 {
        match self {
            Light::Directional(l) => l.size,
            Light::Spot(l) => l.size,
            Light::Point(l) => l.size,
        }
    }

    pub fn set_size(&mut self, size: f32) {
        match self {
            Light::Directional(l) => l.size = size,
            Light::Spot(l) => l.size = size,
            Light::Point(l) => l.size = size,
        }
    }

    /// "directional", "spot" or "point", as scene files name them.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Light::Directional(_) => "directional",
            Light::Spot(_) => "spot",
            Light::Point(_) => "point",
        }
    }

    /// What `size` means for this kind of light, for messages.
    pub fn size_unit(&self) -> &'static str {
        match self {
            Light::Directional(_) => "an angular diameter in degrees (the sun: 0.53)",
            Light::Spot(_) | Light::Point(_) => "a radius in world units",
        }
    }

    /// Why `size` cannot be this light's (named `name`), if it cannot: a finite number, at
    /// least 0, a directional light's diameter under [`MAX_ANGULAR_DIAMETER`] degrees and a
    /// spot or point light's radius under [`MAX_LIGHT_RADIUS`] world units.
    pub fn size_problem(&self, size: f32) -> Option<String> {
        let max = match self {
            Light::Directional(_) => MAX_ANGULAR_DIAMETER,
            Light::Spot(_) | Light::Point(_) => MAX_LIGHT_RADIUS,
        };
        let unit = self.size_unit();
        (!(size.is_finite() && (0.0..max).contains(&size))).then(|| match self {
            Light::Directional(_) => format!("{size}: expected {unit} under {max} (0 = a point)"),
            Light::Spot(_) | Light::Point(_) => {
                format!("{size}: expected {unit} >= 0 and under {max} (0 = a point)")
            }
        })
    }

    pub fn casts_shadows(&self) -> bool {
        match self {
            Light::Directional(l) => l.casts_shadows,
            Light::Spot(l) => l.casts_shadows,
            Light::Point(l) => l.casts_shadows,
        }
    }

    /// The directional light, if this is one.
    pub fn as_directional(&self) -> Option<&DirectionalLight> {
        match self {
            Light::Directional(l) => Some(l),
            Light::Spot(_) | Light::Point(_) => None,
        }
    }

    /// The directional light, if this is one (the DummyGame's angle keys need it).
    pub fn as_directional_mut(&mut self) -> Option<&mut DirectionalLight> {
        match self {
            Light::Directional(l) => Some(l),
            Light::Spot(_) | Light::Point(_) => None,
        }
    }

    /// A short description for titles and reports (with its size, when it has one).
    pub fn describe(&self) -> String {
        let size = match self {
            _ if self.size() == 0.0 => String::new(),
            Light::Directional(_) => format!(", {} deg wide", self.size()),
            Light::Spot(_) | Light::Point(_) => format!(", radius {}", self.size()),
        };
        format!("{}{size}", self.describe_point())
    }

    fn describe_point(&self) -> String {
        match self {
            Light::Directional(l) if l.direction.x == 0.0 => {
                format!("light {:.1} deg", l.angle_deg())
            }
            Light::Directional(l) => format!(
                "light {:.1} deg over azimuth {:.2} (towards {:.2})",
                l.angle_deg(),
                l.azimuth(),
                l.direction
            ),
            Light::Spot(l) => format!("spot at {:.1}", l.position),
            Light::Point(l) => format!("point light at {:.1}", l.position),
        }
    }

    pub fn shading(&self) -> Shading {
        match self {
            Light::Directional(l) => match l.shading_position {
                Some(position) => Shading::Position {
                    position,
                    cone: None,
                },
                None => Shading::Direction(l.direction.normalize()),
            },
            Light::Point(l) => Shading::Position {
                position: l.position,
                cone: None,
            },
            Light::Spot(l) => Shading::Position {
                position: l.position,
                cone: l.cone.then(|| {
                    (
                        (l.fov.to_radians() * 0.5).cos(),
                        (l.target - l.position).normalize_or_zero(),
                    )
                }),
            },
        }
    }
}
