//! GPU time per pass, attached to a renderer as its [`PassHooks`].

use std::cell::Cell;

use crate::engine::{Gl, PassTimer};
use crate::error::Result;
use crate::renderer::{Pass, PassHooks};

/// A timer query for the depth pass and one for the scene pass.
pub struct GpuPassTimes {
    timer: PassTimer,
    /// Which passes were timed since the last read: a frame may have no scene pass (the
    /// depth view draws a map instead), and a query never begun has no result to read.
    timed: Cell<[bool; 2]>,
}

impl GpuPassTimes {
    pub fn new(gl: &Gl) -> Result<GpuPassTimes> {
        Ok(GpuPassTimes {
            timer: PassTimer::new(gl, 2)?,
            timed: Cell::new([false; 2]),
        })
    }

    /// GPU milliseconds of the last frame's depth and scene passes (waits for them); 0 for
    /// a pass the frame did not draw.
    pub fn read_ms(&self) -> [f64; 2] {
        let timed = self.timed.replace([false; 2]);
        [0, 1].map(|i| match timed[i] {
            true => self.timer.read_pass_ms(i),
            false => 0.0,
        })
    }
}

fn index(pass: Pass) -> usize {
    match pass {
        Pass::Depth => 0,
        Pass::Scene => 1,
    }
}

impl PassHooks for GpuPassTimes {
    fn begin(&self, pass: Pass) {
        let mut timed = self.timed.get();
        timed[index(pass)] = true;
        self.timed.set(timed);
        self.timer.begin(index(pass));
    }

    fn end(&self, _pass: Pass) {
        self.timer.end();
    }
}
