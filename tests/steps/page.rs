//! The page `steps` writes: each step's frame and figures, consistent with each other.

use super::*;

/// The text of each `<td>` of an HTML table row, tags inside it removed.
fn cells(row: &str) -> Vec<String> {
    row.split("<td")
        .skip(1)
        .map(|c| {
            let inner = c.split_once('>').map_or("", |(_, rest)| rest);
            let inner = inner.split("</td>").next().unwrap_or("");
            // Drop nested tags (links, <small> notes).
            let mut text = String::new();
            let mut in_tag = false;
            for ch in inner.chars() {
                match ch {
                    '<' => in_tag = true,
                    '>' => in_tag = false,
                    c if !in_tag => text.push(c),
                    _ => {}
                }
            }
            text.trim().to_string()
        })
        .collect()
}

/// A cell's percentage.
fn pct(cell: &str) -> f64 {
    cell.trim_end_matches('%')
        .parse()
        .unwrap_or_else(|_| panic!("not a percentage: {cell}"))
}

/// The page `steps` writes: every step's frame beside its errors, each figure a share of the
/// same receivers (so the parts add up), and each step told against what it builds on.
#[test]
fn the_steps_page_shows_each_step_with_consistent_figures() {
    let dir = std::env::temp_dir().join(format!("shadowmap-gallery-{}", std::process::id()));
    let args = [
        "steps",
        "--scene",
        "dummy",
        "--size",
        "320x180",
        "--supersample",
        "1",
    ];
    common::stdout_of(common::bin().args(args).arg("--out-dir").arg(&dir));
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let scene = Scene::load("dummy").unwrap();
    let sections: Vec<&str> = html.split("<section").skip(1).collect();
    assert_eq!(sections.len(), steps::of(&scene).len());
    for (i, (st, section)) in steps::of(&scene).iter().zip(&sections).enumerate() {
        let frame = format!("{:02}-{}.png", i + 1, st.name);
        let errors = format!("{:02}-{}-error.png", i + 1, st.name);
        assert!(
            section.contains(&format!("id=\"{}\"", st.name)),
            "{}",
            st.name
        );
        assert!(section.contains(&format!("src=\"{frame}\"")), "{}", st.name);
        assert!(dir.join(&frame).is_file(), "{frame}");
        let depth_view = steps::settings_for(&scene, st.name).unwrap().show_depth_map;
        assert_eq!(section.contains(&format!("src=\"{errors}\"")), !depth_view);
        assert_eq!(dir.join(&errors).is_file(), !depth_view, "{errors}");
        let lesson = st.change.replace('&', "&amp;").replace('>', "&gt;");
        assert!(section.contains(&lesson), "{}: its lesson", st.name);
        if depth_view {
            continue;
        }
        // The step's own table: at edges + away from edges = misclassified = the two kinds.
        let value = |label: &str| {
            let row = section
                .split("<tr>")
                .find(|r| r.starts_with(&format!("<td class=n>{label} ")))
                .unwrap_or_else(|| panic!("{}: no row {label}", st.name));
            pct(&cells(row)[1])
        };
        let total = value("misclassified");
        let near = 0.0015;
        assert!((value("false shadow") + value("false light") - total).abs() <= near);
        assert!((value("at edges") + value("away from edges") - total).abs() <= near);
        assert!(value("away from edges") <= total, "{}", st.name);
        if st.name == "no-bias" {
            assert!(
                value("away from edges") > 20.0,
                "no-bias: acne away from edges"
            );
        }
    }
    // Variants do not carry over: the fix is told against the step before them.
    let fix = sections[7];
    assert!(fix.contains("(against step 5, cull-front)"), "{fix}");
    // The overview lists every step with the same figures.
    let overview = html.split("<h2>All steps</h2>").nth(1).unwrap();
    let overview = overview.split("</table>").next().unwrap();
    let rows: Vec<Vec<String>> = overview.split("<tr>").skip(2).map(cells).collect();
    assert_eq!(rows.len(), steps::of(&scene).len());
    for row in rows.iter().filter(|r| r.len() > 2) {
        assert!(
            (pct(&row[1]) + pct(&row[2]) - pct(&row[3])).abs() <= 0.0015,
            "{row:?}"
        );
        assert!(pct(&row[4]) <= pct(&row[3]), "{row:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// On a scene with translucent casters the error images are against the transmittance
/// truth: `volumetric-off` is too bright (blue) under the smoke and the glass, AVSM nearly
/// nowhere; the page says so; each step prints its transmittance line.
#[test]
fn the_smoke_steps_draw_their_errors_against_the_transmittance_truth() {
    let dir = std::env::temp_dir().join(format!("shadowmap-smoke-steps-{}", std::process::id()));
    let args = ["steps", "--scene", "smoke", "--size", "320x180"];
    let out = common::stdout_of(common::bin().args(args).arg("--out-dir").arg(&dir));
    assert_eq!(out.matches("   transmittance: MAE ").count(), 5, "{out}");
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert!(html.contains("the error images are against the transmittance truth"));
    // Strongly blue (too bright) and strongly red (too dark) pixels of an error image.
    let count = |name: &str| {
        let image = shadowmap::image_data::ImageData::load_png(&dir.join(name)).unwrap();
        let px = || image.rgba.chunks(4).take((320 * 180) as usize);
        let strong = |a: u8, b: u8| a > 200 && b < 60;
        let blue = px().filter(|p| strong(p[2], p[0])).count();
        let red = px().filter(|p| strong(p[0], p[2])).count();
        (blue, red)
    };
    let (off_blue, _) = count("01-volumetric-off-error.png");
    let (solid_blue, solid_red) = count("02-volumetric-solid-error.png");
    let (avsm_blue, avsm_red) = count("05-volumetric-avsm-error.png");
    assert!(off_blue > 1000, "off: {off_blue} too bright");
    assert!(
        solid_red > 1000 && solid_blue < 100,
        "solid: {solid_red} {solid_blue}"
    );
    assert!(avsm_blue + avsm_red < 100, "avsm: {avsm_blue} {avsm_red}");
    std::fs::remove_dir_all(&dir).ok();
}
