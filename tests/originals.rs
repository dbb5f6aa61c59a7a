//! The scenes against their originals: numbers read from the tutorials' own programs
//! (LearnOpenGL's `shadow_mapping.cpp` 3.1.3, the shadow-playground's demos), not from
//! their texts.

mod common;

use glam::{Mat4, Vec2, Vec3};
use shadowmap::geometry::MeshData;
use shadowmap::scene::Light;
use shadowmap::settings::LightView;
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
