//! The translucent maps' matrices and optical depths.

use glam::{DMat4, DVec3, Mat4, Vec3};

use super::*;
use crate::shadows::Rays;

fn view(projection: Mat4, view: DMat4) -> ShadowView {
    ShadowView {
        view: view.as_mat4(),
        view64: view,
        projection,
        perspective: false,
        linear_depth: false,
        near: -1.0,
        far: 12.0,
        texel_world: 0.01,
        rays: Rays::Parallel { to_light: Vec3::Y },
    }
}

#[test]
fn the_lookup_matrix_gives_the_lights_texel_and_the_fitted_depth() {
    let light = DMat4::look_at_rh(DVec3::new(0.0, 5.0, 0.0), DVec3::ZERO, DVec3::Z);
    let projection = Mat4::orthographic_rh_gl(-4.0, 4.0, -4.0, 4.0, -1.0, 12.0);
    let v = view(projection, light);
    let camera = DMat4::look_at_rh(DVec3::new(1.0, 2.0, 6.0), DVec3::ZERO, DVec3::Y);
    // The light looks down from y = 5: depth 5 - y; fitted over y in [-1, 1].
    let fit = DepthFit {
        near: 4.0,
        far: 6.0,
    };
    let m = lookup_matrix(&v, fit, 0.0, camera);
    for (world, depth) in [
        (DVec3::new(1.0, 1.0, 2.0), 0.0),
        (DVec3::new(-2.0, -1.0, 0.5), 1.0),
    ] {
        let c = m * camera.transform_point3(world).as_vec3().extend(1.0);
        let clip = projection * light.transform_point3(world).as_vec3().extend(1.0);
        assert!((c.truncate().truncate() - clip.truncate().truncate()).length() < 1e-5);
        assert!((c.z - depth).abs() < 1e-5, "{c} for {world}");
        assert_eq!(c.w, 1.0);
    }
}

#[test]
fn optical_depth_is_minus_ln_of_what_passes_clamped_below_one() {
    assert!((optical_depth(0.5) - std::f32::consts::LN_2).abs() < 1e-6);
    assert_eq!(optical_depth(0.0), 0.0);
    let most = optical_depth(1.0);
    assert!(most.is_finite() && (most - optical_depth(OPACITY_MAX)).abs() < 1e-6);
}
