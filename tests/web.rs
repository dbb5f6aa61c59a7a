//! The browser's build in a real browser: every chapter step of `dummy` and `learnopengl` and
//! the playground's five pages, opened in headless Chromium (`web/test/shoot.mjs`, on
//! puppeteer-core), each canvas compared with `shadowmap render`'s frame of the same scene
//! and step. A step that needs what WebGL2 lacks must be refused on the page with the reason,
//! and only such a step. Needs `web/dist` (scripts/web.sh build), Node.js with
//! `web/test/node_modules` and Chromium, so it is `#[ignore]`d here and run by `.ci/run`.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

use shadowmap::settings::{BiasMode, ShadowTechnique};
use shadowmap::{steps, Scene};

const SIZE: &str = "320x180";

/// What WebGL2 cannot draw of a step, from its settings: the refusal the page must show.
/// (Its lit border and interpolated depths are the shader's there, its cube maps drawn
/// face by face.)
fn lacks(scene: &str, step: Option<&str>) -> Option<&'static str> {
    let s = settings_of(scene, step);
    // A depth-map view draws the map itself, through no shadow test.
    if s.show_depth_map {
        return None;
    }
    (s.technique == ShadowTechnique::Volumes).then_some("needs a geometry shader")
}

fn settings_of(scene: &str, step: Option<&str>) -> shadowmap::ShadowSettings {
    let scene = Scene::load(scene).unwrap();
    match step {
        Some(step) => steps::settings_for(&scene, step).unwrap().effective(),
        None => scene.shadow.effective(),
    }
}

/// The shadowed pixels of a visibility picture: `render --shadow-out`'s (grey, transparent
/// off the geometry) or the page's `&view=visibility` (grey, a blue off the geometry).
fn shadowed(png: &Path) -> Vec<bool> {
    let img = image::open(png).unwrap().to_rgba8();
    img.pixels()
        .map(|p| {
            let [r, g, b, a] = p.0;
            let grey = r.abs_diff(g) <= 4 && g.abs_diff(b) <= 4;
            a > 0 && grey && r < 128
        })
        .collect()
}

/// Intersection over union of two pictures' shadowed regions (1 when neither has any).
fn shadow_iou(a: &Path, b: &Path) -> f64 {
    let (a, b) = (shadowed(a), shadowed(b));
    assert_eq!(a.len(), b.len());
    let both = a.iter().zip(&b).filter(|(x, y)| **x && **y).count();
    let either = a.iter().zip(&b).filter(|(x, y)| **x || **y).count();
    match either {
        0 => 1.0,
        n => both as f64 / n as f64,
    }
}

/// Whether the step has no bias at all, so that its picture is shadow acne.
fn acne(scene: &str, step: Option<&str>) -> bool {
    settings_of(scene, step).bias_mode == BiasMode::None
}

/// The share of 16 x 16 blocks whose shadowed fraction differs by more than a tenth.
fn shadow_block_share(a: &Path, b: &Path) -> f64 {
    let w = image::open(a).unwrap().width() as usize;
    let (a, b) = (shadowed(a), shadowed(b));
    let h = a.len() / w;
    let (bw, bh) = (w / 16, h / 16);
    let fraction = |m: &[bool], bx: usize, by: usize| {
        let mut n = 0;
        for y in by * 16..by * 16 + 16 {
            n += m[y * w + bx * 16..y * w + bx * 16 + 16]
                .iter()
                .filter(|s| **s)
                .count();
        }
        n as f64 / 256.0
    };
    let differ = (0..bh)
        .flat_map(|by| (0..bw).map(move |bx| (bx, by)))
        .filter(|&(bx, by)| (fraction(&a, bx, by) - fraction(&b, bx, by)).abs() > 0.1)
        .count();
    differ as f64 / (bw * bh) as f64
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
    /// The page's note after each key (what the key could not do).
    notes: Vec<String>,
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
            let strings = |key: &str| -> Vec<String> {
                v[key]
                    .as_array()
                    .map(|t| {
                        t.iter()
                            .filter_map(|t| t.as_str().map(String::from))
                            .collect()
                    })
                    .unwrap_or_default()
            };
            Page {
                title: v["title"].as_str().unwrap_or_default().to_string(),
                png: v["png"].as_str().map(PathBuf::from),
                ms: v["ms"].as_f64().unwrap_or(f64::NAN),
                titles: strings("titles"),
                notes: strings("notes"),
            }
        })
        .collect();
    assert_eq!(pages.len(), queries.len(), "{stderr}");
    pages
}

/// Every chapter step of `dummy` and `learnopengl`, the playground's five pages, and
/// `point-shadows` (cube maps, face by face on WebGL2).
fn cases() -> Vec<(&'static str, Option<&'static str>)> {
    let mut cases: Vec<(&str, Option<&str>)> = Vec::new();
    for scene in ["dummy", "learnopengl"] {
        let s = Scene::load(scene).unwrap();
        cases.extend(steps::of(&s).iter().map(|step| (scene, Some(step.name))));
    }
    for step in ["basic", "pcf", "soft-pcf", "variance", "moment"] {
        cases.push(("playground", Some(step)));
    }
    cases.push(("point-shadows", None));
    cases
}

fn query((scene, step): (&str, Option<&str>), extra: &str) -> String {
    let step = step.map(|s| format!("&step={s}")).unwrap_or_default();
    format!("scene={scene}{step}&size={SIZE}&still=1&hud=0{extra}")
}

/// `shadowmap render` of the case, its frame (and with `visibility`, its `--shadow-out`).
fn native(dir: &Path, (scene, step): (&str, Option<&str>), visibility: bool) -> PathBuf {
    let name = format!("{scene}-{}", step.unwrap_or("scene"));
    let out = dir.join(format!("{name}-render.png"));
    let shadow = dir.join(format!("{name}-render-visibility.png"));
    let mut cmd = common::bin();
    cmd.args(["render", "--scene", scene, "--size", SIZE]);
    if let Some(step) = step {
        cmd.args(["--step", step]);
    }
    cmd.arg("--out").arg(&out);
    if visibility {
        cmd.arg("--shadow-out").arg(&shadow);
    }
    common::stdout_of(&mut cmd);
    match visibility {
        true => shadow,
        false => out,
    }
}

#[test]
#[ignore = "needs web/dist, Node.js and Chromium: .ci/run builds and runs it"]
fn the_page_draws_every_chapter_step_as_render_does_or_says_why_not() {
    let (server, dir) = served("web");
    let cases = cases();
    let mut queries: Vec<String> = cases.iter().map(|&c| query(c, "")).collect();
    queries.extend(cases.iter().map(|&c| query(c, "&view=visibility")));
    let pages = shoot(&server.url, &dir, &queries);
    let (frames, visibility) = pages.split_at(cases.len());
    let mut drawn = 0;
    for ((&case, page), seen) in cases.iter().zip(frames).zip(visibility) {
        let (scene, step) = case;
        let name = format!("{scene} {}", step.unwrap_or("(scene)"));
        match (lacks(scene, step), &page.png, &seen.png) {
            (None, Some(png), Some(seen)) => {
                let native_frame = native(&dir, case, false);
                // Without a bias the picture is acne, a moiré of each rasteriser's depth
                // precision: there its density must agree (16 x 16 blocks), not each pixel.
                let (share, what) = match acne(scene, step) {
                    false => (
                        common::step_frames::differing_share(png, &native_frame),
                        "pixels",
                    ),
                    true => (block_share(png, &native_frame), "16 x 16 blocks"),
                };
                assert!(
                    share <= 0.02,
                    "{name}: {:.2}% of the page's {what} differ from render's",
                    share * 100.0
                );
                if settings_of(scene, step).show_depth_map {
                    // No shadow test to show: the visibility view is the map's picture.
                    let differ = common::step_frames::differing_share(seen, png);
                    assert_eq!(differ, 0.0, "{name}: the visibility view is not the map");
                    drawn += 1;
                    println!("{name}: drawn, first frame {:.0} ms", page.ms);
                    continue;
                }
                let native_seen = native(&dir, case, true);
                let iou = shadow_iou(seen, &native_seen);
                match acne(scene, step) {
                    // Acne's shadowed pixels are the moiré: its density must agree.
                    true => {
                        let blocks = shadow_block_share(seen, &native_seen);
                        assert!(
                            blocks <= 0.02,
                            "{name}: the shadow's density differs in {:.2}% of 16 x 16 blocks",
                            blocks * 100.0
                        );
                    }
                    false => assert!(
                        iou >= 0.99,
                        "{name}: the page's shadowed region against render's: IoU {iou:.4}"
                    ),
                }
                drawn += 1;
                println!(
                    "{name}: drawn, first frame {:.0} ms; {:.2}% of the {what} differ; shadow \
                     IoU {iou:.4}",
                    page.ms,
                    share * 100.0
                );
            }
            (Some(reason), None, None) => {
                assert!(
                    page.title.starts_with("error: ") && page.title.contains(reason),
                    "{name}: expected the refusal '{reason}', the page says '{}'",
                    page.title
                );
                println!("{name}: refused ({reason})");
            }
            (None, _, _) => panic!("{name}: not drawn: {} / {}", page.title, seen.title),
            (Some(reason), _, _) => panic!("{name}: drawn, though WebGL2 {reason}"),
        }
    }
    // Each case is drawn, or refused for what WebGL2 lacks (matched above, case by case).
    let refused = cases.iter().filter(|(s, t)| lacks(s, *t).is_some()).count();
    assert_eq!(drawn, cases.len() - refused);
    assert!(drawn >= 30, "only {drawn} cases drawn");
}

#[test]
#[ignore = "needs web/dist, Node.js and Chromium: .ci/run builds and runs it"]
fn a_bad_name_or_what_webgl2_lacks_gets_a_message_on_the_page() {
    let (server, dir) = served("web-bad");
    let pages = shoot(
        &server.url,
        &dir,
        &[
            "scene=dumy".into(),
            "scene=dummy&step=pfc".into(),
            "scene=dummy&technique=volumes&still=1".into(),
        ],
    );
    // What WebGL2 cannot do is refused by name on the page, not drawn blank.
    assert!(
        pages[2].title.starts_with("error: ")
            && pages[2].title.contains("geometry shader")
            && pages[2].png.is_none(),
        "{}",
        pages[2].title
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
fn the_step_keys_walk_the_chapter_in_the_page_past_a_refused_key() {
    let (server, dir) = served("web-keys");
    let query = format!("scene=dummy&size={SIZE}&hud=0#keys=KeyN,KeyN,PageUp,KeyV,KeyN");
    let pages = shoot(&server.url, &dir, &[query]);
    assert_eq!(pages[0].title, "ready");
    let list = steps::of(&Scene::load("dummy").unwrap());
    // N: the first step, N: the second, PageUp: the first again (as in the demo's window);
    // V (shadow volumes, which need a geometry shader) is refused with a note and the page
    // goes on: the same step, then N the second.
    let expected = [
        list[0].name,
        list[1].name,
        list[0].name,
        list[0].name,
        list[1].name,
    ];
    assert_eq!(pages[0].titles.len(), 5, "{:?}", pages[0].titles);
    for (title, step) in pages[0].titles.iter().zip(expected) {
        assert!(
            title.contains(&format!("| step {step} |")),
            "expected step {step}: {title}"
        );
    }
    assert!(pages[0].notes[2].is_empty(), "{:?}", pages[0].notes);
    assert!(
        pages[0].notes[3].starts_with("note: ") && pages[0].notes[3].contains("geometry shader"),
        "{:?}",
        pages[0].notes
    );
}

/// The frame time a title shows: `... | 12.34 ms (WxH)`.
fn title_ms(title: &str) -> Option<f64> {
    let (head, _) = title.rsplit_once(" ms (")?;
    head.rsplit(' ').next()?.parse().ok()
}

/// A benchmark's figure, printed: the DummyGame's frame time in the page (frame to frame, as
/// its title shows it; requestAnimationFrame paces it, so a 60 Hz display's 16.7 ms is its
/// floor) beside `render`'s native headless one, and the page's first frame. The test
/// asserts only that both were measured: machines differ.
#[test]
#[ignore = "needs web/dist, Node.js and Chromium: .ci/run builds and runs it"]
fn the_dummy_games_frame_time_in_the_page_beside_the_native_one() {
    let (server, dir) = served("web-time");
    let size = "640x360";
    // Five waits of 0.7 s (a key that does nothing) while the scene animates.
    let query = format!("scene=dummy&size={size}#keys=Shift,Shift,Shift,Shift,Shift");
    let page = &shoot(&server.url, &dir, &[query])[0];
    assert_eq!(page.title, "ready");
    let ms = page.titles.last().and_then(|t| title_ms(t));
    let ms = ms.unwrap_or_else(|| panic!("no frame time in {:?}", page.titles));
    let out = common::stdout_of(
        common::bin()
            .args([
                "render", "--scene", "dummy", "--size", size, "--frames", "30", "--out",
            ])
            .arg(dir.join("native.png")),
    );
    let native = out
        .lines()
        .find_map(|l| l.split_once("frame time over ").map(|(_, rest)| rest))
        .and_then(|rest| rest.split_once("median ").map(|(_, m)| m))
        .and_then(|m| m.split(' ').next()?.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no frame time in render's output: {out}"));
    println!(
        "dummy {size}: the page {ms:.2} ms a frame (frame to frame), native headless \
         {native:.2} ms (median, glFinish per frame); the page's first frame {:.0} ms",
        page.ms
    );
    assert!(ms > 0.0 && native > 0.0 && page.ms > 0.0);
}
