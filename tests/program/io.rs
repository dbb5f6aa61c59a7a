//! What the program reads and writes, through the real binary: a failed write is an error
//! (never "wrote ..."), PNG inputs are bounded, nothing is written or rendered before every
//! argument is checked, output names need a known extension, and long work says what it is
//! doing. (Tests may run as root, so a read-only folder is no test: /dev/full and a path
//! under a regular file are.)

use crate::common;

use std::path::{Path, PathBuf};
#[cfg(unix)]
use std::process::Command;
use std::time::Duration;

/// A fresh folder for one case.
fn case_dir(case: &str) -> PathBuf {
    common::case_dir("io", case)
}

use common::Run;

/// Runs the binary in `cwd`; a run that does not end in two minutes (a FIFO read, say) is
/// killed and fails the test.
fn run(cwd: &Path, args: &[&str]) -> Run {
    common::run_binary("io", cwd, args, Duration::from_secs(120))
}

/// Checks a run that must fail: exit status, one "error: " message holding every needle,
/// no panic and no "wrote" line.
fn fails(run: &Run, needles: &[&str]) -> Result<(), String> {
    let mut wrong = Vec::new();
    if run.success {
        wrong.push("exit status 0".to_string());
    }
    if !run.stderr.starts_with("error: ") && !run.stderr.contains("\nerror: ") {
        wrong.push("no \"error: \" line".into());
    }
    if run.stderr.contains("panicked") {
        wrong.push("panicked".into());
    }
    if run.stdout.contains("wrote") {
        wrong.push("stdout says it wrote".into());
    }
    for n in needles {
        if !run.stderr.contains(n) {
            wrong.push(format!("stderr lacks {n:?}"));
        }
    }
    match wrong.is_empty() {
        true => Ok(()),
        false => Err(format!(
            "{}\n    stderr: {}\n    stdout: {}",
            wrong.join("; "),
            run.stderr.trim_end(),
            run.stdout.trim_end()
        )),
    }
}

/// Runs every case and reports all failures together.
fn report(cases: Vec<(String, Result<(), String>)>) {
    let failures: Vec<String> = cases
        .into_iter()
        .filter_map(|(name, r)| r.err().map(|e| format!("[{name}] {e}")))
        .collect();
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Every entry of `dir` (to show that nothing was left behind).
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map(|d| {
            d.flatten()
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

#[test]
#[cfg(unix)] // /dev/full, /dev/stdout, FIFOs
fn a_failed_write_is_an_error_naming_the_path() {
    let dir = case_dir("failed-write");
    let plain = dir.join("plain-file");
    std::fs::write(&plain, b"not a folder").unwrap();
    let under_file = plain.join("x.png");
    let out = dir.join("frame.png");
    let render = |extra: &[&str]| {
        let mut args = vec!["render", "--size", "32x18"];
        args.extend_from_slice(extra);
        run(&dir, &args)
    };
    let full = "/dev/full: cannot write the image: No space left on device";
    let mut cases = vec![
        (
            "--out /dev/full".to_string(),
            fails(&render(&["--out", "/dev/full"]), &[full]),
        ),
        (
            "--shadow-out /dev/full".into(),
            fails(
                &render(&["--out", s(&out), "--shadow-out", "/dev/full"]),
                &[full],
            ),
        ),
        (
            "--depth-out /dev/full".into(),
            fails(
                &render(&["--out", s(&out), "--depth-out", "/dev/full"]),
                &[full],
            ),
        ),
        (
            "--out under a regular file".into(),
            fails(
                &render(&["--out", s(&under_file)]),
                &[
                    &format!(
                        "{}: cannot write the image (given to --out)",
                        s(&under_file)
                    ),
                    "plain-file is a file, not a folder",
                ],
            ),
        ),
    ];
    // The folder commands, with the folder under a regular file or a regular file itself.
    for command in ["compare", "bench", "steps"] {
        for (what, target) in [
            ("under a file", plain.join("out")),
            ("a file", plain.clone()),
        ] {
            let r = run(&dir, &[command, "--size", "32x18", "--out-dir", s(&target)]);
            let expected = match what {
                "a file" => "it is a file; expected a folder",
                _ => "is a file, so no folder can be made inside it",
            };
            cases.push((
                format!("{command} --out-dir {what}"),
                fails(
                    &r,
                    &[
                        "cannot use it as the output folder (given to --out-dir)",
                        expected,
                    ],
                ),
            ));
        }
    }
    report(cases);
    // Nothing but the plain file was left behind (no temporary files either).
    assert_eq!(entries(&dir), ["plain-file"]);
}

#[test]
#[cfg(unix)] // /dev/full, /dev/stdout, FIFOs
fn a_device_that_takes_bytes_is_written_in_place() {
    let dir = case_dir("device");
    let r = run(&dir, &["render", "--size", "16x16", "--out", "/dev/null"]);
    assert!(r.success, "{}", r.stderr);
    assert!(r.stdout.starts_with("wrote /dev/null"), "{}", r.stdout);
    assert!(entries(&dir).is_empty(), "{:?}", entries(&dir));
    // /dev/stdout is a link to a pipe here: the PNG goes down the pipe.
    let r = run(&dir, &["render", "--size", "16x16", "--out", "/dev/stdout"]);
    assert!(r.success, "{}", r.stderr);
    // (stdout is read as lossy UTF-8: the signature's first byte turns into U+FFFD.)
    assert!(
        r.stdout.starts_with("\u{FFFD}PNG\r\n") && r.stdout.contains("IHDR"),
        "{:?}",
        r.stdout.chars().take(12).collect::<String>()
    );
    assert!(entries(&dir).is_empty(), "{:?}", entries(&dir));
}

/// A scene whose cube wears the texture at `texture` (absolute, or relative to the scene).
#[cfg(unix)]
fn textured_scene(dir: &Path, texture: &str) -> PathBuf {
    let path = dir.join("scene.toml");
    std::fs::write(
        &path,
        format!("[light]\nangle = 45.0\n\n[[item]]\nmesh = \"cube\"\ntexture = \"{texture}\"\n"),
    )
    .unwrap();
    path
}

/// A PNG header claiming `side` x `side` RGBA pixels (inside the side limit, over the
/// memory budget), with a few bytes of data.
#[cfg(unix)]
fn huge_png(side: u32) -> Vec<u8> {
    common::png_claiming(side, side)
}

#[test]
#[cfg(unix)] // /dev/full, /dev/stdout, FIFOs
fn png_inputs_are_regular_files_of_bounded_size_and_memory() {
    let mut cases = Vec::new();
    let mut check = |case: &str, texture: &str, prepare: &dyn Fn(&Path), needles: &[&str]| {
        let dir = case_dir(case);
        prepare(&dir);
        let scene = textured_scene(&dir, texture);
        let out = dir.join("x.png");
        let r = run(
            &dir,
            &[
                "render",
                "--size",
                "32x18",
                "--scene",
                s(&scene),
                "--out",
                s(&out),
            ],
        );
        let mut result = fails(&r, needles);
        if result.is_ok() && out.exists() {
            result = Err("x.png was written".into());
        }
        cases.push((case.to_string(), result));
    };
    let not_regular = "cannot read texture: not a regular file (a folder, device or pipe); \
                       expected a PNG file";
    check(
        "texture is a FIFO",
        "fifo.png",
        &|dir| {
            let ok = Command::new("mkfifo")
                .arg(dir.join("fifo.png"))
                .status()
                .is_ok_and(|s| s.success());
            assert!(ok, "mkfifo failed");
        },
        &["item[0].texture: ", "fifo.png: ", not_regular],
    );
    check(
        "texture is /dev/zero",
        "/dev/zero",
        &|_| {},
        &["item[0].texture: ", "/dev/zero: ", not_regular],
    );
    check(
        "texture is a folder",
        "sub",
        &|dir| std::fs::create_dir(dir.join("sub")).unwrap(),
        &["item[0].texture: ", not_regular],
    );
    check(
        "texture file over the size limit",
        "big.png",
        &|dir| {
            // Sparse: 65 MiB on paper, nothing on disk.
            let f = std::fs::File::create(dir.join("big.png")).unwrap();
            f.set_len(65 * 1024 * 1024).unwrap();
        },
        &[
            "big.png: cannot read texture: larger than 64 MiB; expected a PNG file of at most \
             that size",
        ],
    );
    check(
        "texture over the decoded budget",
        "huge.png",
        &|dir| std::fs::write(dir.join("huge.png"), huge_png(9000)).unwrap(),
        &[
            "huge.png: not a usable PNG texture: 9000x9000 pixels take ",
            "MiB decoded, over the 256 MiB budget for a texture",
        ],
    );
    report(cases);
}

#[test]
fn nothing_is_rendered_or_written_before_every_argument_is_checked() {
    let dir = case_dir("validate-first");
    let out = dir.join("frame.png");
    let folder = dir.join("results");
    let cases: Vec<(&str, Vec<&str>, Vec<&str>)> = vec![
        (
            "bench --target-error nan",
            vec!["bench", "--target-error", "nan", "--out-dir", s(&folder)],
            vec!["'nan'", "--target-error", "expected a fraction from 0 to 1"],
        ),
        (
            "bench --target-error 2",
            vec!["bench", "--target-error", "2", "--out-dir", s(&folder)],
            vec!["'2'", "expected a fraction from 0 to 1"],
        ),
        (
            "bench --bias -1",
            vec!["bench", "--bias", "-1", "--out-dir", s(&folder)],
            vec!["--bias: shadow.bias = -1: expected 0 to 1"],
        ),
        (
            "render --shadow-out in a missing folder",
            vec![
                "render",
                "--out",
                s(&out),
                "--shadow-out",
                "missing/dir/x.png",
            ],
            vec![
                "missing/dir/x.png: cannot write the image (given to --shadow-out): the folder \
                 missing/dir does not exist",
            ],
        ),
        (
            "render --depth-out with an unknown extension",
            vec!["render", "--out", s(&out), "--depth-out", "depth.tga"],
            vec!["depth.tga: cannot write .tga images (given to --depth-out)"],
        ),
        (
            "render --shadow-out the same as --out",
            vec!["render", "--out", s(&out), "--shadow-out", s(&out)],
            vec!["--shadow-out: the same file as --out"],
        ),
        (
            "compare --light 7",
            vec!["compare", "--light", "7", "--out-dir", s(&folder)],
            vec!["--light 7: the scene <built-in dummy> has 1 light(s), numbered from 0"],
        ),
        (
            "compare --light 3 of three-lights (a fill light)",
            vec![
                "compare",
                "--scene",
                "three-lights",
                "--light",
                "3",
                "--out-dir",
                s(&folder),
            ],
            vec!["--light 3: that light of <built-in three-lights> does not cast shadows"],
        ),
        (
            "compare --cascade-blend 0.9",
            vec!["compare", "--cascade-blend", "0.9", "--out-dir", s(&folder)],
            vec!["--cascade-blend: shadow.cascade_blend = 0.9: expected 0 to 0.5"],
        ),
        (
            "steps --light-angle 181",
            vec!["steps", "--light-angle", "181", "--out-dir", s(&folder)],
            vec!["--light-angle 181: expected degrees from 0 to 180"],
        ),
    ];
    let mut results = Vec::new();
    for (name, args, needles) in cases {
        let r = run(&dir, &args);
        let mut result = fails(&r, &needles);
        if result.is_ok() && !entries(&dir).is_empty() {
            result = Err(format!("left {:?} behind", entries(&dir)));
        }
        // Refused before the sweep: no "bench: ..." progress either.
        if result.is_ok() && r.stderr.contains("configurations") {
            result = Err(format!("started the sweep: {}", r.stderr));
        }
        results.push((name.to_string(), result));
    }
    report(results);
}

#[test]
fn output_images_need_a_png_name() {
    let dir = case_dir("extensions");
    let mut results = Vec::new();
    for (flag, name, shown) in [
        ("--out", "frame.jpg", ".jpg"),
        ("--out", "frame.JPEG", ".jpeg"),
        ("--shadow-out", "shadow.bmp", ".bmp"),
        ("--depth-out", "depth", "extension-less"),
    ] {
        let mut args = vec!["render", "--size", "16x16"];
        if flag != "--out" {
            args.extend(["--out", "frame.png"]);
        }
        args.extend([flag, name]);
        let r = run(&dir, &args);
        let mut result = fails(
            &r,
            &[&format!(
                "{name}: cannot write {shown} images (given to {flag}); expected a file name \
                 ending in .png"
            )],
        );
        if result.is_ok() && !entries(&dir).is_empty() {
            result = Err(format!("left {:?} behind", entries(&dir)));
        }
        results.push((format!("{flag} {name}"), result));
    }
    report(results);
    // Upper case is the same extension.
    let r = run(&dir, &["render", "--size", "16x16", "--out", "FRAME.PNG"]);
    assert!(r.success, "{}", r.stderr);
    let bytes = std::fs::read(dir.join("FRAME.PNG")).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn compare_says_what_it_is_doing_and_what_the_colours_mean() {
    let dir = case_dir("compare-progress");
    let out = dir.join("cmp");
    let r = run(
        &dir,
        &[
            "compare",
            "--size",
            "200x120",
            "--supersample",
            "2",
            "--out-dir",
            s(&out),
        ],
    );
    assert!(r.success, "{}", r.stderr);
    // stderr is a pipe here: plain lines, one when each step starts and one when it ends.
    for line in [
        "compare: tracing the exact reference for the dummy scene at 200x120 (and 2x2 supersampled) ...",
        "compare: rendering light 0's shadow test (",
    ] {
        assert!(r.stderr.contains(line), "{}", r.stderr);
    }
    assert!(
        r.stdout.contains("red = false shadow") && r.stdout.contains("blue = false light"),
        "{}",
        r.stdout
    );
    assert!(r.stdout.contains("wrote "), "{}", r.stdout);
    // error.png keeps the frame's rows and adds its legend below them.
    let vis = image::open(out.join("visibility.png")).unwrap().to_rgba8();
    let err = image::open(out.join("error.png")).unwrap().to_rgba8();
    assert_eq!(err.width(), vis.width());
    assert!(err.height() > vis.height(), "no legend band");
    let below: Vec<[u8; 4]> = (vis.height()..err.height())
        .flat_map(|y| (0..err.width()).map(move |x| (x, y)))
        .map(|(x, y)| err.get_pixel(x, y).0)
        .collect();
    for colour in [[255, 0, 0, 255], [0, 0, 255, 255]] {
        assert!(below.contains(&colour), "the legend lacks {colour:?}");
    }
    // Dark text on white: the legend has words, not only swatches.
    assert!(below.iter().any(|p| p[..3].iter().all(|&c| c < 60)));
}

#[test]
fn bench_reports_progress_from_the_start() {
    let dir = case_dir("bench-progress");
    let out = dir.join("bench");
    let r = run(
        &dir,
        &[
            "bench",
            "--quick",
            "--frames",
            "1",
            "--warmup",
            "0",
            "--supersample",
            "1",
            "--size",
            "32x18",
            "--out-dir",
            s(&out),
        ],
    );
    assert!(r.success, "{}", r.stderr);
    let lines: Vec<&str> = r.stderr.lines().collect();
    // What is being done is said before it is done, first of all the context.
    assert!(
        lines[0].starts_with("bench: opening a headless OpenGL context"),
        "{}",
        r.stderr
    );
    // The count it announces, then each line names its phase and the configuration, out of
    // two passes over them.
    let count: usize = (r.stderr.lines())
        .find_map(|l| {
            l.strip_prefix("bench: ")?
                .split_once(" configurations of ")?
                .0
                .parse()
                .ok()
        })
        .unwrap_or_else(|| panic!("no count of configurations: {}", r.stderr));
    assert!(count > 20, "{count} configurations");
    let steps = 2 * count;
    for needle in [
        "bench: tracing the exact reference at 32x18 ...".to_string(),
        format!("[1/{steps}] pass 1 of 2, compiling and timing: "),
        format!("[{steps}/{steps}] pass 2 of 2, timing and scoring against the reference: "),
    ] {
        assert!(r.stderr.contains(&needle), "lacks {needle:?}: {}", r.stderr);
    }
    for f in ["bench.csv", "bench.md", "pareto.png"] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    assert!(entries(&out).len() == 3, "{:?}", entries(&out));
}
