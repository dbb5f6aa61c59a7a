//! Accuracy of a rendered shadow image against the ray-traced reference.
//!
//! Only pixels that the reference calls receivers and the renderer covers
//! are scored: elsewhere there is no direct light to be right or wrong about.

use super::visibility::RefPixel;

/// Error counts and rates; rates are fractions of the scored pixels.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Metrics {
    /// Scored pixels: reference receiver and rendered value present.
    pub receivers: usize,
    /// |V - V_ref| > 0.5.
    pub misclassified: usize,
    /// Rendered darker than the reference (V < V_ref - 0.5).
    pub false_shadow: usize,
    /// Rendered brighter than the reference (V > V_ref + 0.5).
    pub false_light: usize,
    pub misclassified_rate: f64,
    pub false_shadow_rate: f64,
    pub false_light_rate: f64,
    /// Scored pixels excluded because they lie near a reference shadow edge.
    pub band_pixels: usize,
    pub outside_band_receivers: usize,
    pub misclassified_outside_band: usize,
    pub false_shadow_outside_band: usize,
    pub false_light_outside_band: usize,
    pub misclassified_outside_band_rate: f64,
    /// Mean |V - V_ss| against the supersampled reference, over scored
    /// pixels that are also receivers there; None without one.
    pub mae: Option<f64>,
}

/// How one pixel compares with the reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    NotScored,
    Correct,
    FalseShadow,
    FalseLight,
}

/// Rendered value of a pixel. Non-finite values count as no geometry, so a
/// NaN cannot slip through both comparisons and be scored as correct.
fn rendered_at(rendered: &[Option<f32>], i: usize) -> Option<f32> {
    rendered.get(i).copied().flatten().filter(|v| v.is_finite())
}

fn classify(rendered: &[Option<f32>], reference: &[RefPixel], i: usize) -> Class {
    let (Some(v), Some(r)) = (rendered_at(rendered, i), reference.get(i)) else {
        return Class::NotScored;
    };
    if !r.receiver {
        Class::NotScored
    } else if v < r.visibility - 0.5 {
        Class::FalseShadow
    } else if v > r.visibility + 0.5 {
        Class::FalseLight
    } else {
        Class::Correct
    }
}

fn rate(count: usize, total: usize) -> f64 {
    if total == 0 {
        0.0
    } else {
        count as f64 / total as f64
    }
}

/// Scores `rendered` (visibility 0..1 per pixel, None = no geometry)
/// against the hard `reference`, both `width * height` and row-major.
///
/// A scored pixel is in the edge band when some reference receiver within
/// Chebyshev distance `band` has the other hard value (lit vs shadowed);
/// `band == 0` disables the band. The band exists because a shadow map
/// rasterised at a different resolution must differ within a pixel or two
/// of every edge, and that says nothing about bias or acne.
/// Short slices are read as if padded with uncovered pixels.
pub fn compute_metrics(
    width: usize,
    height: usize,
    rendered: &[Option<f32>],
    reference: &[RefPixel],
    supersampled: Option<&[RefPixel]>,
    band: usize,
) -> Metrics {
    let n = width.saturating_mul(height);
    let in_band = edge_band(width, height, reference, band);
    let mut m = Metrics {
        receivers: 0,
        misclassified: 0,
        false_shadow: 0,
        false_light: 0,
        misclassified_rate: 0.0,
        false_shadow_rate: 0.0,
        false_light_rate: 0.0,
        band_pixels: 0,
        outside_band_receivers: 0,
        misclassified_outside_band: 0,
        false_shadow_outside_band: 0,
        false_light_outside_band: 0,
        misclassified_outside_band_rate: 0.0,
        mae: None,
    };
    let (mut abs_sum, mut abs_count) = (0.0f64, 0usize);
    for i in 0..n {
        let class = classify(rendered, reference, i);
        if class == Class::NotScored {
            continue;
        }
        m.receivers += 1;
        let banded = in_band.get(i).copied().unwrap_or(false);
        if banded {
            m.band_pixels += 1;
        } else {
            m.outside_band_receivers += 1;
        }
        match class {
            Class::FalseShadow => {
                m.false_shadow += 1;
                m.false_shadow_outside_band += !banded as usize;
            }
            Class::FalseLight => {
                m.false_light += 1;
                m.false_light_outside_band += !banded as usize;
            }
            Class::NotScored | Class::Correct => {}
        }
        if let (Some(ss), Some(v)) = (supersampled, rendered_at(rendered, i)) {
            if let Some(s) = ss.get(i).filter(|s| s.receiver) {
                abs_sum += (f64::from(v) - f64::from(s.visibility)).abs();
                abs_count += 1;
            }
        }
    }
    m.misclassified = m.false_shadow + m.false_light;
    m.misclassified_outside_band = m.false_shadow_outside_band + m.false_light_outside_band;
    m.misclassified_rate = rate(m.misclassified, m.receivers);
    m.false_shadow_rate = rate(m.false_shadow, m.receivers);
    m.false_light_rate = rate(m.false_light, m.receivers);
    m.misclassified_outside_band_rate =
        rate(m.misclassified_outside_band, m.outside_band_receivers);
    m.mae = supersampled.map(|_| {
        if abs_count == 0 {
            0.0
        } else {
            abs_sum / abs_count as f64
        }
    });
    m
}

/// Per pixel: is a receiver of the opposite hard value within `band`?
fn edge_band(width: usize, height: usize, reference: &[RefPixel], band: usize) -> Vec<bool> {
    let n = width.saturating_mul(height);
    if band == 0 || n == 0 {
        return vec![false; n];
    }
    let hard = |i: usize| {
        reference
            .get(i)
            .filter(|r| r.receiver)
            .map(|r| r.visibility >= 0.5)
    };
    let lit: Vec<bool> = (0..n).map(|i| hard(i) == Some(true)).collect();
    let dark: Vec<bool> = (0..n).map(|i| hard(i) == Some(false)).collect();
    let lit_near = dilate(&lit, width, height, band);
    let dark_near = dilate(&dark, width, height, band);
    (0..n)
        .map(|i| match hard(i) {
            Some(true) => dark_near[i],
            Some(false) => lit_near[i],
            None => false,
        })
        .collect()
}

/// Square dilation of a mask by radius `r`, done separably with running
/// counts so the cost does not grow with the radius.
fn dilate(mask: &[bool], width: usize, height: usize, r: usize) -> Vec<bool> {
    let horizontal = dilate_lines(mask, width, height, 1, width, r);
    dilate_lines(&horizontal, height, width, width, 1, r)
}

/// Dilates `lines` lines of length `len` in place order; element k of line
/// l is at `l * line_stride + k * step`.
fn dilate_lines(
    mask: &[bool],
    len: usize,
    lines: usize,
    step: usize,
    line_stride: usize,
    r: usize,
) -> Vec<bool> {
    let mut out = vec![false; mask.len()];
    let mut prefix = vec![0usize; len + 1];
    for l in 0..lines {
        let base = l * line_stride;
        for k in 0..len {
            prefix[k + 1] = prefix[k] + mask[base + k * step] as usize;
        }
        for k in 0..len {
            let lo = k.saturating_sub(r);
            let hi = (k + r + 1).min(len);
            out[base + k * step] = prefix[hi] > prefix[lo];
        }
    }
    out
}

/// A rendered image against the soft-shadow truth of a light with a size
/// ([`super::area`]). Rates are fractions of the scored pixels (receivers of the truth with
/// a rendered value).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SoftMetrics {
    /// Rays per pixel of the truth.
    pub rays: usize,
    pub receivers: usize,
    /// Mean |V - V_truth|.
    pub mae: f64,
    /// Light bleeding: lit above 0.5 where the truth is fully shadowed.
    pub light_bleed: usize,
    pub light_bleed_rate: f64,
    /// Shadowed below 0.5 where the truth is fully lit.
    pub false_shadow: usize,
    pub false_shadow_rate: f64,
    /// The truth's shadow edges measured (see [`penumbra_profiles`]).
    pub penumbra_edges: usize,
    /// Mean 10%-90% width across those edges, in pixels: the truth's and the image's.
    pub penumbra_width_truth_px: f64,
    pub penumbra_width_px: f64,
    /// Mean |width - truth's width| over the edges, in pixels.
    pub penumbra_width_error_px: f64,
}

/// One of the truth's shadow edges, measured across: at pixel (x, y), the 10%-90% width
/// of the truth's and of the image's visibility along the truth's gradient, in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PenumbraProfile {
    pub x: usize,
    pub y: usize,
    pub truth_px: f64,
    pub rendered_px: f64,
}

/// The longest walk from an edge to either side, in pixels: a penumbra wider than twice
/// this is not measured.
pub const PENUMBRA_REACH: usize = 48;

/// The truth's shadow edges and their widths. An edge pixel is a receiver where the truth
/// crosses 0.5 towards its right or lower neighbour; the profile runs along the truth's
/// gradient there (Sobel), one pixel per step, up to [`PENUMBRA_REACH`] each way, and the
/// width is the number of steps whose visibility lies strictly between 0.1 and 0.9 (for a
/// ramp, its 10%-90% width), each image counted on each side until it passes the ramp's
/// end there (0.1 below the edge, 0.9 above). An edge is kept only if the truth's profile reaches both 0.1
/// and 0.9 on receivers the image also covers (so occluder silhouettes and image borders
/// do not cut it short).
pub fn penumbra_profiles(
    width: usize,
    height: usize,
    rendered: &[Option<f32>],
    truth: &[RefPixel],
) -> Vec<PenumbraProfile> {
    let n = width.saturating_mul(height);
    let t = |i: usize| truth.get(i).filter(|r| r.receiver).map(|r| r.visibility);
    let both = |x: i64, y: i64| -> Option<(f32, f32)> {
        if x < 0 || y < 0 || x >= width as i64 || y >= height as i64 {
            return None;
        }
        let i = y as usize * width + x as usize;
        Some((t(i)?, rendered_at(rendered, i)?))
    };
    let mut out = Vec::new();
    for i in 0..n {
        let (x, y) = (i % width, i / width);
        let Some(v) = t(i) else { continue };
        let crosses = |j: Option<usize>| j.and_then(t).is_some_and(|w| (v < 0.5) != (w < 0.5));
        let right = (x + 1 < width).then_some(i + 1);
        let down = (y + 1 < height).then_some(i + width);
        if !(crosses(right) || crosses(down)) {
            continue;
        }
        // Sobel on the truth; every neighbour must be a receiver.
        let mut g = [0.0f32; 2];
        let mut whole = true;
        for dy in -1i64..=1 {
            for dx in -1i64..=1 {
                let Some((w, _)) = both(x as i64 + dx, y as i64 + dy) else {
                    whole = false;
                    continue;
                };
                let k = if dx == 0 || dy == 0 { 2.0 } else { 1.0 };
                g[0] += w * dx as f32 * k;
                g[1] += w * dy as f32 * k;
            }
        }
        let len = (g[0] * g[0] + g[1] * g[1]).sqrt();
        if !whole || len.is_nan() || len <= 0.0 {
            continue;
        }
        let dir = [g[0] / len, g[1] / len];
        // Per side, each image is counted until it passes the ramp's end there (so the
        // truth's width does not hang on the image's, nor on features farther on).
        let inside = |v: f32| v > 0.1 && v < 0.9;
        let (mut truth_px, mut rendered_px) = (0.0, 0.0);
        let (mut low, mut high) = (false, false);
        for side in [-1.0f32, 1.0] {
            let past = |v: f32| if side < 0.0 { v <= 0.1 } else { v >= 0.9 };
            let (mut truth_done, mut rendered_done) = (false, false);
            for s in 0..=PENUMBRA_REACH {
                if side > 0.0 && s == 0 {
                    continue;
                }
                let px = (x as f32 + side * s as f32 * dir[0]).round() as i64;
                let py = (y as f32 + side * s as f32 * dir[1]).round() as i64;
                let Some((t, r)) = both(px, py) else { break };
                truth_done |= past(t);
                rendered_done |= past(r);
                truth_px += (!truth_done && inside(t)) as u32 as f64;
                rendered_px += (!rendered_done && inside(r)) as u32 as f64;
                if truth_done && rendered_done {
                    break;
                }
            }
            match side < 0.0 {
                true => low = truth_done,
                false => high = truth_done,
            }
        }
        if !(low && high) {
            continue;
        }
        out.push(PenumbraProfile {
            x,
            y,
            truth_px,
            rendered_px,
        });
    }
    out
}

/// Scores `rendered` against the soft-shadow `truth` made with `rays` rays per pixel.
pub fn compute_soft_metrics(
    width: usize,
    height: usize,
    rendered: &[Option<f32>],
    truth: &[RefPixel],
    rays: usize,
) -> SoftMetrics {
    let n = width.saturating_mul(height);
    let (mut receivers, mut bleed, mut false_shadow, mut abs_sum) = (0usize, 0usize, 0usize, 0.0);
    for i in 0..n {
        let (Some(v), Some(r)) = (rendered_at(rendered, i), truth.get(i)) else {
            continue;
        };
        if !r.receiver {
            continue;
        }
        receivers += 1;
        abs_sum += (f64::from(v) - f64::from(r.visibility)).abs();
        bleed += (r.visibility == 0.0 && v > 0.5) as usize;
        false_shadow += (r.visibility == 1.0 && v < 0.5) as usize;
    }
    let profiles = penumbra_profiles(width, height, rendered, truth);
    let mean = |f: &dyn Fn(&PenumbraProfile) -> f64| match profiles.len() {
        0 => 0.0,
        k => profiles.iter().map(f).sum::<f64>() / k as f64,
    };
    SoftMetrics {
        rays,
        receivers,
        mae: if receivers == 0 {
            0.0
        } else {
            abs_sum / receivers as f64
        },
        light_bleed: bleed,
        light_bleed_rate: rate(bleed, receivers),
        false_shadow,
        false_shadow_rate: rate(false_shadow, receivers),
        penumbra_edges: profiles.len(),
        penumbra_width_truth_px: mean(&|p| p.truth_px),
        penumbra_width_px: mean(&|p| p.rendered_px),
        penumbra_width_error_px: mean(&|p| (p.rendered_px - p.truth_px).abs()),
    }
}

/// RGBA picture of the errors: false shadow red, false light blue, every
/// other pixel the matching `base_grey` value (0 where it is missing).
pub fn error_image(
    width: usize,
    height: usize,
    rendered: &[Option<f32>],
    reference: &[RefPixel],
    base_grey: &[u8],
) -> Vec<[u8; 4]> {
    (0..width.saturating_mul(height))
        .map(|i| match classify(rendered, reference, i) {
            Class::FalseShadow => [255, 0, 0, 255],
            Class::FalseLight => [0, 0, 255, 255],
            Class::NotScored | Class::Correct => {
                let g = base_grey.get(i).copied().unwrap_or(0);
                [g, g, g, 255]
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const W: usize = 4;

    fn px(receiver: bool, visibility: f32) -> RefPixel {
        RefPixel {
            covered: true,
            receiver,
            visibility,
        }
    }

    /// 4x4: left two columns shadowed, right two lit; (3, 3) faces away.
    fn reference() -> Vec<RefPixel> {
        (0..16)
            .map(|i| {
                let (x, y) = (i % W, i / W);
                if (x, y) == (3, 3) {
                    px(false, 0.0)
                } else {
                    px(true, if x < 2 { 0.0 } else { 1.0 })
                }
            })
            .collect()
    }

    /// Rendered = reference, except: (0,0) missing; false shadows at (2,1)
    /// and (3,0); false light at (0,2); within-threshold deviations at (1,1)
    /// (exactly 0.5 off) and (2,2); a value on the non-receiver (3,3).
    fn rendered() -> Vec<Option<f32>> {
        let mut r: Vec<Option<f32>> = reference().iter().map(|p| Some(p.visibility)).collect();
        let mut set = |x: usize, y: usize, v: Option<f32>| r[y * W + x] = v;
        set(0, 0, None);
        set(2, 1, Some(0.0));
        set(3, 0, Some(0.2));
        set(0, 2, Some(0.9));
        set(1, 1, Some(0.5));
        set(2, 2, Some(0.6));
        set(3, 3, Some(1.0));
        r
    }

    #[test]
    fn counts_without_band() {
        let m = compute_metrics(4, 4, &rendered(), &reference(), None, 0);
        assert_eq!(m.receivers, 14);
        assert_eq!((m.misclassified, m.false_shadow, m.false_light), (3, 2, 1));
        assert_eq!(m.misclassified_rate, 3.0 / 14.0);
        assert_eq!(m.false_shadow_rate, 2.0 / 14.0);
        assert_eq!(m.false_light_rate, 1.0 / 14.0);
        assert_eq!((m.band_pixels, m.outside_band_receivers), (0, 14));
        assert_eq!(m.misclassified_outside_band, 3);
        assert_eq!(m.misclassified_outside_band_rate, 3.0 / 14.0);
        assert_eq!(m.mae, None);
    }

    #[test]
    fn band_one_excludes_the_edge_columns() {
        let m = compute_metrics(4, 4, &rendered(), &reference(), None, 1);
        // Columns 1 and 2, all rows; (3, 2) is not in the band although
        // its neighbour (3, 3) is "0.0": that pixel is not a receiver.
        assert_eq!(m.band_pixels, 8);
        assert_eq!(m.outside_band_receivers, 6);
        // (2,1) is in the band; (3,0) and (0,2) are not.
        assert_eq!(m.misclassified_outside_band, 2);
        assert_eq!(m.false_shadow_outside_band, 1);
        assert_eq!(m.false_light_outside_band, 1);
        assert_eq!(m.misclassified_outside_band_rate, 2.0 / 6.0);
        // Band-independent totals are unchanged.
        assert_eq!((m.receivers, m.misclassified), (14, 3));
    }

    #[test]
    fn band_two_covers_everything() {
        let m = compute_metrics(4, 4, &rendered(), &reference(), None, 2);
        assert_eq!((m.band_pixels, m.outside_band_receivers), (14, 0));
        assert_eq!(m.misclassified_outside_band, 0);
        assert_eq!(m.misclassified_outside_band_rate, 0.0);
    }

    #[test]
    fn mae_against_supersampled() {
        let mut ss = reference();
        ss[W + 1].visibility = 0.5; // (1,1) now agrees with the render.
        ss[W + 2].receiver = false; // (2,1) drops out of the MAE.
        let m = compute_metrics(4, 4, &rendered(), &reference(), Some(&ss), 0);
        // |diffs|: (3,0) 0.8, (0,2) 0.9, (2,2) 0.4; others 0; 13 pixels.
        let expect = (0.8 + 0.9 + 0.4) / 13.0;
        let mae = m.mae.unwrap_or(f64::NAN);
        assert!((mae - expect).abs() < 1e-6, "{mae} vs {expect}");
    }

    #[test]
    fn empty_and_nan_inputs() {
        let m = compute_metrics(0, 0, &[], &[], Some(&[]), 3);
        assert_eq!(m.receivers, 0);
        assert_eq!(m.misclassified_rate, 0.0);
        assert_eq!(m.mae, Some(0.0));
        // NaN renders are not scored, short slices read as uncovered.
        let reference = vec![px(true, 1.0); 4];
        let m = compute_metrics(2, 2, &[Some(f32::NAN), Some(0.0)], &reference, None, 0);
        assert_eq!((m.receivers, m.false_shadow), (1, 1));
    }

    #[test]
    fn json_keys_keep_declaration_order() {
        let m = compute_metrics(4, 4, &rendered(), &reference(), None, 1);
        let j = serde_json::to_string(&m).unwrap();
        assert!(
            j.starts_with("{\"receivers\":14,\"misclassified\":3,"),
            "{j}"
        );
        assert!(j.ends_with(",\"mae\":null}"), "{j}");
        assert!(
            j.contains("\"misclassified_outside_band_rate\":0.3333333333333333"),
            "{j}"
        );
    }

    /// A 40 x 9 truth ramping from shadow (x < 10) to light (x >= 20) over ten pixels.
    fn ramp(x0: usize, x1: usize) -> Vec<f32> {
        (0..40 * 9)
            .map(|i| {
                let x = i % 40;
                ((x as f32 - x0 as f32 + 0.5) / (x1 - x0) as f32).clamp(0.0, 1.0)
            })
            .collect()
    }

    #[test]
    fn soft_metrics_measure_widths_bleed_and_false_shadow() {
        let truth: Vec<RefPixel> = ramp(10, 20).into_iter().map(|v| px(true, v)).collect();
        // The same ramp: no error; the truth's width is its 10%-90% part, 8 pixels.
        let same: Vec<Option<f32>> = truth.iter().map(|p| Some(p.visibility)).collect();
        let m = compute_soft_metrics(40, 9, &same, &truth, 64);
        assert_eq!(
            (m.receivers, m.mae, m.light_bleed, m.false_shadow),
            (360, 0.0, 0, 0)
        );
        assert!(m.penumbra_edges >= 7, "{m:?}");
        assert_eq!(m.penumbra_width_truth_px, 8.0);
        assert_eq!(m.penumbra_width_error_px, 0.0);
        // A hard edge in the middle of the ramp: no width, so the error is the truth's;
        // neither bleeding nor false shadow (the truth is partly lit on both sides of it).
        let hard: Vec<Option<f32>> = (0..360)
            .map(|i| Some(if i % 40 < 15 { 0.0 } else { 1.0 }))
            .collect();
        let m = compute_soft_metrics(40, 9, &hard, &truth, 64);
        assert_eq!(m.penumbra_width_px, 0.0);
        assert_eq!(m.penumbra_width_error_px, 8.0);
        assert_eq!((m.light_bleed, m.false_shadow), (0, 0));
        // Twice as wide, about the same middle: wider by 8 pixels.
        let wide: Vec<Option<f32>> = ramp(5, 25).into_iter().map(Some).collect();
        let m = compute_soft_metrics(40, 9, &wide, &truth, 64);
        assert_eq!(m.penumbra_width_px, 16.0);
        assert_eq!(m.penumbra_width_error_px, 8.0);
        // Lit from x = 5: bleeds over the truth's umbra x 5..10; shadowed up to x = 30:
        // false shadow over its full light x 20..30.
        let early: Vec<Option<f32>> = (0..360)
            .map(|i| Some(if i % 40 < 5 { 0.0 } else { 1.0 }))
            .collect();
        let m = compute_soft_metrics(40, 9, &early, &truth, 64);
        assert_eq!(m.light_bleed, 5 * 9);
        assert_eq!(m.light_bleed_rate, 45.0 / 360.0);
        let late: Vec<Option<f32>> = (0..360)
            .map(|i| Some(if i % 40 < 30 { 0.0 } else { 1.0 }))
            .collect();
        assert_eq!(
            compute_soft_metrics(40, 9, &late, &truth, 64).false_shadow,
            10 * 9
        );
    }

    #[test]
    fn error_image_colours() {
        let grey: Vec<u8> = (0..16).map(|i| i as u8 * 10).collect();
        let img = error_image(4, 4, &rendered(), &reference(), &grey);
        assert_eq!(img.len(), 16);
        assert_eq!(img[W + 2], [255, 0, 0, 255]); // (2,1)
        assert_eq!(img[3], [255, 0, 0, 255]); // (3,0)
        assert_eq!(img[2 * W], [0, 0, 255, 255]); // (0,2)
        assert_eq!(img[0], [0, 0, 0, 255]);
        assert_eq!(img[5], [50, 50, 50, 255]);
        assert_eq!(img[15], [150, 150, 150, 255]);
        let coloured = img.iter().filter(|p| p[0] != p[2]).count();
        assert_eq!(coloured, 3);
    }
}
