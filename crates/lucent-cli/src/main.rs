//! `lucent`: render scenes and inspect them from the command line.

mod bench;
mod cli;
mod convert;
mod explain;
mod gallery;
mod info;
mod job;
mod merge;
mod render;
mod study;
mod view;

use clap::Parser;
use lucent_cli::{film_file, output};
use std::process::ExitCode;

fn main() -> ExitCode {
    // A bug must still end in one clear line, not a backtrace.
    std::panic::set_hook(Box::new(|info| {
        eprintln!("lucent: internal error: {info} (please report this)");
    }));
    let args = cli::Cli::parse();
    let result = match args.command {
        cli::Command::Render(a) => render::run(&a),
        cli::Command::Info(a) => info::run(&a),
        cli::Command::Explain(a) => explain::run(&a),
        cli::Command::Gallery(a) => gallery::run(&a),
        cli::Command::Merge(a) => merge::run(&a),
        cli::Command::Convert(a) => convert::run(&a),
        cli::Command::Bench(a) => bench::run(&a),
        cli::Command::Study(cli::StudyCommand::Frameless(a)) => study::frameless(&a),
        cli::Command::View(a) => view::run(&a),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
