//! `demo --step S` draws what `render --step S` draws: the step's view and its settings.
//! Without a display the demo renders headless (its fallback), which is what runs here;
//! `tests/window.rs` does the same in a real window under Xvfb.

use crate::common;

use common::step_frames::{demo_and_render, differing_share, staged_steps};
use common::{bin, stdout_of};

#[test]
fn demo_step_draws_what_render_step_draws_for_every_staged_step() {
    let dir = std::env::temp_dir().join(format!("shadowmap-step-views-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let staged = staged_steps();
    assert!(staged.len() >= 8, "{staged:?}");
    for (scene, step) in staged {
        let (demo, render) = demo_and_render(&dir, scene, step, false);
        let share = differing_share(&demo, &render);
        assert!(
            share <= 0.01,
            "{scene} {step}: {:.2}% of pixels differ",
            share * 100.0
        );
        // The step's view is far from the scene's own, so a demo that drew the step's
        // settings from the scene's own camera would fail the check above.
        let own = dir.join(format!("{scene}-own.png"));
        stdout_of(
            bin()
                .args(["render", "--scene", scene, "--size", "320x180", "--out"])
                .arg(&own),
        );
        let apart = differing_share(&own, &render);
        assert!(
            apart > 0.05,
            "{scene} {step}: only {:.2}% from the scene's own view",
            apart * 100.0
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
