//! The `brdf` command. `brdf --help` lists the subcommands; every subcommand
//! that reports numbers takes `--json`.

use std::process::ExitCode;

use brdf_study::cli::{Cli, Command};
use brdf_study::{StudyError, commands};
use clap::Parser;

fn run() -> Result<(), StudyError> {
    let cli = Cli::parse();
    match cli.command {
        Command::Models(a) => commands::models::run(&a),
        Command::Eval(a) => commands::eval::run(&a),
        Command::Fit(a) => commands::fit::run(&a),
        Command::Batch(a) => commands::batch::run(&a),
        Command::Nist(a) => commands::nist::run(&a),
        Command::Select(a) => commands::select::run(&a),
        Command::Info(a) => commands::info::run(&a),
        Command::Resample(a) => commands::resample::run(&a),
        Command::Export(a) => commands::export::run(&a),
        Command::Reproduce(a) => commands::reproduce::run(&a),
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of our output went away (`brdf info x | head`): done.
        Err(StudyError::Io { source, .. }) if source.kind() == std::io::ErrorKind::BrokenPipe => {
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
