//! The exact reference on rendered G-buffers, and the compare / bench commands end to end.

mod common;

use common::{context, dummy};
use glam::Vec3;
use shadowmap::compare::{compute_reference, CompareOptions};

fn opts(supersample: u32) -> CompareOptions {
    CompareOptions {
        width: 320,
        height: 180,
        supersample,
        band: 1,
        light: 0,
    }
}

#[test]
fn overhead_light_reference_is_exactly_the_footprint() {
    let ctx = context();
    let scene = dummy(90.0);
    let r = compute_reference(ctx.gl(), &scene, &scene.shadow, &opts(1)).unwrap();
    let (mut inside, mut outside) = (0, 0);
    for i in 0..r.gbuffer.positions.len() {
        let p = r.world_position(i).as_vec3();
        if p.y.is_nan() || (p.y + 1.0).abs() >= 1e-4 {
            continue; // not the plane
        }
        let edge = (p.x.abs() - 0.5).abs().min((p.z.abs() - 0.5).abs());
        if edge < 1e-3 {
            continue; // within a thousandth of a unit of the square's boundary
        }
        let under = p.x.abs() < 0.5 && p.z.abs() < 0.5;
        let px = r.hard[i];
        assert!(
            px.receiver,
            "plane pixel {i} at {p} faces the overhead light"
        );
        assert_eq!(px.visibility == 0.0, under, "pixel {i} at {p}");
        if under {
            inside += 1
        } else {
            outside += 1
        }
    }
    assert!(
        inside > 300 && outside > 5000,
        "{inside} inside, {outside} outside"
    );
}

#[test]
fn light_from_below_shadows_nothing_on_top() {
    let ctx = context();
    let mut scene = dummy(90.0);
    scene.light_mut().as_directional_mut().unwrap().direction =
        Vec3::new(0.0, -1.0, 0.3).normalize();
    let r = compute_reference(ctx.gl(), &scene, &scene.shadow, &opts(1)).unwrap();
    let mut tops = 0;
    for (i, n) in r.gbuffer.normals.iter().enumerate() {
        if n[1] > 0.99 {
            tops += 1;
            assert!(
                !r.hard[i].receiver,
                "an upward face receives light from below"
            );
        }
    }
    assert!(tops > 5000, "{tops}");
    // The cube's bottom face does face this light.
    let receivers = r.hard.iter().filter(|p| p.receiver).count();
    assert!(
        receivers > 0,
        "no receiver at all for a light from below and in front"
    );
}

#[test]
fn the_reference_has_no_acne() {
    let ctx = context();
    for angle in [90.0, 45.0, 5.0, 1.0] {
        let mut scene = dummy(angle);
        scene.items.retain(|i| i.name != "cube");
        let r = compute_reference(ctx.gl(), &scene, &scene.shadow, &opts(2)).unwrap();
        let receivers: Vec<_> = r.hard.iter().filter(|p| p.receiver).collect();
        assert!(
            receivers.len() > 10000,
            "angle {angle}: {} receivers",
            receivers.len()
        );
        let dark = receivers.iter().filter(|p| p.visibility < 1.0).count();
        assert_eq!(
            dark, 0,
            "angle {angle}: the reference shadows an unoccluded plane"
        );
        let ss = r.supersampled.as_ref().unwrap();
        let ss_dark = ss
            .iter()
            .filter(|p| p.receiver && p.visibility < 1.0)
            .count();
        assert_eq!(ss_dark, 0, "angle {angle}: supersampled reference");
    }
}

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("shadowmap-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    d
}

#[test]
fn compare_writes_every_output() {
    let dir = tmp("compare");
    let stdout = common::stdout_of(
        common::bin()
            .args([
                "compare",
                "--size",
                "160x90",
                "--supersample",
                "2",
                "--out-dir",
            ])
            .arg(&dir),
    );
    assert!(
        stdout.starts_with("dummy [1024^2 24 pcf3x3, bias 0.05"),
        "{stdout}"
    );
    assert!(
        stdout.contains("misclassified") && stdout.contains("MAE"),
        "{stdout}"
    );
    for f in [
        "visibility.png",
        "reference.png",
        "error.png",
        "metrics.json",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    // float32, 90 x 160 x 3, after a 128-byte header.
    for f in ["positions.npy", "normals.npy"] {
        let bytes = std::fs::read(dir.join(f)).unwrap();
        assert_eq!(bytes.len(), 128 + 90 * 160 * 3 * 4, "{f}");
        assert!(String::from_utf8_lossy(&bytes[..128]).contains("'shape': (90, 160, 3)"));
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("metrics.json")).unwrap()).unwrap();
    let m = &json["metrics"];
    assert!(m["receivers"].as_u64().unwrap() > 1000);
    let rate = m["misclassified_rate"].as_f64().unwrap();
    let (fs, fl) = (
        m["false_shadow_rate"].as_f64().unwrap(),
        m["false_light_rate"].as_f64().unwrap(),
    );
    assert!((rate - (fs + fl)).abs() < 1e-9, "{m}");
    // The book's bias lifts the shadow off the cube's contact: false light dominates.
    assert!(fl > fs, "{m}");
    assert!(m["mae"].as_f64().unwrap() > 0.0);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_sweep_has_rows_for_cascades_and_for_both_point_light_passes() {
    use shadowmap::bench::{sweep, Family};
    let count = |scene: &str, family: Family| {
        let scene = shadowmap::Scene::load(scene).unwrap();
        sweep(&scene.shadow, true, 16384, scene.light())
            .iter()
            .filter(|c| c.family == family)
            .count()
    };
    assert_eq!(count("dummy", Family::Cascades), 8);
    assert_eq!(count("dummy", Family::PointLayered), 0);
    // Every point-light configuration is also drawn face by face.
    let layered = count("point-shadows", Family::PointLayered);
    assert!(layered >= 20, "{layered}");
    assert_eq!(count("point-shadows", Family::PointSixPasses), layered);
    assert_eq!(count("point-shadows", Family::Cascades), 0);
}

#[test]
fn quick_bench_fills_every_csv_column() {
    let dir = tmp("bench");
    let stdout = common::stdout_of(
        common::bin()
            .args([
                "bench",
                "--quick",
                "--frames",
                "3",
                "--warmup",
                "1",
                "--size",
                "160x90",
                "--target-error",
                "0.5",
                "--out-dir",
            ])
            .arg(&dir),
    );
    assert!(
        stdout.contains("cheapest configuration with error <= 50.000%"),
        "{stdout}"
    );
    let csv = std::fs::read_to_string(dir.join("bench.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert!(rows.len() >= 20, "{} rows", rows.len());
    for row in &rows {
        assert_eq!(row.len(), header.len());
        for (h, v) in header.iter().zip(row) {
            assert!(!v.is_empty() && *v != "nan", "column {h} empty in {row:?}");
        }
    }
    let tutorial = header.iter().position(|h| *h == "tutorial").unwrap();
    let labelled: Vec<&str> = rows
        .iter()
        .map(|r| r[tutorial])
        .filter(|t| *t != "-")
        .collect();
    assert_eq!(labelled, ["book", "learnopengl"]);
    let pareto = header.iter().position(|h| *h == "pareto").unwrap();
    assert!(rows.iter().any(|r| r[pareto] == "true"));
    // The DummyGame's light is directional: the sweep has rows with cascades (2 and 4).
    let family = header.iter().position(|h| *h == "family").unwrap();
    let cascades = header.iter().position(|h| *h == "cascades").unwrap();
    let cascaded: Vec<&str> = rows
        .iter()
        .filter(|r| r[family] == "cascades")
        .map(|r| r[cascades])
        .collect();
    assert!(
        cascaded.contains(&"2") && cascaded.contains(&"4"),
        "{cascaded:?}"
    );
    let png = std::fs::read(dir.join("pareto.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    assert!(std::fs::read_to_string(dir.join("bench.md"))
        .unwrap()
        .contains("**book**"));
    std::fs::remove_dir_all(&dir).ok();
}
