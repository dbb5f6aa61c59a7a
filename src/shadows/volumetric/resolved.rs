//! The translucent map resolved for opaque receivers (`opaque_receivers = "resolved"`). A lit
//! opaque receiver is, up to the bias, the surface the light's depth map holds, so the light
//! the translucent casters leave it is their curve read at the depth map's own depth: one
//! transmittance a texel, resolved in one full-screen pass whenever either map is drawn and
//! kept with them. Opaque receivers then read it with one filtered fetch
//! (`resolvedTransmittance`, shaders/lib/volumetric.glsl) instead of the technique's lookup;
//! a receiver in opaque shadow gets 0 from its test whatever it reads. Translucent items are
//! not where the depth map is: they keep the curve.
//!
//! The map has the translucent map's texels (`volumetric_size`): texel for texel what the
//! curve lookup filters, so the two differ only in the depth each texel is read at (the
//! depth map's nearest texel to its centre, where the sizes differ) and in filtering the
//! transmittance rather than what the technique stores.

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use glam::{DMat4, Mat4};

use super::{method, DepthFit, VolumetricMap};
use crate::engine::{FullScreenTriangle, Gl, ResolvedMap, ShaderProgram, Texture};
use crate::error::{Error, Result};
use crate::settings::{OpaqueReceivers, ShadowSettings};
use crate::shaders;
use crate::shadows::camera::texels::TexelRect;
use crate::shadows::ShadowView;

/// Each light's sampler of its resolved map in the scene shader.
pub const SAMPLERS: [&str; crate::scene::MAX_LIGHTS] = [
    "resolvedMap0",
    "resolvedMap1",
    "resolvedMap2",
    "resolvedMap3",
];

/// The units the resolve reads the translucent map and the depth map from (it comes
/// before the scene pass).
const MAP_UNIT: u32 = 0;
const DEPTH_UNIT: u32 = 1;

/// The generated snippet the resolve includes: the technique's library file and `curveAt`.
const SNIPPET: &str = "generated/resolve.glsl";

/// Whether `settings` ask for a resolved map beside the light's translucent map.
pub fn wanted(settings: &ShadowSettings) -> bool {
    settings.opaque_receivers == OpaqueReceivers::Resolved && method(settings.volumetric).is_some()
}

/// One light's resolved map, its program, and what it was last resolved from.
pub struct Resolved {
    map: ResolvedMap,
    program: ShaderProgram,
    triangle: FullScreenTriangle,
    /// The technique and parameter the program reads, and the map's size.
    made_for: (crate::settings::Volumetric, u32, crate::settings::MapSize),
    /// The two maps' keys it was resolved from (`None`: resolve it again).
    key: Option<u64>,
    /// The texels the last resolve wrote.
    written: Option<TexelRect>,
}

impl Resolved {
    /// The resolved map for a light's translucent map under `settings`.
    pub fn new(gl: &Gl, settings: &ShadowSettings) -> Result<Resolved> {
        let m = method(settings.volumetric)
            .ok_or_else(|| Error::Invalid("a resolved map needs a translucent map".into()))?;
        let parameter = m.parameter(settings);
        let (file, call) = m.texel_call(parameter);
        let snippet = format!(
            "// Made by src/shadows/volumetric/resolved.rs: the curve at one texel.\n\
             #include \"{file}\"\n\n\
             float curveAt(ivec2 texel, vec2 uv, float depth)\n{{\n    return {call};\n}}\n"
        );
        let fragment = shaders::resolve(
            "shaders/volumetric_resolve.frag",
            include_str!("../../../shaders/volumetric_resolve.frag"),
            &[(SNIPPET, snippet)],
        )?;
        let size = settings.volumetric_size;
        Ok(Resolved {
            map: ResolvedMap::new(gl, size)?,
            program: ShaderProgram::new(gl, &shaders::depth_view_vert(), &fragment, &[])?,
            triangle: FullScreenTriangle::new(gl)?,
            made_for: (settings.volumetric, parameter, size),
            key: None,
            written: None,
        })
    }

    /// Whether it still matches `settings`.
    pub fn fits(&self, settings: &ShadowSettings) -> bool {
        let parameter = method(settings.volumetric).map(|m| m.parameter(settings));
        let (technique, made, size) = self.made_for;
        technique == settings.volumetric
            && parameter == Some(made)
            && size == settings.volumetric_size
    }

    /// Resolves `translucent` (drawn over `fit`, its casters within `drawn`) at the depths of
    /// `depth`, the light's depth map seen through `view`, unless `key` (both maps' keys,
    /// `None` when either is drawn every frame) is the one it was last resolved from.
    /// Whether it resolved.
    pub fn update(&mut self, from: &Source, key: Option<u64>) -> bool {
        if key.is_some() && key == self.key {
            return false;
        }
        let size = self.map.size();
        // The casters' texels, and those written last time (set back to what the now empty
        // translucent texels give: 1).
        let rect = from
            .drawn
            .union(self.written.unwrap_or(TexelRect::whole(size)));
        self.written = Some(from.drawn);
        self.key = key;
        if rect.is_empty() {
            return true;
        }
        let _pass = self.map.begin_write(rect.pixels());
        let p = &self.program;
        p.bind();
        from.translucent.map().bind(MAP_UNIT);
        self.map.bind_depth(from.depth, DEPTH_UNIT);
        p.set_i32("translucentMap", MAP_UNIT as i32);
        p.set_i32("depthMap", DEPTH_UNIT as i32);
        p.set_mat4("depthToFitted", &depth_to_fitted(from.view, from.fit));
        self.triangle.draw();
        true
    }

    /// The map the opaque receivers read.
    pub fn map(&self) -> &ResolvedMap {
        &self.map
    }
}

/// What a light's map is resolved from.
pub struct Source<'a> {
    pub translucent: &'a dyn VolumetricMap,
    /// The texels its casters covered when it was last drawn.
    pub drawn: TexelRect,
    pub fit: DepthFit,
    pub depth: &'a Texture,
    pub view: &'a ShadowView,
}

/// Both maps' keys as one, `None` when either is drawn every frame.
pub fn key(translucent: Option<u64>, depth: Option<u64>) -> Option<u64> {
    let mut h = DefaultHasher::new();
    (translucent?, depth?).hash(&mut h);
    Some(h.finish())
}

/// The matrix taking a depth map texel's position, (x, y, z) in the light's normalised
/// device coordinates with z = 2 x stored - 1, to the fitted depth as z / w: through the
/// inverse projection to the light's view, then `fit` along its axis. A perspective map of
/// linear depth stores (distance - near) / (far - near) instead: fitted directly.
pub fn depth_to_fitted(view: &ShadowView, fit: DepthFit) -> Mat4 {
    let (near, inv) = (f64::from(fit.near), 1.0 / f64::from(fit.depth()));
    let mut m = DMat4::IDENTITY;
    if view.linear_depth {
        let (vn, vf) = (f64::from(view.near), f64::from(view.far));
        // distance = vn + (z + 1) / 2 (vf - vn)
        m.z_axis.z = 0.5 * (vf - vn) * inv;
        m.w_axis.z = (vn + 0.5 * (vf - vn) - near) * inv;
        return m.as_mat4();
    }
    // Row z: -z_view, moved and scaled; row w: w_view.
    let mut fitted = DMat4::IDENTITY;
    fitted.z_axis.z = -inv;
    fitted.w_axis.z = -near * inv;
    (fitted * view.projection.as_dmat4().inverse()).as_mat4()
}
