//! The bench's findings as text: the Markdown table, the comparison with each tutorial's
//! configuration, and the `--quality` presets' choices.

use super::{BenchRow, Family};

/// A Markdown table: the tutorials' configurations, then the Pareto front of shadow
/// overhead and error, least overhead first (the quantity the comparison text ranks by),
/// then (for a light with a size) every soft filter's configuration, with the figures
/// against the area truth in three more columns.
pub fn to_markdown(rows: &[BenchRow]) -> String {
    let area = rows.iter().any(|r| r.soft.rays > 0);
    let mut header = vec![
        "configuration",
        "wall ms (median / p95)",
        "shadow overhead ms",
        "depth pass ms",
        "scene pass ms",
        "misclassified",
        "false shadow",
        "false light",
        "outside band",
        "MAE",
        "cost: taps / passes / map MiB",
    ];
    if area {
        header.extend([
            "MAE vs area light",
            "light bleeding",
            "penumbra width error px",
        ]);
    }
    let moving = rows.iter().any(|r| r.flicker_energy.is_some());
    if moving {
        header.extend(["flicker energy", "false flicker a frame"]);
    }
    // The delimiter row has as many cells as the header, or no viewer draws a table.
    let mut out = format!(
        "| {} |\n|{}\n",
        header.join(" | "),
        "---|".repeat(header.len())
    );
    let mut shown: Vec<&BenchRow> = rows
        .iter()
        .filter(|r| r.config.tutorial.is_some())
        .collect();
    let mut front: Vec<&BenchRow> = rows
        .iter()
        .filter(|r| r.pareto && r.config.tutorial.is_none())
        .collect();
    front.sort_by(|a, b| a.overhead_ms.total_cmp(&b.overhead_ms));
    shown.extend(front);
    let mut soft: Vec<&BenchRow> = rows
        .iter()
        .filter(|r| r.config.family == Family::Soft && !r.pareto)
        .collect();
    soft.sort_by(|a, b| a.wall_ms.median.total_cmp(&b.wall_ms.median));
    shown.extend(soft);
    for r in shown {
        let name = match (r.config.tutorial, r.pareto) {
            (Some(t), _) => format!("**{t}** ({})", r.label()),
            (None, true) => format!("{} (Pareto)", r.label()),
            (None, false) => format!("{} (soft)", r.label()),
        };
        let m = &r.metrics;
        let pct = |x: f64| format!("{:.3}%", x * 100.0);
        out.push_str(&format!(
            "| {name} | {:.2} / {:.2} | {} | {:.2} | {:.2} | {} | {} | {} | {} | {} | {} |",
            r.wall_ms.median,
            r.wall_ms.p95,
            r.overhead_text(),
            r.depth_wall_ms.median,
            r.scene_wall_ms.median,
            pct(m.misclassified_rate),
            pct(m.false_shadow_rate),
            pct(m.false_light_rate),
            pct(m.misclassified_outside_band_rate),
            m.mae.map_or("n/a".into(), |v| format!("{v:.4}")),
            r.cost_label(),
        ));
        if area {
            let a = &r.soft;
            out.push_str(&format!(
                " {:.4} | {} | {:.2} |",
                a.mae,
                pct(a.light_bleed_rate),
                a.penumbra_width_error_px
            ));
        }
        if moving {
            let e = r.flicker_energy.map_or("n/a".into(), |e| format!("{e:.4}"));
            let f = r.false_flicker.map_or("n/a".into(), pct);
            out.push_str(&format!(" {e} | {f} |"));
        }
        out.push('\n');
    }
    if rows.iter().any(BenchRow::overhead_is_noise) {
        out.push_str(NOISE_NOTE);
    }
    out
}

/// Under a table with a row whose overhead is noise.
pub const NOISE_NOTE: &str = "\n(noise, ±S): the shadow overhead is not above its spread S \
     (the two blocks' medians' difference, or twice the median's standard error): the \
     shadows' cost was lost in the machine's load; the --quality rule leaves the row out.\n";

/// How a configuration compares with a tutorial's on two terms, from one run:
/// the overhead at equal error and the error at equal overhead.
#[derive(Debug, Clone)]
pub struct AgainstTutorial<'a> {
    pub tutorial: &'a BenchRow,
    /// The least shadow overhead with an error no worse than the tutorial's.
    pub at_equal_error: Option<&'a BenchRow>,
    /// The lowest error with an overhead no larger than the tutorial's.
    pub at_equal_overhead: Option<&'a BenchRow>,
}

/// For each tutorial configuration in `rows`: the cheapest other configuration (by
/// overhead) at least as accurate, and the most accurate one at most as expensive.
pub fn against_tutorials(rows: &[BenchRow]) -> Vec<AgainstTutorial<'_>> {
    let others = || rows.iter().filter(|r| r.config.tutorial.is_none());
    rows.iter()
        .filter(|r| r.config.tutorial.is_some())
        .map(|t| AgainstTutorial {
            tutorial: t,
            at_equal_error: others().filter(|r| r.error() <= t.error()).min_by(|a, b| {
                a.overhead_ms
                    .total_cmp(&b.overhead_ms)
                    .then(a.error().total_cmp(&b.error()))
            }),
            at_equal_overhead: others().filter(|r| r.overhead_ms <= t.overhead_ms).min_by(
                |a, b| {
                    a.error()
                        .total_cmp(&b.error())
                        .then(a.overhead_ms.total_cmp(&b.overhead_ms))
                },
            ),
        })
        .collect()
}

/// The comparison as lines of text: overhead ratio at equal error and error ratio at
/// equal overhead.
pub fn against_tutorials_text(rows: &[BenchRow]) -> String {
    let mut out = String::new();
    for a in against_tutorials(rows) {
        let t = a.tutorial;
        let name = t.config.tutorial.unwrap_or_default();
        out.push_str(&format!(
            "against {name} ({}: overhead {:.2} ms, {}):\n",
            t.label(),
            t.overhead_ms,
            t.error_text()
        ));
        match a.at_equal_error {
            Some(r) => out.push_str(&format!(
                "  at equal error or better: {} with overhead {:.2} ms ({}): \
                 {:.2} of the tutorial's overhead\n",
                r.label(),
                r.overhead_ms,
                r.error_text(),
                r.overhead_ms / t.overhead_ms
            )),
            None => out.push_str("  at equal error or better: no other configuration\n"),
        }
        match a.at_equal_overhead {
            Some(r) => out.push_str(&format!(
                "  at equal overhead or less: {}, {} (overhead {:.2} ms): {}\n",
                r.label(),
                r.error_text(),
                r.overhead_ms,
                r.fewer_errors_than(t)
            )),
            None => out.push_str("  at equal overhead or less: no other configuration\n"),
        }
    }
    out
}

/// The `--quality` presets' rule, on the shadow overhead against LearnOpenGL's final
/// configuration's: `low` the configuration with the least overhead; `medium` the most
/// accurate with at most half the tutorial's overhead; `high` the most
/// accurate with no more than the tutorial's. A preset serves every kind of light, so only
/// one-map rows count, and only those whose overhead is above its noise. Absent where the
/// sweep has no such row (or no tutorial row, or the tutorial's overhead is noise).
pub fn preset_choices(rows: &[BenchRow]) -> [(&'static str, Option<&BenchRow>); 3] {
    // A preset must not rest on a figure lost in noise: such rows are left out, and so is
    // a budget taken from a tutorial overhead that is noise.
    let one_map = || {
        rows.iter().filter(|r| {
            r.config.tutorial.is_none()
                && r.config.family == Family::OneMap
                && !r.overhead_is_noise()
        })
    };
    let tutorial = rows
        .iter()
        .find(|r| r.config.tutorial == Some("learnopengl"))
        .filter(|t| !t.overhead_is_noise());
    let most_accurate_within = |budget: f64| {
        one_map()
            .filter(|r| r.overhead_ms <= budget)
            .min_by(|a, b| {
                a.error()
                    .total_cmp(&b.error())
                    .then(a.overhead_ms.total_cmp(&b.overhead_ms))
            })
    };
    let low = one_map().min_by(|a, b| a.overhead_ms.total_cmp(&b.overhead_ms));
    let medium = tutorial.and_then(|t| most_accurate_within(0.5 * t.overhead_ms));
    let high = tutorial.and_then(|t| most_accurate_within(t.overhead_ms));
    [("low", low), ("medium", medium), ("high", high)]
}
