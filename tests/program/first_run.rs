//! A first run through the real binary: help that fits the terminal, a folder given where an
//! image belongs said as a folder, and every file a command writes named once on its output
//! (and no name printed for a file that was not written).

use crate::common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// clap's width when standard output is not a terminal.
const HELP_WIDTH: usize = 100;

/// A fresh folder for one case.
fn case_dir(case: &str) -> PathBuf {
    common::case_dir("first_run", case)
}

/// The subcommands the top-level help lists (without `help`).
fn subcommands() -> Vec<String> {
    let help = common::stdout_of(common::bin().env_remove("COLUMNS").arg("--help"));
    let (_, after) = help.split_once("Commands:\n").expect("a Commands section");
    after
        .lines()
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .map(String::from)
        .collect()
}

#[test]
fn help_fits_the_width_clap_wraps_to() {
    let commands = subcommands();
    assert!(commands.len() >= 7, "{commands:?}");
    let mut runs: Vec<Vec<String>> = vec![vec!["-h".into()], vec!["--help".into()]];
    for c in &commands {
        runs.push(vec![c.clone(), "-h".into()]);
        runs.push(vec![c.clone(), "--help".into()]);
    }
    let mut long = Vec::new();
    for args in &runs {
        let help = common::stdout_of(common::bin().env_remove("COLUMNS").args(args));
        assert!(help.lines().count() > 5, "{args:?}: {help}");
        for line in help.lines() {
            let width = line.chars().count();
            if width > HELP_WIDTH {
                long.push(format!("{args:?} ({width}): {line}"));
            }
        }
    }
    assert!(
        long.is_empty(),
        "lines over {HELP_WIDTH}:\n{}",
        long.join("\n")
    );
}

#[test]
fn a_folder_for_an_image_is_said_to_be_a_folder() {
    let dir = case_dir("folder-out");
    std::fs::create_dir_all(dir.join("shots")).unwrap();
    for (flag, given, instead) in [
        ("--out", "shots", "shots/frame.png"),
        ("--out", "shots/", "shots/frame.png"),
        ("--out", "new-folder/", "new-folder/frame.png"),
        ("--shadow-out", "shots", "shots/shadow.png"),
        ("--depth-out", "shots/", "shots/depth.png"),
    ] {
        let mut args = vec!["render", "--size", "16x16"];
        if flag != "--out" {
            args.extend(["--out", "frame.png"]);
        }
        args.extend([flag, given]);
        let out = common::bin()
            .current_dir(&dir)
            .args(&args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(
            stderr.contains(&format!(
                "{given}: cannot write the image (given to {flag}): it"
            )) && stderr.contains(&format!("folder; expected a file name such as {instead}")),
            "{args:?}: {stderr}"
        );
        assert!(!stderr.contains("extension-less"), "{stderr}");
        let left = files_under(&dir);
        assert!(left.is_empty(), "{args:?} left {left:?}");
    }
}

/// Every file under `dir`, relative to it (folders not listed).
fn files_under(dir: &Path) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let path = e.path();
            match path.is_dir() {
                true => stack.push(path),
                false => {
                    let rel = path.strip_prefix(dir).unwrap();
                    found.insert(rel.to_string_lossy().into_owned());
                }
            }
        }
    }
    found
}

/// The words of `text` that end in the extension of a file the commands write.
fn printed_names(text: &str) -> Vec<String> {
    let exts = [".png", ".csv", ".md", ".json", ".npy", ".html", ".txt"];
    text.split(|c: char| c.is_whitespace() || ",:;()[]".contains(c))
        .filter(|w| exts.iter().any(|e| w.ends_with(e)))
        .map(String::from)
        .collect()
}

/// Runs `args` in a fresh `case` folder: every file that appears there is named exactly once
/// on the output (by its name, or its path below the folder), and every file a "wrote" line
/// names was written.
fn announces_each_file_once(case: &str, args: &[&str]) -> String {
    let dir = case_dir(case);
    let out = common::bin().current_dir(&dir).args(args).output().unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{args:?}: {stderr}");
    let written = files_under(&dir);
    assert!(!written.is_empty(), "{args:?} wrote nothing");
    let all = format!("{stdout}\n{stderr}");
    let names_file = |p: &str, file: &str| {
        let p = p.trim_start_matches("./");
        p == file || file.ends_with(&format!("/{p}"))
    };
    for file in &written {
        let times = printed_names(&all)
            .iter()
            .filter(|p| names_file(p, file))
            .count();
        assert_eq!(times, 1, "{args:?}: {file} named {times} times:\n{all}");
    }
    let announced: Vec<String> = all
        .lines()
        .filter(|l| l.starts_with("wrote "))
        .flat_map(printed_names)
        .collect();
    assert!(!announced.is_empty(), "{args:?}: no \"wrote\" line:\n{all}");
    for p in &announced {
        assert!(
            written.iter().any(|f| names_file(p, f)),
            "{args:?}: {p} announced but not written ({written:?}):\n{all}"
        );
    }
    stderr.into_owned()
}

#[test]
fn render_names_each_written_file_once() {
    announces_each_file_once(
        "render",
        &[
            "render",
            "--size",
            "64x48",
            "--map-size",
            "256",
            "--out",
            "o.png",
            "--shadow-out",
            "s.png",
            "--depth-out",
            "d.png",
        ],
    );
    announces_each_file_once(
        "render-plain",
        &["render", "--size", "64x48", "--out", "only.png"],
    );
}

/// Without a terminal each progress line is printed once, ended with its result; the
/// tracing's own time and the whole step's are both named.
#[test]
fn compare_names_each_written_file_once() {
    let stderr = announces_each_file_once(
        "compare",
        &[
            "compare",
            "--size",
            "80x60",
            "--supersample",
            "1",
            "--out-dir",
            "cmp",
        ],
    );
    let tracing: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("compare: tracing the exact reference"))
        .collect();
    assert_eq!(tracing.len(), 1, "{stderr}");
    assert!(
        tracing[0].contains(" ... 14 caster triangles, rays traced in ")
            && tracing[0].ends_with(" s in all"),
        "{stderr}"
    );
    assert_eq!(
        stderr
            .lines()
            .filter(|l| l.starts_with("compare: rendering light 0's shadow test"))
            .count(),
        1,
        "{stderr}"
    );
}

#[test]
fn steps_names_each_written_file_once() {
    announces_each_file_once("steps", &["steps", "--size", "80x60", "--out-dir", "st"]);
}

#[test]
fn bench_names_each_written_file_once() {
    announces_each_file_once(
        "bench",
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
            "bench",
        ],
    );
}
