//! The chapter's bias steps pinned by their error against the exact reference: each step's
//! false shadow and false light inside the light's box (where acne and peter panning are;
//! outside it is the over-sampling steps' lesson), on both scenes the chapter was written
//! for, each step in the view its page shows. A change of a bias formula or factor moves
//! these figures, whatever the other renders do.
//!
//! On these scenes the slope-bias step's own figures do not see its factor: the faces
//! that turn from the light are far from acne with half of it, and no caster rests on a
//! receiver in its view. `cull-front` keeps the slope bias and shows it at a contact: the
//! floor beside the caster compares against the caster's bottom face, so the band of false
//! light there is as long along the light as the bias (the DummyGame's floor faces its
//! light at 45°: 0.05 (1 - cos 45°) = 0.0146 of its 21 units; with the factor halved,
//! 0.0073, and the band's 0.796% of the receivers falls to 0.409%; LearnOpenGL's from
//! 0.206% to 0.121%).

use super::*;

/// Each bias step's figures inside the light's box at 640 x 360 (one ray a pixel), in its
/// page's view: the scene, the step, its false shadow and its false light, as shares of the
/// receivers there.
const PINNED: &[(&str, &str, f64, f64)] = &[
    ("dummy", "no-bias", 0.474095, 0.0),
    ("dummy", "bias", 0.000712, 0.025508),
    ("dummy", "slope-bias", 0.001037, 0.001587),
    ("dummy", "cull-front", 0.000408, 0.007957),
    ("learnopengl", "no-bias", 0.477425, 0.000244),
    ("learnopengl", "bias", 0.001561, 0.000407),
    ("learnopengl", "slope-bias", 0.000461, 0.000407),
    ("learnopengl", "cull-front", 0.000243, 0.002056),
];

/// How far a share may move: 3% of itself, or 20 pixels of the frame's 640 x 360 receivers
/// (a driver's rounding at a few edge texels), whichever is more.
fn tolerance(pinned: f64) -> f64 {
    (0.03 * pinned).max(20.0 / (640.0 * 360.0))
}

#[test]
fn the_bias_steps_keep_their_error_against_the_reference() {
    let ctx = common::context();
    let mut wrong = Vec::new();
    for &(name, step_name, shadow, light) in PINNED {
        let mut sc = scene(name);
        let s = step(&sc, step_name);
        steps::get(&sc, step_name)
            .unwrap_or_else(|| panic!("{name} has no step {step_name}"))
            .set_stage(&mut sc, false)
            .unwrap();
        let m = score_in_box(&measure(&ctx, &sc, &s, (640, 360), 1), &sc, &s, true);
        show(&format!("{name} {step_name}"), &m);
        for (what, got, pinned) in [
            ("false shadow", m.false_shadow_rate, shadow),
            ("false light", m.false_light_rate, light),
        ] {
            if (got - pinned).abs() > tolerance(pinned) {
                wrong.push(format!(
                    "{name} {step_name}: {what} {got:.6}, pinned {pinned:.6}"
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
