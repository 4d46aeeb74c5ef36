//! `brdf select --data PATH [--tolerance REL] [--json]`: fit the candidate
//! models and choose the smallest one within the tolerance of the best.

use crate::error::CliError;
use brdf_fit::FitOptions;

/// Arguments of `brdf select`.
#[derive(Debug, clap::Args)]
pub struct SelectArgs {
    /// Data set: `PATH` or `PATH#SAMPLE`.
    #[arg(long)]
    pub data: String,
    /// Accept errors up to (1 + REL) times the best.
    #[arg(long, default_value_t = 0.1)]
    pub tolerance: f64,
    /// Drop samples with theta_i or theta_o above this angle (degrees).
    #[arg(long, default_value_t = 80.0)]
    pub limit: f64,
    /// Fit the mean of the channels (grey) instead of every channel.
    #[arg(long)]
    pub grey: bool,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Run `brdf select`.
pub fn run(args: &SelectArgs) -> Result<(), CliError> {
    let data = brdf_io::load(&args.data)?;
    let data = brdf_fit::select::prepare(&data, args.limit, args.grey)?;
    brdf_study::context::progress::set_quiet(args.quiet);
    let bar = brdf_study::context::progress::bar(1, "select");
    let n = brdf_fit::select::candidates(data.channels()).len();
    bar.set_message(format!("fitting {n} candidates to {}", data.name));
    let (rows, choice) = brdf_fit::select::select(&data, args.tolerance, &FitOptions::default())?;
    bar.finish_and_clear();
    if args.json {
        let v = serde_json::json!({ "data": data.name, "tolerance": args.tolerance, "choice": rows[choice], "candidates": rows });
        return say!("{}", serde_json::to_string_pretty(&v)?);
    }
    let table = brdf_fit::select::table(&data.name, &rows, choice, args.tolerance);
    say_raw!("{}", table.markdown())
}
