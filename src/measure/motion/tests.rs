//! The metric on a floor seen straight from above: one pixel is one world unit, and a
//! camera that strafes by whole pixels sees the same points at whole pixels.

use super::*;

const W: usize = 256;
const H: usize = 16;

/// A frame of the floor with the camera moved `shift` units along x; `shadowed(x)` is the
/// truth at world x.
fn floor(shift: f64, shadowed: impl Fn(f64) -> bool) -> MotionFrame {
    // clip.x = (x - shift) / W * 2 - 1, clip.y = 1 - z / H * 2.
    let view_proj = DMat4::from_cols(
        DVec4::new(2.0 / W as f64, 0.0, 0.0, 0.0),
        DVec4::ZERO,
        DVec4::new(0.0, -2.0 / H as f64, 0.0, 0.0),
        DVec4::new(-1.0 - 2.0 * shift / W as f64, 1.0, 0.0, 1.0),
    );
    let world: Vec<DVec3> = (0..W * H)
        .map(|i| DVec3::new((i % W) as f64 + 0.5 + shift, 0.0, (i / W) as f64 + 0.5))
        .collect();
    let truth = world.iter().map(|w| Some(shadowed(w.x))).collect();
    MotionFrame {
        width: W,
        height: H,
        world,
        view_proj,
        truth,
    }
}

/// What a map of texels `texel` wide with its grid at `offset` answers: the truth at the
/// centre of the texel each pixel falls in.
fn through_map(
    frame: &MotionFrame,
    texel: f64,
    offset: f64,
    shadowed: impl Fn(f64) -> bool,
) -> Vec<Option<bool>> {
    frame
        .world
        .iter()
        .map(|w| {
            let cell = ((w.x - offset) / texel).floor();
            Some(shadowed(offset + (cell + 0.5) * texel))
        })
        .collect()
}

#[test]
fn a_still_path_gives_exactly_zero() {
    let edge = |x: f64| x < 100.3;
    let mut meter = FlickerMeter::default();
    for _ in 0..3 {
        let f = floor(0.0, edge);
        let r = through_map(&f, 8.0, 0.0, edge);
        meter.push(f, r);
    }
    let score = meter.finish("still");
    assert_eq!(score.false_flicker, 0.0);
    assert_eq!(score.truth_change, 0.0);
    assert!(score.frames[1].matched == W * H);
    // The map's own error is there (the edge falls inside a texel), but it holds still.
    assert!(score.frames[0].misclassified > 0.0);
}

#[test]
fn an_edge_moved_one_texel_of_a_snapped_map_flips_only_that_texel() {
    // The grid is fixed in the world (snapped); the camera strafes 3 pixels; the true edge
    // moves by one texel, from the middle of texel 12 to the middle of texel 13.
    let t = 8.0;
    let (e0, e1) = (12.5 * t, 13.5 * t);
    let mut meter = FlickerMeter::default();
    let f0 = floor(0.0, |x| x < e0);
    let r0 = through_map(&f0, t, 0.0, |x| x < e0);
    meter.push(f0.clone(), r0.clone());
    let f1 = floor(3.0, |x| x < e1);
    let r1 = through_map(&f1, t, 0.0, |x| x < e1);
    let pair = meter.push(f1.clone(), r1.clone());
    let matched = (W - 3) * H;
    assert_eq!(pair.matched, matched);
    // The rendered state changed exactly on texel 13's pixels: x in [96, 104) of world.
    let one_texel = (t as usize * H) as f64 / matched as f64;
    assert_eq!(pair.flicker, Some(one_texel));
    for (i, w) in f1.world.iter().enumerate() {
        let j = f0.pixel_of(*w);
        let changed = j.is_some_and(|j| r0[j] != r1[i]);
        assert_eq!(
            changed,
            (12.0 * t..13.0 * t).contains(&w.x),
            "at x = {}",
            w.x
        );
    }
    // The truth moved one texel too, half a texel later: half of each flip is false.
    assert_eq!(pair.truth_change, Some(one_texel));
    assert_eq!(pair.false_flicker, Some(one_texel));
}

#[test]
fn a_map_shifted_half_a_texel_without_snapping_flips_texel_over_period() {
    // Stripes of period P (edges every P/2, none on a texel's boundary or centre); a map
    // of texel t whose grid moves by t/2 moves each quantised edge by exactly t/2, so the
    // flipped share is (t/2) / (P/2) = t / P.
    let (t, period) = (8.0, 64.0);
    let stripes = move |x: f64| (x - 11.0).rem_euclid(period) < period / 2.0;
    let mut meter = FlickerMeter::default();
    let f0 = floor(0.0, stripes);
    let r0 = through_map(&f0, t, 0.0, stripes);
    meter.push(f0, r0);
    let f1 = floor(0.0, stripes);
    let r1 = through_map(&f1, t, t / 2.0, stripes);
    let pair = meter.push(f1, r1);
    assert_eq!(pair.truth_change, Some(0.0));
    assert_eq!(pair.false_flicker, Some(t / period));
}

#[test]
fn a_point_hidden_in_the_previous_frame_is_not_matched() {
    let edge = |x: f64| x < 50.0;
    let f0 = floor(0.0, edge);
    let mut f1 = floor(0.0, edge);
    // Another surface, five units above, in the previous frame's pixels 0..10 of each row.
    let mut hidden = f0.clone();
    for i in (0..W * H).filter(|i| i % W < 10) {
        hidden.world[i].y += 5.0;
    }
    f1.truth.iter_mut().for_each(|t| *t = t.map(|s| !s));
    let r: Vec<_> = hidden.truth.clone();
    let r1: Vec<_> = f1.truth.clone();
    let (matched, false_flicker, truth, _) = score_pair(&hidden, &r, &f1, &r1);
    assert_eq!(matched, (W - 10) * H);
    // Every matched truth flipped and so did the frame: no false flicker.
    assert_eq!((false_flicker, truth), (0.0, 1.0));
}
