//! The context with what it has bound: the program in use and the texture on each unit, so
//! a bind that would change nothing is not sent (a scene pass binds the same white texture
//! for every item without one). Every bind in this layer goes through here, or forgets what
//! it knew when it binds behind its back (uploads, the HUD's saved state). Capabilities
//! likewise: glEnable / glDisable only when they change one.

use std::cell::RefCell;
use std::ops::Deref;

/// A GL context and its known bindings; [`super::Gl`] shares it.
pub struct GlContext {
    gl: glow::Context,
    bound: RefCell<Bound>,
    /// What has been done once on this context ([`GlContext::first_time`]).
    done: RefCell<Vec<u32>>,
}

/// What is known bound; `None`: not known (the next bind is sent).
#[derive(Default)]
struct Bound {
    program: Option<Option<glow::Program>>,
    active_unit: Option<u32>,
    /// Per unit, the last texture bound there and its target.
    units: Vec<Option<(u32, glow::Texture)>>,
    /// Capabilities known on or off (glEnable / glDisable), by name.
    caps: Vec<(u32, bool)>,
}

impl Deref for GlContext {
    type Target = glow::Context;

    fn deref(&self) -> &glow::Context {
        &self.gl
    }
}

impl GlContext {
    pub(crate) fn new(gl: glow::Context) -> GlContext {
        GlContext {
            gl,
            bound: RefCell::default(),
            done: RefCell::default(),
        }
    }

    /// Whether `what` (a GL enum naming it) is asked for the first time on this context;
    /// it is remembered. For work a driver needs once, such as compiling its own shaders.
    pub(crate) fn first_time(&self, what: u32) -> bool {
        let mut done = self.done.borrow_mut();
        let first = !done.contains(&what);
        if first {
            done.push(what);
        }
        first
    }

    /// `glUseProgram`, unless `program` is already in use.
    pub(crate) fn use_program_once(&self, program: Option<glow::Program>) {
        let mut b = self.bound.borrow_mut();
        if b.program != Some(program) {
            unsafe { glow::HasContext::use_program(&self.gl, program) };
            b.program = Some(program);
        }
    }

    /// `glActiveTexture` and `glBindTexture`, each unless it would change nothing.
    pub(crate) fn bind_texture_once(&self, unit: u32, target: u32, texture: glow::Texture) {
        let mut b = self.bound.borrow_mut();
        let i = unit as usize;
        if b.units.len() <= i {
            b.units.resize(i + 1, None);
        }
        if b.units[i] == Some((target, texture)) {
            return;
        }
        unsafe {
            if b.active_unit != Some(unit) {
                glow::HasContext::active_texture(&self.gl, glow::TEXTURE0 + unit);
                b.active_unit = Some(unit);
            }
            glow::HasContext::bind_texture(&self.gl, target, Some(texture));
        }
        b.units[i] = Some((target, texture));
    }

    /// `glEnable(cap)` or `glDisable(cap)`, unless `cap` is known to be so already: passes
    /// put their state back when they end, so most of these would change nothing.
    pub(crate) fn set_capability(&self, cap: u32, on: bool) {
        let mut b = self.bound.borrow_mut();
        let known = b.caps.iter_mut().find(|(c, _)| *c == cap);
        if known.as_ref().is_some_and(|(_, now)| *now == on) {
            return;
        }
        match known {
            Some(k) => k.1 = on,
            None => b.caps.push((cap, on)),
        }
        unsafe {
            match on {
                true => glow::HasContext::enable(&self.gl, cap),
                false => glow::HasContext::disable(&self.gl, cap),
            }
        }
    }

    /// After binds made without the calls above: nothing is known bound any more.
    pub(crate) fn forget_bindings(&self) {
        *self.bound.borrow_mut() = Bound::default();
    }

    /// A texture being deleted leaves every unit it was on (GL unbinds it there).
    pub(crate) fn forget_texture(&self, texture: glow::Texture) {
        for unit in self.bound.borrow_mut().units.iter_mut() {
            if unit.is_some_and(|(_, t)| t == texture) {
                *unit = None;
            }
        }
    }

    /// A program being deleted is no longer known to be in use.
    pub(crate) fn forget_program(&self, program: glow::Program) {
        let mut b = self.bound.borrow_mut();
        if b.program == Some(Some(program)) {
            b.program = None;
        }
    }
}
