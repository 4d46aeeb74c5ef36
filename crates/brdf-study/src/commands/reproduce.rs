//! `brdf reproduce`: the study. Runs the parts of [`crate::study::parts`]
//! (all by default; `--only NAMES` or a `--spec FILE` selects), writes
//! their tables, plots and renderings into the output folder, and
//! generates its `README.md`. Nothing outside the selection is loaded or
//! fitted.
//!
//! Data: `--data DIR` or `BRDF_DATA`; without measured data it runs on the
//! built-in synthetic materials into `OUT/synthetic/` (never over measured
//! results) and says so in every table.

use std::path::PathBuf;

use crate::StudyError;
use crate::study::spec::{LafortuneBox, StudySpec};
use crate::study::{Study, create_dir, parts, readme};

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
    /// metrics, limits and Lafortune's box (see the module docs of `study::spec`).
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
}

fn spec_of(args: &ReproduceArgs) -> Result<StudySpec, StudyError> {
    let mut spec = match &args.spec {
        Some(p) => StudySpec::read(p)?,
        None => StudySpec::default(),
    };
    if !args.only.is_empty() {
        spec.tables = args.only.clone();
    }
    if args.lafortune_wide {
        spec.lafortune_box = LafortuneBox::Wide;
    }
    spec.check()
        .map_err(|e| StudyError::Usage(format!("--only/--spec: {e}")))?;
    Ok(spec)
}

/// Run `brdf reproduce`.
pub fn run(args: &ReproduceArgs) -> Result<(), StudyError> {
    if args.list {
        for p in parts::PARTS {
            say!("{:16} {}", p.name, p.about)?;
        }
        return Ok(());
    }
    let spec = spec_of(args)?;
    let data = args
        .data
        .clone()
        .or_else(|| std::env::var_os("BRDF_DATA").map(PathBuf::from));
    // The synthetic demonstration never writes over measured results.
    let out = if data.is_none() {
        let out = args.out.join("synthetic");
        eprintln!(
            "brdf reproduce: no measured data (BRDF_DATA unset, no --data): running on built-in synthetic data into {}",
            out.display()
        );
        out
    } else {
        args.out.clone()
    };
    create_dir(&out)?;
    let mut study = Study::new(data, out, spec);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .map_err(|e| StudyError::Usage(format!("--threads: {e}")))?;
    pool.install(|| parts::run_all(&mut study))?;
    readme::write(&study, &command_line(args))?;
    say!(
        "wrote {} entries into {} (listed in its README.md)",
        study.written.len(),
        study.out.display()
    )?;
    Ok(())
}

/// The command as it was run, for the README (no absolute paths: the data
/// folder is named by `BRDF_DATA`).
fn command_line(args: &ReproduceArgs) -> String {
    let mut s = "brdf reproduce".to_string();
    if !args.only.is_empty() {
        s += &format!(" --only {}", args.only.join(","));
    }
    if let Some(p) = &args.spec {
        s += &format!(
            " --spec {}",
            crate::report::data_name(&p.display().to_string())
        );
    }
    if args.lafortune_wide {
        s += " --lafortune-wide";
    }
    s
}
