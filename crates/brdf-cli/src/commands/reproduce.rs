//! `brdf reproduce`: the study. Runs the parts of [`brdf_study::parts`]
//! (all by default; `--only NAMES` or a `--spec FILE` selects), writes
//! their tables, plots and renderings into the output folder, and
//! generates its `README.md`. Nothing outside the selection is loaded or
//! fitted.
//!
//! Data: `--data DIR` or `BRDF_DATA`; without measured data it runs on the
//! built-in synthetic materials into `OUT/synthetic/` (never over measured
//! results) and says so in every table.

use std::path::PathBuf;

use crate::error::CliError;
use brdf_study::reproduce::Reproduce;

/// Arguments of `brdf reproduce`.
#[derive(Debug, clap::Args)]
pub struct ReproduceArgs {
    /// Folder with the measured data (defaults to `$BRDF_DATA`).
    #[arg(long)]
    pub data: Option<PathBuf>,
    /// Output folder.
    #[arg(long, default_value = "results")]
    pub out: PathBuf,
    /// Run only these parts (comma-separated; `brdf reproduce --list` names them).
    #[arg(long, value_delimiter = ',')]
    pub only: Vec<String>,
    /// A TOML file selecting tables, materials, models, degrees, lobes,
    /// metrics, limits and Lafortune's box (see the module docs of `brdf_study::context::spec`).
    #[arg(long)]
    pub spec: Option<PathBuf>,
    /// Fit Lafortune in the wide box (Cxy, Cz in [-1, 1]) instead of Kurt's.
    #[arg(long)]
    pub lafortune_wide: bool,
    /// Worker threads for the fits (default: all cores). Results are the
    /// same for any count.
    #[arg(long)]
    pub threads: Option<usize>,
    /// List the parts and exit.
    #[arg(long)]
    pub list: bool,
    /// No progress bars.
    #[arg(long)]
    pub quiet: bool,
}

/// The data folder named by `--data` or `BRDF_DATA`, and which named it;
/// an error when it cannot be read, or is empty and no part is `selected`
/// (a typo would otherwise silently give the synthetic study).
fn data_folder(
    arg: Option<&std::path::Path>,
    selected: bool,
) -> Result<Option<(PathBuf, &'static str)>, CliError> {
    let env = std::env::var_os("BRDF_DATA").filter(|d| !d.is_empty());
    let (dir, from) = match (arg, env) {
        (Some(d), _) => (d.to_path_buf(), "--data"),
        (None, Some(d)) => (PathBuf::from(d), "BRDF_DATA"),
        (None, None) => return Ok(None),
    };
    let fix =
        "point it at the folder holding curet/, rgl/, ..., or unset it for the synthetic materials";
    let empty = match std::fs::read_dir(&dir) {
        Err(e) => {
            return Err(CliError::Usage(format!(
                "{from}={}: cannot read the folder ({e}); {fix}",
                dir.display()
            )));
        }
        Ok(mut entries) => entries.next().is_none(),
    };
    // With parts selected, the study says what each one needs.
    if empty && !selected {
        return Err(CliError::Usage(format!(
            "{from}={}: the folder is empty; {fix}",
            dir.display()
        )));
    }
    Ok(Some((dir, from)))
}

/// Run `brdf reproduce`.
pub fn run(args: &ReproduceArgs) -> Result<(), CliError> {
    if args.list {
        for (name, about) in brdf_study::reproduce::list() {
            say!("{name:16} {about}")?;
        }
        return Ok(());
    }
    let selected = !args.only.is_empty() || args.spec.is_some();
    let folder = data_folder(args.data.as_deref(), selected)?;
    let done = brdf_study::reproduce::run(&Reproduce {
        data: args.data.clone(),
        out: args.out.clone(),
        only: args.only.clone(),
        spec: args.spec.clone(),
        lafortune_wide: args.lafortune_wide,
        threads: args.threads,
        progress: Some(std::sync::Arc::new(crate::progress::Bars::new(args.quiet))),
    })
    .map_err(|e| match &folder {
        // Say which folder was read: an empty or wrong one explains most failures.
        Some((dir, from)) => {
            CliError::Usage(format!("{e} (data read from {from}={})", dir.display()))
        }
        None => e.into(),
    })?;
    say!(
        "wrote {} entries into {} (listed in its README.md)",
        done.written,
        done.out.display()
    )
}
