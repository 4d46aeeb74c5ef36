//! # brdf-cli
//!
//! The `brdf` command. `brdf --help` lists the subcommands; every
//! subcommand that reports numbers takes `--json`.
//!
//! ## Layering
//!
//! The top of the workspace: clap argument types ([`cli`], [`opts`]) and
//! one thin function per subcommand ([`commands`]) that calls the library
//! crates — `brdf-fit` (fitting, selection, batches, resampling),
//! `brdf-io` (reading and describing data), `brdf-export` (materials),
//! `brdf-render` (spheres) and `brdf-study` (the reproduction, NIST). No
//! fitting, rendering, table or file-format logic lives here. `main`
//! and [`cli`] know the commands; the commands know only [`opts`],
//! [`output`] and [`error`].

use std::process::ExitCode;

use clap::Parser;

#[macro_use]
mod output;
mod cli;
mod commands;
mod error;
mod opts;
mod progress;

use cli::{Cli, Command};
use error::CliError;

fn run() -> Result<(), CliError> {
    let cli = Cli::parse();
    if cli.no_cache {
        brdf_fit::render_cache::set_enabled(false);
    }
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
        Command::Render(a) => commands::render::run(&a),
        Command::Report(a) => commands::report::run(&a),
        Command::Reproduce(a) => commands::reproduce::run(&a),
    }
}

fn main() -> ExitCode {
    // The same results for any thread count (RAYON_NUM_THREADS).
    brdf_solve::sequential_factorisations();
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of our output went away (`brdf info x | head`): done.
        Err(e) if e.is_broken_pipe() => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
