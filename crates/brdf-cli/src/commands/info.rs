//! `brdf info PATH [--json]`: what a data file holds — format, sample
//! count, channels, invalid count, value range, angle ranges.

use crate::error::CliError;

/// Arguments of `brdf info`.
#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// Data file (`PATH` or `PATH#SAMPLE`).
    pub path: String,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
}

/// Run `brdf info`.
pub fn run(args: &InfoArgs) -> Result<(), CliError> {
    let description = brdf_io::describe::describe(&args.path)?;
    if args.json {
        say!("{}", serde_json::to_string_pretty(&description)?)
    } else {
        say_raw!("{description}")
    }
}
