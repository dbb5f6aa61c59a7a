//! GPU time per pass with `GL_TIME_ELAPSED` queries (core since GL 3.3).

use glow::HasContext;

use super::owned::OwnedQuery;
use super::Gl;
use crate::error::Result;

/// One timer query per pass; owned, deleted on drop.
pub struct PassTimer {
    gl: Gl,
    queries: Vec<OwnedQuery>,
}

impl PassTimer {
    pub fn new(gl: &Gl, passes: usize) -> Result<PassTimer> {
        let queries = (0..passes)
            .map(|_| OwnedQuery::new(gl, "timer query"))
            .collect::<Result<_>>()?;
        Ok(PassTimer {
            gl: gl.clone(),
            queries,
        })
    }

    /// Starts timing pass `i`; only one pass can be timed at a time.
    pub fn begin(&self, i: usize) {
        if let Some(q) = self.queries.get(i) {
            unsafe { self.gl.begin_query(glow::TIME_ELAPSED, q.raw()) };
        }
    }

    pub fn end(&self) {
        unsafe { self.gl.end_query(glow::TIME_ELAPSED) };
    }

    /// The last measured time of every pass in milliseconds (waits for the results).
    pub fn read_ms(&self) -> Vec<f64> {
        (0..self.queries.len())
            .map(|i| self.read_pass_ms(i))
            .collect()
    }

    /// The last measured time of pass `i` in milliseconds (waits for it); 0 for a pass
    /// there is no query for. Only a pass timed at least once has a result to read.
    pub fn read_pass_ms(&self, i: usize) -> f64 {
        let Some(q) = self.queries.get(i) else {
            return 0.0;
        };
        let mut ns: u64 = 0;
        // With no query buffer bound, the "offset" is the address to write to.
        unsafe {
            self.gl.get_query_parameter_u64_with_offset(
                q.raw(),
                glow::QUERY_RESULT,
                &mut ns as *mut u64 as usize,
            )
        };
        ns as f64 / 1.0e6
    }
}
