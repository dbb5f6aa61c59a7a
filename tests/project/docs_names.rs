//! The code names the docs cite, against the code. Re-pointing a name after a move is an
//! edit of the doc alone: nothing here names a file of src/ or shaders/.
//!
//! What counts as a cited code name (the heuristics, kept simple):
//! - Only `inline code` outside fenced blocks is read. A token with a space, an `=`, a quote, a
//!   leading `-` (a flag) or arguments in parentheses is a command, setting or expression, and
//!   is not looked up.
//! - A path (with a `/`) rooted at src/, shaders/, tests/, scripts/, docs/, examples/, assets/
//!   or benches/ must exist (`*` and `{a,b}` expanded). A bare source file name (`maps.rs`,
//!   `volume.geom`) must end the path of some source file.
//! - `A::b::C` paths: every segment must be a name the code defines; `{A, B}` lists are split.
//!   A path whose first segment is a module of src/ (`shadows::plan`, `shadowmap::` and
//!   `crate::` dropped) is walked as the compiler would: each segment a module (`x.rs`,
//!   `x/mod.rs`) of the one before, until one the last module's file defines or re-exports.
//! - A CONSTANT (`SHADOW_MASK_READ`), a camelCase name (a GLSL function or variable:
//!   `calcShadow`), a PascalCase type and a `call()` must appear as a whole word in the
//!   program: src/, shaders/, examples/, scripts/, comment lines and unit tests (`tests.rs`,
//!   an inline `#[cfg(test)] mod`) left out. OpenGL's names (`GL_*`, `gl*`, `gl_*`, `glm::`)
//!   are not looked up, nor placeholders (`crate::X`). A plain lowercase word is also a
//!   setting's or a step's name (`shadow_cache`, `bias`): looked up only when paired.
//! - Paired with a file: a name directly followed by ` (`path`...`, `, `path`` or
//!   ` in `path`` is paired with that path (unless that path opens a claim: `path`:), and
//!   so is the name right after `path` (`name`...; a `path`: followed by a colon pairs
//!   every name after it in its clause (up to `;`, a table cell's end or a sentence's end)
//!   that has no pair of its own, until the next path.
//!   A name paired with a source file must be defined in that file (or under that folder): a
//!   Rust fn, struct, enum, trait, type, const, static, mod, field or variant; a GLSL
//!   function, declaration, `#define` or `#ifdef`; or be a string there (a uniform the file
//!   sets, a step it names). A name beside a test (tests/...) is not looked up there.
//! - The chapters' own names are not the program's: a table column headed "the chapter
//!   says", "the book", "section" or "the slide's point" is the chapter's text, and
//!   `CHAPTER_NAMES` lists, per doc, the names its prose quotes from the chapters.

use std::path::{Path, PathBuf};

use super::{markdown_files, root};

/// Names a doc's prose quotes from the chapters (or from GL and GLSL, not defined here), by
/// doc. A name here is not looked up in the program.
const CHAPTER_NAMES: &[(&str, &[&str])] = &[
    (
        "docs/reading-guide.md",
        &[
            "renderDepthMap",
            "renderScene",
            "simpleDepthShader",
            "LinearizeDepth",
            "planeVertices",
            "renderCube",
            "depth_vertex.vs",
            "depth_fragment.fs",
            "scene_vertex.vs",
            "scene_fragment.fs",
            "RenderScene",
        ],
    ),
    ("docs/techniques/perspective-depth.md", &["LinearizeDepth"]),
];

/// Markdown headers whose column holds the chapter's names, not the program's.
const CHAPTER_COLUMNS: &[&str] = &["the chapter", "the book", "section", "the slide"];

/// Folders whose files are the program whose names the docs cite.
const CODE_DIRS: &[&str] = &["src", "shaders", "examples", "scripts"];

/// Roots a cited path may start from.
const PATH_ROOTS: &[&str] = &[
    "src", "shaders", "tests", "scripts", "docs", "examples", "assets", "benches",
];

/// Extensions of source files, whose bare names (`maps.rs`) are looked up.
const SOURCE_EXTENSIONS: &[&str] = &[".rs", ".glsl", ".frag", ".vert", ".geom", ".sh", ".py"];

struct Code {
    /// Every source file (repository-relative, `/`-separated) and its program text.
    files: Vec<(String, String)>,
    /// Every file of the source folders and tests, for bare file names.
    all_paths: Vec<String>,
    words: std::collections::HashSet<String>,
    definitions: std::collections::HashMap<String, std::collections::HashSet<String>>,
}

fn all_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            all_files(&path, out);
        } else {
            out.push(path);
        }
    }
}

fn relative(path: &Path) -> String {
    let rel = path.strip_prefix(root()).unwrap();
    rel.to_string_lossy().replace('\\', "/")
}

/// A source file's program: comment lines and an inline test module left out.
fn program_text(text: &str) -> String {
    let mut out = String::new();
    let lines: Vec<&str> = text.lines().collect();
    for (i, line) in lines.iter().enumerate() {
        let t = line.trim_start();
        if t.starts_with("#[cfg(test)]") {
            let next = lines[i + 1..].iter().find(|l| !l.trim().is_empty());
            if next.is_some_and(|l| l.trim_end().ends_with('{')) {
                break;
            }
        }
        // Rust and GLSL comment lines, and the shell scripts' (`# `).
        if t.starts_with("//") || t.starts_with("/*") || t.starts_with('*') || t.starts_with("# ") {
            continue;
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

/// The names a file defines (see the heuristics above).
fn definitions_in(text: &str) -> Vec<String> {
    use regex::Regex;
    use std::sync::OnceLock;
    static PATTERNS: OnceLock<Vec<Regex>> = OnceLock::new();
    let patterns = PATTERNS.get_or_init(|| {
        [
            // Rust items.
            r"\b(?:(?:const\s+)?fn|struct|enum|trait|type|const|static|mod|union)\s+([A-Za-z_]\w*)",
            r"macro_rules!\s*([A-Za-z_]\w*)",
            // Rust variants (`Name,` `Name(` `Name {` `Name =`) and fields (`name: T`).
            r"(?m)^\s*([A-Z]\w*)\s*(?:[,({]|=[^=])",
            r"(?m)^\s*(?:pub(?:\([a-z ]+\))?\s+)?([A-Za-z_]\w*)\s*:[^:]",
            // GLSL functions, declarations and parameters, in shaders or generated by Rust.
            r"\b(?:void|float|int|uint|bool|[iu]?vec[234]|mat[234]|sampler\w*)\s+([A-Za-z_]\w*)\s*[\[(;,=)]",
            r"#\s*(?:define|ifdef|ifndef)\s+([A-Za-z_]\w*)",
            r"defined\s*\(\s*([A-Za-z_]\w*)",
        ]
        .iter()
        .map(|p| Regex::new(p).unwrap())
        .collect()
    });
    patterns
        .iter()
        .flat_map(|p| p.captures_iter(text).map(|c| c[1].to_string()))
        .collect()
}

impl Code {
    fn load() -> Code {
        let mut paths = Vec::new();
        for dir in CODE_DIRS.iter().chain(&["tests", "benches"]) {
            all_files(&root().join(dir), &mut paths);
        }
        let all_paths: Vec<String> = paths.iter().map(|p| relative(p)).collect();
        let mut files = Vec::new();
        let mut words = std::collections::HashSet::new();
        let mut definitions = std::collections::HashMap::<_, std::collections::HashSet<_>>::new();
        let word = regex::Regex::new(r"[A-Za-z_]\w*").unwrap();
        for (path, rel) in paths.iter().zip(&all_paths) {
            let code = CODE_DIRS.iter().any(|d| rel.starts_with(&format!("{d}/")));
            if !code || rel.ends_with("/tests.rs") || rel.contains("/tests/") {
                continue;
            }
            let Ok(text) = std::fs::read_to_string(path) else {
                continue;
            };
            let text = program_text(&text);
            words.extend(word.find_iter(&text).map(|m| m.as_str().to_string()));
            for name in definitions_in(&text) {
                definitions.entry(name).or_default().insert(rel.clone());
            }
            files.push((rel.clone(), text));
        }
        Code {
            files,
            all_paths,
            words,
            definitions,
        }
    }

    /// The file of the module at `path` (`src/shadows/plan`): `path.rs` or `path/mod.rs`.
    fn module_file(&self, path: &str) -> Option<&(String, String)> {
        let (file, folder) = (format!("{path}.rs"), format!("{path}/mod.rs"));
        self.files.iter().find(|(f, _)| *f == file || *f == folder)
    }

    /// What is wrong with a `::` path that starts at a module of src/: a segment that is
    /// neither a module of the one before nor an item its file defines or re-exports.
    /// `None` for a path that does not start at a module (`Scene::load`).
    fn module_path_error(&self, segments: &[String]) -> Option<String> {
        let uses = regex::Regex::new(r"\bpub(?:\([a-z ]+\))?\s+use\s+([^;]*);").unwrap();
        let mut dir = String::from("src");
        let mut file = None;
        for (i, segment) in segments.iter().enumerate() {
            let path = format!("{dir}/{segment}");
            if let Some(module) = self.module_file(&path) {
                (dir, file) = (path, Some(module));
                continue;
            }
            let (name, text) = file?;
            let defined = definitions_in(text).iter().any(|d| d == segment);
            let word = regex::Regex::new(&format!(r"\b{segment}\b")).unwrap();
            // A `pub use` of the name, or a glob over the module's own folder.
            let exported = uses.captures_iter(text).any(|c| {
                let glob = c[1].contains('*') && self.defined_in(segment, &format!("{dir}/"));
                word.is_match(&c[1]) || glob
            });
            if defined || exported {
                return None;
            }
            return Some(format!(
                "`{}`: `{segment}` is no module of `{}` (`{dir}/{segment}.rs`) nor defined in \
                 `{name}`",
                segments[..=i].join("::"),
                segments[..i].join("::"),
            ));
        }
        None
    }

    /// Whether `name` is defined in `place`: a file (`src/a.rs`), a folder (`src/a/`) or a
    /// bare file name (`a.rs`, any file whose path ends so).
    fn defined_in(&self, name: &str, place: &str) -> bool {
        let Some(files) = self.definitions.get(name) else {
            return false;
        };
        files.iter().any(|f| {
            if place.ends_with('/') {
                f.starts_with(place)
            } else if PATH_ROOTS
                .iter()
                .any(|r| place.starts_with(&format!("{r}/")))
            {
                f == place
            } else {
                f.ends_with(&format!("/{place}"))
            }
        })
    }
}

/// What a piece of inline code in a doc is, for the check.
#[derive(Debug, PartialEq)]
enum Cited {
    /// A path from the repository's root.
    Path(String),
    /// A source file's bare name, or a path relative to some folder (`shadow_map/fbo.rs`).
    File(String),
    /// A code name: the names that must exist (one, or a `::` path's segments), the one a
    /// paired file must define, and whether it is checked only when paired.
    Name {
        all: Vec<String>,
        last: String,
        only_paired: bool,
        /// The `::` paths cited (a `{A, B}` list gives one a name), segment by segment.
        paths: Vec<Vec<String>>,
    },
    Skip,
}

fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// OpenGL's, GLSL's and glm's own names (`GL_NONE`, `glFinish`, `gl_FragDepth`, `glm::ortho`).
fn is_opengl(name: &str) -> bool {
    let upper_after = |prefix: &str| {
        name.strip_prefix(prefix)
            .is_some_and(|r| r.starts_with(|c: char| c.is_ascii_uppercase()))
    };
    let gl = upper_after("gl") || upper_after("glu");
    gl || name.starts_with("GL_") || name.starts_with("gl_") || name == "glm"
}

fn classify(token: &str) -> Cited {
    let t = token.trim();
    if t.is_empty()
        || t.contains(' ')
        || t.contains('=')
        || t.contains('"')
        || t.starts_with('-')
        || t.starts_with('<')
        || t.contains("://")
    {
        return Cited::Skip;
    }
    if t.contains('/') {
        let first = t.split('/').next().unwrap();
        if PATH_ROOTS.contains(&first) {
            return Cited::Path(t.to_string());
        }
        return match SOURCE_EXTENSIONS.iter().any(|e| t.ends_with(e)) {
            true => Cited::File(t.to_string()),
            false => Cited::Skip,
        };
    }
    if SOURCE_EXTENSIONS.iter().any(|e| t.ends_with(e)) {
        return Cited::File(t.to_string());
    }
    // `name()` is a call; `name(args)` an expression; `name[i]` an array.
    let (t, call) = match t.strip_suffix("()") {
        Some(name) => (name, true),
        None => (t, false),
    };
    let t = t.split('[').next().unwrap();
    if t.contains('(') || t.contains('.') {
        return Cited::Skip;
    }
    if t.contains("::") {
        let segments: Vec<String> = t
            .replace(['{', '}'], "")
            .split("::")
            .flat_map(|s| s.split(','))
            .map(|s| s.trim().to_string())
            .filter(|s| !["crate", "self", "super"].contains(&s.as_str()))
            .collect();
        let placeholder = |s: &String| s.len() == 1;
        if segments.is_empty()
            || !segments.iter().all(|s| is_identifier(s))
            || segments.iter().any(placeholder)
            || is_opengl(&segments[0])
        {
            return Cited::Skip;
        }
        return Cited::Name {
            last: segments.last().unwrap().clone(),
            all: segments,
            only_paired: false,
            paths: module_paths(t),
        };
    }
    if !is_identifier(t) || is_opengl(t) {
        return Cited::Skip;
    }
    let upper = t.chars().any(|c| c.is_ascii_uppercase());
    Cited::Name {
        all: vec![t.to_string()],
        last: t.to_string(),
        // A plain lowercase word is a setting, a step or a name alike.
        only_paired: !upper && !call,
        paths: Vec::new(),
    }
}

/// The `::` paths of a token, `a::{b, c}` as `a::b` and `a::c`, each without its leading
/// `crate`, `self`, `super` or `shadowmap`.
fn module_paths(token: &str) -> Vec<Vec<String>> {
    let split = |p: &str| -> Vec<String> {
        let segments: Vec<String> = p.split("::").map(|s| s.trim().to_string()).collect();
        let skip = segments
            .iter()
            .take_while(|s| ["crate", "self", "super", "shadowmap"].contains(&s.as_str()))
            .count();
        segments[skip..].to_vec()
    };
    match token.split_once('{') {
        Some((head, list)) => list
            .trim_end_matches('}')
            .split(',')
            .map(|alt| split(&format!("{head}{}", alt.trim())))
            .collect(),
        None => vec![split(token)],
    }
}

/// Splits `text` at `sep` characters outside inline code.
fn split_outside_code<'a>(text: &'a str, seps: &[&str]) -> Vec<&'a str> {
    let mut out = Vec::new();
    let mut inside = false;
    let mut start = 0;
    let mut i = 0;
    while i < text.len() {
        let rest = &text[i..];
        if rest.starts_with('`') {
            inside = !inside;
        } else if !inside {
            if let Some(sep) = seps.iter().find(|s| rest.starts_with(**s)) {
                out.push(&text[start..i]);
                i += sep.len();
                start = i;
                continue;
            }
        }
        i += rest.chars().next().unwrap().len_utf8();
    }
    out.push(&text[start..]);
    out
}

/// The inline code of a clause, each with the text after it up to the next.
fn inline_code(clause: &str) -> Vec<(&str, &str)> {
    let pieces: Vec<&str> = clause.split('`').collect();
    (1..pieces.len())
        .step_by(2)
        .map(|i| (pieces[i], pieces.get(i + 1).copied().unwrap_or("")))
        .collect()
}

/// The clauses of a doc to check, as (line, text): paragraphs and list items joined, table
/// cells apart, fenced blocks and the chapters' columns left out, split at `;` and at
/// sentence ends.
fn clauses(text: &str) -> Vec<(usize, String)> {
    let mut blocks: Vec<(usize, String)> = Vec::new();
    let mut fenced = false;
    let mut chapter_columns: Vec<usize> = Vec::new();
    let lines: Vec<&str> = text.lines().collect();
    let mut open = false;
    for (i, line) in lines.iter().enumerate() {
        let t = line.trim();
        if t.starts_with("```") {
            fenced = !fenced;
            open = false;
            continue;
        }
        if fenced || t.is_empty() || t.starts_with('#') {
            open = false;
            continue;
        }
        if t.starts_with('|') {
            open = false;
            let cells = split_outside_code(t.trim_matches('|'), &["|"]);
            if lines
                .get(i + 1)
                .is_some_and(|l| l.trim().starts_with("|--"))
            {
                chapter_columns = (0..cells.len())
                    .filter(|c| {
                        let head = cells[*c].trim().to_lowercase();
                        CHAPTER_COLUMNS.iter().any(|h| head.starts_with(h))
                    })
                    .collect();
            }
            for (c, cell) in cells.iter().enumerate() {
                if !chapter_columns.contains(&c) && !cell.trim().starts_with("--") {
                    blocks.push((i + 1, cell.to_string()));
                }
            }
            continue;
        }
        if open && !t.starts_with("- ") {
            blocks.last_mut().unwrap().1.push(' ');
            blocks.last_mut().unwrap().1.push_str(t);
        } else {
            blocks.push((i + 1, t.to_string()));
            open = true;
        }
    }
    blocks
        .into_iter()
        .flat_map(|(line, block)| {
            split_outside_code(&block, &[";", ". "])
                .into_iter()
                .map(|c| (line, c.to_string()))
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Each code name of a clause with the file it is paired with, if any.
fn paired(clause: &str) -> Vec<(Cited, Option<String>)> {
    let code = inline_code(clause);
    let cited: Vec<Cited> = code.iter().map(|(c, _)| classify(c)).collect();
    let path_of = |c: &Cited| match c {
        Cited::Path(p) | Cited::File(p) => Some(p.clone()),
        _ => None,
    };
    let mut out = Vec::new();
    let mut claim: Option<String> = None;
    // `path` (`name`...: the name right after the parenthesis.
    let mut once: Option<String> = None;
    for (i, c) in cited.into_iter().enumerate() {
        let after = code[i].1;
        if let Some(path) = path_of(&c) {
            claim = after.trim_start().starts_with(':').then(|| path.clone());
            once = (after == " (").then(|| path.clone());
            out.push((c, None));
            continue;
        }
        // A path that opens a claim of its own (`path`: ...) is not this name's.
        let next_path = code
            .get(i + 1)
            .filter(|(_, rest)| !rest.trim_start().starts_with(':'))
            .and_then(|(n, _)| path_of(&classify(n)));
        let own = next_path.filter(|_| [" (", ", ", " in ", " (in "].contains(&after));
        let pair = own.or(once.take()).or_else(|| claim.clone());
        out.push((c, pair));
    }
    out
}

/// Whether `pattern` (a path, maybe with `*` and `{a,b}`) names an existing file or folder.
fn path_exists(pattern: &str) -> bool {
    if let (Some(open), Some(close)) = (pattern.find('{'), pattern.find('}')) {
        let (head, tail) = (&pattern[..open], &pattern[close + 1..]);
        return pattern[open + 1..close]
            .split(',')
            .all(|alt| path_exists(&format!("{head}{}{tail}", alt.trim())));
    }
    if let Some(star) = pattern.find('*') {
        let (dir, name) = pattern.rsplit_once('/').unwrap();
        let (before, after) = name.split_at(star - dir.len() - 1);
        let after = &after[1..];
        let Ok(entries) = std::fs::read_dir(root().join(dir)) else {
            return false;
        };
        return entries.flatten().any(|e| {
            let n = e.file_name().to_string_lossy().to_string();
            n.starts_with(before) && n.ends_with(after)
        });
    }
    root().join(pattern).exists()
}

/// What is wrong with one cited piece of code, if anything.
fn citation_error(code: &Code, cited: &Cited, pair: Option<&str>) -> Option<String> {
    match cited {
        Cited::Skip => None,
        Cited::Path(p) => (!path_exists(p)).then(|| format!("`{p}` does not exist")),
        Cited::File(f) => {
            let file = code.all_paths.iter().any(|p| p.ends_with(&format!("/{f}")));
            // The generated includes are files the program names, not files on disk.
            let named = code
                .files
                .iter()
                .any(|(_, t)| t.contains(&format!("\"{f}\"")));
            (!file && !named).then(|| format!("no source file is `{f}`"))
        }
        Cited::Name {
            all,
            last,
            only_paired,
            paths,
        } => {
            if let Some(e) = paths.iter().find_map(|p| code.module_path_error(p)) {
                return Some(e);
            }
            let multi = all.len() > 1;
            let missing = all.iter().find(|n| match multi {
                true => !code.definitions.contains_key(*n),
                false => !code.words.contains(*n),
            });
            if let Some(n) = missing.filter(|_| !*only_paired || pair.is_some()) {
                return Some(format!("`{n}` is not in the program"));
            }
            // tests/ and docs/ are cited for what they show, not for what they define.
            let place = pair.filter(|p| {
                let root = p.split('/').next().unwrap();
                !p.contains('/') || CODE_DIRS.contains(&root)
            })?;
            // A constant may be used where it is cited; a uniform, step or setting is a
            // string the file sets or names.
            let constant = last.chars().all(|c| !c.is_ascii_lowercase());
            let quoted = format!("\"{last}\"");
            let in_file = code.defined_in(last, place)
                || code.files.iter().any(|(f, text)| {
                    let here = match place.ends_with('/') || place.contains('/') {
                        true => f == place || f.starts_with(place),
                        false => f.ends_with(&format!("/{place}")),
                    };
                    here && (text.contains(&quoted) || constant && text.contains(last.as_str()))
                });
            (!in_file).then(|| format!("`{last}` is not defined in `{place}`"))
        }
    }
}

/// The citations of one doc (`doc` its path from the root, for the allow list and the
/// messages) that are wrong, and how many it makes.
fn check_doc(code: &Code, doc: &str, text: &str) -> (usize, Vec<String>) {
    let allowed: &[&str] = CHAPTER_NAMES
        .iter()
        .find(|(d, _)| *d == doc)
        .map_or(&[], |(_, names)| names);
    let mut wrong = Vec::new();
    let mut checked = 0;
    for (line, clause) in clauses(text) {
        for (cited, pair) in paired(&clause) {
            if let Cited::Name { last, .. } = &cited {
                if allowed.contains(&last.as_str()) {
                    continue;
                }
            }
            if cited != Cited::Skip {
                checked += 1;
            }
            if let Some(e) = citation_error(code, &cited, pair.as_deref()) {
                wrong.push(format!("{doc}:{line}: {e}"));
            }
        }
    }
    (checked, wrong)
}

#[test]
fn every_code_name_the_docs_cite_is_in_the_program() {
    let code = Code::load();
    let mut files = vec![root().join("README.md")];
    markdown_files(&root().join("docs"), &mut files);
    let mut wrong = Vec::new();
    let mut checked = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let (n, errors) = check_doc(&code, &relative(file), &text);
        checked += n;
        wrong.extend(errors);
    }
    assert!(checked > 300, "only {checked} citations");
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// The check itself, on a doc with stale names: each kind of mistake is found, and what
/// the heuristics leave alone is left alone.
#[test]
fn the_code_name_check_finds_stale_names() {
    let code = Code::load();
    let doc = "\
| the chapter says | here |
|---|---|
| `renderDepthMap` | `examples/learnopengl_3_1_3.rs`: `depthBias` (`BIAS_MODE` 1) |

`MeshData::cube` in `src/transformation.rs`, `calcShadow` (`examples/lwjgl_dummygame.rs`).
`src/geometry.rs`: `MeshData::cube`, then `NoSuchType::new`; `src/no/such.rs`.
`src/scene/camera.rs` (`MeshData::plane`, `Camera`).
Flags and settings are not names: `--map-size 512`, `shadow_cache`, `bias = 0.05`, `GL_NONE`.
Modules: `shadows::slots`, `shadows::program::slots::MaskMode`, `steps::{get, of}`, `engine::no_such`.
";
    let (checked, wrong) = check_doc(&code, "docs/test.md", doc);
    let expected = [
        "docs/test.md:3: `depthBias` is not in the program",
        "docs/test.md:3: `BIAS_MODE` is not in the program",
        "docs/test.md:5: `cube` is not defined in `src/transformation.rs`",
        "docs/test.md:5: `NoSuchType` is not in the program",
        "docs/test.md:5: `src/no/such.rs` does not exist",
        "docs/test.md:5: `plane` is not defined in `src/scene/camera.rs`",
        "docs/test.md:5: `shadows::slots`: `slots` is no module of `shadows` \
         (`src/shadows/slots.rs`) nor defined in `src/shadows/mod.rs`",
        "docs/test.md:5: `engine::no_such`: `no_such` is no module of `engine` \
         (`src/engine/no_such.rs`) nor defined in `src/engine/mod.rs`",
    ];
    assert_eq!(wrong, expected);
    assert_eq!(checked, 18, "{wrong:?}");
}

/// The reading guide maps every function of the two one-file examples onto the engine, but
/// their plumbing (reading the frame back, writing it, `main` and its arguments).
#[test]
fn the_reading_guide_maps_every_function_of_the_examples() {
    let guide = std::fs::read_to_string(root().join("docs/reading-guide.md")).unwrap();
    let plumbing = [
        "main",
        "check_args",
        "render_to",
        "read_colour",
        "read_depth",
        "finish",
    ];
    let function = regex::Regex::new(r"(?m)^\s*(?:pub )?fn ([a-z_0-9]+)").unwrap();
    let mut missing = Vec::new();
    for example in ["lwjgl_dummygame", "learnopengl_3_1_3"] {
        let text = std::fs::read_to_string(root().join(format!("examples/{example}.rs"))).unwrap();
        let names: Vec<&str> = function
            .captures_iter(&text)
            .map(|c| c.get(1).unwrap().as_str())
            .filter(|n| !plumbing.contains(n))
            .collect();
        assert!(names.len() >= 6, "{example}: {names:?}");
        for name in names {
            let cited =
                guide.contains(&format!("`{name}`")) || guide.contains(&format!("::{name}`"));
            if !cited {
                missing.push(format!("{example}: {name}"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "not in docs/reading-guide.md: {missing:?}"
    );
}
