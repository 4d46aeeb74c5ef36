//! `brdf nist --dir DIR [--json] [--out DIR]`: certify the solver on every
//! NIST StRD problem of a folder, from both starts.

use std::path::PathBuf;

use brdf_solve::{Damping, LmOptions, Scaling};

use crate::error::CliError;

/// `--damping`: the damping schedule of Levenberg-Marquardt.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum DampingArg {
    /// Nielsen's gain-ratio schedule
    Nielsen,
    /// Sopp's schedule (multiply or divide by a fixed factor)
    Sopp,
}

/// `--scaling`: the scaling of the damping term.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ScalingArg {
    /// Marquardt's: the diagonal of J^T J
    Marquardt,
    /// Levenberg's: the identity
    Identity,
}

/// Arguments of `brdf nist`.
#[derive(Debug, clap::Args)]
pub struct NistArgs {
    /// Folder with StRD `.dat` files (default: `$BRDF_DATA/nist_strd`).
    #[arg(long)]
    pub dir: Option<PathBuf>,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
    /// Run only the configured solver (no fallback strategy); the other
    /// solver options apply only with this flag.
    #[arg(long)]
    pub single: bool,
    /// Damping schedule.
    #[arg(long, value_enum, default_value = "nielsen")]
    pub damping: DampingArg,
    /// Use geodesic acceleration.
    #[arg(long)]
    pub geodesic: bool,
    /// Iteration cap.
    #[arg(long, default_value_t = 1000)]
    pub max_iterations: usize,
    /// Relative-reduction tolerance (0 disables the test: the default, since
    /// a cost test certifies only half the digits of the parameters).
    #[arg(long, default_value_t = 0.0)]
    pub ftol: f64,
    /// Scaling of the damping term.
    #[arg(long, value_enum, default_value = "marquardt")]
    pub scaling: ScalingArg,
    /// Initial damping (default: 1e-3).
    #[arg(long)]
    pub initial_damping: Option<f64>,
    /// Also write `nist.md` and `nist.csv` into this folder.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Run `brdf nist`.
pub fn run(args: &NistArgs) -> Result<(), CliError> {
    let dir = match &args.dir {
        Some(d) => d.clone(),
        None => std::env::var_os("BRDF_DATA")
            .map(|d| PathBuf::from(d).join("nist_strd"))
            .ok_or_else(|| CliError::Usage("give --dir DIR or set BRDF_DATA".into()))?,
    };
    let damping = match args.damping {
        DampingArg::Nielsen => Damping::Nielsen,
        DampingArg::Sopp => Damping::Sopp,
    };
    let scaling = match args.scaling {
        ScalingArg::Marquardt => Scaling::Marquardt,
        ScalingArg::Identity => Scaling::Identity,
    };
    let options = LmOptions {
        scaling,
        damping,
        geodesic_acceleration: args.geodesic,
        max_iterations: args.max_iterations,
        max_evaluations: 20 * args.max_iterations,
        ftol: args.ftol,
        initial_damping: args.initial_damping,
        ..LmOptions::default()
    };
    let strategies = if args.single {
        vec![("LM (as configured)", options)]
    } else {
        brdf_study::nist::strategies()
    };
    let (runs, table) = brdf_study::nist::certify(&dir, &strategies, args.out.as_deref())?;
    if args.json {
        say!("{}", serde_json::to_string_pretty(&runs)?)
    } else {
        say_raw!("{}", table.markdown())
    }
}
