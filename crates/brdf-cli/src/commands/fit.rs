//! `brdf fit`: fit any model to any data set; report parameters (with
//! standard errors and bounds), the error in the chosen metric and Ngan's,
//! the time, iterations and termination; optionally save the model.

use std::path::PathBuf;
use std::sync::Arc;

use brdf_fit::{FitRequest, Material, Solver};
use brdf_models::ModelConfig;

use crate::error::CliError;
use crate::opts::{ChannelsArg, MetricArg, TargetArg};
use crate::progress::Bars;

/// Arguments of `brdf fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {
    /// Data set: `PATH` or `PATH#SAMPLE` (e.g. `$BRDF_DATA/curet/abrdf.dat#25`).
    #[arg(long)]
    pub data: String,
    /// Model name (see `brdf models`).
    #[arg(
        long,
        required_unless_present = "for_renderer",
        conflicts_with = "for_renderer"
    )]
    pub model: Option<String>,
    /// Fit for this renderer: among the models it renders exactly, the one
    /// whose render is closest to the data (fitted for appearance), written
    /// as its material to --out.
    #[arg(long = "for", value_enum, value_name = "RENDERER", requires = "out")]
    pub for_renderer: Option<TargetArg>,
    /// With --for: the material file to write.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Objective and metric: auto (appearance for renderer models on data
    /// that can be rendered, else ngan), appearance (candidates chosen by
    /// image error, refined in the image objective), or one objective.
    #[arg(
        long,
        value_enum,
        default_value = "auto",
        conflicts_with = "for_renderer"
    )]
    pub metric: MetricArg,
    /// Drop samples with theta_i or theta_o above this angle (degrees).
    #[arg(long, default_value_t = 80.0, allow_negative_numbers = true)]
    pub limit: f64,
    /// grey (mean of the channels), rgb (shared non-linear, per-channel
    /// linear parameters) or per-channel (everything per channel).
    #[arg(
        long,
        value_enum,
        default_value = "rgb",
        conflicts_with = "for_renderer"
    )]
    pub channels: ChannelsArg,
    /// Solver: auto (default: IRLS bisquare for the polynomial, direct least
    /// squares for other linear models, sqp otherwise), sqp (linear
    /// parameters projected out), lm, sopp (Sopp's two stages), ols or
    /// irls or irls:WEIGHT (all-linear models).
    #[arg(long, default_value = "auto", value_parser = crate::opts::solver, conflicts_with = "for_renderer")]
    pub solver: Solver,
    /// Multi-start count.
    #[arg(long, default_value_t = 12, conflicts_with = "for_renderer")]
    pub starts: usize,
    /// Reweighting cap of a robust (IRLS) fit (50 is MATLAB's
    /// `robustfit`'s); a fit whose reweighting cycles stops earlier, when
    /// a weighted solution recurs, and says so.
    #[arg(long, default_value_t = brdf_fit::options::IRLS_MAX_ITERATIONS, conflicts_with = "for_renderer")]
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
    #[arg(long, default_value_t = 1, value_parser = crate::opts::at_least_one, conflicts_with = "for_renderer")]
    pub lobes: usize,
    /// Koenderink expansion order.
    #[arg(long, default_value_t = 8, conflicts_with = "for_renderer")]
    pub order: usize,
    /// Polynomial degree (Kurt's model).
    #[arg(long, default_value_t = 7, conflicts_with = "for_renderer")]
    pub degree: usize,
    /// Write a self-contained HTML report of the fit here.
    #[arg(long, conflicts_with = "for_renderer")]
    pub report: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Run `brdf fit`: a [`FitRequest`] built from the arguments, its
/// outcome printed, saved and reported.
pub fn run(args: &FitArgs) -> Result<(), CliError> {
    let material = Arc::new(Material::load(&args.data)?);
    for n in &material.samples().notes {
        eprintln!("note: {n}");
    }
    let bars = Bars::new(args.quiet);
    let (Some(model), None) = (&args.model, args.for_renderer) else {
        return fit_for(args, &material, &bars);
    };
    let request = FitRequest {
        metric: args.metric.metric()?,
        channels: args.channels.mode()?,
        solver: args.solver,
        starts: args.starts,
        irls_max_iterations: args.irls_max_iterations,
        limit_deg: args.limit,
        config: ModelConfig {
            lobes: args.lobes,
            order: args.order,
            degree: args.degree,
            ..ModelConfig::default()
        },
        polish: args.polish,
        progress: &bars,
        ..FitRequest::new(&material, brdf_fit::resolve(model)?)
    };
    if args.polish && !request.resolved_metric().0 {
        return Err(CliError::Usage(format!(
            "--polish refines a fit for appearance, which `{}` with --metric {} on {} is not: use a renderer model (principled, gltf, gltf-ext, ggx) or --metric appearance on RGL `.bsdf` or MERL `.binary` data",
            model,
            request.metric.name(),
            args.data
        )));
    }
    let wants_one = args.save.is_some() || args.report.is_some();
    if wants_one && request.channels.models(material.samples()) > 1 {
        return Err(CliError::Usage(
            "--save and --report need one model: use --channels rgb or grey".into(),
        ));
    }
    let outcome = request.run()?;
    if wants_one {
        let report = outcome.report()?;
        let saved = report.saved_model(material.name())?;
        if let Some(path) = &args.save {
            saved.save(path)?;
        }
        if let Some(path) = &args.report {
            write_report(args, &material, &saved, report, outcome.seconds, path)?;
        }
    }
    if args.json {
        let v = brdf_fit::fit_json(&outcome.reports, material.samples())?;
        say!("{}", serde_json::to_string_pretty(&v)?)?;
        return Ok(());
    }
    for rep in &outcome.reports {
        say_raw!("{}", brdf_fit::report_text::text(rep))?;
    }
    say!(
        "wall time: {:.2} s (the whole command's fit, image errors included)",
        outcome.seconds
    )
}

/// `brdf fit --for RENDERER --out FILE`: the renderer's exact models fitted
/// for appearance, the closest written as its material.
fn fit_for(args: &FitArgs, material: &Material, bars: &Bars) -> Result<(), CliError> {
    let (Some(target), Some(out)) = (args.for_renderer, &args.out) else {
        return Err(CliError::Usage(
            "brdf fit needs --model NAME, or --for RENDERER --out FILE".into(),
        ));
    };
    let write = brdf_export::WriteOptions {
        name: brdf_export::identifier(
            &std::path::Path::new(material.name())
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default(),
        ),
        ..brdf_export::WriteOptions::default()
    };
    let request = brdf_fit::SelectRequest {
        limit_deg: args.limit,
        polish: args.polish,
        progress: bars,
        ..brdf_fit::SelectRequest::new(material)
    };
    let done = brdf_export::for_renderer::fit_for(&request, target.target(), &write)?;
    std::fs::write(out, &done.text).map_err(|source| CliError::Io {
        path: out.display().to_string(),
        source,
    })?;
    if let Some(path) = &args.save {
        done.report.saved_model(material.name())?.save(path)?;
    }
    if args.json {
        let v = brdf_fit::select_by_image_json(&material.samples().name, &done.rows, done.choice)?;
        return say!("{}", serde_json::to_string_pretty(&v)?);
    }
    crate::commands::select::print_by_image(&done.rows, done.choice)?;
    crate::commands::select::print_samples(&done.rows[done.choice])?;
    say!(
        "wrote {} ({}, exact in the renderer)\n{}",
        out.display(),
        done.rows[done.choice].label,
        target.target().usage(&out.display().to_string())
    )
}

/// The HTML report of a fit (`--report`), with the whole fit's `seconds`
/// (candidates and image errors included, as `brdf batch` gives them) and
/// how its kept solve ended; the page reuses the material's renders.
fn write_report(
    args: &FitArgs,
    material: &Arc<Material>,
    saved: &brdf_models::saved_model::SavedModel,
    report: &brdf_fit::FitReport,
    seconds: f64,
    path: &std::path::Path,
) -> Result<(), CliError> {
    let run = brdf_report::RunInfo {
        seconds,
        termination: report.summary.termination.to_string(),
        ended: Some(report.summary.termination.clone()),
        iterations: Some(report.summary.iterations),
    };
    let input = brdf_report::FitInput {
        data: &args.data,
        saved,
        fit_source: "brdf fit",
        run: Some(run),
        selection: None,
    };
    let mut analyser = brdf_report::Analyser::with_material(Arc::clone(material));
    crate::commands::report::fit_report(&input, path, args.quiet, &mut analyser)
}
