//! `brdf fit`: fit any model to any data set; report parameters (with
//! standard errors and bounds), the error in the chosen metric and Ngan's,
//! the time, iterations and termination; optionally save the model.

use std::path::PathBuf;

use brdf_fit::{Channels, Fit, Objective, Solver, judged};
use brdf_render::judge::{Judge, REPORT_SIZE};

use crate::error::CliError;

/// Arguments of `brdf fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {
    /// Data set: `PATH` or `PATH#SAMPLE` (e.g. `$BRDF_DATA/curet/abrdf.dat#25`).
    #[arg(long)]
    pub data: String,
    /// Model name (see `brdf models`).
    #[arg(long)]
    pub model: String,
    /// Objective and metric: auto (appearance for renderer models on data
    /// that can be rendered, else ngan), appearance (candidates chosen by
    /// image error, refined in the image objective), ngan, sopp,
    /// sopp-unweighted, lafortune, log, cube-root, relative, image.
    #[arg(long, default_value = "auto")]
    pub metric: String,
    /// Drop samples with theta_i or theta_o above this angle (degrees).
    #[arg(long, default_value_t = 80.0)]
    pub limit: f64,
    /// grey (mean of the channels), rgb (shared non-linear, per-channel
    /// linear parameters) or per-channel (everything per channel).
    #[arg(long, default_value = "rgb")]
    pub channels: String,
    /// Solver: auto (default: IRLS bisquare for the polynomial, direct least
    /// squares for other linear models, sqp otherwise), sqp (linear
    /// parameters projected out), lm, sopp (Sopp's two stages), ols or
    /// irls or irls:WEIGHT (all-linear models).
    #[arg(long, default_value = "auto")]
    pub solver: String,
    /// Multi-start count.
    #[arg(long, default_value_t = 12)]
    pub starts: usize,
    /// Reweighting cap of a robust (IRLS) fit (50 is MATLAB's
    /// `robustfit`'s); a fit whose reweighting cycles stops earlier, when
    /// a weighted solution recurs, and says so.
    #[arg(long, default_value_t = brdf_fit::options::IRLS_MAX_ITERATIONS)]
    pub irls_max_iterations: usize,
    /// End the fit for appearance with a search on the judge's own metric,
    /// the mean HDR-FLIP of the renders: a lower image error for a few
    /// seconds more.
    #[arg(long)]
    pub polish: bool,
    /// Write the fitted model (JSON) here.
    #[arg(long)]
    pub save: Option<PathBuf>,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
    /// Specular lobes (Lafortune, Cook-Torrance).
    #[arg(long, default_value_t = 1, value_parser = crate::opts::at_least_one)]
    pub lobes: usize,
    /// Koenderink expansion order.
    #[arg(long, default_value_t = 8)]
    pub order: usize,
    /// Polynomial degree (Kurt's model).
    #[arg(long, default_value_t = 7)]
    pub degree: usize,
    /// Write a self-contained HTML report of the fit here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Run `brdf fit`: a thin layer over [`brdf_fit::Fit`].
pub fn run(args: &FitArgs) -> Result<(), CliError> {
    let (path, _) = brdf_io::load::resolve_spec(&args.data)?;
    if path.is_dir() {
        return Err(CliError::Usage(format!(
            "`{0}` is a folder: fit one file, or `brdf batch --data {0}`",
            args.data
        )));
    }
    let data = brdf_io::load(&args.data)?;
    let sets = match args.channels.as_str() {
        "rgb" => vec![(data.clone(), Channels::All)],
        "grey" => vec![(data.clone(), Channels::Grey)],
        "per-channel" => (0..data.channels())
            .map(|c| (data.single_channel(c), Channels::All))
            .collect(),
        other => {
            return Err(CliError::Usage(format!(
                "--channels {other}: expected grey, rgb or per-channel"
            )));
        }
    };
    if (args.save.is_some() || args.report.is_some()) && sets.len() > 1 {
        return Err(CliError::Usage(
            "--save and --report need one model: use --channels rgb or grey".into(),
        ));
    }
    let dense = brdf_io::load_dense(&args.data)?;
    let entry = brdf_fit::resolve(&args.model)?;
    // Per-channel fits are grey models of one channel: not rendered.
    let dense = dense.as_deref().filter(|_| args.channels != "per-channel");
    let (appearance, metric) = judged::metric_choice(&args.metric, entry.name, dense.is_some());
    if args.polish && !appearance {
        return Err(CliError::Usage(format!(
            "--polish refines a fit for appearance, which `{}` with --metric {} on {} is not: use a renderer model (principled, gltf, gltf-ext, ggx) or --metric appearance on RGL `.bsdf` or MERL `.binary` data",
            args.model, args.metric, args.data
        )));
    }
    let mut reports = Vec::new();
    brdf_study::context::progress::set_quiet(args.quiet);
    let bar = brdf_study::context::progress::bar(sets.len(), "fit");
    for (set, channels) in &sets {
        bar.set_message(format!("{} on {}", args.model, set.name));
        let fit = Fit::entry(entry)
            .objective(Objective::parse(metric)?)
            .solver(Solver::parse(&args.solver)?)
            .starts(args.starts)
            .irls_max_iterations(args.irls_max_iterations)
            .limit_deg(args.limit)
            .channels(*channels)
            .lobes(args.lobes)
            .order(args.order)
            .degree(args.degree)
            .polish_on_flip(args.polish);
        let t0 = std::time::Instant::now();
        // With --report on data that can be rendered, the judge of the
        // fit's image errors also makes the page (the data rendered once).
        let (report, judge) = match dense.filter(|_| args.report.is_some()) {
            Some(d) => {
                let judge = Judge::with_data(REPORT_SIZE, d)?;
                let report = judged::fit_judged_on(&fit, set, d, appearance, &judge)?;
                (report, Some(judge))
            }
            None => (judged::fit_judged(&fit, set, dense, appearance)?, None),
        };
        let seconds = t0.elapsed().as_secs_f64();
        if let Some(path) = &args.save {
            report
                .saved_model(&brdf_fit::data_name(&args.data))?
                .save(path)?;
        }
        if let Some(path) = &args.report {
            write_report(args, &report, seconds, judge, path)?;
        }
        reports.push(report);
        bar.inc(1);
    }
    bar.finish_and_clear();
    if args.json {
        let v = brdf_fit::fit_json(&reports, &data)?;
        say!("{}", serde_json::to_string_pretty(&v)?)?;
        return Ok(());
    }
    for rep in &reports {
        say_raw!("{}", brdf_fit::report_text::text(rep))?;
    }
    Ok(())
}

/// The HTML report of a fit (`--report`), with the whole fit's `seconds`
/// (candidates and image errors included, as `brdf batch` gives them) and
/// how its kept solve ended.
fn write_report(
    args: &FitArgs,
    report: &brdf_fit::FitReport,
    seconds: f64,
    judge: Option<Judge>,
    path: &std::path::Path,
) -> Result<(), CliError> {
    let saved = report.saved_model(&brdf_fit::data_name(&args.data))?;
    let run = brdf_report::RunInfo {
        seconds,
        termination: report.summary.termination.to_string(),
        ended: Some(report.summary.termination.clone()),
        iterations: Some(report.summary.iterations),
    };
    let input = brdf_report::FitInput {
        data: &args.data,
        saved: &saved,
        fit_source: "brdf fit",
        run: Some(run),
        selection: None,
    };
    let mut analyser = match judge {
        Some(judge) => brdf_report::Analyser::with_judge(&args.data, judge)?,
        None => brdf_report::Analyser::new(REPORT_SIZE),
    };
    crate::commands::report::fit_report(&input, path, args.quiet, &mut analyser)
}
