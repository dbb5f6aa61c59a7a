//! Bad flags and output paths, and a machine without an EGL driver.

use std::path::Path;
use std::process::Command;

use crate::{case_dir, check_error, report, run_in};

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
            &[
                "'0' for '--frames",
                "expected a whole number of frames from 1 to 4294967295",
            ],
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
