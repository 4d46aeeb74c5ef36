//! `brdf resample --from PATH --to merl|sopp-grid|csv OUT`: convert data
//! or a saved model; the conversion is [`brdf_fit::resample`].

use std::path::PathBuf;

use crate::error::CliError;

/// Arguments of `brdf resample`.
#[derive(Debug, clap::Args)]
pub struct ResampleArgs {
    /// Source: a data file, or a model saved by `brdf fit --save` (`.json`).
    #[arg(long)]
    pub from: String,
    /// Target: merl, sopp-grid or csv.
    #[arg(long)]
    pub to: String,
    /// Output file.
    pub out: PathBuf,
}

/// Run `brdf resample`.
pub fn run(args: &ResampleArgs) -> Result<(), CliError> {
    let to: brdf_fit::resample::Target = args.to.parse()?;
    if let Some(note) = brdf_fit::resample::resample(&args.from, to, &args.out)? {
        say!("{note}")?;
    }
    say!("wrote {}", args.out.display())
}
