//! A 2D map's light camera: the book's `OrthoCoords` box with its angle-built view (or
//! LearnOpenGL's look-at), a perspective frustum (LearnOpenGL's comparison, the slides, the
//! blog), a spot's frustum, or a box fitted to the scene ([`crate::shadows::camera::fitted`]).

use crate::scene::{Light, Scene};
use crate::settings::{Fit, LightProjection, ShadowSettings};
use crate::shadows::camera::fitted;
use crate::shadows::camera::{perspective_view, point_camera, Perspective};
use crate::shadows::{Rays, ShadowView};

/// Light `index`'s camera for its 2D map under `settings`: its own, or with
/// `fit = "scene"` an orthographic box fitted to this scene ([`fitted::fit_ortho`]).
pub fn camera(scene: &Scene, index: usize, settings: &ShadowSettings) -> ShadowView {
    camera_and_casters(scene, index, settings).0
}

/// [`camera`], with the casters a fitted box was fitted to: the only ones its depth pass
/// needs (`None`: the light's own camera, every caster that lands in it).
pub fn camera_and_casters(
    scene: &Scene,
    index: usize,
    settings: &ShadowSettings,
) -> (ShadowView, Option<Vec<usize>>) {
    let light = &scene.lights[index];
    match (light, settings.light_projection, settings.fit) {
        (Light::Directional(l), LightProjection::Ortho, Fit::Scene) => {
            let (fitted, casters) =
                fitted::fit_ortho_casters(scene, l.direction, settings.map_size, settings.snap);
            (fitted.shadow_view(l.direction), Some(casters))
        }
        (Light::Directional(_), LightProjection::Ortho, Fit::Manual)
        | (Light::Directional(_), LightProjection::Perspective, _)
        | (Light::Spot(_) | Light::Point(_), _, _) => (own_camera(light, settings), None),
    }
}

/// The light's own camera. A directional light with `LightProjection::Perspective` becomes
/// a point-like light at its shadow position looking at the origin (LearnOpenGL's
/// "orthographic vs perspective" comparison).
fn own_camera(light: &Light, settings: &ShadowSettings) -> ShadowView {
    match (light, settings.light_projection) {
        (Light::Directional(l), LightProjection::Ortho) => {
            let o = &l.ortho;
            let view = l.view_matrix(settings.light_view);
            ShadowView {
                view,
                view64: view.as_dmat4(),
                projection: l.projection_matrix(),
                perspective: false,
                linear_depth: false,
                near: o.near,
                far: o.far,
                texel_world: ((o.right - o.left) / settings.map_size.width as f32)
                    .max((o.top - o.bottom) / settings.map_size.height as f32),
                rays: Rays::Parallel {
                    to_light: l.direction.normalize(),
                },
            }
        }
        (Light::Directional(l), LightProjection::Perspective) => {
            let eye = l.position();
            // A perspective frustum needs a positive near: a box that starts at or behind
            // the light (the book's near is -1) gets 1 (LearnOpenGL's comparison uses 1).
            let near = if l.ortho.near > 0.0 {
                l.ortho.near
            } else {
                1.0
            };
            let far = l.ortho.far.max(near * 2.0);
            let frustum = Perspective {
                fov: settings.perspective_fov,
                aspect: settings.map_size.aspect(),
                near,
                far,
            };
            perspective_view(
                eye,
                eye - l.direction.normalize() * l.shadow_pos_mult,
                None,
                frustum,
                settings.map_size,
            )
        }
        (Light::Spot(s), _) => {
            let frustum = Perspective {
                fov: s.fov,
                aspect: s.aspect,
                near: s.near,
                far: s.far,
            };
            perspective_view(s.position, s.target, s.up, frustum, settings.map_size)
        }
        // A point light's camera is its cube's.
        (Light::Point(p), _) => point_camera(p, settings),
    }
}
