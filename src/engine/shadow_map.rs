//! `ShadowMap`: the FBO the depth pass renders into, and its depth texture
//! ("Shadows", section "Shadow Mapping": the `ShadowMap` class).

mod fbo;
mod layered;

use glow::HasContext;

use super::framebuffer::{Framebuffer, Part};
use super::texture::Texture;
use super::Gl;
use crate::error::Result;
use crate::settings::{DepthFormat, MapSize};
pub use layered::{CascadeShadowMap, CubeShadowMap};

/// Owns the framebuffer and the depth texture attached to it; both are freed on drop.
pub struct ShadowMap {
    gl: Gl,
    fbo: Framebuffer,
    depth_map: Texture,
    format: DepthFormat,
}

impl ShadowMap {
    /// Creates a depth-only framebuffer of `size` (square in the chapters, the canvas' shape
    /// in the shadow-playground). Like the book, it has no colour buffer (draw and read
    /// buffer NONE) and its completeness is checked.
    pub fn new(gl: &Gl, size: impl Into<MapSize>, format: DepthFormat) -> Result<ShadowMap> {
        let size = size.into();
        let texture = Texture::depth(gl, size.width, size.height, format)?;
        Self::from_texture(gl, texture, format)
    }

    /// Builds the framebuffer around an existing texture. A texture that cannot be a depth
    /// attachment gives [`Error::IncompleteFramebuffer`], never a silently black map.
    pub fn from_texture(gl: &Gl, depth_map: Texture, format: DepthFormat) -> Result<ShadowMap> {
        let (width, height) = (depth_map.width(), depth_map.height());
        let what = format!("shadow map {width}x{height}");
        let fbo = fbo::depth_only(gl, &depth_map, Part::Image, &what)?;
        // Once per context and depth format (a patched map's clear; see the function).
        if gl.first_time(super::texture::depth_internal_format(format)) {
            fbo::warm_scissored_clear(gl, &fbo);
        }
        Ok(ShadowMap {
            gl: gl.clone(),
            fbo,
            depth_map,
            format,
        })
    }

    /// Binds the FBO and sets the viewport to the map's size (the start of `renderDepthMap`).
    pub fn bind_for_writing(&self) {
        self.fbo.bind();
        let (width, height) = (self.depth_map.width(), self.depth_map.height());
        unsafe { self.gl.viewport(0, 0, width as i32, height as i32) };
    }

    pub fn depth_map_texture(&self) -> &Texture {
        &self.depth_map
    }

    pub fn size(&self) -> MapSize {
        MapSize {
            width: self.depth_map.width(),
            height: self.depth_map.height(),
        }
    }

    pub fn format(&self) -> DepthFormat {
        self.format
    }

    /// Reads the depth values back (row 0 at the bottom, as GL stores them).
    pub fn read_depth(&self) -> Vec<f32> {
        fbo::read_depth(&self.gl, &self.fbo, self.size())
    }
}
