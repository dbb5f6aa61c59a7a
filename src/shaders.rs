//! The GLSL sources, embedded at build time so the binary runs from any directory.

use crate::engine::ShaderSource;

macro_rules! shader {
    ($name:ident, $file:literal) => {
        /// The embedded text of `shaders/` + the file name.
        pub fn $name() -> ShaderSource {
            ShaderSource::new(
                concat!("shaders/", $file),
                include_str!(concat!("../shaders/", $file)),
            )
        }
    };
}

shader!(depth_vert, "depth.vert");
shader!(depth_frag, "depth.frag");
shader!(scene_vert, "scene.vert");
shader!(scene_frag, "scene.frag");
shader!(depth_view_vert, "depth_view.vert");
shader!(depth_view_frag, "depth_view.frag");
shader!(depth_point_vert, "depth_point.vert");
shader!(depth_point_frag, "depth_point.frag");
shader!(depth_point_layered_vert, "depth_point_layered.vert");
shader!(depth_point_layered_geom, "depth_point_layered.geom");
shader!(text_vert, "text.vert");
shader!(text_frag, "text.frag");
