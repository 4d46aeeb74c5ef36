//! `fit_loop`: run one `brdf fit` (the library's [`Fit`] builder) many times
//! in one process, for profiling (`perf record -- fit_loop ...`) and quick
//! timing of the automatic multi-start fits (issue 16).
//!
//! ```text
//! fit_loop DATA MODEL [--grey] [--reps N] [--lobes K] [--tol T] [--search-tol T]
//! ```
//!
//! DATA is anything `brdf_io::load` reads (`$BRDF_DATA/curet/abrdf.dat#25`).
//! Prints the median wall time per fit and the final cost of the last fit.

use std::time::Instant;

use brdf_fit::{Channels, Fit};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let usage = "fit_loop DATA MODEL [--grey] [--reps N] [--lobes K] [--tol T] [--search-tol T]";
    let data = args.next().ok_or(usage)?;
    let model = args.next().ok_or(usage)?;
    let (mut reps, mut grey, mut lobes) = (10usize, false, 1usize);
    let mut lm = brdf_solve::LmOptions::default();
    let mut search = None;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--grey" => grey = true,
            "--reps" => reps = args.next().ok_or(usage)?.parse()?,
            "--lobes" => lobes = args.next().ok_or(usage)?.parse()?,
            "--search-tol" => search = Some(args.next().ok_or(usage)?.parse()?),
            "--tol" => {
                let t: f64 = args.next().ok_or(usage)?.parse()?;
                (lm.ftol, lm.xtol, lm.gtol) = (t, t, t);
            }
            _ => return Err(usage.into()),
        }
    }
    let samples = brdf_io::load(&data)?;
    let channels = if grey { Channels::Grey } else { Channels::All };
    let mut fit = Fit::model(&model)?.channels(channels).lobes(lobes);
    if lm != brdf_solve::LmOptions::default() {
        fit = fit.lm_options(lm);
    }
    if let Some(t) = search {
        fit = fit.search_tolerance(t);
    }
    let mut times = Vec::with_capacity(reps);
    let mut last = None;
    for _ in 0..reps.max(1) {
        let t = Instant::now();
        last = Some(fit.run(&samples)?);
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    let r = last.ok_or("no run")?;
    println!(
        "{model}: median {:.3} ms per fit over {} runs; Ngan L2 {:.12e}; {} iterations; {} of {} samples; {}",
        1e3 * times[times.len() / 2],
        times.len(),
        r.summary.ngan_l2,
        r.summary.iterations,
        r.summary.samples,
        r.samples_present,
        r.summary.termination
    );
    Ok(())
}
