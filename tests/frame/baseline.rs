//! LearnOpenGL's program 3.1.3 (`examples/learnopengl_3_1_3.rs`, the yardstick of the
//! `learnopengl` scene): it draws the tutorial's frame, and its shadows fall where a ray
//! test against the three cubes puts them. `tests/program/examples.rs` holds the renderer's frame
//! and depth map to it.

use crate::common;

#[allow(dead_code)]
#[path = "../../examples/learnopengl_3_1_3.rs"]
mod learnopengl;

use glam::{Mat4, Vec3, Vec4};
use learnopengl::ShadowMapping;

const W: usize = 800;
const H: usize = 600;
/// glClearColor(0.1, 0.1, 0.1) in RGBA8.
const CLEAR: [u8; 4] = [26, 26, 26, 255];

/// The tutorial's cubes ([-1, 1]^3 under these model matrices).
fn cubes() -> [Mat4; 3] {
    let at =
        |x, y, z, s| Mat4::from_translation(Vec3::new(x, y, z)) * Mat4::from_scale(Vec3::splat(s));
    let axis = Vec3::new(1.0, 0.0, 1.0).normalize();
    [
        at(0.0, 1.5, 0.0, 0.5),
        at(2.0, 0.0, 1.0, 0.5),
        at(-1.0, 0.0, 2.0, 1.0)
            * Mat4::from_axis_angle(axis, 60f32.to_radians())
            * Mat4::from_scale(Vec3::splat(0.25)),
    ]
}

/// The nearest t > 0 where `origin + t dir` enters a cube, if it does.
fn hit_cube(model: &Mat4, origin: Vec3, dir: Vec3) -> Option<f32> {
    let inv = model.inverse();
    let (o, d) = (inv.transform_point3(origin), inv.transform_vector3(dir));
    let (mut near, mut far) = (f32::NEG_INFINITY, f32::INFINITY);
    for k in 0..3 {
        let (a, b) = ((-1.0 - o[k]) / d[k], (1.0 - o[k]) / d[k]);
        near = near.max(a.min(b));
        far = far.min(a.max(b));
    }
    (near <= far && far > 0.0).then_some(near.max(0.0))
}

/// The floor point (y = -0.5, inside the 50 x 50 floor) seen at pixel (x, y), if no cube is in front.
fn floor_point(inv_view_proj: &Mat4, x: f32, y: f32) -> Option<Vec3> {
    let ndc = Vec3::new(x / W as f32 * 2.0 - 1.0, 1.0 - y / H as f32 * 2.0, -1.0);
    let unproject = |z: f32| {
        let p = *inv_view_proj * Vec4::new(ndc.x, ndc.y, z, 1.0);
        p.truncate() / p.w
    };
    let (origin, far) = (unproject(-1.0), unproject(1.0));
    let dir = far - origin;
    let t = (-0.5 - origin.y) / dir.y;
    let p = origin + dir * t;
    let visible = t > 0.0 && p.x.abs() <= 25.0 && p.z.abs() <= 25.0;
    let blocked = cubes()
        .iter()
        .any(|m| hit_cube(m, origin, dir).is_some_and(|c| c < t));
    (visible && !blocked).then_some(p)
}

/// Whether a cube lies between `p` and the light, along the shadow map's parallel rays (the
/// orthographic light looks from (-2, 4, -1) at the origin).
fn occluded(p: Vec3) -> bool {
    let to_light = Vec3::new(-2.0, 4.0, -1.0).normalize();
    cubes().iter().any(|m| hit_cube(m, p, to_light).is_some())
}

/// Floor pixels the ray test calls shadowed and lit, away from shadow and silhouette edges:
/// every neighbour 2 pixels away must see the floor too, and points 0.1 units around `p`
/// must agree.
fn classify_floor() -> (Vec<usize>, Vec<usize>) {
    let view = Mat4::look_at_rh(Vec3::new(0.0, 0.0, 3.0), Vec3::new(0.0, 0.0, 2.0), Vec3::Y);
    let proj = Mat4::perspective_rh_gl(45f32.to_radians(), 4.0 / 3.0, 0.1, 100.0);
    let inv = (proj * view).inverse();
    let (mut shadowed, mut lit) = (Vec::new(), Vec::new());
    for y in 0..H {
        for x in 0..W {
            let (fx, fy) = (x as f32 + 0.5, y as f32 + 0.5);
            let Some(p) = floor_point(&inv, fx, fy) else {
                continue;
            };
            let around = [(2.0, 0.0), (-2.0, 0.0), (0.0, 2.0), (0.0, -2.0)];
            if around
                .iter()
                .any(|(dx, dy)| floor_point(&inv, fx + dx, fy + dy).is_none())
            {
                continue;
            }
            let offsets = [
                Vec3::ZERO,
                Vec3::X * 0.1,
                -Vec3::X * 0.1,
                Vec3::Z * 0.1,
                -Vec3::Z * 0.1,
            ];
            let votes = offsets.iter().filter(|o| occluded(p + **o)).count();
            match votes {
                5 => shadowed.push(y * W + x),
                0 => lit.push(y * W + x),
                _ => {}
            }
        }
    }
    (shadowed, lit)
}

#[test]
fn the_tutorial_frame_has_its_shadows_where_rays_put_them() {
    let ctx = common::context();
    let program = ShadowMapping::new(ctx.gl()).unwrap();
    program.render_frame();
    let image = program.read_colour();
    assert_eq!(image.len(), W * H * 4);

    let drawn = image.chunks_exact(4).filter(|p| *p != CLEAR).count();
    assert!(
        drawn > W * H / 4,
        "only {drawn} pixels differ from the clear colour"
    );

    let (shadowed, lit) = classify_floor();
    let red = |i: &usize| image[i * 4] as f64;
    let mean = |v: &[usize]| v.iter().map(red).sum::<f64>() / v.len() as f64;
    eprintln!(
        "floor pixels: {} shadowed (mean red {:.1}), {} lit (mean red {:.1})",
        shadowed.len(),
        mean(&shadowed),
        lit.len(),
        mean(&lit)
    );
    assert!(
        shadowed.len() > 2000,
        "only {} shadowed floor pixels in view",
        shadowed.len()
    );
    // In shadow only ambient light is left: 0.09 x the wood's albedo, whose red is at most
    // 0.78 x 0.9, so red <= 0.09 x 0.70 x 255 = 16.1.
    let dark = shadowed.iter().filter(|i| red(i) <= 17.0).count();
    assert!(
        dark as f64 >= 0.99 * shadowed.len() as f64,
        "{dark} of {} shadowed floor pixels are as dark as ambient light alone",
        shadowed.len()
    );
    // Lit floor adds 0.3 x n.l (n.l from 0.36 far away to 0.9 near the cubes) to the 0.09.
    assert!(
        mean(&lit) > 2.0 * mean(&shadowed),
        "lit floor is not clearly brighter than shadowed floor"
    );
}
