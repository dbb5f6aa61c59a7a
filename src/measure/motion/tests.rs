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
    let truth: Vec<_> = world.iter().map(|w| Some(shadowed(w.x))).collect();
    let truth_visibility = truth.iter().map(|t| t.map(lit)).collect();
    MotionFrame {
        width: W,
        height: H,
        world,
        view_proj,
        truth,
        truth_visibility,
    }
}

/// The visibility of a shadowed (0) or lit (1) state.
fn lit(shadowed: bool) -> f32 {
    f32::from(u8::from(!shadowed))
}

/// What a map of texels `texel` wide with its grid at `offset` answers: the truth at the
/// centre of the texel each pixel falls in.
fn through_map(
    frame: &MotionFrame,
    texel: f64,
    offset: f64,
    shadowed: impl Fn(f64) -> bool,
) -> Vec<Option<f32>> {
    frame
        .world
        .iter()
        .map(|w| {
            let cell = ((w.x - offset) / texel).floor();
            Some(lit(shadowed(offset + (cell + 0.5) * texel)))
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
    assert_eq!(score.energy, 0.0);
    assert_eq!(score.excess_energy, 0.0);
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
    // Δe = ±1 on the half texels where only one moved: [96, 100) and [104, 108); beyond
    // the truth's own steps only the frame's half, [96, 100), is charged.
    let score = meter.finish("strafe");
    let per_matched = |pixels: usize| ((pixels * H) as f64 / matched as f64).sqrt();
    assert!((score.energy - per_matched(8)).abs() < 1e-12, "{score:?}");
    assert!((score.excess_energy - per_matched(4)).abs() < 1e-12);
    assert!((score.truth_energy - per_matched(8)).abs() < 1e-12);
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
    f1.truth_visibility = f1.truth.iter().map(|t| t.map(lit)).collect();
    let r = hidden.truth_visibility.clone();
    let r1 = f1.truth.iter().map(|t| t.map(lit)).collect::<Vec<_>>();
    let pair = score_pair(&hidden, &r, &f1, &r1);
    assert_eq!(pair.matched, (W - 10) * H);
    assert_eq!(pair.changes.len(), (W - 10) * H);
    // Every matched truth flipped and so did the frame: no false flicker, no energy.
    assert_eq!((pair.false_flicker, pair.truth_change), (0.0, 1.0));
    assert_eq!(pair.energy(), 0.0);
}

/// How a filter reads a map whose texels `k < edge` are shadowed, texels `t` pixels wide,
/// its grid slid by `slide` texels.
#[derive(Clone, Copy)]
enum Lookup {
    /// The texel the point falls in.
    Single,
    /// The mean of the `n` texels about it (n odd), as an n x n box over an edge along z.
    Box(i64),
    /// Bilinear between the two nearest texel centres (hardware 2 x 2).
    Bilinear,
}

fn filtered(
    frame: &MotionFrame,
    (t, slide): (f64, f64),
    edge: i64,
    lookup: Lookup,
) -> Vec<Option<f32>> {
    let texel = |k: i64| f64::from(lit(k < edge));
    let at = |x: f64| match lookup {
        Lookup::Single => texel((x / t).floor() as i64),
        Lookup::Box(n) => {
            let k = (x / t).floor() as i64;
            (k - n / 2..=k + n / 2).map(texel).sum::<f64>() / n as f64
        }
        Lookup::Bilinear => {
            let u = x / t - 0.5;
            let (k, f) = (u.floor() as i64, u - u.floor());
            (1.0 - f) * texel(k) + f * texel(k + 1)
        }
    };
    let x = |w: &DVec3| w.x - slide * t;
    frame.world.iter().map(|w| Some(at(x(w)) as f32)).collect()
}

/// The truth holds still; the map's edge moves by one texel (texel 12 turns shadowed, as
/// when an unsnapped grid slides across it): the pair's score and each point's Δe.
fn one_texel_step(lookup: Lookup) -> (PairScore, Vec<f64>) {
    let t = 8.0;
    let f = floor(0.0, |x| x < 100.3);
    let r0 = filtered(&f, (t, 0.0), 12, lookup);
    let r1 = filtered(&f, (t, 0.0), 13, lookup);
    let pair = score_pair(&f, &r0, &f, &r1);
    let mut de = vec![0.0; W * H];
    for &(i, dv, dt) in &pair.changes {
        de[i] = dv - dt;
    }
    (pair, de)
}

/// The world x of each pixel where |Δe| is `value` (within f32's rounding).
fn where_change_is(de: &[f64], value: f64) -> Vec<f64> {
    let mut xs: Vec<f64> = (0..W * H)
        .filter(|&i| (de[i].abs() - value).abs() < 1e-6)
        .map(|i| (i % W) as f64 + 0.5)
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    xs
}

fn pixels_between(from: f64, to: f64) -> Vec<f64> {
    (from as usize..to as usize)
        .map(|x| x as f64 + 0.5)
        .collect()
}

#[test]
fn a_single_lookups_edge_moved_one_texel_changes_by_one_on_exactly_the_flipped_receivers() {
    let (pair, de) = one_texel_step(Lookup::Single);
    assert_eq!(where_change_is(&de, 1.0), pixels_between(96.0, 104.0));
    assert_eq!(where_change_is(&de, 0.0).len(), W - 8);
    let share = 8.0 / W as f64;
    assert_eq!(pair.flicker, share);
    assert!((pair.energy() - share.sqrt()).abs() < 1e-12);
}

#[test]
fn a_3x3_box_spreads_the_step_over_three_texels_of_a_third_each() {
    let (single, _) = one_texel_step(Lookup::Single);
    let (pair, de) = one_texel_step(Lookup::Box(3));
    assert_eq!(where_change_is(&de, 1.0 / 3.0), pixels_between(88.0, 112.0));
    assert_eq!(where_change_is(&de, 0.0).len(), W - 24);
    // Energy: 3 x (1/3)^2 against 1, so 1/sqrt(3) of the single lookup's.
    let ratio = pair.energy() / single.energy();
    assert!((ratio - 1.0 / 3f64.sqrt()).abs() < 1e-6, "{ratio}");
    // The binary state is blind to it: the box's mean crosses one half in texel 12 too.
    assert_eq!(pair.flicker, single.flicker);
    assert_eq!(pair.false_flicker, single.false_flicker);
    // A 5 x 5 box: five steps of a fifth, 1/sqrt(5).
    let (five, _) = one_texel_step(Lookup::Box(5));
    assert!((five.energy() / single.energy() - 1.0 / 5f64.sqrt()).abs() < 1e-6);
}

#[test]
fn hardware_2x2_changes_as_the_linear_ramp_says() {
    // The ramp between texel centres 11.5 and 12.5 moves by a texel: |Δv| is texel 12's
    // bilinear weight, a tent over two texels, (2j + 1) / 2n at the n = 8 pixels of each
    // side. Σ Δv² = (4n² - 1) / 6n against the single lookup's n: 2/3 as n grows.
    let (single, _) = one_texel_step(Lookup::Single);
    let (pair, de) = one_texel_step(Lookup::Bilinear);
    let n = 8.0;
    for j in 0..8 {
        let value = (2.0 * j as f64 + 1.0) / (2.0 * n);
        let xs = where_change_is(&de, value);
        assert_eq!(xs, [92.5 + j as f64, 107.5 - j as f64], "{value}");
    }
    let ratio = (pair.energy() / single.energy()).powi(2);
    assert!(
        (ratio - (4.0 * n * n - 1.0) / (6.0 * n * n)).abs() < 1e-6,
        "{ratio}"
    );
}

#[test]
fn hardware_2x2_slid_by_part_of_a_texel_changes_by_that_part_not_by_a_step() {
    // The map's grid slides by d texels under a still truth (an unsnapped map): each
    // point's lookup moves by d. The single lookup and the boxes step (a share d of the
    // points changes by 1 / n for an n-tap box); the bilinear ramp changes by d where it
    // is, so its squares are d - d²/3 of the single lookup's (less 1 / 6m² at m pixels a
    // texel): the smaller the step a frame, the steadier it is against the others.
    let f = floor(0.0, |x| x < 100.3);
    let m = 8.0;
    for d in [0.25, 0.5, 1.0] {
        let squares = |lookup| {
            let r0 = filtered(&f, (m, 0.0), 12, lookup);
            let r1 = filtered(&f, (m, d), 12, lookup);
            score_pair(&f, &r0, &f, &r1).energy().powi(2)
        };
        let single = squares(Lookup::Single);
        let ramp = squares(Lookup::Bilinear) / single;
        let expected = d - d * d / 3.0 - 1.0 / (6.0 * m * m);
        assert!(
            (ramp - expected).abs() < 1e-6,
            "slid {d}: {ramp} against {expected}"
        );
        let boxed = squares(Lookup::Box(3)) / single;
        assert!(
            (boxed - 1.0 / 3.0).abs() < 1e-6,
            "slid {d}: 3 x 3 box {boxed}"
        );
    }
}
