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

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let usage = "fit_loop DATA MODEL [--grey] [--reps N] [--lobes K] [--tol T] [--search-tol T] [--metric M] [--json]";
    let data = args.next().ok_or(usage)?;
    let model = args.next().ok_or(usage)?;
    let (mut reps, mut grey, mut lobes) = (10usize, false, 1usize);
    let mut lm = brdf_solve::LmOptions::default();
    let mut search = None;
    let mut json = false;
    let mut metric = None;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--grey" => grey = true,
            "--json" => json = true,
            "--reps" => reps = args.next().ok_or(usage)?.parse()?,
            "--lobes" => lobes = args.next().ok_or(usage)?.parse()?,
            "--metric" => metric = Some(brdf_fit::Objective::parse(&args.next().ok_or(usage)?)?),
            "--search-tol" => search = Some(args.next().ok_or(usage)?.parse()?),
            "--tol" => {
                let t: f64 = args.next().ok_or(usage)?.parse()?;
                (lm.ftol, lm.xtol, lm.gtol) = (t, t, t);
            }
            _ => return Err(usage.into()),
        }
    }
    // The samples alone (no dense data): a fit's time, not the judge's.
    let material = Material::new(&data, brdf_io::load(&data)?, None);
    let mut request = FitRequest::new(&material, brdf_fit::resolve(&model)?);
    request.channels = if grey {
        ChannelMode::Grey
    } else {
        ChannelMode::Rgb
    };
    request.config.lobes = lobes;
    request.lm = lm;
    if let Some(o) = metric {
        request.metric = Metric::Objective(o);
    }
    if let Some(t) = search {
        request.search_tolerance = t;
    }
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
