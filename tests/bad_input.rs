//! Bad input, through the real binary: one clear error and a non-zero exit, never a panic, a
//! hang, a GL error or a black image. Every message must start with "error: ", name the file
//! (or the flag) and say what was expected; no output image may be written.
//!
//! Committed inputs live in tests/data/bad/ (each scene there can be tried by hand with
//! `shadowmap render --scene tests/data/bad/<case>.toml`); binary ones (PNGs, a binary OBJ) are
//! made here, in a folder under CARGO_TARGET_TMPDIR.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

/// No case may take longer than this (a hang is a failure).
const TIMEOUT: Duration = Duration::from_secs(120);

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/bad")
        .join(name)
}

/// A fresh, empty folder for one case's generated files and output.
fn case_dir(case: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("bad_input")
        .join(case.replace(|c: char| !c.is_ascii_alphanumeric(), "_"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

use common::Run;

/// Runs the binary in `cwd` with a time limit; a hang kills it and fails the case.
fn run_in(case: &str, cwd: &Path, args: &[&str]) -> Run {
    common::run_binary(case, cwd, args, TIMEOUT)
}

/// `shadowmap render --scene <scene> --out <dir>/x.png --size 64x36 <extra>`.
fn render(case: &str, cwd: &Path, scene: &str, extra: &[&str]) -> (Run, PathBuf) {
    let dir = case_dir(case);
    let out = dir.join("x.png");
    let mut args = vec![
        "render",
        "--scene",
        scene,
        "--out",
        out.to_str().unwrap(),
        "--size",
        "64x36",
    ];
    args.extend_from_slice(extra);
    (run_in(case, cwd, &args), out)
}

/// Checks one bad-input run; returns a description of what is wrong, or None.
/// `needles`: everything stderr must contain (the file or flag, the line or field, and what
/// was expected).
fn check_error(case: &str, run: &Run, out: &Path, needles: &[&str]) -> Option<String> {
    let e = &run.stderr;
    // Shown with --nocapture: what the user sees for each case.
    println!("[{case}] {}", e.trim_end().replace('\n', " | "));
    let mut wrong = Vec::new();
    if run.success {
        wrong.push("exit status 0".to_string());
    }
    if e.contains("panicked") {
        wrong.push("panicked".to_string());
    }
    if !e.starts_with("error: ") {
        wrong.push("stderr does not start with \"error: \"".to_string());
    }
    for n in needles {
        if !e.contains(n) {
            wrong.push(format!("stderr lacks {n:?}"));
        }
    }
    if out.exists() {
        wrong.push(format!("{} was written", out.display()));
    }
    (!wrong.is_empty()).then(|| {
        format!(
            "[{case}] {}\n    stderr: {}\n    stdout: {}",
            wrong.join("; "),
            e.trim_end().replace('\n', "\n            "),
            run.stdout.trim_end()
        )
    })
}

/// A bad committed scene: stderr must name the scene file and contain every needle.
fn bad_scene(case: &str, scene: &str, needles: &[&str]) -> Option<String> {
    let path = data(scene);
    let (run, out) = render(case, Path::new("."), path.to_str().unwrap(), &[]);
    let mut all = vec![scene];
    all.extend_from_slice(needles);
    check_error(case, &run, &out, &all)
}

/// A bad scene written to a temporary folder with its generated files.
fn bad_generated(case: &str, files: &[(&str, &[u8])], needles: &[&str]) -> Option<String> {
    let dir = case_dir(&format!("{case}-input"));
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let scene = dir.join("scene.toml");
    let (run, out) = render(case, Path::new("."), scene.to_str().unwrap(), &[]);
    let mut all = vec!["scene.toml"];
    all.extend_from_slice(needles);
    check_error(case, &run, &out, &all)
}

/// Fails with every broken case listed, so one run shows them all.
fn report(failures: Vec<Option<String>>) {
    let failures: Vec<String> = failures.into_iter().flatten().collect();
    assert!(
        failures.is_empty(),
        "{} case(s) failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A successful render: exit 0, the image written, and something other than the clear colour
/// drawn at each of `pixels` (x, y from the top left of the 64 x 36 frame).
fn check_success(case: &str, run: &Run, out: &Path, pixels: &[(u32, u32)]) -> Option<String> {
    println!(
        "[{case}] exit {}: {}",
        if run.success { "0" } else { "non-zero" },
        run.stdout.trim_end()
    );
    if !run.success || run.stderr.contains("panicked") {
        return Some(format!(
            "[{case}] must succeed but failed\n    stderr: {}",
            run.stderr.trim_end()
        ));
    }
    let image = match image::open(out) {
        Ok(i) => i.to_rgba8(),
        Err(e) => return Some(format!("[{case}] {} not readable: {e}", out.display())),
    };
    if image.dimensions() != (64, 36) {
        return Some(format!(
            "[{case}] image is {:?}, not 64x36",
            image.dimensions()
        ));
    }
    for &(x, y) in pixels {
        let p = image.get_pixel(x, y).0;
        if p[0].max(p[1]).max(p[2]) < 40 {
            return Some(format!(
                "[{case}] pixel ({x}, {y}) is {p:?}: the model is not drawn there (black image?)"
            ));
        }
    }
    None
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

/// The driver's largest texture side (what `map_size` may be).
fn driver_max_texture_size() -> u32 {
    let ctx = shadowmap::engine::HeadlessContext::new()
        .unwrap_or_else(|e| panic!("headless EGL context: {e}"));
    shadowmap::engine::gl_limits(ctx.gl()).max_texture_size
}

#[test]
fn crc32_matches_the_png_reference() {
    // The IEND chunk's CRC is fixed: AE 42 60 82.
    assert_eq!(common::crc32(b"IEND"), 0xae42_6082);
    assert_eq!(common::crc32(b"123456789"), 0xcbf4_3926);
}

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
                "near: 5.0, far: 5.0",
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
fn bad_cli_values_give_one_clear_error() {
    let here = Path::new(".");
    // `shadowmap render --out <tmp>/x.png <extra>` (the built-in scene unless `extra` names one).
    let cli = |case: &str, extra: &[&str], needles: &[&str]| {
        let out = case_dir(case).join("x.png");
        let mut args = vec!["render", "--out", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        let run = run_in(case, here, &args);
        check_error(case, &run, &out, needles)
    };
    let unwritable_dir = case_dir("unwritable-folder").join("no/such/folder/x.png");
    let unwritable_dir = unwritable_dir.to_str().unwrap();
    let unwritable = |case: &str, path: &str| {
        let run = run_in(
            case,
            here,
            &[
                "render", "--scene", "dummy", "--size", "64x36", "--out", path,
            ],
        );
        check_error(
            case,
            &run,
            Path::new(path),
            &[&format!("{path}: cannot write the image")],
        )
    };
    report(vec![
        cli(
            "--size 0x0",
            &["--size", "0x0"],
            &[
                "--size",
                "'0x0': expected WIDTHxHEIGHT with both at least 1",
            ],
        ),
        cli(
            "--size abc",
            &["--size", "abc"],
            &["--size", "'abc': expected WIDTHxHEIGHT"],
        ),
        cli(
            "--size 100000x100000",
            &["--size", "100000x100000"],
            &["100000x100000: expected each side from 1 to"],
        ),
        cli(
            "--scene nosuch",
            &["--size", "64x36", "--scene", "nosuch"],
            &["unknown scene 'nosuch': expected one of dummy"],
        ),
        cli(
            "--step nosuch",
            &["--size", "64x36", "--step", "nosuch"],
            &["'nosuch' for '--step", "depth-map", "pcf"],
        ),
        unwritable("--out /proc/x.png", "/proc/x.png"),
        unwritable("--out in a missing folder", unwritable_dir),
        cli(
            "--frames 0",
            &["--size", "64x36", "--frames", "0"],
            &["'0' for '--frames", "0 is not in 1.."],
        ),
        cli(
            "--light-angle nan",
            &["--size", "64x36", "--light-angle", "nan"],
            &["--light-angle NaN: expected degrees from 0 to 180"],
        ),
        cli(
            "--cascades 9",
            &["--size", "64x36", "--cascades", "9"],
            &["--cascades: shadow.cascades = 9: expected 1 (one map) to 4"],
        ),
        cli(
            "--cascade-lambda 2",
            &["--size", "64x36", "--cascade-lambda", "2"],
            &["--cascade-lambda: shadow.cascade_lambda = 2: expected 0 to 1"],
        ),
        cli(
            "--cascade-blend 0.9",
            &["--size", "64x36", "--cascade-blend", "0.9"],
            &["--cascade-blend: shadow.cascade_blend = 0.9: expected 0 to 0.5"],
        ),
        cli(
            "--depth-out of a point light",
            &[
                "--size",
                "64x36",
                "--depth-out",
                "/tmp/never.png",
                "--scene",
                "point-shadows",
            ],
            &["--depth-out /tmp/never.png: the first light has no 2D depth map"],
        ),
        {
            let case = "compare --light 3";
            let dir = case_dir(case);
            let args = ["compare", "--size", "64x36", "--light", "3", "--out-dir"];
            let mut args: Vec<&str> = args.to_vec();
            args.push(dir.to_str().unwrap());
            let run = run_in(case, here, &args);
            check_error(
                case,
                &run,
                &dir.join("metrics.json"),
                &["light 3: the scene <built-in dummy> has 1 light(s), numbered from 0"],
            )
        },
    ]);
}

#[test]
fn missing_egl_driver_names_the_packages_to_install() {
    // Point the EGL loader at a vendor file that does not exist: no driver can load.
    let dir = case_dir("no-egl");
    let out = Command::new(env!("CARGO_BIN_EXE_shadowmap"))
        .args(["render", "--size", "16x16", "--out"])
        .arg(dir.join("x.png"))
        .env("__EGL_VENDOR_LIBRARY_FILENAMES", dir.join("none.json"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success(),
        "rendering without a driver must fail"
    );
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(
        stderr.contains("apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!dir.join("x.png").exists());
}

/// Runs the demo in `dir` with no display at all.
fn demo_without_display(dir: &Path, args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_shadowmap"))
        .args(args)
        .current_dir(dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap()
}

/// The fallback's one line, as `demo` prints it.
fn fallback_line(frames: &str, path: &Path, replacing: bool) -> String {
    format!(
        "No display for a window (DISPLAY and WAYLAND_DISPLAY are not set): rendered {frames} \
         of the dummy scene headless to {}{} instead. For a window, run under X11: \
         `apt-get install xvfb`, `Xvfb :99 &`, then `DISPLAY=:99 shadowmap`.\n",
        path.display(),
        if replacing {
            " (replacing the file there)"
        } else {
            ""
        }
    )
}

#[test]
fn no_display_falls_back_to_a_headless_picture() {
    let dir = case_dir("no-display").canonicalize().unwrap();
    let demo_png = dir.join("shadowmap-demo.png");
    let out = demo_without_display(&dir, &[]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    // One line: no winit source path, nothing on standard error.
    assert_eq!(stdout, fallback_line("1 frame", &demo_png, false));
    assert_eq!(stderr, "");
    let png = std::fs::read(&demo_png).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let first = image::load_from_memory(&png).unwrap().to_rgba8();
    assert_eq!(
        first.dimensions(),
        (1280, 720),
        "the DummyGame's window size"
    );

    // Run again: the picture is replaced, and the line says so.
    let out = demo_without_display(&dir, &[]);
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        fallback_line("1 frame", &demo_png, true)
    );
}

#[test]
fn a_scripted_demo_without_display_renders_its_frames_headless_too() {
    // The same behaviour as `demo`: N frames headless, the last written to --screenshot.
    let dir = case_dir("no-display-scripted").canonicalize().unwrap();
    let shot = dir.join("shot.png");
    let out = demo_without_display(
        &dir,
        &[
            "demo",
            "--size",
            "64x36",
            "--exit-after-frames",
            "3",
            "--screenshot",
            "shot.png",
        ],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        fallback_line("3 frames", &shot, false)
    );
    let img = image::open(&shot).unwrap().to_rgba8();
    assert_eq!(img.dimensions(), (64, 36));
    // --screenshot is where it goes: the default picture is left alone.
    assert!(!dir.join("shadowmap-demo.png").exists());

    // Without --screenshot: the default picture, N frames.
    let out = demo_without_display(
        &dir,
        &["demo", "--size", "64x36", "--exit-after-frames", "2"],
    );
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        fallback_line("2 frames", &dir.join("shadowmap-demo.png"), false)
    );
}

#[test]
fn a_bad_screenshot_path_is_refused_before_anything_opens() {
    let dir = case_dir("no-display-bad-shot");
    for (path, expected) in [
        (
            "missing/shot.png",
            "cannot write the image (given to --screenshot): the folder missing does not exist",
        ),
        (
            "shot.jpg",
            "cannot write .jpg images (given to --screenshot)",
        ),
    ] {
        let out = demo_without_display(
            &dir,
            &["demo", "--exit-after-frames", "2", "--screenshot", path],
        );
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{path}");
        assert!(stderr.starts_with(&format!("error: {path}: ")), "{stderr}");
        assert!(stderr.contains(expected), "{stderr}");
        assert_eq!(
            String::from_utf8_lossy(&out.stdout),
            "",
            "{path}: nothing rendered"
        );
        assert!(!dir.join("shadowmap-demo.png").exists());
    }
}

#[test]
fn a_short_soak_reports_memory_and_no_error() {
    let out = Command::new(env!("CARGO_BIN_EXE_shadowmap"))
        .args(["soak", "--frames", "300", "--size", "64x36"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.starts_with("soak: 300 frames of the dummy scene"),
        "{stdout}"
    );
    assert!(stdout.contains("no error; resident memory"), "{stdout}");
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

/// `mkfifo path`: a named pipe, which blocks whoever opens it for reading until a writer
/// comes (none will).
fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success(), "mkfifo {}", path.display());
}

/// Runs `render` on a scene in `dir` (made by the caller) and checks the error.
fn bad_prepared(case: &str, dir: &Path, needles: &[&str]) -> Option<String> {
    let scene = dir.join("scene.toml");
    let (run, out) = render(case, Path::new("."), scene.to_str().unwrap(), &[]);
    check_error(case, &run, &out, needles)
}

#[test]
fn unreadable_inputs_are_refused_without_blocking() {
    let obj_scene = b"[light]\nangle = 45.0\n\n[[item]]\nmesh = \"model.obj\"\n";

    let fifo_scene = case_dir("fifo-scene-input");
    mkfifo(&fifo_scene.join("scene.toml"));

    let zero_scene = case_dir("zero-scene-input");
    std::os::unix::fs::symlink("/dev/zero", zero_scene.join("scene.toml")).unwrap();

    // 65 MiB without writing them: a sparse file.
    let huge_scene = case_dir("huge-scene-input");
    std::fs::File::create(huge_scene.join("scene.toml"))
        .unwrap()
        .set_len(65 << 20)
        .unwrap();

    let folder_scene = case_dir("folder-scene-input");
    std::fs::create_dir(folder_scene.join("scene.toml")).unwrap();

    let fifo_obj = case_dir("fifo-obj-input");
    std::fs::write(fifo_obj.join("scene.toml"), obj_scene).unwrap();
    mkfifo(&fifo_obj.join("model.obj"));

    let zero_obj = case_dir("zero-obj-input");
    std::fs::write(zero_obj.join("scene.toml"), obj_scene).unwrap();
    std::os::unix::fs::symlink("/dev/zero", zero_obj.join("model.obj")).unwrap();

    let huge_obj = case_dir("huge-obj-input");
    std::fs::write(huge_obj.join("scene.toml"), obj_scene).unwrap();
    std::fs::File::create(huge_obj.join("model.obj"))
        .unwrap()
        .set_len(513 << 20)
        .unwrap();

    let not_regular = "it is not a regular file but";
    report(vec![
        bad_prepared(
            "scene is a FIFO",
            &fifo_scene,
            &[
                "scene.toml: cannot read scene file: ",
                not_regular,
                "a FIFO",
            ],
        ),
        bad_prepared(
            "scene is /dev/zero",
            &zero_scene,
            &[
                "scene.toml: cannot read scene file: ",
                not_regular,
                "a character device",
            ],
        ),
        bad_prepared(
            "scene over 64 MiB",
            &huge_scene,
            &["scene.toml: cannot read scene file: it is larger than the limit of 64 MiB"],
        ),
        bad_prepared(
            "scene is a folder",
            &folder_scene,
            &[
                "scene.toml: cannot read scene file: ",
                not_regular,
                "a folder",
            ],
        ),
        bad_prepared(
            "obj is a FIFO",
            &fifo_obj,
            &[
                "item[0].mesh: ",
                "model.obj: cannot read OBJ model: ",
                not_regular,
                "a FIFO",
            ],
        ),
        bad_prepared(
            "obj is /dev/zero",
            &zero_obj,
            &[
                "item[0].mesh: ",
                "model.obj: cannot read OBJ model: ",
                not_regular,
                "a character device",
            ],
        ),
        bad_prepared(
            "obj over 512 MiB",
            &huge_obj,
            &["model.obj: cannot read OBJ model: it is larger than the limit of 512 MiB"],
        ),
        bad_scene(
            "obj face of two vertices",
            "obj_degenerate_face.toml",
            &[
                "item[0].mesh: ",
                "obj_degenerate_face.obj: not a valid OBJ model at line 5: a face with 2 \
                 corners: expected at least three",
                "refused, not dropped",
            ],
        ),
        bad_scene(
            "obj index that wraps in 32 bits",
            "obj_index_wrap.toml",
            &[
                "obj_index_wrap.obj: not a valid OBJ model at line 5: face index out of \
                 range: '4294967297', but there are 3 'v' lines before it",
            ],
        ),
    ]);
}
