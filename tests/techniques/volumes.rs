//! Stencil shadow volumes against the exact CPU reference: closed
//! casters at 640 x 360 leave nothing wrong outside a 1-pixel band around the true shadow
//! edges and at most 0.05% of receivers wrong inside it; the same with the camera inside a
//! volume, at a grazing light and far from the origin; open meshes cast as documented in
//! `shadowmap::shadows::volumes`.

use crate::common;

use common::context;
use glam::Vec3;
use shadowmap::compare::{compare, CompareOptions};
use shadowmap::engine::HeadlessContext;
use shadowmap::settings::ShadowTechnique;
use shadowmap::{Scene, ShadowSettings};

fn volumes(scene: &Scene) -> ShadowSettings {
    ShadowSettings {
        technique: ShadowTechnique::Volumes,
        ..scene.shadow
    }
}

/// Scores light `light`'s volumes in `scene` at 640 x 360 against the reference and checks
/// the bounds above; returns (receivers, misclassified) for further checks.
fn holds(ctx: &HeadlessContext, scene: &Scene, light: usize, what: &str) -> (usize, usize) {
    let opts = CompareOptions {
        width: 640,
        height: 360,
        supersample: 1,
        band: 1,
        light,
        rays: shadowmap::compare::AREA_RAYS,
    };
    let c =
        compare(ctx.gl(), scene, &volumes(scene), &opts).unwrap_or_else(|e| panic!("{what}: {e}"));
    let m = &c.metrics;
    let vis = c.frame.visibility.as_ref().unwrap();
    let wrong: Vec<String> = (0..vis.len())
        .filter(|&i| {
            let r = c.reference.hard[i];
            r.receiver && vis[i].is_some_and(|v| (v - r.visibility).abs() > 0.5)
        })
        .take(8)
        .map(|i| {
            format!(
                "({}, {}) at {:.4} rendered {:?} reference {}",
                i % 640,
                i / 640,
                c.reference.world_position(i),
                vis[i],
                c.reference.hard[i].visibility
            )
        })
        .collect();
    assert!(
        m.receivers > 10_000,
        "{what}: only {} receivers",
        m.receivers
    );
    assert_eq!(
        m.misclassified_outside_band, 0,
        "{what}: {m:?}; first wrong pixels: {wrong:?}"
    );
    let in_band = m.misclassified - m.misclassified_outside_band;
    assert!(
        in_band as f64 <= 0.0005 * m.receivers as f64,
        "{what}: {in_band} of {} receivers wrong in the band; {wrong:?}",
        m.receivers
    );
    (m.receivers, m.misclassified)
}

/// The scene's shadowed receivers under light `light` as the reference sees them (so a
/// test cannot pass on a frame with no shadow at all).
fn shadowed_receivers(ctx: &HeadlessContext, scene: &Scene, light: usize) -> usize {
    let opts = CompareOptions {
        width: 640,
        height: 360,
        supersample: 1,
        band: 1,
        light,
        rays: shadowmap::compare::AREA_RAYS,
    };
    let c = compare(ctx.gl(), scene, &volumes(scene), &opts).unwrap();
    c.reference
        .hard
        .iter()
        .filter(|r| r.receiver && r.visibility < 0.5)
        .count()
}

#[test]
fn closed_casters_match_the_reference() {
    let ctx = context();
    for name in ["dummy", "learnopengl", "point-shadows"] {
        let scene = common::frozen(name);
        holds(&ctx, &scene, 0, name);
        assert!(shadowed_receivers(&ctx, &scene, 0) > 500, "{name}");
    }
    let scene = common::frozen("three-lights");
    for (light, what) in [(0, "three-lights' sun"), (1, "three-lights' spot")] {
        holds(&ctx, &scene, light, what);
        assert!(shadowed_receivers(&ctx, &scene, light) > 500, "{what}");
    }
}

/// The DummyGame's cube frozen, lit from `angle` degrees.
fn dummy(angle: f32) -> Scene {
    common::dummy(angle)
}

/// Whether the ray from `origin` along `dir` passes through the box |p| <= `half` (slabs).
fn ray_hits_box(origin: Vec3, dir: Vec3, half: f32) -> bool {
    let (mut near, mut far) = (0.0f32, f32::INFINITY);
    for k in 0..3 {
        let (o, d) = (origin[k], dir[k]);
        if d.abs() < 1e-12 {
            if o.abs() > half {
                return false;
            }
            continue;
        }
        let (a, b) = ((-half - o) / d, (half - o) / d);
        near = near.max(a.min(b));
        far = far.min(a.max(b));
    }
    near <= far
}

#[test]
fn z_fail_holds_with_the_camera_inside_a_volume() {
    let ctx = context();
    let mut scene = dummy(45.0);
    // Under and behind the cube, in its shadow, looking down the shadow on the plane.
    scene.camera.position = Vec3::new(0.0, -0.8, -1.0);
    scene.camera.rotation = Vec3::new(30.0, 0.0, 0.0);
    let to_light = Vec3::new(0.0, 45f32.to_radians().sin(), 45f32.to_radians().cos());
    assert!(
        ray_hits_box(scene.camera.position, to_light, 0.5),
        "the camera must sit in the cube's shadow"
    );
    holds(&ctx, &scene, 0, "camera inside the cube's volume");
    assert!(shadowed_receivers(&ctx, &scene, 0) > 500);
}

#[test]
fn a_grazing_light_and_a_scene_far_from_the_origin_hold() {
    let ctx = context();
    // 1 degree over the horizon: the shadow starts 29 units behind the cube and ends 86
    // units behind it, so the plane grows to 200 x 200, the cube to 8 units wide, and the
    // camera looks down on the far plane from 8 units up.
    let mut grazing = dummy(1.0);
    for item in &mut grazing.items {
        match item.name.as_str() {
            "plane" => item.scale = Vec3::splat(100.0),
            _ => item.scale = Vec3::new(4.0, 0.5, 0.5),
        }
    }
    grazing.camera.position = Vec3::new(0.0, 8.0, 0.0);
    grazing.camera.rotation = Vec3::new(10.0, 0.0, 0.0);
    holds(&ctx, &grazing, 0, "light at 1 degree");
    assert!(shadowed_receivers(&ctx, &grazing, 0) > 500);
    let offset = Vec3::new(1e5, 0.0, 1e5);
    let mut far = dummy(60.0);
    far.items.iter_mut().for_each(|i| i.position += offset);
    far.camera.position += offset;
    holds(&ctx, &far, 0, "the DummyGame 1e5 from the origin");
    assert!(shadowed_receivers(&ctx, &far, 0) > 500);
    let mut far_point = common::frozen("point-shadows");
    far_point
        .items
        .iter_mut()
        .for_each(|i| i.position += offset);
    far_point.camera.position += offset;
    for light in &mut far_point.lights {
        if let shadowmap::scene::Light::Point(p) = light {
            p.position += offset;
        }
    }
    holds(&ctx, &far_point, 0, "point-shadows 1e5 from the origin");
    assert!(shadowed_receivers(&ctx, &far_point, 0) > 500);
}

/// The DummyGame with its cube's mesh replaced by `mesh` (an open one).
fn with_caster(mesh: shadowmap::geometry::MeshData, angle: f32) -> Scene {
    let mut scene = dummy(angle);
    scene.meshes.push(mesh);
    let id = scene.meshes.len() - 1;
    let cube = scene.items.iter_mut().find(|i| i.name == "cube").unwrap();
    cube.mesh = id;
    scene
}

#[test]
fn a_single_sided_plane_casts_from_either_side_as_the_ray_cast() {
    use shadowmap::geometry::MeshData;
    use shadowmap::shadows::volumes::Adjacency;
    let ctx = context();
    let plane = MeshData::plane(1.0);
    let a = Adjacency::of(&plane);
    assert_eq!((a.open_edges, a.non_manifold_edges), (4, 0));
    // Lit on its front (facing up, light above) and on its back (wound the other way).
    for (mesh, what) in [
        (plane.clone(), "a plane lit on its front"),
        (plane.flip_winding(), "a plane lit on its back"),
    ] {
        let scene = with_caster(mesh, 60.0);
        holds(&ctx, &scene, 0, what);
        assert!(shadowed_receivers(&ctx, &scene, 0) > 500, "{what}");
    }
    // LearnOpenGL's floor is one (wound clockwise, lit on its back): the scene holds in
    // `closed_casters_match_the_reference` with it casting from both sides.
    let learnopengl = common::frozen("learnopengl");
    let floor = learnopengl
        .items
        .iter()
        .find(|i| i.name == "floor")
        .unwrap();
    assert!(floor.casts_shadows);
    assert!(!Adjacency::of(&learnopengl.meshes[floor.mesh]).is_closed());
}

#[test]
fn a_box_without_a_face_casts_its_whole_shape() {
    use shadowmap::geometry::MeshData;
    use shadowmap::shadows::volumes::Adjacency;
    let ctx = context();
    // Without its lid (the light looks in from above) and without its side towards the
    // light (the light looks in from the side).
    for (axis, what) in [(1, "a box without its lid"), (2, "a box without its side")] {
        let mut mesh = MeshData::cube();
        let positions = mesh.positions.clone();
        mesh.indices = mesh
            .indices
            .chunks_exact(3)
            .filter(|t| !t.iter().all(|&i| positions[i as usize][axis] == 1.0))
            .flatten()
            .copied()
            .collect();
        let a = Adjacency::of(&mesh);
        assert_eq!((a.open_edges, a.non_manifold_edges), (4, 0), "{what}");
        let scene = with_caster(mesh, 60.0);
        holds(&ctx, &scene, 0, what);
        assert!(shadowed_receivers(&ctx, &scene, 0) > 500, "{what}");
    }
}

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("shadowmap-volumes-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    d
}

fn metrics_of(dir: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("metrics.json")).unwrap()).unwrap()
}

#[test]
fn compare_scores_volumes_and_takes_them_as_the_truth() {
    let size = [
        "--scene",
        "learnopengl",
        "--size",
        "320x180",
        "--supersample",
        "1",
    ];
    // --technique volumes against the ray cast: nothing wrong outside the band.
    let cpu = tmp("cpu");
    let out = common::stdout_of(
        common::bin()
            .args(["compare", "--technique", "volumes"])
            .args(size)
            .arg("--out-dir")
            .arg(&cpu),
    );
    assert!(out.contains("[stencil shadow volumes"), "{out}");
    let m = &metrics_of(&cpu)["metrics"];
    assert_eq!(m["misclassified_outside_band"], 0, "{m}");
    assert!(m["receivers"].as_u64().unwrap() > 5000, "{m}");
    // The maps against the volumes' truth score as they do against the ray cast (the
    // volumes agree with it), and the agreement is printed and written.
    let maps_cpu = tmp("maps-cpu");
    common::stdout_of(
        common::bin()
            .arg("compare")
            .args(size)
            .arg("--out-dir")
            .arg(&maps_cpu),
    );
    let maps_vol = tmp("maps-vol");
    let out = common::stdout_of(
        common::bin()
            .args(["compare", "--truth", "volumes"])
            .args(size)
            .arg("--out-dir")
            .arg(&maps_vol),
    );
    assert!(
        out.contains("truth: stencil shadow volumes; against the CPU ray cast they agree on"),
        "{out}"
    );
    let json = metrics_of(&maps_vol);
    assert_eq!(json["truth"], "volumes");
    let agreement = &json["volumes_vs_cpu"];
    assert_eq!(agreement["misclassified_outside_band"], 0, "{agreement}");
    let against_volumes = json["metrics"]["misclassified"].as_u64().unwrap() as i64;
    let against_cpu = metrics_of(&maps_cpu)["metrics"]["misclassified"]
        .as_u64()
        .unwrap() as i64;
    assert!(
        against_cpu > 20,
        "the maps must have errors to find: {against_cpu}"
    );
    let wrong_volumes = agreement["misclassified"].as_u64().unwrap() as i64;
    assert!(
        (against_volumes - against_cpu).abs() <= wrong_volumes,
        "maps: {against_volumes} wrong against the volumes, {against_cpu} against the ray cast"
    );
    for d in [cpu, maps_cpu, maps_vol] {
        std::fs::remove_dir_all(d).ok();
    }
}

#[test]
fn an_unshadowed_pixel_looks_the_same_with_maps_and_volumes() {
    let ctx = context();
    // Three-lights has four lights (sun, spot, point and a fill that casts nothing); with
    // no casters every pixel is unshadowed, drawn in one pass by the maps and in five
    // (ambient, then each light added) by the volumes.
    let mut scene = common::frozen("three-lights");
    scene.items.iter_mut().for_each(|i| i.casts_shadows = false);
    let maps = ShadowSettings {
        shadows: false,
        ..scene.shadow
    };
    let a = common::render(&ctx, &mut scene.clone(), &maps, 320, 180);
    let b = common::render(&ctx, &mut scene.clone(), &volumes(&scene), 320, 180);
    let diffs: Vec<i32> = a
        .colour
        .rgba
        .iter()
        .zip(&b.colour.rgba)
        .map(|(x, y)| (i32::from(*x) - i32::from(*y)).abs())
        .collect();
    let lit = a.colour.rgba.iter().filter(|&&v| v > 40).count();
    assert!(lit > 10_000, "the frame must be lit: {lit} bright channels");
    // Each pass rounds to 8 bits: at most half a level each, five passes.
    let max = diffs.iter().max().copied().unwrap_or(0);
    let mean = diffs.iter().map(|&d| f64::from(d)).sum::<f64>() / diffs.len() as f64;
    assert!(max <= 3 && mean < 0.5, "max {max}, mean {mean}");
}

#[test]
fn a_light_with_its_own_volumes_mixes_with_maps() {
    let ctx = context();
    let mut scene = common::frozen("three-lights");
    // The spot (light 1) casts volumes from its own table; the sun and the point light keep
    // their maps.
    scene.lights[1].shadow_patch_mut().technique = Some(ShadowTechnique::Volumes);
    let opts = |light| CompareOptions {
        width: 640,
        height: 360,
        supersample: 1,
        band: 1,
        light,
        rays: shadowmap::compare::AREA_RAYS,
    };
    let spot = compare(ctx.gl(), &scene, &scene.shadow, &opts(1)).unwrap();
    assert_eq!(
        spot.metrics.misclassified_outside_band, 0,
        "{:?}",
        spot.metrics
    );
    assert!(spot.metrics.receivers > 10_000);
    // The sun's map scores the same in the frame drawn light by light as in the maps' one
    // pass.
    let mixed = compare(ctx.gl(), &scene, &scene.shadow, &opts(0)).unwrap();
    let maps = compare(
        ctx.gl(),
        &common::frozen("three-lights"),
        &scene.shadow,
        &opts(0),
    )
    .unwrap();
    assert!(
        maps.metrics.misclassified > 0,
        "the sun's map has errors to compare"
    );
    assert_eq!(mixed.metrics, maps.metrics);
}

#[test]
fn map_flags_with_volumes_and_show_volumes_with_maps_are_said_to_do_nothing() {
    let dir = tmp("idle");
    std::fs::create_dir_all(&dir).unwrap();
    let run = |args: &[&str]| {
        let out = common::bin()
            .args(["render", "--size", "160x90", "--out", "x.png"])
            .args(args)
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(out.status.success(), "{args:?}: {out:?}");
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let stderr = run(&["--technique", "volumes", "--filter", "single"]);
    assert!(
        stderr.contains("warning: --filter single: every casting light has shadow volumes"),
        "{stderr}"
    );
    let stderr = run(&["--show-volumes"]);
    assert!(
        stderr.contains("no light has shadow volumes (--technique volumes)"),
        "{stderr}"
    );
    assert!(!run(&["--technique", "volumes", "--show-volumes"]).contains("warning"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn render_says_which_meshes_cast_from_both_sides() {
    let dir = tmp("open");
    std::fs::create_dir_all(&dir).unwrap();
    let stdout = common::stdout_of(
        common::bin()
            .args(["render", "--scene", "learnopengl", "--technique", "volumes"])
            .args(["--size", "160x90", "--out", "x.png"])
            .current_dir(&dir),
    );
    assert!(
        stdout.contains(
            "shadow volumes: mesh 'plane' is not closed (4 open, 0 non-manifold edges): it \
             casts from both sides of each triangle"
        ),
        "{stdout}"
    );
    // The cubes are closed: one line, the floor's.
    assert_eq!(stdout.matches("is not closed").count(), 1, "{stdout}");
    std::fs::remove_dir_all(&dir).ok();
}
