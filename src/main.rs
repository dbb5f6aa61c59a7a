//! The `shadowmap` program: the demo window and the headless commands.

mod app;

use std::process::ExitCode;

use clap::Parser;
use shadowmap::engine::context;

fn main() -> ExitCode {
    context::start();
    let cli = match app::cli::Cli::try_parse_from(context::args()) {
        Ok(cli) => cli,
        Err(e) if context::HAS_TERMINAL => app::cli::nearer_suggestion(e).exit(),
        Err(e) => {
            let text = app::cli::nearer_suggestion(e).render().to_string();
            context::report_error(text.trim().trim_start_matches("error: "));
            return ExitCode::FAILURE;
        }
    };
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
            context::report_error(&e.to_string());
            ExitCode::FAILURE
        }
    }
}
