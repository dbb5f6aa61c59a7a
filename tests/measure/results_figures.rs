//! docs/results.md against the scripts that write its figures and the program that measures
//! them: the learnopengl fitted box's error by map size is the table
//! `scripts/map-size-figures.py` wrote, under the command the doc cites, and that command
//! still gives the table's first and last rows.

use crate::common;

use std::collections::BTreeMap;
use std::path::Path;

fn read(path: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(root.join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The first "misclassified X%" a line of `compare` (or of a table) gives.
fn misclassified(text: &str) -> String {
    let re = regex::Regex::new(r"misclassified ([0-9.]+%)").unwrap();
    re.captures(text)
        .unwrap_or_else(|| panic!("no misclassified share in: {text}"))[1]
        .to_string()
}

/// The doc's sentence: the cited arguments (less `--map-size N`) and each size's share.
fn cited() -> (String, BTreeMap<u32, String>) {
    let doc = read("docs/results.md");
    let re =
        regex::Regex::new(r"`compare ([^`]+) --map-size N`:\s*((?:\d+ [0-9.]+%,?\s*)+);").unwrap();
    let c = re
        .captures(&doc)
        .expect("docs/results.md cites `compare ... --map-size N`: N X%, ...;");
    let pair = regex::Regex::new(r"(\d+) ([0-9.]+%)").unwrap();
    let figures = pair
        .captures_iter(&c[2])
        .map(|p| (p[1].parse().unwrap(), p[2].to_string()))
        .collect();
    (c[1].to_string(), figures)
}

/// The script's table: its command (less `--map-size N`) and each size's share.
fn written() -> (String, BTreeMap<u32, String>) {
    let table = read("assets/readme/map-sizes-learnopengl.md");
    let command = table
        .lines()
        .next()
        .and_then(|l| l.strip_prefix("`shadowmap compare "))
        .and_then(|l| l.split_once(" --map-size N`"))
        .map(|(args, _)| args.to_string())
        .expect("the table names its command first");
    let row = regex::Regex::new(r"(?m)^\| (\d+) \| ([0-9.]+%) \|").unwrap();
    let figures = row
        .captures_iter(&table)
        .map(|r| (r[1].parse().unwrap(), r[2].to_string()))
        .collect();
    (command, figures)
}

#[test]
fn the_map_size_figures_are_the_scripts_and_the_program_still_gives_them() {
    let (args, figures) = cited();
    let (script_args, table) = written();
    assert_eq!(args, script_args, "the doc's command is not the script's");
    assert!(args.contains("--view code"), "{args}");
    assert_eq!(figures, table, "docs/results.md against the script's table");
    let dir = tempfile::tempdir().unwrap();
    let (first, last) = (figures.keys().min().unwrap(), figures.keys().max().unwrap());
    for size in [first, last] {
        let out = common::stdout_of(
            common::bin()
                .arg("compare")
                .args(args.split(' '))
                .args(["--map-size", &size.to_string(), "--out-dir"])
                .arg(dir.path().join(size.to_string())),
        );
        let line = out
            .lines()
            .find(|l| l.starts_with("learnopengl ["))
            .unwrap_or_else(|| panic!("no summary line:\n{out}"));
        assert_eq!(
            misclassified(line),
            figures[size],
            "compare {args} --map-size {size}"
        );
    }
}
