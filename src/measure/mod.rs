//! Measurement, on top of the renderer: headless frames read back ([`frame`]), the exact
//! ray-traced reference ([`reference`]), a frame scored against it ([`compare`]), the
//! speed-versus-accuracy sweep ([`bench`]), how time grows with the work ([`scale`]) and
//! GPU pass timers ([`timing`]). It attaches to the renderer through its public API,
//! [`crate::renderer::PassHooks`] and the target's extra outputs; nothing in the renderer,
//! the techniques or the scene imports it.

pub mod bench;
pub mod compare;
pub mod frame;
pub mod motion;
pub mod reference;
pub mod scale;
pub mod timing;
