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
    // A group right after `super::` is read as its members' paths.
    let paths = module_refs("use super::{a, b::c};", &["m".into(), "n".into()]);
    assert_eq!(paths, [vec!["m", "a"], vec!["m", "b", "c"]]);
}

#[test]
fn no_module_uses_a_layer_of_its_rank_or_higher() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let ranks = ranks();
    let rank = |m: &str| ranks.iter().find(|(n, _)| n == m).map(|(_, r)| *r);
    // The crate root's re-exports (`crate::bench` is `measure`'s, `crate::Renderer` the
    // renderer's) count as the layer they come from.
    let modules: BTreeSet<Vec<String>> = files.iter().map(|f| module_path(&src, f)).collect();
    let lib = code_of(&std::fs::read_to_string(src.join("lib.rs")).unwrap());
    let exports = re_exports(&[(Vec::new(), lib)], &modules);
    let top_of = |name: String| match exports.get(&(Vec::new(), name.clone())) {
        Some(path) => path[0].clone(),
        None => name,
    };
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
        for name in crate_refs(&text).into_iter().map(top_of) {
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

/// A module's path from the crate root: `src/shadows/volumetric/mod.rs` and
/// `src/shadows/map2d.rs` give `["shadows", "volumetric"]` and `["shadows", "map2d"]`.
fn module_path(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut path: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().to_string())
        .collect();
    if matches!(
        path.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        path.pop();
    }
    path
}

/// Every path a `use` tree or expression starting at `code[at..]` names, its segments
/// expanded through groups: `a::{b, c::{d, e}}` gives `a::b`, `a::c::d` and `a::c::e`.
fn paths_at(code: &str) -> Vec<Vec<String>> {
    fn tree(s: &str, prefix: &[String], out: &mut Vec<Vec<String>>) {
        let mut path = prefix.to_vec();
        let mut rest = s;
        loop {
            // A group, at the start (`super::{a, b}`) or after a segment.
            if let Some(group) = rest.trim_start().strip_prefix('{') {
                let (mut depth, mut start) = (0usize, 0usize);
                for (k, c) in group.char_indices() {
                    match c {
                        '{' => depth += 1,
                        '}' if depth == 0 => {
                            tree(&group[start..k], &path, out);
                            return;
                        }
                        '}' => depth -= 1,
                        ',' if depth == 0 => {
                            tree(&group[start..k], &path, out);
                            start = k + 1;
                        }
                        _ => {}
                    }
                }
                return;
            }
            let name = ident(rest);
            if name.is_empty() {
                break;
            }
            rest = rest.trim_start()[name.len()..].trim_start();
            path.push(name);
            match rest.strip_prefix("::") {
                Some(r) => rest = r.trim_start(),
                None => break,
            }
        }
        out.push(path);
    }
    let mut out = Vec::new();
    tree(code, &[], &mut out);
    out
}

/// The modules a file (at `own`, its module path) refers to through `crate::` and `super::`
/// paths, each as the full path named (the caller finds the module in it).
fn module_refs(code: &str, own: &[String]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let bytes = code.as_bytes();
    for (at, _) in code
        .match_indices("crate::")
        .chain(code.match_indices("super::"))
    {
        let before = at.checked_sub(1).map(|b| bytes[b] as char);
        if before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_' || c == ':') {
            continue; // the middle of a path (`super::super::x`) is read from its start
        }
        // `super` is the parent of the file's module; a folder's own file is its module.
        let mut base: Vec<String> = own.to_vec();
        let mut rest = &code[at..];
        if let Some(r) = rest.strip_prefix("crate::") {
            base.clear();
            rest = r;
        } else {
            while let Some(r) = rest.strip_prefix("super::") {
                base.pop();
                rest = r.trim_start();
            }
        }
        for p in paths_at(rest) {
            out.push(base.iter().cloned().chain(p).collect());
        }
    }
    out
}

/// For each folder module, a circle among its children, if any: a child is a file or a
/// whole sub-folder, and child A uses child B when any file inside A names anything inside
/// B. The folder's own file (`mod.rs`, or `x.rs` beside `x/`) holds the children and is
/// left out. This finds circles at any depth: `cache -> casters -> volumetric -> patch ->
/// cache` in `shadows` is one when a file in `shadows/volumetric/` names `shadows::patch`.
fn circles(src: &Path) -> Vec<String> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let modules: BTreeSet<Vec<String>> = files.iter().map(|f| module_path(src, f)).collect();
    // Each file's module and the modules it names (the longest known prefix of each path).
    let codes: Vec<(Vec<String>, String)> = files
        .iter()
        .map(|f| {
            let text = std::fs::read_to_string(f).unwrap();
            (module_path(src, f), code_of(library_part(&text)))
        })
        .collect();
    let exports = re_exports(&codes, &modules);
    let mut uses: Vec<(Vec<String>, BTreeSet<Vec<String>>)> = Vec::new();
    for (own, code) in &codes {
        let named = module_refs(code, own)
            .iter()
            .filter_map(|path| module_named(path, &modules, &exports))
            .collect();
        uses.push((own.clone(), named));
    }
    let mut found = Vec::new();
    for parent in modules.iter().filter(|m| !m.is_empty()) {
        let depth = parent.len();
        let child_of = |m: &Vec<String>| {
            (m.len() > depth && m[..depth] == parent[..]).then(|| m[depth].clone())
        };
        let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (own, named) in &uses {
            let Some(from) = child_of(own) else { continue };
            let entry = edges.entry(from.clone()).or_default();
            entry.extend(named.iter().filter_map(child_of).filter(|to| *to != from));
        }
        if let Some(circle) = first_circle(&edges) {
            found.push(format!("{}: {circle}", parent.join("::")));
        }
    }
    found
}

/// The part of a file the library is built from: up to its `#[cfg(test)] mod tests`
/// (a unit test may open a context to test a part below it).
fn library_part(text: &str) -> &str {
    text.find("#[cfg(test)]\nmod ").map_or(text, |i| &text[..i])
}

/// What each module re-exports: (the module, the name it exports) to the path it names,
/// from its `pub use` and `pub(crate) use` lines (`pub use camera::{camera, fit}` in
/// `shadows::map2d` exports `camera` as `shadows::map2d::camera::camera`).
fn re_exports(
    codes: &[(Vec<String>, String)],
    modules: &BTreeSet<Vec<String>>,
) -> BTreeMap<(Vec<String>, String), Vec<String>> {
    let mut out = BTreeMap::new();
    for (own, code) in codes {
        for keyword in ["pub use ", "pub(crate) use ", "pub(super) use "] {
            for (at, _) in code.match_indices(keyword) {
                let tree = &code[at + keyword.len()..];
                let tree = &tree[..tree.find(';').unwrap_or(tree.len())];
                for path in exported_paths(tree, own, modules) {
                    let name = path.last().cloned().unwrap_or_default();
                    out.insert((own.clone(), name), path);
                }
            }
        }
    }
    out
}

/// The absolute paths a `pub use` tree of module `own` names: `crate::`, `super::` and
/// `self::` as in [`module_refs`], and a bare first segment as a child module of `own`
/// (or, when `own` has no such child, a crate from outside, left out).
fn exported_paths(tree: &str, own: &[String], modules: &BTreeSet<Vec<String>>) -> Vec<Vec<String>> {
    let mut base: Vec<String> = own.to_vec();
    let mut rest = tree.trim_start();
    if let Some(r) = rest.strip_prefix("crate::") {
        base.clear();
        rest = r;
    } else if let Some(r) = rest.strip_prefix("self::") {
        rest = r;
    } else {
        while let Some(r) = rest.strip_prefix("super::") {
            base.pop();
            rest = r.trim_start();
        }
    }
    paths_at(rest)
        .into_iter()
        .map(|p| base.iter().cloned().chain(p).collect::<Vec<_>>())
        .filter(|p| p.len() > own.len().min(base.len()) && modules.contains(&p[..p.len() - 1]))
        .collect()
}

/// The module a path names: its longest prefix that is a module, followed through the
/// re-exports of that module when the next segment is one (`engine::ShaderProgram` is
/// `engine::shader_program`'s), so a `pub use` cannot hide a circle.
fn module_named(
    path: &[String],
    modules: &BTreeSet<Vec<String>>,
    exports: &BTreeMap<(Vec<String>, String), Vec<String>>,
) -> Option<Vec<String>> {
    let mut path = path.to_vec();
    for _ in 0..16 {
        let n = (1..=path.len())
            .rev()
            .find(|&n| modules.contains(&path[..n]))?;
        let Some(next) = path.get(n) else {
            return Some(path);
        };
        let Some(target) = exports.get(&(path[..n].to_vec(), next.clone())) else {
            return Some(path[..n].to_vec());
        };
        if target[..] == path[..=n] {
            return Some(path[..n].to_vec());
        }
        path = target.iter().chain(&path[n + 1..]).cloned().collect();
    }
    None
}

/// The first circle of a directed graph by depth-first search, as `a -> b -> a`.
fn first_circle(edges: &BTreeMap<String, BTreeSet<String>>) -> Option<String> {
    fn visit<'a>(
        m: &'a String,
        edges: &'a BTreeMap<String, BTreeSet<String>>,
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
    edges
        .keys()
        .find_map(|m| visit(m, edges, &mut Vec::new(), &mut done))
}

#[test]
fn no_import_circles_at_any_depth() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let found = circles(&src);
    assert!(found.is_empty(), "import circles:\n{}", found.join("\n"));
}

#[test]
fn a_circle_through_a_nested_folder_is_found() {
    // cache -> casters -> volumetric (a folder, through its own file) -> patch (named from
    // inside the folder) -> cache, and a two-file circle across folders.
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path();
    let write = |rel: &str, text: &str| {
        let path = src.join(rel);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    };
    write("lib.rs", "pub mod shadows;");
    write(
        "shadows/mod.rs",
        "pub mod cache; pub mod casters; pub mod patch;",
    );
    write("shadows/cache.rs", "use super::casters::may_land;");
    write(
        "shadows/casters.rs",
        "fn f() { super::volumetric::draw_solid(); }",
    );
    write("shadows/volumetric/mod.rs", "mod resolved;");
    write(
        "shadows/volumetric/resolved.rs",
        "use crate::shadows::{patch::TexelRect};",
    );
    write("shadows/patch.rs", "use super::cache::LightFacts;");
    let found = circles(src);
    assert_eq!(
        found,
        ["shadows: cache -> casters -> volumetric -> patch -> cache"]
    );
    // Broken at one edge, no circle is left; a folder's own file naming its children is
    // not one.
    write("shadows/casters.rs", "");
    write("shadows/patch.rs", "use super::volumetric::Maps;");
    write(
        "shadows/volumetric/mod.rs",
        "mod resolved; use resolved::X; use super::cache;",
    );
    assert_eq!(circles(src), ["shadows: patch -> volumetric -> patch"]);
    write("shadows/patch.rs", "");
    assert!(circles(src).is_empty(), "{:?}", circles(src));
    // `super::super::` from a nested file.
    write("shadows/program.rs", "use super::volumetric::receivers;");
    write(
        "shadows/volumetric/receivers.rs",
        "use super::super::program::light_part;",
    );
    assert_eq!(circles(src), ["shadows: program -> volumetric -> program"]);
    // Through a re-export: `super::Program` is `program`'s, which the folder's own file
    // re-exports, so the circle through it is seen.
    write("shadows/volumetric/receivers.rs", "");
    write(
        "shadows/mod.rs",
        "pub mod cache; pub mod casters; pub mod patch; pub mod program; \
         pub use program::{Program, light_part};",
    );
    write("shadows/cache.rs", "use super::Program;");
    write(
        "shadows/program.rs",
        "fn f() -> super::casters::X { todo!() }",
    );
    write("shadows/casters.rs", "use super::cache::Y;");
    assert_eq!(
        circles(src),
        ["shadows: cache -> program -> casters -> cache"]
    );
}

#[test]
fn the_architecture_page_names_every_source_file() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    // The architecture page and its index of files, read as one.
    let doc = ["docs/architecture.md", "docs/source-files.md"]
        .map(|d| std::fs::read_to_string(root.join(d)).unwrap())
        .join("\n");
    let src = root.join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let missing: Vec<String> = files
        .iter()
        .map(|f| {
            f.strip_prefix(&src)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/")
        })
        .filter(|rel| !doc.contains(&format!("`{rel}`")) && !doc.contains(&format!("`src/{rel}`")))
        .collect();
    assert!(
        missing.is_empty(),
        "docs/architecture.md and docs/source-files.md do not name: {missing:?}"
    );
    // And every file it names under `src/` is there.
    let named: Vec<&str> = doc
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|t| t.ends_with(".rs") && !t.contains(' '))
        .collect();
    // A bare name (`casters.rs`, beside the folder the sentence names) is some file's name.
    rust_files(&root.join("tests"), &mut files);
    let exists = |t: &str| match t.contains('/') {
        true => src.join(t.trim_start_matches("src/")).exists() || root.join(t).exists(),
        false => files.iter().any(|f| f.file_name().is_some_and(|n| n == t)),
    };
    let gone: Vec<&&str> = named.iter().filter(|t| !exists(t)).collect();
    assert!(
        gone.is_empty(),
        "docs/architecture.md or docs/source-files.md names files that are not there: {gone:?}"
    );
}

/// The tests' layout (docs/architecture.md, "The tests"): one binary per area, a folder whose
/// `main.rs` names every file beside it; at the top only the window and browser tests,
/// which `.ci/run` runs on their own.
#[test]
fn every_test_file_is_a_module_of_its_area() {
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let doc = std::fs::read_to_string(tests.join("../docs/architecture.md")).unwrap();
    let mut loose = Vec::new();
    let mut areas = 0;
    for entry in std::fs::read_dir(&tests).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if path.is_file() {
            if !["window.rs", "web.rs"].contains(&name.as_str()) {
                loose.push(name);
            }
            continue;
        }
        let main = path.join("main.rs");
        if !main.exists() {
            continue; // common/ and data/: shared, not an area
        }
        areas += 1;
        assert!(
            doc.contains(&format!("`tests/{name}/`")),
            "docs/architecture.md's test table has no row for tests/{name}/"
        );
        let main = std::fs::read_to_string(main).unwrap();
        for file in std::fs::read_dir(&path).unwrap() {
            let file = file.unwrap().path();
            let stem = file.file_stem().unwrap().to_string_lossy().to_string();
            let named = stem == "main"
                || main.contains(&format!("mod {stem};"))
                || is_included(&path, &stem);
            assert!(
                named,
                "tests/{name}/{stem}.rs is not a module of its area's main.rs"
            );
        }
    }
    assert!(areas >= 6, "only {areas} areas");
    assert!(loose.is_empty(), "test files outside an area: {loose:?}");
}

/// Whether some file of `dir` includes `stem.rs` as a module of its own (`#[path]`).
fn is_included(dir: &Path, stem: &str) -> bool {
    std::fs::read_dir(dir).unwrap().any(|f| {
        std::fs::read_to_string(f.unwrap().path())
            .is_ok_and(|t| t.contains(&format!("#[path = \"{stem}.rs\"]")))
    })
}
