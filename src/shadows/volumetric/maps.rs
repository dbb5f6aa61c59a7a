//! Every light's translucent map, beside the lights' depth maps: made to match the plan,
//! drawn after the depth pass (before the scene pass) when what it holds changed
//! ([`super::cache`]), and bound for the scene pass.

use glam::{DMat4, DVec3, Mat4, Vec4};

use super::cache::{self, MapDraws};
use super::resolved::{self, Resolved};
use super::{method, translucent_casters, DepthFit, Draw, VolumetricMap, SAMPLERS};
use crate::engine::{Gl, Mesh, ShaderProgram, Texture};
use crate::error::Result;
use crate::scene::Scene;
use crate::settings::{MapSize, ShadowSettings, Volumetric};
use crate::shadows::camera::texels::{footprint, TexelRect};
use crate::shadows::ShadowView;

/// One per scene light, `None` for a light without one; with the technique each was
/// made for and the depth range each was last drawn over.
#[derive(Default)]
pub struct Maps {
    maps: Vec<Option<Box<dyn VolumetricMap>>>,
    techniques: Vec<Option<Volumetric>>,
    fits: Vec<DepthFit>,
    /// The texels each map's casters covered when it was last drawn (`None`: a new map,
    /// all of it unknown).
    drawn: Vec<Option<TexelRect>>,
    /// What each map is made for ([`cache::settings_key`]), and with `shadow_cache` on.
    made_for: Vec<(u64, bool)>,
    /// What each map holds ([`cache::content_key`]); `None`: draw it again.
    keys: Vec<Option<u64>>,
    /// Each map resolved for opaque receivers, where the light asks for it.
    resolved: Vec<Option<Resolved>>,
    /// Each light's depth map's size and its translucent map's, for the lookup's lift.
    sizes: Vec<(MapSize, MapSize)>,
    draws: MapDraws,
}

/// A light's depth map, for the resolve: its texture and what it holds (the shadow cache's
/// key, `None` when drawn every frame).
pub type DepthMap<'a> = Option<(&'a Texture, Option<u64>)>;

impl Maps {
    /// Makes each light's map match `lights`, each light's own settings and the translucent
    /// technique its plan gives it (a light keeps a map when that technique keeps one,
    /// [`crate::shadows::plan::LightPlan::volumetric`]).
    pub fn prepare(
        &mut self,
        gl: &Gl,
        lights: impl ExactSizeIterator<Item = (ShadowSettings, Option<Volumetric>)> + Clone,
    ) -> Result<()> {
        let n = lights.len();
        self.maps.resize_with(n, || None);
        self.fits.resize(
            n,
            DepthFit {
                near: 0.0,
                far: 1.0,
            },
        );
        self.techniques.resize(n, None);
        self.drawn.resize(n, None);
        self.made_for.resize(n, (0, false));
        self.keys.resize(n, None);
        self.resolved.resize_with(n, || None);
        self.sizes.clear();
        (self.sizes).extend(lights.clone().map(|(s, _)| (s.map_size, s.volumetric_size)));
        for (i, (settings, volumetric)) in lights.enumerate() {
            let (map, technique) = (&mut self.maps[i], &mut self.techniques[i]);
            let Some(m) = volumetric.and_then(method) else {
                (*map, *technique) = (None, None);
                (self.keys[i], self.resolved[i]) = (None, None);
                continue;
            };
            let resolved = &mut self.resolved[i];
            if !resolved::wanted(&settings) {
                *resolved = None;
            } else if !resolved.as_ref().is_some_and(|r| r.fits(&settings)) {
                *resolved = Some(Resolved::new(gl, &settings)?);
            }
            let fits = map.as_ref().is_some_and(|t| t.fits(&settings));
            if !fits || *technique != volumetric {
                *map = Some(m.create(gl, &settings)?);
                *technique = volumetric;
                (self.drawn[i], self.keys[i]) = (None, None);
            }
            let made_for = (cache::settings_key(&settings), settings.shadow_cache);
            if self.made_for[i] != made_for {
                (self.made_for[i], self.keys[i]) = (made_for, None);
            }
        }
        Ok(())
    }

    /// Draws each light's map through its camera in `views` (the depth pass' light
    /// cameras); `boxes`: every item's world box. With `shadow_cache` a map whose
    /// [`cache::content_key`] is the one it was drawn with is kept; without, every frame.
    /// Then resolves each map a light asks for at its `depth` map's depths, where either
    /// map changed.
    pub fn render(
        &mut self,
        gl: &Gl,
        meshes: &[Mesh],
        scene: &Scene,
        views: &[Option<ShadowView>],
        boxes: &[(DVec3, DVec3)],
        depth: &[DepthMap],
    ) -> Result<()> {
        self.draw(gl, meshes, scene, views, boxes)?;
        self.resolve(views, depth);
        Ok(())
    }

    /// Resolves each light's map for opaque receivers where it or the depth map changed.
    fn resolve(&mut self, views: &[Option<ShadowView>], depth: &[DepthMap]) {
        for (i, resolved) in self.resolved.iter_mut().enumerate() {
            let Some(r) = resolved else { continue };
            let (Some(map), Some(Some(view)), Some(Some((texture, depth_key)))) =
                (&self.maps[i], views.get(i), depth.get(i))
            else {
                continue;
            };
            let size = map.map().size();
            let source = resolved::Source {
                translucent: &**map,
                drawn: self.drawn[i].unwrap_or(TexelRect::whole(size)),
                fit: self.fits[i],
                depth: texture,
                view,
            };
            if r.update(&source, resolved::key(self.keys[i], *depth_key)) {
                self.draws.resolved += 1;
            }
        }
    }

    /// Draws each light's translucent map that changed ([`Maps::render`]).
    fn draw(
        &mut self,
        gl: &Gl,
        meshes: &[Mesh],
        scene: &Scene,
        views: &[Option<ShadowView>],
        boxes: &[(DVec3, DVec3)],
    ) -> Result<()> {
        for (i, map) in self.maps.iter_mut().enumerate() {
            let (Some(map), Some(Some(view))) = (map, views.get(i)) else {
                continue;
            };
            let fit = DepthFit::of(scene, boxes, view.view64);
            let (settings, cached) = self.made_for[i];
            let key = cached.then(|| cache::content_key(scene, view, settings, fit));
            if key.is_some() && key == self.keys[i] {
                self.draws.kept += 1;
                continue;
            }
            // Forgotten first: a draw that fails leaves the map to be drawn again.
            self.keys[i] = None;
            self.fits[i] = fit;
            // Only the texels the casters cover now or covered last time are cleared and
            // drawn: the rest hold 0 from before.
            let size = map.map().size();
            let covered = translucent_casters(scene)
                .filter_map(|(k, _)| boxes.get(k))
                .map(|&(lo, hi)| footprint(view, size, lo, hi))
                .fold(TexelRect::default(), TexelRect::union);
            let before = self.drawn[i].unwrap_or(TexelRect::whole(size));
            self.drawn[i] = Some(covered);
            let draw = Draw {
                gl,
                meshes,
                scene,
                view,
                fit,
                region: covered.union(before).pixels(),
            };
            map.render(&draw)?;
            self.keys[i] = key;
            self.draws.drawn += 1;
        }
        Ok(())
    }

    /// What each light's map holds ([`cache::content_key`]), `None` where it has none or is
    /// drawn every frame (`shadow_cache` off).
    pub fn keys(&self) -> &[Option<u64>] {
        &self.keys
    }

    /// Maps drawn and kept so far.
    pub fn draws(&self) -> MapDraws {
        self.draws
    }

    /// Binds each light's map on its unit for `program` and sets the matrices that find an
    /// opaque fragment in it (`camera_view`: the scene camera's view).
    pub fn bind(&self, program: &ShaderProgram, views: &[Option<ShadowView>], camera_view: DMat4) {
        if self.maps.iter().all(Option::is_none) {
            return;
        }
        let mut footprints = vec![Vec4::ZERO; self.maps.len()];
        for (i, map) in self.maps.iter().enumerate() {
            let (Some(map), Some(Some(_))) = (map, views.get(i)) else {
                continue;
            };
            let drawn = self.drawn[i].unwrap_or(TexelRect::whole(map.map().size()));
            footprints[i] = lookup_footprint(drawn, map.map().size());
            let unit = crate::shadows::units::volumetric_unit(i);
            program.set_i32(SAMPLERS[i], unit as i32);
            map.map().bind(unit);
            if let Some(r) = &self.resolved[i] {
                let unit = crate::shadows::units::resolved_unit(i);
                program.set_i32(resolved::SAMPLERS[i], unit as i32);
                r.map().bind(unit);
            }
        }
        self.set_matrices(program, views, camera_view, false);
        program.set_vec4_array("volumetricFootprint", &footprints);
    }

    /// Sets the matrices that find a fragment in each light's map on `program`, bound
    /// ([`Maps::bind`]): for a translucent item's fragment (`translucent`), read
    /// [`super::self_shadow_lift`] nearer the light, so it does not shade itself.
    pub fn set_matrices(
        &self,
        program: &ShaderProgram,
        views: &[Option<ShadowView>],
        camera_view: DMat4,
        translucent: bool,
    ) {
        if self.maps.iter().all(Option::is_none) {
            return;
        }
        let mut matrices = vec![Mat4::IDENTITY; self.maps.len()];
        for (i, map) in self.maps.iter().enumerate() {
            let (Some(_), Some(Some(view))) = (map, views.get(i)) else {
                continue;
            };
            let (depth, size) = self.sizes[i];
            let lift = match translucent {
                true => super::self_shadow_lift(view.texel_world, depth, size),
                false => 0.0,
            };
            matrices[i] = super::lookup_matrix(view, self.fits[i], lift, camera_view);
        }
        program.set_mat4_array("volumetricMatrix", &matrices);
    }

    /// Light `index`'s map, if it has one.
    pub fn get(&self, index: usize) -> Option<&dyn VolumetricMap> {
        self.maps.get(index)?.as_deref()
    }

    /// The depth range light `index`'s map was last drawn over.
    pub fn fit(&self, index: usize) -> Option<DepthFit> {
        self.fits.get(index).copied()
    }

    /// Bytes of GPU memory the maps hold.
    pub fn bytes(&self) -> u64 {
        let resolved: u64 = self
            .resolved
            .iter()
            .flatten()
            .map(|r| r.map().bytes())
            .sum();
        self.maps
            .iter()
            .flatten()
            .map(|m| m.map().bytes())
            .sum::<u64>()
            + resolved
    }

    /// Light `index`'s resolved map, if it has one.
    pub fn resolved(&self, index: usize) -> Option<&Resolved> {
        self.resolved.get(index)?.as_ref()
    }
}

/// The lookup's footprint (shaders/lib/volumetric.glsl's `volumetricFootprint`): the texels
/// `drawn` covers in a `size` map, a texel wider each side, as the map's xy (0 to 1). Past
/// it a lookup's bilinear reads (and AVSM's four texels) meet only texels no caster
/// reached: it skips them, reading 1.
pub fn lookup_footprint(drawn: TexelRect, size: MapSize) -> Vec4 {
    let (w, h) = (size.width as f32, size.height as f32);
    let side = |t: u32, grow: f32, n: f32| (t as f32 + grow) / n;
    Vec4::new(
        side(drawn.x0, -1.0, w),
        side(drawn.y0, -1.0, h),
        side(drawn.x1, 1.0, w),
        side(drawn.y1, 1.0, h),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lookup_footprint_is_the_drawn_texels_a_texel_wider_each_side() {
        let drawn = TexelRect {
            x0: 10,
            y0: 20,
            x1: 30,
            y1: 40,
        };
        let size = MapSize {
            width: 100,
            height: 200,
        };
        let f = lookup_footprint(drawn, size);
        let expected = Vec4::new(9.0 / 100.0, 19.0 / 200.0, 31.0 / 100.0, 41.0 / 200.0);
        assert!((f - expected).abs().max_element() < 1e-7, "{f}");
        // A bilinear read just inside it reaches texel 9, which no caster covered; texel 10
        // (the first drawn) is read from x > 9.5 texels on, well inside.
        let whole = lookup_footprint(TexelRect::whole(size), size);
        assert_eq!(whole, Vec4::new(-0.01, -0.005, 1.01, 1.005));
    }
}
