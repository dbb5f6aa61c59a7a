//! `bench --scale` end to end, the `--quality` presets and
//! `--target-error` on `render`. No timing is asserted: only that each is measured, written
//! and acted on.

use crate::common;

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("shadowmap-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    d
}

fn render(args: &[&str], out: &std::path::Path) -> String {
    common::stdout_of(
        common::bin()
            .args(["render", "--size", "160x90", "--out"])
            .arg(out)
            .args(args),
    )
}

/// The settings summary `render` prints: "wrote FILE (WxH, scene S, LIGHT, SETTINGS) in N ms".
fn summary(stdout: &str) -> &str {
    stdout
        .lines()
        .find(|l| l.starts_with("wrote "))
        .unwrap_or_else(|| panic!("no summary in {stdout}"))
}

#[test]
fn quick_scale_writes_every_column_a_plot_and_finite_exponents() {
    let dir = tmp("scale");
    let stdout = common::stdout_of(
        common::bin()
            .args(["bench", "--scale", "--quick", "--out-dir"])
            .arg(&dir),
    );
    let csv = std::fs::read_to_string(dir.join("scale.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    for column in [
        "axis",
        "work",
        "triangles",
        "pixels",
        "map_size",
        "lights",
        "cascades",
        "frames",
        "depth_wall_ms_median",
        "scene_wall_ms_median",
    ] {
        assert!(header.contains(&column), "no {column} in {header:?}");
    }
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    // Two points on each of the five axes, every time measured and positive.
    assert_eq!(rows.len(), 10, "{csv}");
    for axis in ["triangles", "pixels", "map-texels", "lights", "cascades"] {
        let on: Vec<&Vec<&str>> = rows.iter().filter(|r| r[col("axis")] == axis).collect();
        assert_eq!(on.len(), 2, "{axis}: {csv}");
        let work: Vec<f64> = on.iter().map(|r| r[col("work")].parse().unwrap()).collect();
        assert!(work[1] > work[0], "{axis}: {work:?}");
    }
    for row in &rows {
        assert_eq!(row.len(), header.len());
        for name in [
            "depth_wall_ms_median",
            "scene_wall_ms_median",
            "frame_wall_ms_median",
        ] {
            let v: f64 = row[col(name)].parse().unwrap();
            assert!(v.is_finite() && v > 0.0, "{name} = {v} in {row:?}");
        }
    }
    // The triangle axis counts what the generated scene holds: about 1e3 and 1e4.
    let triangles: Vec<f64> = rows
        .iter()
        .filter(|r| r[col("axis")] == "triangles")
        .map(|r| r[col("triangles")].parse().unwrap())
        .collect();
    assert!((900.0..1200.0).contains(&triangles[0]), "{triangles:?}");
    assert!((9000.0..11000.0).contains(&triangles[1]), "{triangles:?}");
    // An exponent for every axis and pass, each a finite number.
    let fits = std::fs::read_to_string(dir.join("scale-fit.csv")).unwrap();
    let fit_rows: Vec<Vec<&str>> = fits
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(fit_rows.len(), 15, "{fits}");
    for r in &fit_rows {
        assert_eq!(r[2], "all", "{r:?}");
        let e: f64 = r[3].parse().unwrap();
        assert!(e.is_finite(), "{r:?}");
    }
    assert!(stdout.contains("| caster triangles |"), "{stdout}");
    let png = std::fs::read(dir.join("scale.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let image = image::load_from_memory(&png).unwrap().to_rgb8();
    // Not a blank page: the points and lines are drawn in colour.
    let coloured = image
        .pixels()
        .filter(|p| p.0.iter().max().unwrap() - p.0.iter().min().unwrap() > 80)
        .count();
    assert!(coloured > 500, "{coloured} coloured pixels");
    std::fs::remove_dir_all(&dir).ok();
}

/// A preset from the data file as flags: `--map-size 512 --filter single ...`.
fn preset_flags(level: &str) -> Vec<String> {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/quality.toml"),
    )
    .unwrap();
    let all: toml::Table = toml::from_str(&text).unwrap();
    let mut flags = Vec::new();
    for (key, value) in all[level].as_table().unwrap() {
        flags.push(format!("--{}", key.replace('_', "-")));
        flags.push(match value {
            toml::Value::String(s) => s.clone(),
            toml::Value::Array(a) => a
                .iter()
                .map(|v| v.to_string())
                .collect::<Vec<_>>()
                .join(","),
            v => v.to_string(),
        });
    }
    flags
}

#[test]
fn quality_presets_apply_and_flags_win() {
    let dir = tmp("quality");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("q.png");
    let mut images = Vec::new();
    for level in ["low", "medium", "high"] {
        let stdout = render(&["--quality", level], &out);
        let by_preset = std::fs::read(&out).unwrap();
        let flags = preset_flags(level);
        let map = &flags[flags.iter().position(|f| f == "--map-size").unwrap() + 1];
        let filter = &flags[flags.iter().position(|f| f == "--filter").unwrap() + 1];
        // The preset says what it set, and the frame's settings are those.
        assert!(
            stdout.contains(&format!("quality {level}: "))
                && stdout.contains(&format!("map_size {map}")),
            "{stdout}"
        );
        assert!(
            summary(&stdout).contains(&format!("{map}^2 24 {filter}")),
            "{stdout}"
        );
        // The same settings given as flags draw the same image.
        let args: Vec<&str> = flags.iter().map(String::as_str).collect();
        render(&args, &out);
        assert_eq!(
            std::fs::read(&out).unwrap(),
            by_preset,
            "{level}: {flags:?}"
        );
        images.push(by_preset);
    }
    // Each preset changes the frame: none draws the scene's own settings' image.
    render(&[], &out);
    let own = std::fs::read(&out).unwrap();
    for (level, image) in ["low", "medium", "high"].iter().zip(&images) {
        assert!(
            *image != own,
            "--quality {level} draws the scene's own image"
        );
    }
    // An explicit flag wins over the preset, and the preset's line says so.
    let mixed = render(&["--quality", "high", "--map-size", "256"], &out);
    assert!(summary(&mixed).contains("256^2 24 "), "{mixed}");
    assert!(mixed.contains("(flags win: --map-size)"), "{mixed}");
    assert!(!mixed.contains("map_size"), "{mixed}");
    std::fs::remove_dir_all(&dir).ok();
}

/// "(X ms a frame, Y% misclassified)" of the chosen configuration, as a fraction.
fn chosen_error(stdout: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.starts_with("cheapest configuration with error <="))
        .unwrap_or_else(|| panic!("no choice in {stdout}"));
    let pct = line
        .rsplit_once("ms a frame, ")
        .and_then(|(_, rest)| rest.split_once("% misclassified"))
        .map(|(v, _)| v.parse::<f64>().unwrap())
        .unwrap_or_else(|| panic!("no error in {line}"));
    pct / 100.0
}

#[test]
fn target_error_picks_a_configuration_that_meets_it() {
    let dir = tmp("target");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("t.png");
    let target = 0.02;
    let stdout = render(&["--target-error", "0.02"], &out);
    let error = chosen_error(&stdout);
    assert!(error <= target, "{error} > {target}: {stdout}");
    // The frame is drawn with the chosen configuration: its flags give the same image.
    let flags = stdout
        .lines()
        .find_map(|l| l.trim().strip_prefix("as flags: "))
        .unwrap_or_else(|| panic!("no flags in {stdout}"));
    let chosen = std::fs::read(&out).unwrap();
    let args: Vec<&str> = flags.split_whitespace().collect();
    render(&args, &out);
    assert_eq!(std::fs::read(&out).unwrap(), chosen, "{flags}");
    // And compare, scoring the same frame on its own, finds it as accurate.
    let cmp = dir.join("cmp");
    common::stdout_of(
        common::bin()
            .args([
                "compare",
                "--size",
                "160x90",
                "--supersample",
                "1",
                "--out-dir",
            ])
            .arg(&cmp)
            .args(&args),
    );
    let metrics = std::fs::read_to_string(cmp.join("metrics.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&metrics).unwrap();
    let rate = json["metrics"]["misclassified_rate"].as_f64().unwrap();
    assert!((rate - error).abs() < 1e-4, "{rate} against {error}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `shadowmap render --scene SCENE --size 160x90 --target-error E [extra] --out OUT`, run to
/// its end whatever it says.
fn target_error_run(
    scene: &str,
    target: &str,
    extra: &[&str],
    out: &std::path::Path,
) -> std::process::Output {
    common::bin()
        .args([
            "render",
            "--scene",
            scene,
            "--size",
            "160x90",
            "--target-error",
            target,
        ])
        .args(extra)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

#[test]
fn target_error_out_of_reach_is_refused_with_the_best_reached() {
    let dir = tmp("target-none");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("none.png");
    // The large scene's best quick configuration (its shadow volumes) misclassifies
    // about 0.013% at 160 x 90; no configuration reaches 0.001%.
    let run = target_error_run("large", "0.00001", &[], &out);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success());
    assert!(
        stderr.contains(
            "error: --target-error 0.00001: no configuration reached an error of 0.001% or less \
             (best: "
        ) && stderr.contains("% misclassified)"),
        "{stderr}"
    );
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn target_error_keeps_to_the_settings_given_as_flags() {
    let dir = tmp("target-flags");
    std::fs::create_dir_all(&dir).unwrap();
    // With --technique maps the volumes (exact, so the answer for a tight error) are not
    // searched: the choice is a map, drawn with the flag still holding.
    let out = dir.join("maps.png");
    let run = target_error_run("learnopengl", "0.01", &["--technique", "maps"], &out);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{stdout}");
    // Every configuration of the quick sweep but the volumes row was timed.
    let scene = shadowmap::Scene::load("learnopengl").unwrap();
    let all = shadowmap::bench::sweep(&scene.shadow, true, 16384, scene.light());
    let volumes = all
        .iter()
        .filter(|c| c.family == shadowmap::bench::Family::Volumes)
        .count();
    assert_eq!(volumes, 1);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains(&format!(
            "timing and scoring {} configurations",
            all.len() - volumes
        )),
        "{stderr}"
    );
    let flags = stdout
        .lines()
        .find(|l| l.trim_start().starts_with("as flags:"))
        .unwrap_or_else(|| panic!("no flags in {stdout}"));
    assert!(flags.contains("--technique maps"), "{flags}");
    assert!(out.exists());
    // Flags no configuration of the sweep has: said, and nothing written.
    let out = dir.join("none.png");
    let run = target_error_run("learnopengl", "0.01", &["--map-size", "300"], &out);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success());
    assert!(
        stderr.contains(
            "error: --target-error 0.01: no configuration of the quick sweep has the settings \
             given as flags (map_size): give fewer of them, or leave out --target-error"
        ),
        "{stderr}"
    );
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).ok();
}
