//! `Transformation` and the light matrices against double-precision references written out
//! from their textbook formulas. Tolerance: 1e-5 relative to the largest entry (f32 rounding
//! after a handful of operations).

use glam::{Mat4, Vec3};
use shadowmap::scene::DirectionalLight;
use shadowmap::settings::LightView;
use shadowmap::transformation::Transformation;

type M = [[f64; 4]; 4]; // row-major: m[row][col]

fn mul(a: &M, b: &M) -> M {
    let mut r = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            r[i][j] = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    r
}

fn ident() -> M {
    let mut r = [[0.0; 4]; 4];
    (0..4).for_each(|i| r[i][i] = 1.0);
    r
}

fn translate(t: [f64; 3]) -> M {
    let mut r = ident();
    (0..3).for_each(|i| r[i][3] = t[i]);
    r
}

fn scale(s: f64) -> M {
    let mut r = ident();
    (0..3).for_each(|i| r[i][i] = s);
    r
}

/// Right-handed rotation about axis 0 (x), 1 (y) or 2 (z) by `deg` degrees.
fn rot(axis: usize, deg: f64) -> M {
    let (s, c) = deg.to_radians().sin_cos();
    let (i, j) = [(1, 2), (2, 0), (0, 1)][axis];
    let mut r = ident();
    r[i][i] = c;
    r[j][j] = c;
    r[i][j] = -s;
    r[j][i] = s;
    r
}

/// gluPerspective.
fn perspective(fov_deg: f64, aspect: f64, n: f64, f: f64) -> M {
    let t = 1.0 / (fov_deg.to_radians() / 2.0).tan();
    let mut r = [[0.0; 4]; 4];
    r[0][0] = t / aspect;
    r[1][1] = t;
    r[2][2] = (f + n) / (n - f);
    r[2][3] = 2.0 * f * n / (n - f);
    r[3][2] = -1.0;
    r
}

/// glOrtho.
fn ortho(l: f64, r_: f64, b: f64, t: f64, n: f64, f: f64) -> M {
    let mut r = ident();
    r[0][0] = 2.0 / (r_ - l);
    r[1][1] = 2.0 / (t - b);
    r[2][2] = -2.0 / (f - n);
    r[0][3] = -(r_ + l) / (r_ - l);
    r[1][3] = -(t + b) / (t - b);
    r[2][3] = -(f + n) / (f - n);
    r
}

fn assert_close(what: &str, got: &Mat4, want: &M) {
    let g = got.to_cols_array_2d(); // g[col][row]
    let scale = want.iter().flatten().fold(1.0f64, |m, v| m.max(v.abs()));
    for row in 0..4 {
        for col in 0..4 {
            let d = (g[col][row] as f64 - want[row][col]).abs();
            assert!(
                d <= 1e-5 * scale,
                "{what}: entry ({row},{col}) = {} but the f64 reference is {} (diff {d:e})",
                g[col][row],
                want[row][col]
            );
        }
    }
}

#[test]
fn projection_matches_glu_perspective() {
    for (fov, w, h, n, f) in [
        (60.0, 1280.0, 720.0, 0.01, 1000.0),
        (45.0, 800.0, 600.0, 0.1, 100.0),
    ] {
        let got = Transformation::projection(fov as f32, w as f32, h as f32, n as f32, f as f32);
        assert_close("projection", &got, &perspective(fov, w / h, n, f));
    }
}

#[test]
fn ortho_matches_gl_ortho() {
    let got = Transformation::ortho(-10.0, 10.0, -10.0, 10.0, -1.0, 20.0);
    assert_close("ortho", &got, &ortho(-10.0, 10.0, -10.0, 10.0, -1.0, 20.0));
    let got = Transformation::ortho(-3.0, 5.0, -2.0, 7.0, 1.0, 7.5);
    assert_close("ortho", &got, &ortho(-3.0, 5.0, -2.0, 7.0, 1.0, 7.5));
}

#[test]
fn view_and_model_match_the_book_formulas() {
    let pos = [0.3, -1.2, 2.5];
    let rotation = [20.0, -35.0, 0.0];
    let got = Transformation::view(
        Vec3::new(pos[0] as f32, pos[1] as f32, pos[2] as f32),
        Vec3::new(rotation[0] as f32, rotation[1] as f32, 0.0),
    );
    let want = mul(
        &mul(&rot(0, rotation[0]), &rot(1, rotation[1])),
        &translate(pos.map(|v| -v)),
    );
    assert_close("view", &got, &want);

    let r = [15.0, 40.0, -70.0];
    let got = Transformation::model(
        Vec3::new(1.0, -1.0, 0.5),
        Vec3::new(r[0] as f32, r[1] as f32, r[2] as f32),
        Vec3::splat(2.5),
    );
    let want = mul(
        &mul(
            &mul(
                &mul(&translate([1.0, -1.0, 0.5]), &rot(0, -r[0])),
                &rot(1, -r[1]),
            ),
            &rot(2, -r[2]),
        ),
        &scale(2.5),
    );
    assert_close("model", &got, &want);
}

#[test]
fn book_light_view_looks_along_the_light_in_the_yz_plane() {
    // For the DummyGame's directions (no x component) the book's angles map the direction
    // onto +Z.
    for a in [1.0f32, 20.0, 45.0, 89.0, 90.0, 91.0, 135.0, 179.0] {
        let light = DirectionalLight {
            direction: DirectionalLight::direction_from_angle(a),
            ..dummy_light()
        };
        let book = light.view_matrix(LightView::BookAngles);
        let d = book.transform_vector3(light.direction);
        assert!(
            (d - Vec3::Z).length() < 1e-5,
            "angle {a}: direction maps to {d}"
        );
        // Against a look-at view: the same depth for every point and the same distance from
        // the view axis; only the roll about the axis may differ (past 90 degrees the book's
        // rotation turns the map upside down, which changes no shadow).
        let look = light.view_matrix(LightView::LookAt);
        for p in [
            Vec3::new(1.0, -1.0, 0.5),
            Vec3::new(-2.0, 0.3, -1.5),
            Vec3::new(0.2, 3.0, 2.0),
        ] {
            let (b, l) = (book.transform_point3(p), look.transform_point3(p));
            assert!(
                (b.z - l.z).abs() < 1e-5,
                "angle {a}: depth {} vs {}",
                b.z,
                l.z
            );
            let (rb, rl) = (b.truncate().length(), l.truncate().length());
            assert!((rb - rl).abs() < 1e-5, "angle {a}: radius {rb} vs {rl}");
        }
    }
}

#[test]
fn book_light_view_breaks_with_an_x_component() {
    // Where the book's approach stops working: a direction with x != 0 is no longer mapped
    // onto the view axis. The error grows with x; the look-at view stays exact.
    let light = DirectionalLight {
        direction: Vec3::new(0.5, 0.7, 0.5).normalize(),
        ..dummy_light()
    };
    let book = light
        .view_matrix(LightView::BookAngles)
        .transform_vector3(light.direction);
    let look = light
        .view_matrix(LightView::LookAt)
        .transform_vector3(light.direction);
    assert!((look - Vec3::Z).length() < 1e-5);
    let off = book.angle_between(Vec3::Z).to_degrees();
    assert!(
        off > 10.0,
        "the book's view should look {off} degrees away from the light"
    );
}

fn dummy_light() -> DirectionalLight {
    *shadowmap::Scene::load("dummy")
        .unwrap()
        .light()
        .as_directional()
        .unwrap()
}

#[test]
fn axis_angle_converts_to_the_book_angles() {
    // LearnOpenGL's third cube: 60 degrees about normalize(1, 0, 1).
    let q = glam::Quat::from_axis_angle(Vec3::new(1.0, 0.0, 1.0).normalize(), 60f32.to_radians());
    let angles = Transformation::book_angles(q);
    let got = Transformation::model(Vec3::ZERO, angles, Vec3::ONE);
    let want = Mat4::from_quat(q);
    let diff = (got - want)
        .abs()
        .to_cols_array()
        .into_iter()
        .fold(0.0f32, f32::max);
    assert!(diff < 1e-5, "angles {angles} give a matrix off by {diff}");
}
