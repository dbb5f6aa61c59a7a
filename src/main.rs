//! The `shadowmap` program: the demo window and the headless commands.

mod app;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = app::cli::Cli::try_parse().unwrap_or_else(|e| app::cli::nearer_suggestion(e).exit());
    let result = match cli.command {
        None => app::demo::run(&cli.demo),
        Some(app::cli::Command::Demo(args)) => app::demo::run(&args),
        Some(app::cli::Command::Render(args)) => app::render::run(&args),
        Some(app::cli::Command::Compare(args)) => app::compare::run(&args),
        Some(app::cli::Command::Bench(args)) => app::bench::run(&args),
        Some(app::cli::Command::Steps(args)) => app::gallery::run(&args),
        Some(app::cli::Command::Soak(args)) => app::soak::run(&args),
        Some(app::cli::Command::Shaders(args)) => app::shaders::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
