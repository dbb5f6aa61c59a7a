//! The chapter's map in the kind table: its HUD words, its storage, its bench family and the
//! settings only a 2D depth map reads.

use super::{glsl, Map2d, SAMPLERS};
use crate::scene::Light;
use crate::settings::{Filter, Fit, LightProjection, ShadowSettings};
use crate::shadows::kind::{
    self, Family, IdleRules, Idles, KindFacts, LightIdle, SceneIdle, Storage, TechniqueFacts,
};
use crate::shadows::{volumetric, ShadowKind};

/// The 2D depth map's row of the kind table.
pub const KIND: KindFacts = KindFacts {
    technique: Some(TechniqueFacts {
        create: |gl, s| Ok(Box::new(Map2d::new(gl, s)?)),
        glsl,
        samplers: &SAMPLERS,
        map_slot: true,
    }),
    words: |s| {
        let (size, depth) = (kind::sides(s.map_size), kind::depth_words(s.depth_format));
        format!("Shadow: one {size} depth map, {depth}")
    },
    storage: |s| {
        Some(Storage {
            what: format!("one {} depth texture", kind::sides(s.map_size)),
            bytes: s.map_size.texels() * kind::DEPTH_TEXEL_BYTES,
        })
    },
    follows_camera,
    layers: None,
    // Not PCSS's nor the rotated disk's: they read the pixel itself.
    per_vertex: |t| t.depth().is_some_and(|d| !d.kernel.glsl().per_pixel),
    family: |s| match s.filter.soft() {
        true => Family::Soft,
        false => Family::OneMap,
    },
    idle: IdleRules {
        no_map: None,
        depth_lookup: |filter| {
            filter.hardware().then_some(
                "the hardware filters compare in the sampler, which filters LINEAR whatever it \
                 says",
            )
        },
        light: of_light,
        scene: of_scene,
    },
};

/// Whether a 2D map's box follows the camera: the case [`super::camera`] fits to the scene.
pub fn follows_camera(light: &Light, settings: &ShadowSettings) -> bool {
    matches!(light, Light::Directional(_))
        && settings.light_projection == LightProjection::Ortho
        && settings.fit == Fit::Scene
}

/// Whether `perspective_depth` decides what light's map stores: a perspective depth map
/// (not with PCSS: [`super::stores_linear_depth`]).
fn linear_depth_can_apply(light: &Light, kind: ShadowKind, s: &ShadowSettings) -> bool {
    let perspective = match light {
        Light::Spot(_) => true,
        Light::Directional(_) => s.light_projection == LightProjection::Perspective,
        Light::Point(_) => false,
    };
    kind == ShadowKind::Map && perspective && s.filter != Filter::Pcss
}

/// The settings only a 2D depth map reads that do nothing for light `v`.
fn of_light(v: &LightIdle, idle: &mut Idles) {
    if !linear_depth_can_apply(v.light, v.kind, v.settings) {
        idle.push(
            "perspective_depth",
            "only a perspective depth map stores it (a spot light's, a directional light's \
             perspective one), and not with pcss",
        );
    }
    volumetric::idle::of_light(v, idle);
}

/// The settings only a 2D depth map reads that do nothing for every light of scene `v`.
fn of_scene(v: &SceneIdle, idle: &mut Idles) {
    let perspective_maps =
        (v.lights.iter()).any(|l| linear_depth_can_apply(l.light, l.kind, l.settings));
    if !perspective_maps {
        idle.push(
            "perspective_depth",
            "no light has a perspective depth map (a spot light, or --light-projection \
             perspective) without pcss; it says what such a map stores",
        );
    }
    volumetric::idle::of_scene(v, idle);
}
