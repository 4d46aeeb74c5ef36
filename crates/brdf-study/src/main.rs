//! The `brdf` command. `brdf --help` lists the subcommands; every subcommand
//! that reports numbers takes `--json`.

use std::process::ExitCode;

use clap::Parser;

mod cli;
mod commands;
mod error;
#[cfg(feature = "plots")]
mod plots;
mod render;
mod report;
mod synthetic;

use cli::{Cli, Command};
pub use error::StudyError;

fn run() -> Result<(), StudyError> {
    let cli = Cli::parse();
    match cli.command {
        Command::Models(a) => commands::models::run(&a),
        Command::Eval(a) => commands::eval::run(&a),
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
