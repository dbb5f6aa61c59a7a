//! Counts of the GL objects made and the programs linked on this thread, so a test can hold
//! a frame after the first to making none (a shader compiled mid-run is a visible hitch).

use std::cell::Cell;

/// GL objects made so far on this thread (its context's).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Created {
    pub programs: u64,
    pub textures: u64,
    pub framebuffers: u64,
    pub renderbuffers: u64,
    pub buffers: u64,
}

thread_local! {
    static CREATED: Cell<Created> = const { Cell::new(Created {
        programs: 0,
        textures: 0,
        framebuffers: 0,
        renderbuffers: 0,
        buffers: 0,
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
