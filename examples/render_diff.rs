//! Compares two folders of renders, file by file: the share of pixels that differ and the
//! largest channel difference. Used to show that a refactor left every picture as it was:
//!
//! ```sh
//! scripts/render-all.sh OLD_BINARY before/ && scripts/render-all.sh target/release/shadowmap after/
//! cargo run --release --example render_diff -- before/ after/ 0.1
//! ```
//!
//! Exits with 1 when a file is missing or more than the given percentage of its pixels
//! differ (default 0.1).

use std::path::Path;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: cargo run --release --example render_diff -- BEFORE_DIR AFTER_DIR \
                 [MAX_PERCENT]\ncompares two folders of renders file by file; fails when a file \
                 is missing or more than MAX_PERCENT (default 0.1) of its pixels differ";
    if let Err(code) = shadowmap::input::check_args(&args, 2..=3, usage) {
        return code;
    }
    let (a, b) = (&args[0], &args[1]);
    let limit: f64 = match args.get(2).map(|s| s.parse()) {
        None => 0.1,
        Some(Ok(v)) => v,
        Some(Err(_)) => {
            eprintln!("MAX_PERCENT: expected a number, like 0.1");
            return ExitCode::from(2);
        }
    };
    match compare(Path::new(a), Path::new(b), limit) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

fn compare(a: &Path, b: &Path, limit: f64) -> Result<bool, String> {
    let mut names: Vec<_> = std::fs::read_dir(a)
        .map_err(|e| format!("{}: {e}", a.display()))?
        .filter_map(|e| e.ok().map(|e| e.file_name()))
        .filter(|n| n.to_string_lossy().ends_with(".png"))
        .collect();
    names.sort();
    let (mut ok, mut identical, mut worst) = (true, 0, (0.0f64, String::new()));
    for name in &names {
        let shown = name.to_string_lossy();
        let load = |dir: &Path| {
            image::open(dir.join(name))
                .map(|i| i.to_rgba8())
                .map_err(|e| format!("{}: {e}", dir.join(name).display()))
        };
        let (x, y) = match (load(a), load(b)) {
            (Ok(x), Ok(y)) => (x, y),
            (Err(e), _) | (_, Err(e)) => {
                println!("MISSING {shown}: {e}");
                ok = false;
                continue;
            }
        };
        if x.dimensions() != y.dimensions() {
            println!("SIZE {shown}: {:?} vs {:?}", x.dimensions(), y.dimensions());
            ok = false;
            continue;
        }
        let (mut differ, mut max) = (0usize, 0u8);
        for (p, q) in x.pixels().zip(y.pixels()) {
            let d =
                p.0.iter()
                    .zip(q.0)
                    .map(|(u, v)| u.abs_diff(v))
                    .max()
                    .unwrap_or(0);
            differ += usize::from(d > 0);
            max = max.max(d);
        }
        let pct = 100.0 * differ as f64 / (x.width() * x.height()) as f64;
        if differ == 0 {
            identical += 1;
        } else {
            println!("{shown}: {pct:.4}% of pixels differ (largest difference {max}/255)");
        }
        if pct > worst.0 {
            worst = (pct, shown.to_string());
        }
        if pct > limit {
            ok = false;
        }
    }
    println!(
        "{} files: {identical} identical; the most changed: {} ({:.4}%); limit {limit}%: {}",
        names.len(),
        if worst.1.is_empty() { "none" } else { &worst.1 },
        worst.0,
        if ok { "within" } else { "EXCEEDED" }
    );
    Ok(ok)
}
