//! The browser's build in a real browser: every chapter step of `dummy` and `learnopengl` and
//! the playground's five pages, opened in headless Chromium (`web/test/shoot.mjs`, on
//! puppeteer-core), each canvas compared with `shadowmap render`'s frame of the same scene
//! and step. A step that needs what WebGL2 lacks must be refused on the page with the reason,
//! and only such a step. Needs `web/dist` (scripts/web.sh build), Node.js with
//! `web/test/node_modules` and Chromium, so it is `#[ignore]`d here and run by `.ci/run`.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

use shadowmap::settings::{BiasMode, DepthLookup, ShadowTechnique};
use shadowmap::{steps, Scene};

const SIZE: &str = "320x180";

/// What WebGL2 cannot draw of a step, from its settings: the refusal the page must show.
fn lacks(scene: &str, step: &str) -> Option<&'static str> {
    let scene = Scene::load(scene).unwrap();
    let s = steps::settings_for(&scene, step).unwrap().effective();
    // A depth-map view draws the map itself, through no shadow test.
    if s.show_depth_map {
        return None;
    }
    if s.technique == ShadowTechnique::Volumes {
        return Some("needs a geometry shader");
    }
    if s.depth_lookup == DepthLookup::Linear && !s.filter.hardware() && !s.filter.moments() {
        return Some("reads the shadow map's depths interpolated");
    }
    None
}

/// Whether the step has no bias at all, so that its picture is shadow acne.
fn acne(scene: &str, step: &str) -> bool {
    let scene = Scene::load(scene).unwrap();
    steps::settings_for(&scene, step)
        .unwrap()
        .effective()
        .bias_mode
        == BiasMode::None
}

/// The share of 16 x 16 blocks whose mean colour differs by more than 16 levels in a channel.
fn block_share(a: &Path, b: &Path) -> f64 {
    let (a, b) = (
        image::open(a).unwrap().to_rgb8(),
        image::open(b).unwrap().to_rgb8(),
    );
    assert_eq!(a.dimensions(), b.dimensions());
    let (w, h) = (a.width() / 16, a.height() / 16);
    let mean = |img: &image::RgbImage, bx: u32, by: u32, c: usize| -> f64 {
        let mut sum = 0.0;
        for y in by * 16..by * 16 + 16 {
            for x in bx * 16..bx * 16 + 16 {
                sum += f64::from(img.get_pixel(x, y)[c]);
            }
        }
        sum / 256.0
    };
    let mut differ = 0;
    for by in 0..h {
        for bx in 0..w {
            if (0..3).any(|c| (mean(&a, bx, by, c) - mean(&b, bx, by, c)).abs() > 16.0) {
                differ += 1;
            }
        }
    }
    f64::from(differ) / f64::from(w * h)
}

/// `web/dist` served on a free loopback port by Python's http.server, stopped on drop.
struct Server {
    child: Child,
    url: String,
}

impl Server {
    fn start(dist: &Path) -> Server {
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let child = Command::new("python3")
            .args([
                "-m",
                "http.server",
                &port.to_string(),
                "--bind",
                "127.0.0.1",
            ])
            .arg("--directory")
            .arg(dist)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("python3 serves web/dist");
        // Made first, so that a server that never answers is still stopped (on drop).
        let server = Server {
            child,
            url: format!("http://127.0.0.1:{port}"),
        };
        for _ in 0..100 {
            if std::net::TcpStream::connect(("127.0.0.1", port)).is_ok() {
                return server;
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        panic!("the server on {} never came up", server.url);
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The built page served, and a fresh folder for the case's pictures.
fn served(case: &str) -> (Server, PathBuf) {
    let dist = Path::new(env!("CARGO_MANIFEST_DIR")).join("web/dist");
    assert!(
        dist.join("shadowmap_bg.wasm").is_file(),
        "web/dist is not built: run scripts/web.sh build"
    );
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(case);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    (Server::start(&dist), dir)
}

/// One page as `shoot.mjs` reports it.
struct Page {
    title: String,
    png: Option<PathBuf>,
    ms: f64,
    /// The window's title after each key the query asked for (`#keys=`).
    titles: Vec<String>,
}

/// Opens every query in one browser; the pages' reports in order.
fn shoot(url: &str, dir: &Path, queries: &[String]) -> Vec<Page> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new("node")
        .arg(root.join("web/test/shoot.mjs"))
        .arg(url)
        .arg(dir)
        .args(queries)
        .output()
        .expect("node runs web/test/shoot.mjs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "shoot.mjs failed: {stderr}");
    let pages: Vec<Page> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|line| {
            let v: serde_json::Value = serde_json::from_str(line).unwrap();
            Page {
                title: v["title"].as_str().unwrap_or_default().to_string(),
                png: v["png"].as_str().map(PathBuf::from),
                ms: v["ms"].as_f64().unwrap_or(f64::NAN),
                titles: v["titles"]
                    .as_array()
                    .map(|t| {
                        t.iter()
                            .filter_map(|t| t.as_str().map(String::from))
                            .collect()
                    })
                    .unwrap_or_default(),
            }
        })
        .collect();
    assert_eq!(pages.len(), queries.len(), "{stderr}");
    pages
}

#[test]
#[ignore = "needs web/dist, Node.js and Chromium: .ci/run builds and runs it"]
fn the_page_draws_every_chapter_step_as_render_does_or_says_why_not() {
    let (server, dir) = served("web");

    let mut cases: Vec<(&str, &str)> = Vec::new();
    for scene in ["dummy", "learnopengl"] {
        let s = Scene::load(scene).unwrap();
        cases.extend(steps::of(&s).iter().map(|step| (scene, step.name)));
    }
    for step in ["basic", "pcf", "soft-pcf", "variance", "moment"] {
        cases.push(("playground", step));
    }
    let queries: Vec<String> = cases
        .iter()
        .map(|(scene, step)| format!("scene={scene}&step={step}&size={SIZE}&still=1&hud=0"))
        .collect();
    let pages = shoot(&server.url, &dir, &queries);
    let mut drawn = 0;
    for ((scene, step), page) in cases.iter().zip(&pages) {
        match (lacks(scene, step), &page.png) {
            (None, Some(png)) => {
                let native = dir.join(format!("{scene}-{step}-render.png"));
                common::stdout_of(
                    common::bin()
                        .args(["render", "--scene", scene, "--step", step, "--size", SIZE])
                        .arg("--out")
                        .arg(&native),
                );
                // Without a bias the picture is acne, a moiré of each rasteriser's depth
                // precision: there its density must agree (16 x 16 blocks), not each pixel.
                let (share, what) = match acne(scene, step) {
                    false => (common::step_frames::differing_share(png, &native), "pixels"),
                    true => (block_share(png, &native), "16 x 16 blocks"),
                };
                assert!(
                    share <= 0.02,
                    "{scene} {step}: {:.2}% of the page's {what} differ from render's",
                    share * 100.0
                );
                drawn += 1;
                println!("{scene} {step}: drawn, first frame {:.0} ms", page.ms);
            }
            (Some(reason), None) => {
                assert!(
                    page.title.starts_with("error: ") && page.title.contains(reason),
                    "{scene} {step}: expected the refusal '{reason}', the page says '{}'",
                    page.title
                );
                println!("{scene} {step}: refused ({reason})");
            }
            (None, None) => panic!("{scene} {step}: not drawn: {}", page.title),
            (Some(reason), Some(_)) => {
                panic!("{scene} {step}: drawn, though WebGL2 {reason}")
            }
        }
    }
    assert!(drawn >= 12, "only {drawn} steps drawn");
}

#[test]
#[ignore = "needs web/dist, Node.js and Chromium: .ci/run builds and runs it"]
fn a_bad_name_in_the_address_gets_the_command_lines_message() {
    let (server, dir) = served("web-bad");
    let pages = shoot(
        &server.url,
        &dir,
        &["scene=dumy".into(), "scene=dummy&step=pfc".into()],
    );
    assert!(
        pages[0]
            .title
            .starts_with("error: unknown scene 'dumy' (did you mean 'dummy'?)"),
        "{}",
        pages[0].title
    );
    // The same words as the command line's.
    let cli = Command::new(env!("CARGO_BIN_EXE_shadowmap"))
        .args(["render", "--scene", "dummy", "--step", "pfc", "--out"])
        .arg(dir.join("x.png"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&cli.stderr);
    let first = stderr.lines().next().unwrap_or_default();
    assert!(first.contains("pfc"), "{stderr}");
    let words = first.trim_start_matches("error: ");
    assert!(
        pages[1].title.contains(words) && stderr.contains("a similar value exists: 'pcf'"),
        "{stderr}"
    );
    assert!(
        pages[1].title.contains("a similar value exists: 'pcf'"),
        "the page says '{}', the command line '{first}'",
        pages[1].title
    );
}

#[test]
#[ignore = "needs web/dist, Node.js and Chromium: .ci/run builds and runs it"]
fn the_step_keys_walk_the_chapter_in_the_page() {
    let (server, dir) = served("web-keys");
    let query = format!("scene=dummy&size={SIZE}&hud=0#keys=KeyN,KeyN,PageUp");
    let pages = shoot(&server.url, &dir, &[query]);
    assert_eq!(pages[0].title, "ready");
    let list = steps::of(&Scene::load("dummy").unwrap());
    // N: the first step, N: the second, PageUp: the first again (as in the demo's window).
    let expected = [list[0].name, list[1].name, list[0].name];
    assert_eq!(pages[0].titles.len(), 3, "{:?}", pages[0].titles);
    for (title, step) in pages[0].titles.iter().zip(expected) {
        assert!(
            title.contains(&format!("| step {step} |")),
            "expected step {step}: {title}"
        );
    }
}
