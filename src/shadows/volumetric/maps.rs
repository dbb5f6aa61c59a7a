//! Every light's translucent map, beside the lights' depth maps: made to match the plan,
//! drawn after the depth pass (before the scene pass) and bound for the scene pass.

use glam::{DMat4, DVec3, Mat4};

use super::{method, translucent_casters, DepthFit, Draw, VolumetricMap, SAMPLERS};
use crate::engine::{Gl, Mesh, ShaderProgram};
use crate::error::Result;
use crate::scene::Scene;
use crate::settings::Volumetric;
use crate::shadows::patch::{footprint, TexelRect};
use crate::shadows::plan::ShadowPlan;
use crate::shadows::{slots, ShadowView};

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
}

impl Maps {
    /// Makes each light's map match `plan` (a light keeps one when the plan gives it a
    /// technique that keeps one, [`crate::shadows::plan::LightPlan::volumetric`]).
    pub fn prepare(&mut self, gl: &Gl, plan: &ShadowPlan) -> Result<()> {
        let n = plan.lights.len();
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
        let slots = (self.maps.iter_mut().zip(&mut self.techniques)).zip(&mut self.drawn);
        for (own, ((map, technique), drawn)) in plan.lights.iter().zip(slots) {
            let Some(m) = own.volumetric.and_then(method) else {
                (*map, *technique) = (None, None);
                continue;
            };
            let fits = map.as_ref().is_some_and(|t| t.fits(&own.settings));
            if !fits || *technique != own.volumetric {
                *map = Some(m.create(gl, &own.settings)?);
                *technique = own.volumetric;
                *drawn = None;
            }
        }
        Ok(())
    }

    /// Draws each light's map through its camera in `views` (the depth pass' light
    /// cameras); `boxes`: every item's world box. Every frame: the translucent casters
    /// are few and the depth map's cache does not follow them.
    pub fn render(
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
        }
        Ok(())
    }

    /// Binds each light's map on its unit for `program` and sets the matrices that find a
    /// fragment in it (`camera_view`: the scene camera's view).
    pub fn bind(&self, program: &ShaderProgram, views: &[Option<ShadowView>], camera_view: DMat4) {
        if self.maps.iter().all(Option::is_none) {
            return;
        }
        let mut matrices = vec![Mat4::IDENTITY; self.maps.len()];
        for (i, map) in self.maps.iter().enumerate() {
            let (Some(map), Some(Some(view))) = (map, views.get(i)) else {
                continue;
            };
            matrices[i] = super::lookup_matrix(view, self.fits[i], camera_view);
            let unit = slots::volumetric_unit(i);
            program.set_i32(SAMPLERS[i], unit as i32);
            map.map().bind(unit);
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
        self.maps.iter().flatten().map(|m| m.map().bytes()).sum()
    }
}
