//! The `--motion` flags every command that draws frames shares.

use clap::Args;
use shadowmap::scene::motion::{MotionPath, PathKind};
use shadowmap::{Result, Scene};

/// The path flags every command that draws frames shares.
#[derive(Args, Debug, Clone, Default)]
pub struct MotionArgs {
    /// A scripted path, the same picture at the same frame every run: the camera moves
    /// (dolly: forward; strafe: to its right; orbit: about the point it looks at on the
    /// ground, or nearest the origin on its view), the first light turns (light-sweep, as
    /// the DummyGame's UP/DOWN keys; a spot light rises about its target), or the scene
    /// file's `[motion] keyframes`. Frame 0 is the scene's own view; the demo draws one
    /// frame of the path a frame.
    #[arg(long, value_enum, value_name = "PATH")]
    pub motion: Option<PathKind>,
    /// The path's step a frame: world units for dolly and strafe (default 0.05, the
    /// DummyGame's camera step), degrees for orbit and light-sweep (default 0.5).
    #[arg(long, value_name = "STEP", requires = "motion", allow_hyphen_values = true,
          value_parser = shadowmap::settings::parse_finite)]
    pub motion_step: Option<f32>,
}

impl MotionArgs {
    /// The path from the scene's pose, or why it cannot be had; `None` without `--motion`.
    pub fn path(&self, scene: &Scene) -> Result<Option<MotionPath>> {
        self.motion
            .map(|kind| MotionPath::new(kind, self.motion_step, scene))
            .transpose()
    }

    /// Sets the scene moving along the path (each `Scene::update` is its next frame).
    pub fn start(&self, scene: &mut Scene) -> Result<()> {
        scene.motion = self.path(scene)?;
        Ok(())
    }
}
