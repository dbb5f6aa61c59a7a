//! Counts of the GL objects made and the programs linked on this thread, so a test can hold
//! a frame after the first to making none (a shader compiled mid-run is a visible hitch).

use std::cell::Cell;

/// GL objects made so far on this thread (its context's), by kind. Every object is made
/// through [`super::owned::Owned`], which counts it, so none escapes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Created {
    pub programs: u64,
    pub shaders: u64,
    pub textures: u64,
    pub framebuffers: u64,
    pub renderbuffers: u64,
    pub buffers: u64,
    pub vertex_arrays: u64,
    pub queries: u64,
    pub samplers: u64,
}

impl Created {
    /// What was made after `earlier` (a count taken before this one).
    pub fn since(self, earlier: Created) -> Created {
        Created {
            programs: self.programs - earlier.programs,
            shaders: self.shaders - earlier.shaders,
            textures: self.textures - earlier.textures,
            framebuffers: self.framebuffers - earlier.framebuffers,
            renderbuffers: self.renderbuffers - earlier.renderbuffers,
            buffers: self.buffers - earlier.buffers,
            vertex_arrays: self.vertex_arrays - earlier.vertex_arrays,
            queries: self.queries - earlier.queries,
            samplers: self.samplers - earlier.samplers,
        }
    }
}

thread_local! {
    static CREATED: Cell<Created> = const { Cell::new(Created {
        programs: 0,
        shaders: 0,
        textures: 0,
        framebuffers: 0,
        renderbuffers: 0,
        buffers: 0,
        vertex_arrays: 0,
        queries: 0,
        samplers: 0,
    }) };
}

/// What has been made on this thread so far.
pub fn created() -> Created {
    CREATED.with(Cell::get)
}

pub(crate) fn count(add: impl FnOnce(&mut Created)) {
    CREATED.with(|c| {
        let mut now = c.get();
        add(&mut now);
        c.set(now);
    });
}

thread_local! {
    static DRAWS: Cell<u64> = const { Cell::new(0) };
}

/// Draw calls of meshes sent so far on this thread (an instanced draw is one), so a test can
/// hold a frame to its batches.
pub fn draws() -> u64 {
    DRAWS.with(Cell::get)
}

pub(crate) fn count_draw() {
    DRAWS.with(|d| d.set(d.get() + 1));
}
