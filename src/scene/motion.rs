//! Motion paths: where the camera and the first light are at each frame of a scripted run
//! (`--motion`), so a shadow's flicker and crawl can be rendered, timed and scored the same
//! way every time. A pose is a function of the frame number alone, taken from the scene as
//! it was at frame 0: frame N is the same picture however it was reached.

use glam::Vec3;
use serde::Deserialize;

use super::{Camera, Light, Scene};
use crate::error::{Error, Result};

/// The path's kind (`--motion`).
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathKind {
    /// Nothing moves (every frame is frame 0).
    Still,
    /// The camera moves forward along its view direction (world units a frame).
    Dolly,
    /// The camera moves to its right, keeping its direction (world units a frame).
    Strafe,
    /// The camera turns about a vertical axis through the point it looks at on the ground
    /// (y = 0; looking above the horizon, the point of its view nearest the origin), still
    /// looking at it (degrees a frame).
    Orbit,
    /// The first light turns about its azimuth as the DummyGame's UP/DOWN keys turn it
    /// (degrees a frame, up to 180); a spot light rises the same way about its target.
    LightSweep,
    /// The scene file's `[motion] keyframes`, interpolated linearly between them.
    Keyframes,
}

impl PathKind {
    /// The step a frame when none is given: the DummyGame's camera step (0.05 a frame),
    /// half a degree for the turns.
    pub fn default_step(self) -> f32 {
        match self {
            PathKind::Dolly | PathKind::Strafe => 0.05,
            PathKind::Orbit | PathKind::LightSweep => 0.5,
            PathKind::Still | PathKind::Keyframes => 0.0,
        }
    }

    /// The step's unit, for messages.
    pub fn unit(self) -> &'static str {
        match self {
            PathKind::Dolly | PathKind::Strafe => "world units",
            PathKind::Orbit | PathKind::LightSweep => "degrees",
            PathKind::Still | PathKind::Keyframes => "(no step)",
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            PathKind::Still => "still",
            PathKind::Dolly => "dolly",
            PathKind::Strafe => "strafe",
            PathKind::Orbit => "orbit",
            PathKind::LightSweep => "light-sweep",
            PathKind::Keyframes => "keyframes",
        }
    }
}

/// One keyframe of a scene file's `[motion]` table; what it leaves out is frame 0's.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Keyframe {
    pub frame: u32,
    #[serde(default)]
    pub position: Option<[f32; 3]>,
    /// The book's angles: pitch, yaw, roll in degrees.
    #[serde(default)]
    pub rotation: Option<[f32; 3]>,
    /// The first light's angle in degrees (a directional or spot light only).
    #[serde(default)]
    pub light_angle: Option<f32>,
}

/// What a light sweep turns: a directional light's direction, or a spot light's position
/// about its target (its frame-0 offset from it turned in the azimuth's vertical plane),
/// both by the angle above the azimuth's horizon, so the spot's shadows sweep as the
/// sun's do.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Turned {
    Direction,
    Spot { target: Vec3, offset: Vec3 },
}

/// The first light's azimuth, angle and what turns, if it has an angle.
fn light_turn(scene: &Scene) -> Option<(Vec3, f32, Turned)> {
    match scene.lights.first()? {
        Light::Directional(l) => {
            let azimuth = l.azimuth();
            Some((azimuth, l.angle_about(azimuth), Turned::Direction))
        }
        Light::Spot(l) => {
            let o = l.position - l.target;
            let azimuth = Vec3::new(o.x, 0.0, o.z).try_normalize()?;
            let angle = o.y.atan2(o.dot(azimuth)).to_degrees();
            let target = l.target;
            Some((azimuth, angle, Turned::Spot { target, offset: o }))
        }
        Light::Point(_) => None,
    }
}

/// A path from a scene's frame-0 pose.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionPath {
    pub kind: PathKind,
    /// World units or degrees a frame (see [`PathKind::unit`]).
    pub step: f32,
    camera: Camera,
    /// The first light's azimuth and angle at frame 0, and what turns.
    light: Option<(Vec3, f32, Turned)>,
    pivot: Vec3,
    keyframes: Vec<Keyframe>,
    /// The frame the scene shows now (advanced by [`Scene::update`]).
    pub frame: u32,
}

impl MotionPath {
    /// The path `kind` from the scene's current pose, or the reason it cannot be had:
    /// a light sweep needs a directional first light; keyframes need the scene's table.
    pub fn new(kind: PathKind, step: Option<f32>, scene: &Scene) -> Result<MotionPath> {
        let step = step.unwrap_or(kind.default_step());
        if !step.is_finite() {
            return Err(Error::Invalid(format!(
                "--motion-step {step}: expected a finite number of {} a frame",
                kind.unit()
            )));
        }
        let light = light_turn(scene);
        let keyed_angle = scene
            .motion_keyframes
            .iter()
            .any(|k| k.light_angle.is_some());
        let needs_angle = match kind {
            PathKind::LightSweep => true,
            PathKind::Keyframes => keyed_angle,
            PathKind::Still | PathKind::Dolly | PathKind::Strafe | PathKind::Orbit => false,
        };
        if needs_angle && light.is_none() {
            return Err(Error::Invalid(format!(
                "--motion {}: the {} scene's first light is a {}; only a directional light \
                 has an angle to turn (the DummyGame's UP/DOWN keys), and a spot light a \
                 height about its target",
                kind.name(),
                scene.name,
                scene.light().describe()
            )));
        }
        if kind == PathKind::Keyframes && scene.motion_keyframes.is_empty() {
            return Err(Error::Invalid(format!(
                "--motion keyframes: the {} scene has no [motion] keyframes (see \
                 docs/scene-format.md)",
                scene.name
            )));
        }
        Ok(MotionPath {
            kind,
            step,
            camera: scene.camera,
            light,
            pivot: orbit_pivot(&scene.camera),
            keyframes: scene.motion_keyframes.clone(),
            frame: 0,
        })
    }

    /// Puts the scene's camera and first light where the path has them at `frame`.
    pub fn pose(&self, scene: &mut Scene, frame: u32) {
        let t = frame as f32 * self.step;
        let mut camera = self.camera;
        let mut angle = self.light.map(|(_, a, _)| a);
        match self.kind {
            PathKind::Still => {}
            PathKind::Dolly => camera.position += view_direction(&camera) * t,
            PathKind::Strafe => camera.position += right_direction(&camera) * t,
            PathKind::Orbit => {
                let turn = glam::Quat::from_rotation_y(t.to_radians());
                camera.position = self.pivot + turn * (camera.position - self.pivot);
                camera.rotation.y -= t;
            }
            PathKind::LightSweep => angle = angle.map(|a| (a + t).clamp(0.0, 180.0)),
            PathKind::Keyframes => {
                let k = interpolate(&self.keyframes, frame);
                camera.position = k.position.map_or(camera.position, Vec3::from);
                camera.rotation = k.rotation.map_or(camera.rotation, Vec3::from);
                angle = k.light_angle.or(angle);
            }
        }
        scene.camera = camera;
        let (Some((azimuth, start, turned)), Some(a)) = (self.light, angle) else {
            return;
        };
        match (turned, scene.lights.first_mut()) {
            (Turned::Direction, _) => {
                scene.set_light_angle_about(azimuth, a);
            }
            (Turned::Spot { target, offset }, Some(Light::Spot(l))) => {
                // Turned from frame 0's offset, so frame 0 is the scene's exactly.
                let turn = (a.clamp(0.0, 180.0) - start).to_radians();
                let axis = azimuth.cross(Vec3::Y).normalize();
                l.position = target + glam::Quat::from_axis_angle(axis, turn) * offset;
            }
            (Turned::Spot { .. }, _) => {}
        }
    }
}

/// The unit vector the camera looks along (the book's view: pitch down, yaw right).
pub fn view_direction(camera: &Camera) -> Vec3 {
    let (p, y) = (
        camera.rotation.x.to_radians(),
        camera.rotation.y.to_radians(),
    );
    Vec3::new(p.cos() * y.sin(), -p.sin(), -p.cos() * y.cos())
}

/// The camera's right, horizontal.
pub fn right_direction(camera: &Camera) -> Vec3 {
    let y = camera.rotation.y.to_radians();
    Vec3::new(y.cos(), 0.0, y.sin())
}

/// Where the view meets the ground (y = 0); when it does not, the point of the view's line
/// nearest the world's origin (where the scenes stand), else 10 units ahead.
fn orbit_pivot(camera: &Camera) -> Vec3 {
    let d = view_direction(camera);
    let hit = -camera.position.y / d.y;
    let nearest = -camera.position.dot(d);
    if hit.is_finite() && hit > 0.0 && hit < camera.far {
        camera.position + d * hit
    } else if nearest > 0.0 {
        camera.position + d * nearest
    } else {
        camera.position + d * 10.0
    }
}

/// The keyframes' values at `frame`: linear between the two around it, held past the ends;
/// a field a keyframe leaves out is taken from the nearest one that has it before.
fn interpolate(keys: &[Keyframe], frame: u32) -> Keyframe {
    let lerp3 = |a: [f32; 3], b: [f32; 3], s: f32| Vec3::from(a).lerp(Vec3::from(b), s).to_array();
    let after = keys.iter().position(|k| k.frame > frame);
    let (a, b) = match after {
        Some(0) => (keys[0], keys[0]),
        Some(i) => (filled(keys, i - 1), filled(keys, i)),
        None => (filled(keys, keys.len() - 1), filled(keys, keys.len() - 1)),
    };
    let span = b.frame.saturating_sub(a.frame).max(1) as f32;
    let s = (frame.saturating_sub(a.frame) as f32 / span).clamp(0.0, 1.0);
    Keyframe {
        frame,
        position: a.position.zip(b.position).map(|(p, q)| lerp3(p, q, s)),
        rotation: a.rotation.zip(b.rotation).map(|(p, q)| lerp3(p, q, s)),
        light_angle: a
            .light_angle
            .zip(b.light_angle)
            .map(|(p, q)| p + (q - p) * s),
    }
}

/// Keyframe `i` with its missing fields taken from the keyframes before it.
fn filled(keys: &[Keyframe], i: usize) -> Keyframe {
    let mut k = keys[i];
    for before in keys[..i].iter().rev() {
        k.position = k.position.or(before.position);
        k.rotation = k.rotation.or(before.rotation);
        k.light_angle = k.light_angle.or(before.light_angle);
    }
    k
}

/// A scene file's keyframes must run forward in frames and hold finite values.
pub fn check_keyframes(keys: &[Keyframe]) -> std::result::Result<(), (String, String)> {
    for (i, k) in keys.iter().enumerate() {
        let field = |f: &str| format!("motion.keyframes[{i}].{f}");
        if i > 0 && k.frame <= keys[i - 1].frame {
            return Err((
                field("frame"),
                format!(
                    "{}: expected a frame after the previous keyframe's {}",
                    k.frame,
                    keys[i - 1].frame
                ),
            ));
        }
        if let Some(a) = k.light_angle {
            if !(0.0..=180.0).contains(&a) {
                return Err((field("light_angle"), format!("{a}: expected 0 to 180")));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        Scene::load("dummy").unwrap()
    }

    #[test]
    fn frame_zero_is_the_scene_and_still_never_moves() {
        let base = scene();
        for kind in [
            PathKind::Still,
            PathKind::Dolly,
            PathKind::Strafe,
            PathKind::Orbit,
        ] {
            let path = MotionPath::new(kind, None, &base).unwrap();
            let mut s = base.clone();
            path.pose(&mut s, 0);
            assert_eq!(s.camera, base.camera, "{kind:?}");
        }
        let path = MotionPath::new(PathKind::Still, None, &base).unwrap();
        let mut s = base.clone();
        path.pose(&mut s, 17);
        assert_eq!(s.camera, base.camera);
    }

    #[test]
    fn strafe_and_dolly_move_by_the_step_a_frame() {
        let base = scene();
        for kind in [PathKind::Dolly, PathKind::Strafe] {
            let path = MotionPath::new(kind, Some(0.25), &base).unwrap();
            let mut s = base.clone();
            path.pose(&mut s, 4);
            let moved = s.camera.position.distance(base.camera.position);
            assert!((moved - 1.0).abs() < 1e-5, "{kind:?} moved {moved}");
        }
    }

    #[test]
    fn an_orbit_keeps_the_pivot_in_the_view_centre() {
        let mut base = scene();
        base.camera = Camera::look_at(Vec3::new(3.0, 4.0, 6.0), Vec3::ZERO).unwrap();
        let path = MotionPath::new(PathKind::Orbit, Some(30.0), &base).unwrap();
        let mut s = base.clone();
        path.pose(&mut s, 3);
        let to_pivot = (Vec3::ZERO - s.camera.position).normalize();
        assert!(view_direction(&s.camera).dot(to_pivot) > 0.9999);
        assert!((s.camera.position.length() - base.camera.position.length()).abs() < 1e-4);
    }

    #[test]
    fn a_light_sweep_turns_the_dummy_light_by_the_step() {
        let base = scene();
        let path = MotionPath::new(PathKind::LightSweep, Some(2.0), &base).unwrap();
        let mut s = base.clone();
        path.pose(&mut s, 5);
        let before = base.lights[0].as_directional().unwrap().angle_deg();
        let after = s.lights[0].as_directional().unwrap().angle_deg();
        assert!((after - before - 10.0).abs() < 1e-3, "{before} -> {after}");
    }

    #[test]
    fn a_light_sweep_raises_a_spot_about_its_target_by_the_step() {
        let base = Scene::load("penumbra").unwrap();
        let path = MotionPath::new(PathKind::LightSweep, Some(2.0), &base).unwrap();
        let mut s = base.clone();
        path.pose(&mut s, 0);
        assert_eq!(s.lights, base.lights, "frame 0 is the scene's");
        path.pose(&mut s, 5);
        let (Light::Spot(before), Light::Spot(after)) = (&base.lights[0], &s.lights[0]) else {
            panic!("penumbra's first light is a spot");
        };
        let (o0, o1) = (
            before.position - before.target,
            after.position - after.target,
        );
        let turned = o0.angle_between(o1).to_degrees();
        assert!((turned - 10.0).abs() < 1e-3, "turned {turned}");
        assert!((o1.length() - o0.length()).abs() < 1e-4);
        // It rises towards the overhead, in the vertical plane of its azimuth.
        assert!(o1.y > o0.y);
        assert!(o0.cross(o1).y.abs() < 1e-4);
    }

    #[test]
    fn a_light_sweep_on_a_point_light_is_refused_with_the_reason() {
        let base = Scene::load("point-shadows").unwrap();
        let e = MotionPath::new(PathKind::LightSweep, None, &base).unwrap_err();
        assert!(e.to_string().contains("only a directional light"), "{e}");
    }

    #[test]
    fn keyframes_interpolate_and_hold() {
        let k = |frame, x: f32| Keyframe {
            frame,
            position: Some([x, 1.0, 2.0]),
            rotation: None,
            light_angle: None,
        };
        let keys = [k(0, 0.0), k(10, 5.0)];
        assert_eq!(interpolate(&keys, 4).position, Some([2.0, 1.0, 2.0]));
        assert_eq!(interpolate(&keys, 30).position, Some([5.0, 1.0, 2.0]));
        assert!(check_keyframes(&[k(3, 0.0), k(3, 1.0)]).is_err());
    }
}
