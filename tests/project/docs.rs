//! The documentation against the program: the reference scene file loads, renders and shows
//! every field the loader knows; every link in the README and `docs/` reaches a file; the
//! bench's help states its sweep's counts; and which commands take which flags. Nothing here
//! reads prose: the checks are on files and on the program's own output.

use crate::common;

use std::path::{Path, PathBuf};

use shadowmap::bench::{configuration_counts, sweep, Family};
use shadowmap::settings::Filter;
use shadowmap::Scene;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

const REFERENCE: &str = "docs/reference-scene.toml";

fn reference_text() -> String {
    std::fs::read_to_string(root().join(REFERENCE)).unwrap()
}

#[test]
fn the_reference_scene_loads_and_renders() {
    let path = root().join(REFERENCE);
    let mut scene = Scene::load(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.name, "reference");
    assert_eq!(scene.lights.len(), 3, "a sun, a spot and a point light");
    // Four items and six scattered pillars.
    assert_eq!(scene.items.len(), 10);
    let ctx = common::context();
    let settings = scene.shadow;
    let frame = common::render(&ctx, &mut scene, &settings, 320, 180);
    let vis: Vec<f32> = frame.visibility.unwrap().into_iter().flatten().collect();
    let shadowed = vis.iter().filter(|v| **v < 0.5).count();
    let lit = vis.iter().filter(|v| **v > 0.5).count();
    assert!(shadowed > 100, "only {shadowed} shadowed pixels");
    assert!(lit > 10 * shadowed, "{lit} lit against {shadowed} shadowed");
}

/// Loads `text` as a scene file.
fn load_text(text: &str) -> shadowmap::Result<Scene> {
    let path = std::env::temp_dir().join(format!(
        "shadowmap-docs-{}-{}.toml",
        std::process::id(),
        text.len()
    ));
    std::fs::write(&path, text).unwrap();
    let scene = Scene::load(path.to_str().unwrap());
    std::fs::remove_file(&path).ok();
    scene
}

/// The fields a table of the scene file takes, as the loader lists them when it refuses an
/// unknown one (`expected one of `a`, `b`` or `... takes a, b`).
fn loader_fields(text: &str) -> Vec<String> {
    let message = match load_text(text) {
        Ok(_) => panic!("an unknown field was accepted:\n{text}"),
        Err(e) => e.to_string(),
    };
    if let Some((_, list)) = message.split_once("expected one of") {
        return list
            .split('`')
            .skip(1)
            .step_by(2)
            .map(String::from)
            .collect();
    }
    let (_, list) = message
        .split_once(" takes ")
        .unwrap_or_else(|| panic!("no list of fields in: {message}"));
    list.split(',').map(|f| f.trim().to_string()).collect()
}

#[test]
fn the_reference_scene_shows_every_field_of_the_scene_file() {
    let text = reference_text();
    let light = "[light]\nangle = 45.0\n";
    let item = "[[item]]\nmesh = \"cube\"\n";
    let tables = [
        ("top level", format!("not_a_field = 1\n{light}")),
        ("[camera]", format!("{light}[camera]\nnot_a_field = 1\n")),
        ("directional [light]", format!("{light}not_a_field = 1\n")),
        (
            "spot [light]",
            "[light]\nkind = \"spot\"\nnot_a_field = 1\n".into(),
        ),
        (
            "point [light]",
            "[light]\nkind = \"point\"\nnot_a_field = 1\n".into(),
        ),
        ("ortho", "[light]\northo = { not_a_field = 1 }\n".into()),
        ("[shadow]", format!("{light}[shadow]\nnot_a_field = 1\n")),
        ("[steps]", format!("{light}[steps]\nnot_a_field = 1\n")),
        ("[[item]]", format!("{light}{item}not_a_field = 1\n")),
        (
            "scatter",
            format!("{light}{item}scatter = {{ not_a_field = 1 }}\n"),
        ),
    ];
    for (table, scene) in tables {
        let fields = loader_fields(&scene);
        assert!(fields.len() > 4, "{table}: {fields:?}");
        for f in fields {
            let shown = [
                format!("{f} ="),
                format!("[{f}]"),
                format!("[[{f}]]"),
                format!("{f}s]]"),
            ]
            .iter()
            .any(|s| text.contains(s.as_str()));
            assert!(shown, "{table}: {REFERENCE} lacks `{f}`");
        }
    }
}

#[test]
fn the_reference_scene_lists_every_filter() {
    let text = reference_text();
    let line = text
        .lines()
        .find(|l| l.starts_with("filter ="))
        .expect("a filter line");
    let comment = line
        .split_once('#')
        .expect("a comment listing the filters")
        .1;
    let listed: Vec<&str> = comment.split('"').skip(1).step_by(2).collect();
    let all: Vec<&str> = Filter::ALL
        .iter()
        .chain(&Filter::SOFT)
        .chain(&Filter::MOMENTS)
        .chain(&Filter::SOFT_MOMENTS)
        .map(|f| f.name())
        .collect();
    assert_eq!(listed, all, "{REFERENCE}: {line}");
    // And every filter is a value the scene files take.
    for name in all {
        let text = format!("[light]\nangle = 45.0\n[shadow]\nfilter = \"{name}\"\n");
        load_text(&text).unwrap_or_else(|e| panic!("filter {name}: {e}"));
    }
}

fn markdown_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            markdown_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "md") {
            out.push(path);
        }
    }
}

/// The relative targets of a Markdown text's links and images: `](target)` and
/// `src="target"`, anchors and web addresses left out.
fn link_targets(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (open, close) in [("](", ')'), ("src=\"", '"')] {
        for piece in text.split(open).skip(1) {
            let target = piece.split(close).next().unwrap_or("");
            let target = target.split('#').next().unwrap_or("");
            if !target.is_empty() && !target.contains("://") && !target.contains(' ') {
                out.push(target.to_string());
            }
        }
    }
    out
}

#[test]
fn every_link_in_the_docs_reaches_a_file() {
    let mut files = vec![root().join("README.md")];
    markdown_files(&root().join("docs"), &mut files);
    assert!(files.len() > 10, "{files:?}");
    let mut missing = Vec::new();
    let mut checked = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for target in link_targets(&text) {
            checked += 1;
            let path = file.parent().unwrap().join(&target);
            if !path.exists() {
                missing.push(format!("{}: {target}", file.display()));
            }
        }
    }
    assert!(checked > 100, "only {checked} links");
    assert!(
        missing.is_empty(),
        "links to nothing:\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_bench_help_states_the_sweeps_counts() {
    let dummy = Scene::load("dummy").unwrap();
    // llvmpipe's largest map, which the full sweep includes.
    let full = sweep(&dummy.shadow, false, 16384, dummy.light());
    let quick = sweep(&dummy.shadow, true, 16384, dummy.light());
    let volumes = full.iter().filter(|c| c.family == Family::Volumes).count();
    assert_eq!(volumes, 1, "the sweep has the volumes once");
    assert!(full.iter().any(|c| c.family == Family::Cascades));
    assert!(full.iter().any(|c| c.family == Family::Groups));
    let counts = configuration_counts(16384);
    // The DummyGame's settings give the same counts as the defaults the help states.
    let directional = counts.iter().find(|c| c.0 == "directional").unwrap();
    assert_eq!((directional.1, directional.2), (quick.len(), full.len()));
    let help = common::stdout_of(common::bin().args(["bench", "--help"]));
    let help = help.split_whitespace().collect::<Vec<_>>().join(" ");
    for (kind, quick, full) in counts {
        for n in [quick, full] {
            let said = format!("{n} for a {kind} light");
            assert!(
                help.contains(&said),
                "bench --help lacks \"{said}\":\n{help}"
            );
        }
    }
}

#[test]
fn steps_takes_no_step_and_the_other_commands_do() {
    for (command, takes) in [
        ("render", true),
        ("compare", true),
        ("bench", true),
        ("soak", true),
        ("demo", true),
        ("steps", false),
    ] {
        let help = common::stdout_of(common::bin().args([command, "--help"]));
        assert_eq!(help.contains("--step <STEP>"), takes, "{command} --help");
        // Every command takes the scene and camera flags.
        for flag in [
            "--scene",
            "--size",
            "--light-angle",
            "--camera-position",
            "--camera-rotation",
            "--camera-target",
        ] {
            assert!(help.contains(flag), "{command} --help lacks {flag}");
        }
    }
}

/// A steps page's figures by step: "false shadow F, false light L, MAE M", or "(depth map)"
/// for a step without a table.
fn page_figures(page: &str) -> Vec<(String, String)> {
    let text = std::fs::read_to_string(root().join(page)).unwrap();
    let row = regex::Regex::new(
        r"<tr><td class=n>(false shadow|false light|MAE) <small>[^<]*</small></td><td>([^<]*)</td>",
    )
    .unwrap();
    let mut out = Vec::new();
    for section in text.split(r#"<section class="step" id=""#).skip(1) {
        let (step, body) = section.split_once('"').unwrap();
        let body = body.split("</section>").next().unwrap();
        let cells: Vec<String> = row.captures_iter(body).map(|c| c[2].to_string()).collect();
        let figures = match cells.as_slice() {
            [] => "(depth map)".to_string(),
            [shadow, light, .., mae] => {
                format!("false shadow {shadow}, false light {light}, MAE {mae}")
            }
            _ => panic!("{page} {step}: {cells:?}"),
        };
        out.push((step.to_string(), figures));
    }
    out
}

/// The reading guide's table of the chapters' steps quotes each step's figures as its page
/// (written by `scripts/results.sh steps`) gives them, for both scenes.
#[test]
fn the_reading_guides_step_figures_are_the_step_pages() {
    let guide = std::fs::read_to_string(root().join("docs/reading-guide.md")).unwrap();
    let dummy = page_figures("assets/readme/steps-dummy/index.html");
    let learnopengl = page_figures("assets/readme/steps-learnopengl/index.html");
    assert_eq!(dummy.len(), 13, "{dummy:?}");
    for ((step, d), (step_l, l)) in dummy.iter().zip(&learnopengl) {
        assert_eq!(step, step_l);
        let row = guide
            .lines()
            .find(|line| line.contains(&format!(". `{step}` |")) && line.contains("steps-dummy"))
            .unwrap_or_else(|| panic!("docs/reading-guide.md has no row for {step}"));
        assert!(
            row.ends_with(&format!("| {d} | {l} |")),
            "docs/reading-guide.md, {step}: the pages say \"{d}\" and \"{l}\":\n{row}"
        );
    }
}

/// The code names the docs cite, against the code.
#[path = "docs_names.rs"]
mod names;
