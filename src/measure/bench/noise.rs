//! How far a configuration's shadow overhead can be trusted: the overhead is a difference
//! of two frame times, so on a loaded machine it can come out near zero or below it. A
//! figure within its own spread of zero is noise, flagged in the table and the plot and
//! kept out of the `--quality` presets' rule.

/// The per-frame overheads of a block: each shadowed frame minus the frame without
/// shadows drawn just before it.
pub(super) fn per_frame(wall: &[f64], plain: &[f64]) -> Vec<f64> {
    wall.iter().zip(plain).map(|(w, p)| w - p).collect()
}

/// The `q` quantile of `values` (nearest rank, as [`super::Stat`] takes its median).
fn quantile(values: &[f64], q: f64) -> f64 {
    let mut t = values.to_vec();
    if t.is_empty() {
        return f64::NAN;
    }
    t.sort_by(f64::total_cmp);
    t[((t.len() - 1) as f64 * q).round() as usize]
}

/// The spread of a block's overhead median, in milliseconds: the larger of the two blocks'
/// medians' difference (the same configuration timed twice) and twice the standard error
/// of the kept block's median (1.253 sigma / sqrt(n), sigma from the interquartile range
/// over 1.349, which a burst of load in a few frames does not inflate).
pub fn overhead_spread(kept: &[f64], other: &[f64]) -> f64 {
    let between = (quantile(kept, 0.5) - quantile(other, 0.5)).abs();
    let iqr = quantile(kept, 0.75) - quantile(kept, 0.25);
    let within = 2.0 * 1.253 * (iqr / 1.349) / (kept.len().max(1) as f64).sqrt();
    match (between.is_nan(), within.is_nan()) {
        (false, false) => between.max(within),
        (true, false) => within,
        (false, true) => between,
        (true, true) => f64::NAN,
    }
}

/// Whether an overhead is noise: not above its spread (negative, near zero, or unknown).
pub fn is_noise(overhead_ms: f64, spread_ms: f64) -> bool {
    // NaN compares false: an overhead or spread that could not be measured is noise too.
    overhead_ms.partial_cmp(&spread_ms) != Some(std::cmp::Ordering::Greater)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_negative_or_near_zero_overhead_is_noise_and_a_clear_one_is_not() {
        assert!(is_noise(-1.33, 0.2));
        assert!(is_noise(0.1, 0.3));
        assert!(is_noise(f64::NAN, 0.1));
        assert!(is_noise(1.0, f64::NAN));
        assert!(!is_noise(1.72, 0.3));
    }

    #[test]
    fn the_spread_is_the_blocks_difference_or_the_medians_error() {
        // Two blocks 0.5 ms apart, each steady: the difference dominates.
        let a = vec![2.0; 20];
        let b = vec![2.5; 20];
        assert!((overhead_spread(&a, &b) - 0.5).abs() < 1e-12);
        // Equal medians, a wide block: 2 x 1.253 x (IQR / 1.349) / sqrt(n).
        let wide: Vec<f64> = (0..21).map(|i| f64::from(i) * 0.1).collect();
        let iqr = quantile(&wide, 0.75) - quantile(&wide, 0.25);
        let want = 2.0 * 1.253 * iqr / 1.349 / 21f64.sqrt();
        assert!((overhead_spread(&wide, &wide) - want).abs() < 1e-12);
        assert!(overhead_spread(&wide, &wide) > 0.0);
        assert_eq!(per_frame(&[3.0, 4.0], &[1.0, 5.0]), vec![2.0, -1.0]);
    }
}
