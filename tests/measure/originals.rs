//! The scenes against their originals: numbers read from the tutorials' own programs
//! (LearnOpenGL's `shadow_mapping.cpp` 3.1.3, the shadow-playground's demos), not from
//! their texts.

use crate::common;

use glam::{Mat4, Vec2, Vec3};
use shadowmap::compare::{compare, CompareOptions};
use shadowmap::geometry::MeshData;
use shadowmap::scene::Light;
use shadowmap::settings::{LightView, MapSize};
use shadowmap::Scene;

/// The largest difference between two matrices' entries.
fn max_diff(a: Mat4, b: Mat4) -> f32 {
    (a - b)
        .to_cols_array()
        .iter()
        .fold(0.0f32, |m, v| m.max(v.abs()))
}

#[test]
fn learnopengl_floor_ends_at_row_313() {
    // `planeVertices` span -25..25 at y = -0.5; from the camera at (0, 0, 3) (fov 45,
    // 800 x 600) the far edge z = -25 projects to 300 (1 + 0.5 / 28 / tan 22.5) = 312.9
    // rows from the top: row 313 is the first whose centre sees the floor (a 25 x 25 floor
    // would end at row 323).
    let ctx = common::context();
    let mut scene = Scene::load("learnopengl").unwrap();
    let settings = scene.shadow;
    let frame = common::render(&ctx, &mut scene, &settings, 800, 600);
    let positions = frame.world_positions().unwrap();
    let normals = frame.normals.as_ref().unwrap();
    let floor = |row: usize| {
        let i = row * 800 + 400;
        let (p, n) = (Vec3::from(positions[i]), Vec3::from(normals[i]));
        (p.y + 0.5).abs() < 1e-3 && n.y > 0.99
    };
    let first = (0..600)
        .find(|&r| floor(r))
        .expect("no floor in the centre column");
    assert!(
        (312..=314).contains(&first),
        "the floor's far edge is at row {first}, the tutorial's at 313"
    );
    // The texture repeats 25 times over the 50 units, as the tutorial's coordinates 0..25.
    let floor_item = scene.items.iter().find(|i| i.name == "floor").unwrap();
    assert_eq!(floor_item.scale, Vec3::splat(25.0));
}

#[test]
fn learnopengl_light_view_is_glm_look_at() {
    // lightView = glm::lookAt(lightPos, vec3(0), vec3(0, 1, 0)) with lightPos (-2, 4, -1).
    let scene = Scene::load("learnopengl").unwrap();
    let Light::Directional(l) = scene.light() else {
        panic!("LearnOpenGL's light is directional");
    };
    let eye = Vec3::new(-2.0, 4.0, -1.0);
    let glm = Mat4::look_at_rh(eye, Vec3::ZERO, Vec3::Y);
    let ours = l.view_matrix(LightView::LookAt);
    assert!(
        max_diff(ours, glm) < 1e-5,
        "ours {ours} against lookAt {glm}"
    );
    // So the depth map's up (the view's y row) is lookAt's: +Y projected across the view.
    let up = ours.row(1).truncate();
    assert!((up - glm.row(1).truncate()).length() < 1e-5);
    assert!(up.y > 0.0, "the map's up points up the world: {up}");
    // The scene's shadow camera is that view too.
    let view = shadowmap::shadows::light_camera(&scene, 0, &scene.shadow).view;
    assert!(max_diff(view, glm) < 1e-5, "{view} against {glm}");
}

#[test]
fn spot_light_without_up_looks_at_with_up_y() {
    // The playground's bulb: lookAt((0, 10, 30), (0, 0, 18), (0, 1, 0)).
    let scene = Scene::load("playground").unwrap();
    let view = shadowmap::shadows::light_camera(&scene, 0, &scene.shadow).view;
    let glm = Mat4::look_at_rh(
        Vec3::new(0.0, 10.0, 30.0),
        Vec3::new(0.0, 0.0, 18.0),
        Vec3::Y,
    );
    assert!(max_diff(view, glm) < 1e-5, "{view} against {glm}");
}

/// A corner of a face: its position and its texture coordinates (s, t).
type Corner = ([f32; 3], [f32; 2]);

/// LearnOpenGL's `renderCube`: for each face (its normal), the texture coordinates of its
/// four corners, read from the vertex array.
#[rustfmt::skip]
const RENDER_CUBE: [([f32; 3], [Corner; 4]); 6] = [
    // back face
    ([0., 0., -1.], [([-1., -1., -1.], [0., 0.]), ([1., 1., -1.], [1., 1.]),
                     ([1., -1., -1.], [1., 0.]), ([-1., 1., -1.], [0., 1.])]),
    // front face
    ([0., 0., 1.], [([-1., -1., 1.], [0., 0.]), ([1., -1., 1.], [1., 0.]),
                    ([1., 1., 1.], [1., 1.]), ([-1., 1., 1.], [0., 1.])]),
    // left face
    ([-1., 0., 0.], [([-1., 1., 1.], [1., 0.]), ([-1., 1., -1.], [1., 1.]),
                     ([-1., -1., -1.], [0., 1.]), ([-1., -1., 1.], [0., 0.])]),
    // right face
    ([1., 0., 0.], [([1., 1., 1.], [1., 0.]), ([1., -1., -1.], [0., 1.]),
                    ([1., 1., -1.], [1., 1.]), ([1., -1., 1.], [0., 0.])]),
    // bottom face
    ([0., -1., 0.], [([-1., -1., -1.], [0., 1.]), ([1., -1., -1.], [1., 1.]),
                     ([1., -1., 1.], [1., 0.]), ([-1., -1., 1.], [0., 0.])]),
    // top face
    ([0., 1., 0.], [([-1., 1., -1.], [0., 1.]), ([1., 1., 1.], [1., 0.]),
                    ([1., 1., -1.], [1., 1.]), ([-1., 1., 1.], [0., 0.])]),
];

#[test]
fn builtin_cube_has_render_cubes_texture_coordinates() {
    let cube = MeshData::cube();
    for (normal, corners) in RENDER_CUBE {
        for (position, st) in corners {
            let i = (0..cube.positions.len())
                .find(|&i| cube.positions[i] == position && cube.normals[i] == normal)
                .unwrap_or_else(|| panic!("no corner {position:?} on the face {normal:?}"));
            assert_eq!(
                Vec2::from(cube.tex_coords[i]),
                Vec2::from(st),
                "corner {position:?} of the face {normal:?}"
            );
        }
    }
    // Four corners per face, nothing else.
    assert_eq!(cube.positions.len(), 24);
}

#[test]
fn book_angles_are_refused_where_they_cannot_work() {
    // LearnOpenGL's light has an x component: the book's angles would turn its map away.
    let out = common::bin()
        .args([
            "render",
            "--scene",
            "learnopengl",
            "--light-view",
            "book-angles",
            "--out",
            "/dev/null",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        err.contains(
            "--light-view: shadow.light_view = \"book-angles\" cannot build the view of light 0"
        ),
        "{err}"
    );
    // A scene file: the field and the light are named.
    let dir = std::env::temp_dir().join(format!("originals-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("askew.toml");
    std::fs::write(
        &path,
        "[light]\ndirection = [0.5, 1.0, 0.2]\n[shadow]\nlight_view = \"book-angles\"\n\
         [[item]]\nmesh = \"cube\"\n",
    )
    .unwrap();
    let err = Scene::load(path.to_str().unwrap()).unwrap_err().to_string();
    assert!(err.contains("shadow.light_view"), "{err}");
    assert!(err.contains("cannot build the view of light"), "{err}");
    // Without light_view the same file gets look-at and loads; the DummyGame keeps its angles.
    std::fs::write(
        &path,
        "[light]\ndirection = [0.5, 1.0, 0.2]\n[[item]]\nmesh = \"cube\"\n",
    )
    .unwrap();
    let scene = Scene::load(path.to_str().unwrap()).unwrap();
    assert_eq!(scene.shadow.light_view, LightView::LookAt);
    assert_eq!(
        Scene::load("dummy").unwrap().shadow.light_view,
        LightView::BookAngles
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn playground_light_is_the_demos_bulb() {
    // js/cube-scene.js: lookAt((0, 10, 30), (0, 0, 18), +Y), perspective(30 degrees, the
    // canvas' aspect 4:3, near 10, far 30); the basic demo's depth map is the canvas' size,
    // 400 x 300; clear colour (0.8, 0.9, 0.8).
    let scene = Scene::load("playground").unwrap();
    let Light::Spot(l) = scene.light() else {
        panic!("the playground's light is a spot");
    };
    assert_eq!((l.fov, l.near, l.far, l.up), (30.0, 10.0, 30.0, None));
    assert!((l.aspect - 4.0 / 3.0).abs() < 1e-6, "aspect {}", l.aspect);
    assert!(!l.cone, "the bulb has no cone");
    assert_eq!(
        scene.shadow.map_size,
        MapSize {
            width: 400,
            height: 300
        }
    );
    assert_eq!(scene.clear_colour.truncate(), Vec3::new(0.8, 0.9, 0.8));
    let camera = shadowmap::shadows::light_camera(&scene, 0, &scene.shadow);
    let glm = Mat4::perspective_rh_gl(30f32.to_radians(), 4.0 / 3.0, 10.0, 30.0);
    assert!(
        max_diff(camera.projection, glm) < 1e-6,
        "{}",
        camera.projection
    );
}

#[test]
fn playground_bulb_lights_its_whole_frustum_where_rays_say() {
    let ctx = common::context();
    let scene = Scene::load("playground").unwrap();
    let opts = CompareOptions {
        rays: shadowmap::compare::AREA_RAYS,
        width: 400,
        height: 300,
        supersample: 1,
        band: 1,
        light: 0,
    };
    let c = compare(ctx.gl(), &scene, &scene.shadow, &opts).unwrap_or_else(|e| panic!("{e}"));
    let m = &c.metrics;
    eprintln!(
        "playground: {} receivers, {:.3}% misclassified ({} outside the edge band)",
        m.receivers,
        m.misclassified_rate * 100.0,
        m.misclassified_outside_band
    );
    assert!(m.receivers > 20_000, "the slab and the cube face the bulb");
    assert!(m.misclassified_rate < 0.01, "{m:?}");
    assert_eq!(m.misclassified_outside_band, 0, "{m:?}");

    let (checked, dark_pixels) = left_at_ambient(&ctx, &scene, &c);
    eprintln!("{checked} lit receivers in the frustum, {dark_pixels} left at ambient");
    assert!(checked > 10_000, "{checked}");
    assert_eq!(dark_pixels, 0, "receivers left at the ambient colour");
    // A cone would be seen: the same bulb with a 30-degree cone lights (and so has as
    // receivers) far less of the slab than the whole frustum.
    let mut coned = scene.clone();
    if let Light::Spot(l) = &mut coned.lights[0] {
        l.cone = true;
    }
    let c = compare(ctx.gl(), &coned, &coned.shadow, &opts).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("with a cone: {} receivers", c.metrics.receivers);
    assert!(
        c.metrics.receivers + 1000 < m.receivers,
        "a cone lights {} receivers, the bulb {}",
        c.metrics.receivers,
        m.receivers
    );
}

/// Of the receivers inside the light's frustum that rays and the test both call lit and
/// that face the bulb by more than a glancing angle: how many, and how many show no more
/// than ambient light (the same frame with the bulb switched off).
fn left_at_ambient(
    ctx: &shadowmap::engine::HeadlessContext,
    scene: &Scene,
    c: &shadowmap::compare::Comparison,
) -> (usize, usize) {
    let mut dark = scene.clone();
    if let Light::Spot(l) = &mut dark.lights[0] {
        l.colour = Vec3::ZERO;
    }
    let ambient = shadowmap::compare::render_visibility(ctx.gl(), &dark, &dark.shadow, 400, 300, 0)
        .unwrap()
        .colour;
    let light = shadowmap::shadows::light_camera(scene, 0, &scene.shadow);
    let to_clip = light.projection * light.view;
    let Light::Spot(bulb) = scene.light() else {
        unreachable!()
    };
    let positions = c.frame.world_positions().unwrap();
    let normals = c.frame.normals.as_ref().unwrap();
    let visibility = c.frame.visibility.as_ref().unwrap();
    let (mut checked, mut dark_pixels) = (0, 0);
    for (i, r) in c.reference.hard.iter().enumerate() {
        let Some(v) = visibility[i] else { continue };
        if !(r.receiver && r.visibility == 1.0 && v == 1.0) {
            continue;
        }
        let p = Vec3::from(positions[i]);
        let ndc = to_clip.project_point3(p);
        if ndc.abs().max_element() > 1.0 {
            continue;
        }
        let n_dot_l = Vec3::from(normals[i]).dot((bulb.position - p).normalize());
        if n_dot_l < 0.2 {
            continue;
        }
        checked += 1;
        let lit = &c.frame.colour.rgba[i * 4..i * 4 + 3];
        let amb = &ambient.rgba[i * 4..i * 4 + 3];
        if lit.iter().zip(amb).all(|(a, b)| a.abs_diff(*b) <= 2) {
            dark_pixels += 1;
        }
    }
    (checked, dark_pixels)
}

/// The steps from `bias` to `over-sampling`, in order.
const MIDDLE_STEPS: [&str; 6] = [
    "bias",
    "slope-bias",
    "cull-front",
    "over-sampling-repeat",
    "over-sampling-book",
    "over-sampling",
];

/// For each pair of consecutive [`MIDDLE_STEPS`] of `scene` seen from `camera`: whether their
/// settings differ, and how many pixels change between their images.
fn step_changes(
    ctx: &shadowmap::engine::HeadlessContext,
    scene: &Scene,
    camera: shadowmap::scene::Camera,
) -> Vec<(bool, usize)> {
    let mut scene = scene.clone();
    scene.camera = camera;
    let shots: Vec<_> = MIDDLE_STEPS
        .iter()
        .map(|name| {
            let settings = shadowmap::steps::settings_for(&scene, name).unwrap();
            let frame =
                shadowmap::compare::render_visibility(ctx.gl(), &scene, &settings, 400, 300, 0)
                    .unwrap();
            (settings, frame.colour.rgba)
        })
        .collect();
    shots
        .windows(2)
        .map(|w| {
            let changed = w[0]
                .1
                .chunks_exact(4)
                .zip(w[1].1.chunks_exact(4))
                .filter(|(a, b)| a != b)
                .count();
            (w[0].0 != w[1].0, changed)
        })
        .collect()
}

#[test]
fn learnopengl_steps_differ_from_the_steps_camera() {
    let ctx = common::context();
    let scene = Scene::load("learnopengl").unwrap();
    // The tutorial's camera stays the scene's; the steps have their own, over the cubes.
    assert_eq!(scene.camera.position, Vec3::new(0.0, 0.0, 3.0));
    let view = scene.steps_camera();
    assert_eq!(view.position, Vec3::new(2.0, 7.5, 8.5));
    assert_eq!(view.fov, 45.0, "fields left out come from [camera]");
    let tutorial = step_changes(&ctx, &scene, scene.camera);
    let steps = step_changes(&ctx, &scene, view);
    for (k, ((differ, seen), (_, before))) in steps.iter().zip(&tutorial).enumerate() {
        let pair = (MIDDLE_STEPS[k], MIDDLE_STEPS[k + 1]);
        eprintln!(
            "{pair:?}: {seen} pixels change from the steps camera, {before} from the tutorial's"
        );
        if !differ {
            // LearnOpenGL starts with REPEAT, so its `over-sampling-repeat` variant is the
            // step before it: nothing to show from anywhere.
            assert_eq!(pair, ("cull-front", "over-sampling-repeat"));
            assert_eq!(*seen, 0);
            continue;
        }
        assert!(*seen > 50, "{pair:?}: {seen} pixels change");
        assert!(
            seen >= before,
            "{pair:?}: {seen} pixels change, {before} from the tutorial's camera"
        );
    }
}

#[test]
fn a_bad_steps_camera_is_named() {
    let dir = std::env::temp_dir().join(format!("originals-steps-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("steps.toml");
    for (table, field) in [
        (
            "{ near = 5.0, far = 1.0 }",
            "steps.camera: near = 5, far = 1: expected 0 < near < far",
        ),
        (
            "{ fov = 0.0 }",
            "steps.camera.fov: 0: expected degrees between 0 and 180",
        ),
        ("{ zoom = 2.0 }", "zoom"),
    ] {
        std::fs::write(
            &path,
            format!(
                "[light]\nangle = 45.0\n[steps]\ncamera = {table}\n[[item]]\nmesh = \"cube\"\n"
            ),
        )
        .unwrap();
        let err = Scene::load(path.to_str().unwrap()).unwrap_err().to_string();
        assert!(err.contains(field), "{table}: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
