//! The README's numbers and lists against the code they describe: the bench's counts, the
//! filters, the scene files' fields, and which commands take which flags. Each statement
//! is parsed out of the README, so a change on either side fails here.

mod common;

use shadowmap::bench::{configuration_counts, sweep, Family};
use shadowmap::settings::Filter;
use shadowmap::Scene;

fn readme() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap()
}

/// The README's text collapsed to single spaces (its sentences wrap anywhere).
fn prose() -> String {
    readme().split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The number right after `before` in `text`.
fn number_after(text: &str, before: &str) -> usize {
    let at = text
        .find(before)
        .unwrap_or_else(|| panic!("the README no longer says \"{before}\""));
    let digits: String = text[at + before.len()..]
        .chars()
        .take_while(|c| c.is_ascii_digit())
        .collect();
    digits
        .parse()
        .unwrap_or_else(|_| panic!("no number after \"{before}\""))
}

/// The README's `### Fields` block: the commented scene file.
fn fields_block() -> String {
    let text = readme();
    let start = text.find("### Fields").expect("a Fields section");
    let body = &text[start..];
    let open = body.find("```toml").expect("a toml block") + "```toml".len();
    let close = body[open..].find("```").expect("the block's end");
    body[open..open + close].to_string()
}

#[test]
fn the_bench_counts_are_the_sweeps() {
    let text = prose();
    let dummy = Scene::load("dummy").unwrap();
    // llvmpipe's largest map, which the README's sweep includes.
    let full = sweep(&dummy.shadow, false, 16384, dummy.light());
    let quick = sweep(&dummy.shadow, true, 16384, dummy.light());
    let cascaded = full.iter().filter(|c| c.family == Family::Cascades).count();
    let grouped = full.iter().filter(|c| c.family == Family::Groups).count();
    let volumes = full.iter().filter(|c| c.family == Family::Volumes).count();
    assert_eq!(volumes, 1, "the sweep has the volumes once");
    assert_eq!(
        number_after(&text, "2 or 4 caster groups: "),
        full.len(),
        "the full sweep"
    );
    assert_eq!(
        number_after(&text, "configurations on the DummyGame ("),
        full.len() - cascaded - grouped - volumes,
        "one-map configurations"
    );
    assert_eq!(
        number_after(&text, " with one map, "),
        cascaded,
        "configurations with cascades"
    );
    assert_eq!(
        number_after(&text, " with cascades, "),
        grouped,
        "configurations with caster groups"
    );
    assert_eq!(number_after(&text, "`--quick` runs "), quick.len());
    let counts = configuration_counts(16384);
    let spot_quick = counts.iter().find(|c| c.0 == "spot").unwrap().1;
    assert_eq!(
        number_after(&text, "of them on the DummyGame ("),
        spot_quick,
        "quick, spot"
    );
    // The DummyGame's settings give the same counts as the defaults the help states.
    let directional = counts.iter().find(|c| c.0 == "directional").unwrap();
    assert_eq!((directional.1, directional.2), (quick.len(), full.len()));
    // The plot and the table are of the one-map sweep: its CSV has that many rows.
    let csv = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/readme/bench-dummy.csv"
    ))
    .unwrap();
    assert_eq!(
        number_after(&text, "they hold the "),
        csv.lines().count() - 1
    );
}

#[test]
fn the_bench_help_states_the_sweeps_counts() {
    let help = common::stdout_of(common::bin().args(["bench", "--help"]));
    let help = help.split_whitespace().collect::<Vec<_>>().join(" ");
    for (kind, quick, full) in configuration_counts(16384) {
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
fn the_readme_lists_every_filter() {
    let block = fields_block();
    let line = block
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
        .map(|f| f.name())
        .collect();
    assert_eq!(listed, all, "README: {line}");
    // And every filter is a value the scene files take.
    for name in all {
        let text = format!("[light]\nangle = 45.0\n[shadow]\nfilter = \"{name}\"\n");
        load_text(&text).unwrap_or_else(|e| panic!("filter {name}: {e}"));
    }
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
/// unknown one.
fn loader_fields(text: &str) -> Vec<String> {
    let message = match load_text(text) {
        Ok(_) => panic!("an unknown field was accepted:\n{text}"),
        Err(e) => e.to_string(),
    };
    let list = message
        .split_once("expected one of")
        .unwrap_or_else(|| panic!("{message}"))
        .1;
    list.split('`')
        .skip(1)
        .step_by(2)
        .map(String::from)
        .collect()
}

#[test]
fn the_readme_shows_every_field_of_the_scene_file() {
    let block = fields_block();
    let light = "[light]\nangle = 45.0\n";
    let tables = [
        ("top level", format!("not_a_field = 1\n{light}")),
        ("[camera]", format!("{light}[camera]\nnot_a_field = 1\n")),
        (
            "[[item]]",
            format!("{light}[[item]]\nmesh = \"cube\"\nnot_a_field = 1\n"),
        ),
    ];
    for (table, text) in tables {
        let fields = loader_fields(&text);
        assert!(fields.len() > 4, "{table}: {fields:?}");
        for f in fields {
            let shown = [format!("{f} ="), format!("[{f}]"), format!("[[{f}]]")]
                .iter()
                .any(|s| block.contains(s.as_str()));
            assert!(shown, "{table}: the README's Fields block lacks `{f}`");
        }
    }
}

#[test]
fn steps_takes_no_step_and_the_other_commands_do() {
    let text = prose();
    assert!(
        text.contains(
            "every command but `steps` (which renders every step) also takes `--step NAME`"
        ),
        "the README's statement changed"
    );
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
        // Every command takes the camera flags the README names.
        for flag in ["--camera-position", "--camera-rotation", "--camera-target"] {
            assert!(help.contains(flag), "{command} --help lacks {flag}");
        }
    }
}
