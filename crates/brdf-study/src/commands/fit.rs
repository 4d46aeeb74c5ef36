//! `brdf fit`: fit any model to any data set; report parameters (with
//! standard errors and bounds), the error in the chosen metric and Ngan's,
//! the time, iterations and termination; optionally save the model.

use std::path::PathBuf;

use brdf_models::{ModelConfig, entry};

use crate::StudyError;
use crate::pipeline::{FitOptions, FitSummary, Objective, Solver, fit, fit_sopp};
use crate::saved_model::SavedModel;

/// Arguments of `brdf fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {
    /// Data set: `PATH` or `PATH#SAMPLE` (e.g. `$BRDF_DATA/curet/abrdf.dat#25`).
    #[arg(long)]
    pub data: String,
    /// Model name (see `brdf models`).
    #[arg(long)]
    pub model: String,
    /// Objective and metric: ngan, sopp, sopp-unweighted, lafortune, log.
    #[arg(long, default_value = "ngan")]
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
    /// irls[:WEIGHT] (all-linear models).
    #[arg(long, default_value = "auto")]
    pub solver: String,
    /// Multi-start count.
    #[arg(long, default_value_t = 12)]
    pub starts: usize,
    /// Write the fitted model (JSON) here.
    #[arg(long)]
    pub save: Option<PathBuf>,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
    /// Specular lobes (Lafortune, Cook-Torrance).
    #[arg(long, default_value_t = 1)]
    pub lobes: usize,
    /// Koenderink expansion order.
    #[arg(long, default_value_t = 8)]
    pub order: usize,
    /// Polynomial degree (Kurt's model).
    #[arg(long, default_value_t = 7)]
    pub degree: usize,
}

/// Run `brdf fit`.
pub fn run(args: &FitArgs) -> Result<(), StudyError> {
    if !(args.limit > 0.0 && args.limit <= 90.0) {
        return Err(StudyError::Usage(format!(
            "--limit {} must be in (0, 90] degrees",
            args.limit
        )));
    }
    let opts = FitOptions {
        objective: Objective::parse(&args.metric)?,
        solver: Solver::parse(&args.solver)?,
        starts: args.starts,
        ..FitOptions::default()
    };
    let data = crate::data::load(&args.data)?;
    let (data, invalid) = data.filter_invalid(false);
    let (data, angle) = data.filter_angle_limit(args.limit.to_radians());
    let sets = match args.channels.as_str() {
        "rgb" => vec![data.clone()],
        "grey" => vec![data.mean_channel()],
        "per-channel" => (0..data.channels())
            .map(|c| data.single_channel(c))
            .collect(),
        other => {
            return Err(StudyError::Usage(format!(
                "--channels {other}: expected grey, rgb or per-channel"
            )));
        }
    };
    let e = entry(&args.model).ok_or_else(|| {
        StudyError::Usage(format!("no such model `{}`; see `brdf models`", args.model))
    })?;
    let mut reports: Vec<FitSummary> = Vec::new();
    for set in &sets {
        let config = ModelConfig {
            channels: set.channels(),
            lobes: args.lobes,
            order: args.order,
            degree: args.degree,
        };
        let build = |config: &ModelConfig| e.build_for(config, set.pairs());
        let mut model = build(&config)?;
        let report = if opts.solver == Solver::Sopp {
            let mut grey = build(&ModelConfig {
                channels: 1,
                ..config
            })?;
            fit_sopp(grey.as_mut(), model.as_mut(), set, &opts)?
        } else {
            fit(model.as_mut(), set, &opts)?
        };
        if let Some(path) = &args.save {
            if sets.len() > 1 {
                return Err(StudyError::Usage(
                    "--save needs one model: use --channels rgb or grey".into(),
                ));
            }
            let prov = format!(
                "{} on {}, {} = {:.6e}",
                report.solver, report.data, report.objective, report.error
            );
            SavedModel::capture(model.as_ref(), &config, set.pairs(), prov)?.save(path)?;
        }
        reports.push(report);
    }
    if args.json {
        let v = serde_json::json!({
            "fits": reports,
            "dropped_invalid": invalid.dropped(),
            "dropped_angle": angle.dropped(),
            "negative_values_kept": data.count_negative(),
        });
        say!("{}", serde_json::to_string_pretty(&v)?)?;
        return Ok(());
    }
    for r in &reports {
        say!(
            "model {} on {} ({} samples; dropped {} invalid, {} beyond {} deg)",
            r.model,
            r.data,
            r.samples,
            invalid.dropped(),
            angle.dropped(),
            args.limit
        )?;
        say!("solver: {}", r.solver)?;
        say!(
            "iterations {}, {}; starts {} ({} converged, {} at the best cost)",
            r.iterations,
            r.termination,
            r.starts.0,
            r.starts.1,
            r.starts.2
        )?;
        for p in &r.parameters {
            let se = p
                .std_error
                .map(|s| format!("+- {s:.3e}"))
                .unwrap_or_default();
            let b = p
                .at_bound
                .map(|b| format!(" [at {b} bound]"))
                .unwrap_or_default();
            let pr = if p.projected { " (projected)" } else { "" };
            say!("  {:<8} {:>14.6e} {se}{b}{pr}", p.name, p.value)?;
        }
        say!(
            "{} error: {:.6e}  Ngan L2: {:.6e}  time: {:.3} ms",
            r.objective,
            r.error,
            r.ngan_l2,
            r.seconds * 1e3
        )?;
    }
    Ok(())
}
