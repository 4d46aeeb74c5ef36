//! `fit_loop`: run one `brdf fit` (the library's [`FitRequest`]) many times
//! in one process, for profiling (`perf record -- fit_loop ...`) and quick
//! timing of the automatic multi-start fits.
//!
//! ```text
//! fit_loop DATA MODEL [--grey] [--reps N] [--lobes K] [--tol T] [--search-tol T] [--metric M] [--json]
//! ```
//!
//! DATA is anything `brdf_io::load` reads (`$BRDF_DATA/curet/abrdf.dat#25`).
//! Prints the median wall time and the mean processor time (whole process,
//! all threads) per fit and the final cost of the last fit; `--json` prints
//! them as one JSON object (read by `benches/peers/report.py`).

use std::time::Instant;

use brdf_benches::peers::process_cpu_seconds;
use brdf_fit::{ChannelMode, FitOutcome, FitRequest, Material, Metric};

const USAGE: &str = "fit_loop DATA MODEL [--grey] [--reps N] [--lobes K] [--tol T] [--search-tol T] [--metric M] [--json]";

/// The command line: the data, the model, the repetitions, JSON output,
/// and the request's settings ([`Settings::apply`]).
struct Args {
    data: String,
    model: String,
    reps: usize,
    json: bool,
    settings: Settings,
}

/// What the command line changes in the fit request.
#[derive(Default)]
struct Settings {
    grey: bool,
    lobes: Option<usize>,
    lm: brdf_solve::LmOptions,
    search: Option<f64>,
    metric: Option<brdf_fit::Objective>,
}

impl Settings {
    fn apply(self, request: &mut FitRequest) {
        if self.grey {
            request.channels = ChannelMode::Grey;
        }
        if let Some(k) = self.lobes {
            request.config.lobes = k;
        }
        request.lm = self.lm;
        if let Some(o) = self.metric {
            request.metric = Metric::Objective(o);
        }
        if let Some(t) = self.search {
            request.search_tolerance = t;
        }
    }
}

fn parse_args() -> Result<Args, Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let data = args.next().ok_or(USAGE)?;
    let model = args.next().ok_or(USAGE)?;
    let (mut reps, mut json, mut settings) = (10usize, false, Settings::default());
    while let Some(a) = args.next() {
        let mut value = || args.next().ok_or(USAGE);
        match a.as_str() {
            "--grey" => settings.grey = true,
            "--json" => json = true,
            "--reps" => reps = value()?.parse()?,
            "--lobes" => settings.lobes = Some(value()?.parse()?),
            "--metric" => settings.metric = Some(brdf_fit::Objective::parse(&value()?)?),
            "--search-tol" => settings.search = Some(value()?.parse()?),
            "--tol" => {
                let t: f64 = value()?.parse()?;
                let lm = &mut settings.lm;
                (lm.ftol, lm.xtol, lm.gtol) = (t, t, t);
            }
            _ => return Err(USAGE.into()),
        }
    }
    Ok(Args {
        data,
        model,
        reps,
        json,
        settings,
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let Args {
        data,
        model,
        reps,
        json,
        settings,
    } = parse_args()?;
    let grey = settings.grey;
    // The samples alone (no dense data): a fit's time, not the judge's.
    let material = Material::new(&data, brdf_io::load(&data)?, None);
    let mut request = FitRequest::new(&material, brdf_fit::resolve(&model)?);
    settings.apply(&mut request);
    let mut times = Vec::with_capacity(reps);
    let mut last = None;
    let cpu0 = process_cpu_seconds();
    for _ in 0..reps.max(1) {
        let t = Instant::now();
        last = Some(request.run().and_then(FitOutcome::into_report)?);
        times.push(t.elapsed().as_secs_f64());
    }
    let cpu = (process_cpu_seconds() - cpu0) / times.len() as f64;
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    let r = last.ok_or("no run")?;
    let s = &r.summary;
    if json {
        let data = match std::env::var("BRDF_DATA") {
            Ok(root) if !root.is_empty() => data.replacen(&root, "$BRDF_DATA", 1),
            _ => data.clone(),
        };
        let v = serde_json::json!({
            "model": model, "data": data, "channels": if grey { "grey" } else { "all" },
            "samples": s.samples, "samples_present": r.samples_present,
            "runs": times.len(), "median_seconds": median, "cpu_seconds": cpu,
            "ngan_l2": s.ngan_l2, "error": s.error, "iterations": s.iterations, "starts": s.starts,
            "termination": s.termination, "solver": s.solver,
            "threads": rayon::current_num_threads(),
        });
        println!("{v}");
    } else {
        println!(
            "{model}: median {:.3} ms (CPU {:.3} ms) per fit over {} runs; Ngan L2 {:.12e}; {} iterations; {} of {} samples; {}",
            1e3 * median,
            1e3 * cpu,
            times.len(),
            s.ngan_l2,
            s.iterations,
            s.samples,
            r.samples_present,
            s.termination
        );
    }
    Ok(())
}
