//! GPU time per pass, attached to a renderer as its [`PassHooks`].

use crate::engine::{Gl, PassTimer};
use crate::error::Result;
use crate::renderer::{Pass, PassHooks};

/// A timer query for the depth pass and one for the scene pass.
pub struct GpuPassTimes {
    timer: PassTimer,
}

impl GpuPassTimes {
    pub fn new(gl: &Gl) -> Result<GpuPassTimes> {
        Ok(GpuPassTimes {
            timer: PassTimer::new(gl, 2)?,
        })
    }

    /// GPU milliseconds of the last frame's depth and scene passes (waits for them).
    pub fn read_ms(&self) -> [f64; 2] {
        let t = self.timer.read_ms();
        [t[0], t[1]]
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
        self.timer.begin(index(pass));
    }

    fn end(&self, _pass: Pass) {
        self.timer.end();
    }
}
