//! Scene files that cannot be loaded: TOML errors, values out of range, values that used
//! to be accepted silently; and relative paths, which resolve from the scene's folder.

use std::path::Path;

use crate::{bad_generated, bad_scene, case_dir, check_success, data, render, report};

/// The driver's largest texture side (what `map_size` may be).
fn driver_max_texture_size() -> u32 {
    let ctx = shadowmap::engine::HeadlessContext::new()
        .unwrap_or_else(|e| panic!("headless EGL context: {e}"));
    shadowmap::engine::gl_limits(ctx.gl()).max_texture_size
}

#[test]
fn bad_scene_files_give_one_clear_error() {
    let max = driver_max_texture_size();
    let expected_max = format!("expected 1 to {max} (the driver's maximum texture size)");
    // Above the driver's maximum but below the file loader's own bound of 65536.
    let above_driver = (max + 1).to_string();
    let above_scene = format!("[light]\nangle = 45.0\n\n[shadow]\nmap_size = {above_driver}\n");
    let above_needle = format!("shadow.map_size = {above_driver}: {expected_max}");
    let five_lights = "[[lights]]\nangle = 45.0\n\n".repeat(5);
    let both_lights = "[light]\nangle = 45.0\n\n[[lights]]\nangle = 90.0\n";
    let bad_second_light = "[[lights]]\nangle = 45.0\n\n[[lights]]\nkind = \"point\"\n";
    let bad_scatter = "[light]\nangle = 45.0\n\n[[item]]\nmesh = \"cube\"\n\
                       scatter = { count = 0, area = [-1.0, 1.0, -1.0, 1.0] }\n";
    report(vec![
        bad_generated(
            "toml five lights",
            &[("scene.toml", five_lights.as_bytes())],
            &["lights: 5 lights: expected at most 4 (each has a texture unit and a block of the scene shader)"],
        ),
        bad_generated(
            "toml light and lights",
            &[("scene.toml", both_lights.as_bytes())],
            &["light: give either one [light] table or [[lights]] tables, not both"],
        ),
        bad_generated(
            "toml second light without position",
            &[("scene.toml", bad_second_light.as_bytes())],
            &["lights[1].position: a point light needs it"],
        ),
        bad_generated(
            "toml scatter count 0",
            &[("scene.toml", bad_scatter.as_bytes())],
            &["item[0].scatter.count: 0: expected 1 to 10000"],
        ),
        bad_generated(
            "toml sphere detail too small",
            &[(
                "scene.toml",
                b"[light]\nangle = 45.0\n\n[[item]]\nmesh = \"sphere\"\ndetail = [2, 2]\n",
            )],
            &["item[0].detail: [2, 2] for mesh 'sphere': expected [segments 3..512, rings 2..256]"],
        ),
        bad_generated(
            "toml no light",
            &[("scene.toml", b"name = \"dark\"\n")],
            &["light: missing: expected a [light] table or one to 4 [[lights]] tables"],
        ),
        bad_scene(
            "toml syntax error",
            "toml_syntax.toml",
            &["line 6, column 18, at `1.0 0.0`: string values must be quoted"],
        ),
        bad_scene(
            "toml unknown key",
            "toml_unknown_key.toml",
            &["line 7, column 1: unknown field `shininess`, expected one of"],
        ),
        bad_scene(
            "toml wrong type",
            "toml_wrong_type.toml",
            &["line 3, column 13: invalid type: string \"bright\", expected"],
        ),
        bad_scene(
            "toml NaN",
            "toml_nan.toml",
            &["light.intensity: line 3, column 13: NaN is not a finite number"],
        ),
        // The message must name the field, camera.far, not just the table.
        bad_scene(
            "toml inf",
            "toml_inf.toml",
            &["camera.far: line 3, column 7: inf is not a finite number"],
        ),
        bad_scene(
            "toml negative scale",
            "toml_negative_scale.toml",
            &["item[0].scale: [1.0, -1.0, 1.0]: expected a finite number > 0"],
        ),
        bad_scene(
            "toml zero scale",
            "toml_zero_scale.toml",
            &["item[0].scale: 0: expected a finite number > 0"],
        ),
        bad_scene(
            "toml map_size 0",
            "toml_map_size_zero.toml",
            &[&format!("shadow.map_size = 0: {expected_max}")],
        ),
        bad_scene(
            "toml map_size 1000000",
            "toml_map_size_huge.toml",
            &[&format!("shadow.map_size = 1000000: {expected_max}")],
        ),
        bad_generated(
            "toml map_size just above the driver's maximum",
            &[("scene.toml", above_scene.as_bytes())],
            &[&above_needle],
        ),
        bad_scene(
            "toml ortho near >= far",
            "toml_ortho_near_far.toml",
            &[
                "light.ortho: ",
                "near = 5, far = 5 }: near = 5 is not below far = 5",
                "expected",
                "near < far",
            ],
        ),
        bad_scene(
            "toml spot near >= far",
            "toml_spot_near_far.toml",
            &["light: near = 10, far = 1: expected 0 < near < far"],
        ),
        bad_scene(
            "toml item without mesh",
            "toml_no_mesh.toml",
            &["line 4, column 1: missing field `mesh`"],
        ),
        // mesh = "" and texture = "": the message should say a path is needed, not
        // ".../tests/data/bad/: ... Is a directory".
        bad_scene(
            "toml blank mesh path",
            "toml_blank_mesh.toml",
            &[
                "item[0].mesh: ",
                "expected a built-in mesh",
                "or a path to an OBJ",
            ],
        ),
        bad_scene(
            "toml blank texture path",
            "tex_blank_path.toml",
            &["item[0].texture: ", "expected a path to a PNG"],
        ),
        bad_scene(
            "toml scene file missing",
            "does_not_exist.toml",
            &["does_not_exist.toml: cannot read scene file: No such file"],
        ),
    ]);
}

#[test]
fn relative_paths_resolve_from_the_scene_folder() {
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let scene = data("relative/scene.toml");
    let elsewhere = case_dir("relative-cwd");
    let mut failures = Vec::new();
    // A relative scene path from tests/, and an absolute one from an unrelated folder.
    for (case, cwd, scene) in [
        (
            "relative scene path",
            tests.as_path(),
            "data/bad/relative/scene.toml",
        ),
        (
            "absolute scene path",
            elsewhere.as_path(),
            scene.to_str().unwrap(),
        ),
    ] {
        let (run, out) = render(case, cwd, scene, &[]);
        // The textured triangle (yellow texture) covers pixel (32, 20).
        failures.push(check_success(case, &run, &out, &[(32, 20)]).or_else(|| {
            let p = image::open(&out).unwrap().to_rgba8().get_pixel(32, 20).0;
            (p[0] < p[2].saturating_add(40)).then(|| {
                format!("[{case}] pixel (32, 20) is {p:?}: the yellow texture is not used")
            })
        }));
    }
    report(failures);
}

#[test]
fn scene_values_that_were_silently_accepted_give_one_clear_error() {
    report(vec![
        bad_scene(
            "toml size with a third number",
            "toml_size_three.toml",
            &["size: line 2, column 8: 3 values given: expected exactly 2 numbers"],
        ),
        bad_scene(
            "toml colour with a fifth number",
            "toml_colour_five.toml",
            &["item[0].colour: line 6, column 10: 5 values given: expected exactly 4 numbers"],
        ),
        bad_scene(
            "toml camera position of four",
            "toml_camera_four.toml",
            &["camera.position: line 5, column 12: 4 values given: expected exactly 3 numbers"],
        ),
        bad_scene(
            "toml polygon_offset of three",
            "toml_polygon_offset_three.toml",
            &["shadow.polygon_offset: line 5, column 18: 3 values given: expected exactly 2 numbers [factor, units]"],
        ),
        bad_generated(
            "toml sphere detail of three",
            &[(
                "scene.toml",
                b"[light]\nangle = 45.0\n\n[[item]]\nname = \"ball\"\nmesh = \"sphere\"\ndetail = [8, 8, 8]\n",
            )],
            &["item[0] (\"ball\").detail: line 7, column 10: 3 values given: expected exactly 2 numbers"],
        ),
        bad_generated(
            "toml scatter area of five",
            &[(
                "scene.toml",
                b"[light]\nangle = 45.0\n\n[[item]]\nmesh = \"cube\"\n\
                  scatter = { count = 2, area = [0.0, 1.0, 0.0, 1.0, 5.0] }\n",
            )],
            &["item[0].scatter.area: line 6, column 31: 5 values given: expected exactly 4 numbers"],
        ),
        bad_scene(
            "toml NaN in [steps]",
            "toml_steps_nan.toml",
            &["steps.bias: line 5, column 8: NaN is not a finite number"],
        ),
        bad_generated(
            "toml NaN in [shadow]",
            &[(
                "scene.toml",
                b"[light]\nangle = 45.0\n\n[shadow]\ncascade_lambda = nan\n",
            )],
            &["shadow.cascade_lambda: line 5, column 18: NaN is not a finite number"],
        ),
        bad_scene(
            "toml negative ambient",
            "toml_negative_ambient.toml",
            &["ambient: [0.3, -0.2, 0.3]: expected numbers >= 0"],
        ),
        bad_generated(
            "toml negative specular power",
            &[(
                "scene.toml",
                b"specular_power = -4.0\n\n[light]\nangle = 45.0\n",
            )],
            &["specular_power: -4: expected a number > 0"],
        ),
        bad_generated(
            "toml negative intensity",
            &[(
                "scene.toml",
                b"[light]\nangle = 45.0\nintensity = -0.5\n",
            )],
            &["light.intensity: -0.5: expected a number >= 0"],
        ),
        bad_scene(
            "toml ortho width overflows f32",
            "toml_ortho_overflow.toml",
            &["light.ortho: ", "right - left overflows 32-bit floats: expected a box less than"],
        ),
        bad_scene(
            "toml scale is a word",
            "toml_scale_word.toml",
            &["item[0] (\"crate\").scale: line 7, column 9: invalid type: string \"large\", \
               expected a number > 0 or three of them, [x, y, z]"],
        ),
        bad_generated(
            "toml number is a word",
            &[(
                "scene.toml",
                b"[light]\nangle = 45.0\n\n[[item]]\nmesh = \"cube\"\ntiles = \"many\"\n",
            )],
            &["item[0].tiles: line 6, column 9: invalid type: string \"many\", expected a number"],
        ),
        bad_scene(
            "toml misspelt built-in mesh",
            "toml_misspelt_mesh.toml",
            &[
                "item[0].mesh: 'cueb' is not a built-in mesh (cube, plane, sphere, terrain), \
                 and there is no OBJ file at ",
                "tests/data/bad/cueb",
            ],
        ),
        bad_scene(
            "toml field of another light kind",
            "toml_light_field_of_another_kind.toml",
            &["lights[1].fov: line 7, column 1: not used by a point light; it takes kind, \
               colour, intensity, position, near, far, oscillate, casts_shadows"],
        ),
        bad_generated(
            "toml invalid UTF-8",
            &[(
                "scene.toml",
                b"name = \"caf\xc3\xa9\"\n[light]\nangle = \xff45.0\n",
            )],
            &["scene.toml: cannot read scene file: line 3, column 9: byte 0xff is not UTF-8 text"],
        ),
    ]);
}
