//! The examples' command lines: `--help`, and a clear refusal of anything else, before any
//! work. Shared by every example through `#[path]`, so each example's own file reads as the
//! program it ports.

use std::process::ExitCode;

/// `--help` (or `-h`) prints the usage and succeeds; an option this program does not take,
/// or a wrong count of arguments (`count`), is refused with the usage, before any work.
pub fn check_args(
    args: &[String],
    count: std::ops::RangeInclusive<usize>,
    usage: &str,
) -> std::result::Result<(), ExitCode> {
    if args.iter().any(|a| a == "--help" || a == "-h") {
        println!("{usage}");
        return Err(ExitCode::SUCCESS);
    }
    let problem = match args
        .iter()
        .find(|a| a.starts_with('-') && a.parse::<f64>().is_err())
    {
        Some(option) => format!("unknown option '{option}'"),
        None if !count.contains(&args.len()) => format!(
            "expected {} argument{}, got {}",
            match count.start() == count.end() {
                true => count.start().to_string(),
                false => format!("{} to {}", count.start(), count.end()),
            },
            if *count.end() == 1 { "" } else { "s" },
            args.len()
        ),
        None => return Ok(()),
    };
    eprintln!("error: {problem}\n\n{usage}");
    Err(ExitCode::from(2))
}
