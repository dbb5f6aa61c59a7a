//! The GL-facing engine: every `unsafe` OpenGL call of the project lives in this module.
//!
//! Each type owns its GL objects through [`owned::Owned`], which makes, counts and deletes
//! them, so app code never sees a raw GL name; every framebuffer is put together by
//! [`framebuffer::Framebuffer::build`]. The names follow the LWJGL book's classes (`Texture`, `ShadowMap`, `ShaderProgram`,
//! `Mesh`); `RenderTarget` is the headless stand-in for the window's framebuffer.

pub mod bindings;
pub mod blend;
pub mod check;
pub mod context;
pub mod counters;
pub mod depth_peel;
pub mod framebuffer;
pub mod instances;
pub mod mesh;
pub mod moment_map;
pub mod owned;
pub mod render_target;
pub mod sampler;
pub mod shader_program;
pub mod shadow_map;
pub mod state;
pub mod summed_area;
pub mod text;
pub mod texture;
pub mod timer;
pub mod translucent_map;
pub mod vertex_capture;
pub mod volume;

use std::rc::Rc;

/// A shared handle to the current GL context; every GL object keeps one so it can free itself.
pub type Gl = Rc<bindings::GlContext>;

pub use blend::TranslucentBlend;
pub use check::{check_gl, gl_limits, GlLimits};
pub use context::{HeadlessContext, WindowApi, WindowContext};
pub use depth_peel::{DepthPeel, PeelPass};
pub use instances::{InstanceBuffer, Instanced};
pub use mesh::{FullScreenTriangle, Mesh};
pub use moment_map::MomentMap;
pub use render_target::{Outputs, RenderTarget};
pub use sampler::{BoundSampler, Sampler, Samplers, Sampling};
pub use shader_program::{Dialect, ShaderProgram, ShaderSource};
pub use shadow_map::{CascadeShadowMap, CubeShadowMap, ShadowMap};
pub use state::{DepthPassGuard, DepthState, OverlayViewport, PixelRect};
pub use summed_area::SummedAreaTable;
pub use texture::Texture;
pub use timer::PassTimer;
pub use translucent_map::{MapPass, ResolvedMap, TranslucentMap};
pub use vertex_capture::{CapturePass, VertexCapture};
pub use volume::{
    AdjacencyMesh, LightPass, LightPassGuard, SamplesQuery, VolumeDraw, VolumePassGuard,
};
