//! `GameItem` and `Material`: an instance of a mesh placed in the world (the book's
//! `GameItem`), and how it is coloured.

use glam::{DMat4, Mat4, Vec3, Vec4};

use crate::transformation::Transformation;

/// Colour or texture, and how shiny (the book's `Material`, with one colour for ambient,
/// diffuse and specular as its constructor does).
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    pub colour: Vec4,
    /// Index into [`Scene::textures`](super::Scene::textures); replaces the colour.
    pub texture: Option<usize>,
    pub reflectance: f32,
}

/// An item: a mesh, where it is, how it is turned and scaled, and its material.
#[derive(Debug, Clone, PartialEq)]
pub struct GameItem {
    pub name: String,
    /// Index into [`Scene::meshes`](super::Scene::meshes).
    pub mesh: usize,
    pub position: Vec3,
    /// Degrees, applied as the book does: see [`Transformation::model`].
    pub rotation: Vec3,
    /// Scale per axis (the book's items scale uniformly).
    pub scale: Vec3,
    pub material: Material,
    /// Degrees added to `rotation` per update (the DummyGame's cube turns 0.5 about Y).
    pub spin: Vec3,
    /// Whether the item is drawn into the shadow map (never a translucent one: see
    /// `casts_translucent`).
    pub casts_shadows: bool,
    /// How much of the light a crossing of its surface stops: each crossing multiplies the
    /// light left by (1 - opacity). 1 = opaque, the chapters' items.
    pub opacity: f32,
    /// A translucent item's own `casts_shadows`: whether it casts at all, by the light's
    /// volumetric technique (`crate::shadows::volumetric`) rather than the depth map.
    pub casts_translucent: bool,
}

impl GameItem {
    /// Whether light passes it in part (opacity below 1).
    pub fn is_translucent(&self) -> bool {
        self.opacity < 1.0
    }

    pub fn model_matrix(&self) -> Mat4 {
        Transformation::model(self.position, self.rotation, self.scale)
    }

    /// The model matrix in double precision (see `Camera::view_matrix64`).
    pub fn model_matrix64(&self) -> DMat4 {
        Transformation::model64(self.position, self.rotation, self.scale)
    }

    /// One fixed update of the animation (the book runs 30 per second).
    pub fn update(&mut self) {
        self.rotation += self.spin;
        // Keep angles small so long runs keep their precision.
        self.rotation = Vec3::new(
            self.rotation.x % 360.0,
            self.rotation.y % 360.0,
            self.rotation.z % 360.0,
        );
    }
}
