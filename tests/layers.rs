//! The library's layers, checked from the source against their one description, the table
//! in `docs/architecture.md`: a module uses only the layers below it, every module of the
//! library has its row, and no two modules of one folder use each other (directly or round a
//! circle).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layer table of `docs/architecture.md`: each module named in its `modules` column
/// (back-quoted names) with the row's rank.
fn ranks() -> Vec<(String, u32)> {
    let doc = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/architecture.md");
    let text = std::fs::read_to_string(&doc).unwrap();
    let mut lines = text
        .lines()
        .skip_while(|l| !l.starts_with("| rank | layer | modules |"));
    assert!(
        lines.next().is_some(),
        "no layer table in {}",
        doc.display()
    );
    let mut out = Vec::new();
    for line in lines.skip(1).take_while(|l| l.starts_with('|')) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let rank: u32 = cells[1]
            .parse()
            .unwrap_or_else(|_| panic!("not a rank: {line}"));
        for name in cells[3].split('`').skip(1).step_by(2) {
            out.push((name.to_string(), rank));
        }
    }
    assert!(out.len() > 8, "the layer table names only {out:?}");
    out
}

/// The library's top-level modules, from `pub mod` lines of `src/lib.rs`.
fn library_modules() -> BTreeSet<String> {
    let lib = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs");
    std::fs::read_to_string(lib)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod "))
        .map(|l| l.trim_end_matches(';').to_string())
        .collect()
}

#[test]
fn the_layer_table_names_every_module_once() {
    let ranks = ranks();
    let named: Vec<&String> = ranks.iter().map(|(n, _)| n).collect();
    let unique: BTreeSet<String> = named.iter().map(|n| n.to_string()).collect();
    assert_eq!(unique.len(), named.len(), "a module in two rows: {named:?}");
    assert_eq!(
        unique,
        library_modules(),
        "docs/architecture.md against src/lib.rs"
    );
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The text without `//` comments, lines joined (so a `use` group over several lines reads
/// as one).
fn code_of(text: &str) -> String {
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The first identifier of `s` (after spaces).
fn ident(s: &str) -> String {
    s.trim_start()
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect()
}

/// Every module name that follows `prefix` in `code`: `prefix::a` gives `a`, and a group
/// `prefix::{a, b::c, d::{e, f}}` gives `a`, `b` and `d`.
fn names_after(code: &str, prefix: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut rest = code;
    while let Some(i) = rest.find(prefix) {
        rest = &rest[i + prefix.len()..];
        let Some(group) = rest.trim_start().strip_prefix('{') else {
            out.insert(ident(rest));
            continue;
        };
        // Split the group's top level at its commas.
        let (mut depth, mut start) = (0usize, 0usize);
        for (k, c) in group.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth == 0 => {
                    out.insert(ident(&group[start..k]));
                    break;
                }
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    out.insert(ident(&group[start..k]));
                    start = k + 1;
                }
                _ => {}
            }
        }
    }
    out.remove("");
    out
}

/// Every `crate::NAME` the text refers to (outside comments), groups included.
fn crate_refs(text: &str) -> BTreeSet<String> {
    names_after(&code_of(text), "crate::")
}

#[test]
fn grouped_and_nested_imports_are_read() {
    let code = code_of("use super::{a, b::c,\n d::{e, f}}; // super::x\nuse crate::g::h;");
    let names: Vec<String> = names_after(&code, "super::").into_iter().collect();
    assert_eq!(names, ["a", "b", "d"]);
    assert_eq!(crate_refs("use crate::{g, i::j};").len(), 2);
}

#[test]
fn no_module_uses_a_layer_of_its_rank_or_higher() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let ranks = ranks();
    let rank = |m: &str| ranks.iter().find(|(n, _)| n == m).map(|(_, r)| *r);
    let mut wrong = Vec::new();
    let mut checked = 0;
    for file in &files {
        let rel = file.strip_prefix(&src).unwrap();
        let top = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy()
            .trim_end_matches(".rs")
            .to_string();
        let Some(own) = rank(&top) else {
            continue; // lib.rs, main.rs and the program (app/) sit above everything
        };
        checked += 1;
        let text = std::fs::read_to_string(file).unwrap();
        for name in crate_refs(&text) {
            match rank(&name) {
                Some(r) if name != top && r >= own => {
                    wrong.push(format!("{} uses crate::{name}", rel.display()))
                }
                _ => {}
            }
        }
    }
    assert!(checked > 40, "only {checked} files checked");
    assert!(wrong.is_empty(), "layer violations:\n{}", wrong.join("\n"));
}

#[test]
fn no_import_circles_between_modules_of_one_folder() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    // Folder -> module -> the sibling modules it names (`super::x` or `crate::folder::x`).
    let mut graphs: BTreeMap<PathBuf, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for file in &files {
        let (Some(dir), Some(stem)) = (file.parent(), file.file_stem()) else {
            continue;
        };
        let stem = stem.to_string_lossy().to_string();
        if stem == "mod" || stem == "lib" || stem == "main" {
            continue;
        }
        let text = std::fs::read_to_string(file).unwrap();
        let folder = dir
            .strip_prefix(&src)
            .unwrap()
            .to_string_lossy()
            .to_string();
        let code = code_of(&text);
        let mut names = names_after(&code, "super::");
        names.extend(names_after(&code, &format!("crate::{folder}::")));
        names.remove(&stem);
        graphs
            .entry(dir.to_path_buf())
            .or_default()
            .insert(stem, names);
    }
    for (dir, graph) in &graphs {
        // Keep only edges to sibling files; then look for a circle by depth-first search.
        let edges: BTreeMap<&String, Vec<&String>> = graph
            .iter()
            .map(|(m, names)| (m, names.iter().filter(|n| graph.contains_key(*n)).collect()))
            .collect();
        fn visit<'a>(
            m: &'a String,
            edges: &BTreeMap<&'a String, Vec<&'a String>>,
            path: &mut Vec<&'a String>,
            done: &mut BTreeSet<&'a String>,
        ) -> Option<String> {
            if let Some(i) = path.iter().position(|p| *p == m) {
                let circle: Vec<&str> = path[i..].iter().map(|s| s.as_str()).collect();
                return Some(format!("{} -> {m}", circle.join(" -> ")));
            }
            if done.contains(m) {
                return None;
            }
            path.push(m);
            for n in edges.get(m).into_iter().flatten() {
                if let Some(c) = visit(n, edges, path, done) {
                    return Some(c);
                }
            }
            path.pop();
            done.insert(m);
            None
        }
        let mut done = BTreeSet::new();
        for m in edges.keys() {
            if let Some(circle) = visit(m, &edges, &mut Vec::new(), &mut done) {
                panic!("import circle in {}: {circle}", dir.display());
            }
        }
    }
}
