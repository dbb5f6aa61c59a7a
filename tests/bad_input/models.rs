//! OBJ models and PNG textures that cannot be read, and OBJ models that render although
//! they are unusual (no normals, polygons).

use std::path::Path;

use crate::{bad_generated, bad_scene, check_success, common, data, render, report};

#[test]
fn crc32_matches_the_png_reference() {
    // The IEND chunk's CRC is fixed: AE 42 60 82.
    assert_eq!(common::crc32(b"IEND"), 0xae42_6082);
    assert_eq!(common::crc32(b"123456789"), 0xcbf4_3926);
}

/// Deterministic noise bytes.
fn noise(n: usize, seed: u32) -> Vec<u8> {
    let mut x = seed;
    (0..n)
        .map(|_| {
            x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (x >> 24) as u8
        })
        .collect()
}

/// A valid 32 x 32 RGBA PNG of noise (so the compressed data is not tiny).
fn valid_png() -> Vec<u8> {
    let pixels = noise(32 * 32 * 4, 7);
    let mut bytes = Vec::new();
    image::ImageEncoder::write_image(
        image::codecs::png::PngEncoder::new(&mut bytes),
        &pixels,
        32,
        32,
        image::ExtendedColorType::Rgba8,
    )
    .unwrap();
    bytes
}

/// A PNG whose header claims 100000 x 100000 RGBA pixels (40 GB).
fn absurd_png() -> Vec<u8> {
    common::png_claiming(100_000, 100_000)
}

const TEXTURED_SCENE: &[u8] =
    b"[light]\nangle = 45.0\n\n[[item]]\nmesh = \"cube\"\ntexture = \"tex.png\"\n";

#[test]
fn bad_obj_models_give_one_clear_error() {
    let binary: Vec<u8> = [b"\x7fELF\x02\x01\x01\x00".to_vec(), noise(120, 3)].concat();
    let obj = "item[0].mesh: ";
    report(vec![
        bad_scene(
            "obj missing",
            "obj_missing.toml",
            &[
                obj,
                "does_not_exist.obj: cannot read OBJ model: No such file",
            ],
        ),
        bad_scene(
            "obj is plain text",
            "obj_text.toml",
            &[
                obj,
                "obj_text.obj: the OBJ model has no faces: expected at least one 'f' line",
            ],
        ),
        bad_generated(
            "obj is binary",
            &[
                (
                    "scene.toml",
                    b"[light]\nangle = 45.0\n\n[[item]]\nmesh = \"model.obj\"\n",
                ),
                ("model.obj", &binary),
            ],
            &[obj, "model.obj: cannot read OBJ model", "UTF-8"],
        ),
        bad_scene(
            "obj truncated mid-number",
            "obj_truncated_number.toml",
            &[
                obj,
                "obj_truncated_number.obj: ",
                "at line 3: expected 'v x y z' with numbers",
            ],
        ),
        bad_scene(
            "obj truncated: face before its vertices",
            "obj_truncated_face.toml",
            &[
                obj,
                "obj_truncated_face.obj: ",
                "at line 3: face index out of range",
            ],
        ),
        bad_scene(
            "obj face index out of range",
            "obj_index_range.toml",
            &[
                obj,
                "obj_index_range.obj: ",
                "at line 4: face index out of range",
            ],
        ),
        bad_scene(
            "obj without faces",
            "obj_empty.toml",
            &[
                obj,
                "obj_empty.obj: the OBJ model has no faces: expected at least one 'f' line",
            ],
        ),
        bad_scene(
            "obj NaN coordinate",
            "obj_nan.toml",
            &[
                obj,
                "obj_nan.obj: ",
                "[NaN, 0.0, 0.0]: expected finite coordinates",
            ],
        ),
        bad_scene(
            "obj huge coordinate",
            "obj_huge.toml",
            &[
                obj,
                "obj_huge.obj: ",
                "[1e30, 0.0, 0.0]: expected finite coordinates within",
            ],
        ),
    ]);
}

#[test]
fn obj_models_without_normals_or_with_polygons_render() {
    let mut failures = Vec::new();
    let scene = data("obj_no_normals.toml");
    let (run, out) = render(
        "obj without normals",
        Path::new("."),
        scene.to_str().unwrap(),
        &[],
    );
    // The triangle's centroid, (0, -0.17) in the model, is near pixel (32, 20).
    failures.push(check_success(
        "obj without normals",
        &run,
        &out,
        &[(32, 20)],
    ));
    let scene = data("obj_polygons.toml");
    let (run, out) = render("obj polygons", Path::new("."), scene.to_str().unwrap(), &[]);
    // The quad's centre (-0.5, 0) and the pentagon's (0.5, 0.05): pixels (24, 18) and (40, 17).
    failures.push(check_success(
        "obj polygons",
        &run,
        &out,
        &[(24, 18), (40, 17)],
    ));
    report(failures);
}

#[test]
fn bad_png_textures_give_one_clear_error() {
    let tex = "item[0].texture: ";
    let png = valid_png();
    assert!(
        image::load_from_memory(&png).is_ok(),
        "the uncut PNG must be valid"
    );
    report(vec![
        bad_scene(
            "png missing",
            "tex_missing.toml",
            &[
                tex,
                "tex_does_not_exist.png: cannot read texture: No such file",
            ],
        ),
        bad_generated(
            "png is random bytes",
            &[("scene.toml", TEXTURED_SCENE), ("tex.png", &noise(200, 11))],
            &[
                tex,
                "tex.png: not a readable PNG texture",
                "expected a complete PNG file",
            ],
        ),
        bad_generated(
            "png truncated",
            &[
                ("scene.toml", TEXTURED_SCENE),
                ("tex.png", &png[..png.len() / 2]),
            ],
            &[
                tex,
                "tex.png: not a readable PNG texture",
                "expected a complete PNG file",
            ],
        ),
        bad_generated(
            "png claims 100000x100000",
            &[("scene.toml", TEXTURED_SCENE), ("tex.png", &absurd_png())],
            &[
                tex,
                "tex.png: not a readable PNG texture",
                "expected a PNG of at most 16384x16384 pixels",
            ],
        ),
    ]);
}
