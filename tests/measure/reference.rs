//! The exact reference on rendered G-buffers, and the compare / bench commands end to end.

use crate::common;

use common::{context, dummy};
use glam::Vec3;
use shadowmap::compare::{compute_reference, CompareOptions};

fn opts(supersample: u32) -> CompareOptions {
    CompareOptions {
        rays: shadowmap::compare::AREA_RAYS,
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
    // The arrays only on request: without --arrays, no .npy and none announced.
    let npy = |dir: &std::path::Path| {
        std::fs::read_dir(dir)
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .path()
                    .extension()
                    .is_some_and(|x| x == "npy")
            })
            .count()
    };
    assert_eq!(npy(&dir), 0, "{stdout}");
    assert!(!stdout.contains(".npy"), "{stdout}");
    let arrays = tmp("compare-arrays");
    let stdout = common::stdout_of(
        common::bin()
            .args([
                "compare",
                "--size",
                "160x90",
                "--supersample",
                "1",
                "--arrays",
            ])
            .arg("--out-dir")
            .arg(&arrays),
    );
    assert_eq!(npy(&arrays), 2, "{stdout}");
    assert!(stdout.contains("positions.npy, normals.npy"), "{stdout}");
    // float32, 90 x 160 x 3, after a 128-byte header.
    for f in ["positions.npy", "normals.npy"] {
        let bytes = std::fs::read(arrays.join(f)).unwrap();
        assert_eq!(bytes.len(), 128 + 90 * 160 * 3 * 4, "{f}");
        assert!(String::from_utf8_lossy(&bytes[..128]).contains("'shape': (90, 160, 3)"));
    }
    std::fs::remove_dir_all(&arrays).ok();
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
    // bench.md: every row of its table, the delimiter row included, has the header's cells.
    let md = std::fs::read_to_string(dir.join("bench.md")).unwrap();
    let cells = |l: &str| l.trim().trim_matches('|').split('|').count();
    let table: Vec<&str> = md.lines().filter(|l| l.starts_with('|')).collect();
    assert!(table.len() >= 4 && table[1].starts_with("|---|"), "{md}");
    for line in &table {
        assert_eq!(cells(line), cells(table[0]), "{line}");
    }
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

/// The slides scene (a spot light, a smooth sphere) and its reference at 640 x 360.
fn slides_reference() -> (shadowmap::Scene, shadowmap::compare::Reference) {
    let ctx = context();
    let scene = shadowmap::Scene::load("slides").unwrap();
    let opts = CompareOptions {
        rays: shadowmap::compare::AREA_RAYS,
        width: 640,
        height: 360,
        ..opts(1)
    };
    let r = compute_reference(ctx.gl(), &scene, &scene.shadow, &opts).unwrap();
    (scene, r)
}

/// The slides' spot: (position, unit axis, cosine of the half angle).
fn slides_spot(scene: &shadowmap::Scene) -> (Vec3, Vec3, f32) {
    match scene.light() {
        shadowmap::scene::Light::Spot(s) => (
            s.position,
            (s.target - s.position).normalize(),
            (s.fov.to_radians() * 0.5).cos(),
        ),
        other => panic!("the slides' light is a spot, not {other:?}"),
    }
}

#[test]
fn a_spot_scores_no_receiver_outside_its_cone() {
    let (scene, r) = slides_reference();
    let (light, axis, cos_half) = slides_spot(&scene);
    let (mut outside_facing, mut inside) = (0, 0);
    for (i, px) in r.hard.iter().enumerate() {
        let p = r.world_position(i).as_vec3();
        let n = Vec3::from(r.gbuffer.normals[i]);
        if !p.is_finite() {
            continue;
        }
        let c = (p - light).normalize().dot(axis);
        // What the old definition took as a receiver: facing the light, anywhere.
        let facing = n.dot(light - p) > 0.0;
        if c < cos_half && facing {
            outside_facing += 1;
            assert!(
                !px.receiver,
                "pixel {i} at {p} is outside the cone (cos {c})"
            );
        }
        if px.receiver {
            // The rim (the shader's soft last 0.01 of cosine) is left out too.
            assert!(
                c >= cos_half + shadowmap::compare::CONE_RIM - 1e-4,
                "{p}: {c}"
            );
            inside += 1;
        }
    }
    eprintln!("{outside_facing} facing pixels outside the cone, {inside} receivers inside");
    // The terrain reaches past the cone: those pixels used to be scored.
    assert!(outside_facing > 10_000, "{outside_facing}");
    assert!(inside > 30_000, "{inside}");
}

#[test]
fn no_receiver_on_the_smooth_sphere_has_a_triangle_facing_away() {
    let (scene, r) = slides_reference();
    let (light, _, _) = slides_spot(&scene);
    let item = scene.items.iter().find(|i| i.name == "sphere").unwrap();
    let m = item.model_matrix();
    // The sphere's triangles in the world, each with its outward normal.
    let tris: Vec<([Vec3; 3], Vec3)> = scene.meshes[item.mesh]
        .triangles()
        .map(|t| {
            let [a, b, c] = t.map(|p| m.transform_point3(p));
            let n = (b - a).cross(c - a).normalize();
            let out = if n.dot(a - item.position) < 0.0 {
                -n
            } else {
                n
            };
            ([a, b, c], out)
        })
        .collect();
    // The triangles a point lies on: on the plane and inside the edges (with a little
    // slack for the rasteriser's rounding, so a point on an edge has both neighbours).
    let triangles_of = |p: Vec3| {
        tris.iter()
            .filter(|([a, b, c], n)| {
                let inside = |u: Vec3, v: Vec3| (v - u).cross(p - u).dot(*n) > -1e-4;
                n.dot(p - *a).abs() < 1e-3 && inside(*a, *b) && inside(*b, *c) && inside(*c, *a)
            })
            .map(|(_, n)| *n)
            .collect::<Vec<Vec3>>()
    };
    let (mut on_sphere, mut smooth_only) = (0, 0);
    for (i, px) in r.hard.iter().enumerate() {
        let p = r.world_position(i).as_vec3();
        if !p.is_finite() || ((p - item.position).length() - 1.0).abs() > 0.05 {
            continue;
        }
        // Another item (the terrain where it meets the sphere) has its own normal there.
        let n = Vec3::from(r.gbuffer.normals[i]);
        let faces = triangles_of(p);
        if faces.is_empty() || n.dot((p - item.position).normalize()) < 0.95 {
            continue;
        }
        let towards = |f: &Vec3| f.dot(light - p) > 0.0;
        smooth_only += usize::from(n.dot(light - p) > 0.0 && !faces.iter().any(towards));
        if px.receiver {
            on_sphere += 1;
            assert!(
                faces.iter().any(towards),
                "receiver {i} at {p}: its triangle faces away"
            );
        }
    }
    eprintln!("{on_sphere} receivers on the sphere; {smooth_only} pixels face the light only by their interpolated normal");
    assert!(on_sphere > 2000, "{on_sphere}");
    assert!(smooth_only > 0, "the terminator's pixels were not found");
}

/// What the shadow test does under the slides' sphere (the terrain within 1.5 units of its
/// centre across, below its equator), at 640 x 360.
#[derive(Debug, Default)]
struct UnderTheSphere {
    receivers: usize,
    /// Lit by the shadow test, shadowed by the rays.
    false_light: usize,
    /// Of those, the ones the bias does not explain (see `bias_reach`).
    unexplained: usize,
    /// Shadowed receivers within the bias' reach: where the bias may light the terrain.
    within_reach: usize,
}

/// Light-space depth ([0, 1], as the map stores it) from the sphere's far side to `p`
/// along the light's ray, or None when the ray misses the sphere. With front faces culled
/// the map holds the sphere's far side, so a point is lit by the bias when this is at most
/// the bias.
fn bias_reach(scene: &shadowmap::Scene, centre: Vec3, p: Vec3) -> Option<f32> {
    let shadowmap::scene::Light::Spot(s) = scene.light() else {
        return None;
    };
    let axis = (s.target - s.position).normalize();
    let (l, u) = (s.position, (p - s.position).normalize());
    // |l + t u - centre| = 1 (the sphere's radius): the far root is the far side.
    let b = u.dot(l - centre);
    let disc = b * b - ((l - centre).length_squared() - 1.0);
    let t_far = -b + disc.sqrt();
    if !(disc > 0.0 && t_far < (p - l).length()) {
        return None;
    }
    let depth = |z: f32| s.far / (s.far - s.near) * (1.0 - s.near / z);
    Some(depth((p - l).dot(axis)) - depth((l + u * t_far - l).dot(axis)))
}

fn under_the_sphere(
    scene: &shadowmap::Scene,
    settings: &shadowmap::ShadowSettings,
) -> UnderTheSphere {
    let ctx = context();
    let opts = CompareOptions {
        rays: shadowmap::compare::AREA_RAYS,
        width: 640,
        height: 360,
        ..opts(1)
    };
    let c = shadowmap::compare::compare(ctx.gl(), scene, settings, &opts).unwrap();
    let centre = scene
        .items
        .iter()
        .find(|i| i.name == "sphere")
        .unwrap()
        .position;
    let vis = c.frame.visibility.as_deref().unwrap();
    let mut u = UnderTheSphere::default();
    for (i, px) in c.reference.hard.iter().enumerate() {
        let p = c.reference.world_position(i).as_vec3();
        let across = glam::Vec2::new(p.x - centre.x, p.z - centre.z).length();
        if !px.receiver || p.y > centre.y || across > 1.5 {
            continue;
        }
        u.receivers += 1;
        let reach = bias_reach(scene, centre, p);
        let within = reach.is_some_and(|d| d <= settings.bias);
        u.within_reach += usize::from(px.visibility == 0.0 && within);
        let lit = vis.get(i).copied().flatten().unwrap_or(0.0) >= 0.5;
        if lit && px.visibility == 0.0 {
            u.false_light += 1;
            u.unexplained += usize::from(!within);
        }
    }
    u
}

#[test]
fn the_crescent_under_the_slides_sphere_is_the_bias() {
    let scene = shadowmap::Scene::load("slides").unwrap();
    let own = under_the_sphere(&scene, &scene.shadow);
    let unbiased = shadowmap::ShadowSettings {
        bias: 0.0,
        ..scene.shadow
    };
    let none = under_the_sphere(&scene, &unbiased);
    eprintln!("slides' bias: {own:?}\nbias 0: {none:?}");
    assert!(own.receivers > 1000, "{own:?}");
    // Without the bias only the edges of the sphere's shadow are falsely lit (3 x 3 PCF
    // reaches past the silhouette): a handful of pixels.
    assert!(none.false_light <= 10, "{none:?}");
    // With it, every falsely lit pixel but such edge pixels lies within the bias' reach
    // of the sphere's far side, so that reach bounds the crescent...
    assert!(own.unexplained <= 10, "{own:?}");
    assert!(own.false_light <= own.within_reach + 10, "{own:?}");
    // ...and the crescent is that reach, not a few stray pixels.
    assert!(own.false_light * 2 >= own.within_reach, "{own:?}");
    assert!(own.within_reach > 50, "{own:?}");
}
