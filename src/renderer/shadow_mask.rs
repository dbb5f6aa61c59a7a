//! The cached shadow mask (past the chapters, which test every light at every pixel every
//! frame). With `shadow_cache` on, a frame whose camera, items, target size, programs and
//! shadow maps are all as they were the frame before has the same tests at every pixel. The
//! second such frame (and the very first frame) writes them into a float target, one light per component, with the
//! scene shader's own tests (`SHADOW_MASK_WRITE`); from then on the scene pass reads them
//! back (`SHADOW_MASK_READ`: one fetch a pixel instead of each light's filter) until
//! something changes. The mask holds the very floats the tests give, so a frame drawn from
//! it is the same, pixel for pixel, as one drawn without it (`tests/frame/cache.rs`).

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use super::{scene_pass, Renderer};
use crate::engine::{Gl, Outputs, RenderTarget, Samplers, ShaderProgram, Texture};
use crate::error::Result;
use crate::scene::Scene;
use crate::shadows::program::slots::MaskMode;
use crate::shadows::program::ProgramKey;

/// What a frame does with the mask.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plan {
    /// Test every light per pixel: something changed since the last frame, or the frame
    /// cannot be cached.
    Test,
    /// The frame (this key) is as the last one: write the tests into the mask, then read
    /// them.
    Write(u64),
    /// The mask holds this frame's tests: read them.
    Read,
}

/// Frames drawn writing the mask and reading it, so far.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MaskUses {
    pub written: u64,
    pub read: u64,
}

/// The mask's target and what it holds.
#[derive(Default)]
pub struct ShadowMask {
    /// The target, and how many lights' channels it has (one float each: a scene with one
    /// light fetches 4 bytes a pixel, not 16).
    target: Option<(RenderTarget, usize)>,
    /// The key of the frame whose tests the mask holds.
    holds: Option<u64>,
    /// The key of the last frame drawn.
    last: Option<u64>,
    /// Whether a frame has been planned yet.
    started: bool,
    pub uses: MaskUses,
}

impl ShadowMask {
    /// What this frame, summed up by `key` (`None`: it cannot be cached), does with the
    /// mask. A frame that changes nothing twice in a row is worth writing down; one that
    /// changes every frame never pays for the write, but for the very first frame's: it
    /// writes too, so a still scene's second frame reads the mask at once instead of
    /// stalling on the write (a hitch after the first frame; the first one is set-up).
    pub fn plan(&mut self, key: Option<u64>) -> Plan {
        let previous = std::mem::replace(&mut self.last, key);
        let first = !std::mem::replace(&mut self.started, true);
        let plan = match key {
            None => Plan::Test,
            Some(k) if self.holds == Some(k) => Plan::Read,
            Some(k) if previous == Some(k) || first => Plan::Write(k),
            Some(_) => Plan::Test,
        };
        if plan != Plan::Test {
            self.uses.read += 1;
        }
        plan
    }

    /// The mask's target at `width` x `height` with a channel for each of the first
    /// `channels` lights (made or remade to fit), forgetting what it held: the caller
    /// writes it now.
    pub fn begin_write(
        &mut self,
        gl: &Gl,
        (width, height): (u32, u32),
        channels: usize,
    ) -> Result<&RenderTarget> {
        self.holds = None;
        self.fit(gl, (width, height), channels)?;
        match &self.target {
            Some((t, _)) => Ok(t),
            None => Err(crate::Error::Invalid("the shadow mask is missing".into())),
        }
    }

    /// Makes the target fit `width` x `height` and `channels` (before the frame that writes
    /// it, so that frame compiles and allocates nothing); a new one holds nothing yet.
    pub fn fit(&mut self, gl: &Gl, (width, height): (u32, u32), channels: usize) -> Result<()> {
        let fits = self
            .target
            .as_ref()
            .is_some_and(|(t, c)| (t.width(), t.height()) == (width, height) && *c == channels);
        if !fits {
            self.holds = None;
            self.target = None;
            self.target = Some((RenderTarget::float(gl, width, height, channels)?, channels));
        }
        Ok(())
    }

    /// The mask now holds the tests of the frame `key`.
    pub fn written(&mut self, key: u64) {
        self.holds = Some(key);
        self.uses.written += 1;
    }

    /// The mask's texture, for a frame that reads it.
    pub fn texture(&self) -> Option<&Texture> {
        self.holds
            .and(self.target.as_ref())
            .map(|(t, _)| t.colour())
    }
}

/// A number that changes whenever a pixel's shadow tests could: the camera, the target's
/// size, every item's mesh, placement and opacity (receivers as well as casters: they decide
/// which surface a pixel shows), the scene program, and what each light's maps hold (`maps`,
/// the shadow cache's keys, the translucent maps' among them; `None` when a map is drawn
/// every frame: then nothing is cached). Translucent items do not keep a frame from it: the
/// mask holds the opaque surfaces' tests, and they take their own
/// ([`super::translucent_pass`]).
pub fn frame_key(
    scene: &Scene,
    size: (u32, u32),
    program: &ProgramKey,
    maps: &[Option<u64>],
) -> Option<u64> {
    let mut h = DefaultHasher::new();
    for key in maps {
        key.ok_or(()).ok()?.hash(&mut h);
    }
    scene.camera.hash_bits(&mut h);
    size.hash(&mut h);
    program.hash(&mut h);
    for item in &scene.items {
        crate::shadows::cache::hash_placement(item, &mut h);
        item.opacity.to_bits().hash(&mut h);
    }
    Some(h.finish())
}

impl Renderer {
    /// What this frame does with the mask: with shadow volumes every light is tested (a
    /// pass per light), else as [`ShadowMask::plan`] says for this frame's key.
    pub(super) fn mask_plan(&mut self, scene: &Scene, size: (u32, u32)) -> Result<Plan> {
        if self.uses_volumes() {
            return Ok(Plan::Test);
        }
        let key = self.mask_key(scene, size)?;
        Ok(self.mask.plan(key))
    }

    /// What this frame's shadow tests depend on ([`frame_key`]); `None` when the mask
    /// cannot stand for them: no light with a map, a map drawn every frame (`shadow_cache`
    /// off), or a program the mask cannot serve.
    fn mask_key(&self, scene: &Scene, size: (u32, u32)) -> Result<Option<u64>> {
        let program = self.program_key(scene, Outputs::default())?;
        let mut maps: Vec<Option<u64>> = self
            .shadows
            .iter()
            .zip(self.schedule.keys())
            .filter(|(t, _)| t.is_some())
            .map(|(_, key)| *key)
            .collect();
        if maps.is_empty() || !program.maskable() {
            return Ok(None);
        }
        let translucent = &self.volumetric;
        maps.extend(
            (translucent.keys().iter().enumerate())
                .filter(|(i, _)| translucent.get(*i).is_some())
                .map(|(_, key)| *key),
        );
        Ok(frame_key(scene, size, &program, &maps))
    }

    /// The program `mode`'s scene program draws the translucent items with: none when it
    /// writes the mask; their own when a light tests them per vertex or resolves its
    /// translucent map for the opaque items ([`MaskMode::Vertex`]); else itself when it tests, the testing one beside a program
    /// that reads the mask ([`Renderer::keep_tests_program`] keeps those compiled).
    pub(super) fn translucent_program(&self, key: ProgramKey) -> Option<&ShaderProgram> {
        let wanted = match key.mask() {
            MaskMode::Write => return None,
            _ if key.translucent_apart() => key.with_mask(MaskMode::Vertex),
            MaskMode::Off | MaskMode::Vertex => key,
            MaskMode::Read => key.with_mask(MaskMode::Off),
        };
        self.program(wanted)
    }

    /// With translucent items to draw, makes sure the program they are drawn with beside
    /// `mode`'s (for `outputs`) is compiled: their own ([`MaskMode::Vertex`]), or beside a
    /// program that reads the mask the one that tests.
    pub(super) fn keep_tests_program(
        &mut self,
        scene: &Scene,
        outputs: Outputs,
        mode: MaskMode,
    ) -> Result<()> {
        if !scene.items.iter().any(|i| i.is_translucent()) {
            return Ok(());
        }
        if self.program_key(scene, outputs)?.translucent_apart() {
            self.use_program(scene, outputs, MaskMode::Vertex)?;
        } else if mode == MaskMode::Read {
            self.use_program(scene, outputs, MaskMode::Off)?;
        }
        Ok(())
    }

    /// One channel per light up to the last with a map.
    fn mask_channels(&self) -> usize {
        1 + self.shadows.iter().rposition(Option::is_some).unwrap_or(0)
    }

    /// Makes the mask's programs (writing it, and the scene program reading it for
    /// `outputs`) and its target at `size` now, when the mask may serve the frames to come,
    /// beside the scene program without the mask.
    pub(super) fn prepare_mask(
        &mut self,
        scene: &Scene,
        size: (u32, u32),
        outputs: Outputs,
    ) -> Result<()> {
        let may_serve = self.settings.shadow_cache
            && !self.uses_volumes()
            && self.shadows.iter().any(Option::is_some)
            && self.program_key(scene, Outputs::default())?.maskable();
        if may_serve {
            self.use_program(scene, Outputs::default(), MaskMode::Write)?;
            self.use_program(scene, outputs, MaskMode::Read)?;
            let channels = self.mask_channels();
            self.mask.fit(&self.gl, size, channels)?;
        }
        self.use_program(scene, outputs, MaskMode::Off)?;
        Ok(())
    }

    /// Draws every pixel's shadow tests into the mask (the scene pass with
    /// `SHADOW_MASK_WRITE`, into the mask's own float target of the frame's size), as the
    /// tests of the frame `key`.
    pub(super) fn write_mask(
        &mut self,
        scene: &Scene,
        (width, height): (u32, u32),
        key: u64,
        samplers: &mut Samplers,
    ) -> Result<()> {
        let program = self.use_program(scene, Outputs::default(), MaskMode::Write)?;
        let channels = self.mask_channels();
        self.mask
            .begin_write(&self.gl, (width, height), channels)?
            .bind_and_clear([1.0; 4]);
        let inputs = self.scene_inputs(program)?;
        scene_pass::draw(&inputs, samplers, &self.gl, scene, (width, height))?;
        self.mask.written(key);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_frame_writes_the_mask_and_a_still_second_reads_it() {
        let mut mask = ShadowMask::default();
        // `written` stands for the write the renderer does on a Write plan.
        let frame = |mask: &mut ShadowMask, key| {
            let plan = mask.plan(key);
            if let Plan::Write(k) = plan {
                mask.written(k);
            }
            plan
        };
        assert_eq!(frame(&mut mask, Some(1)), Plan::Write(1));
        assert_eq!(frame(&mut mask, Some(1)), Plan::Read);
        // Changing every frame: tested, never written again.
        assert_eq!(frame(&mut mask, Some(2)), Plan::Test);
        assert_eq!(frame(&mut mask, Some(3)), Plan::Test);
        // Still again: the second unchanged frame writes.
        assert_eq!(frame(&mut mask, Some(3)), Plan::Write(3));
        assert_eq!(frame(&mut mask, Some(3)), Plan::Read);
        assert_eq!(frame(&mut mask, None), Plan::Test);
        assert_eq!(mask.uses.written, 2);
    }
}
