//! `irls_peer`: the Rust side of the IRLS comparison. Writes
//! the IRLS designs (Kurt's degree-7 polynomial designs of the isotropic
//! CUReT materials and the 900,000 x 10 synthetic design) where
//! `benches/peers/irls_statsmodels.py` reads them, and times
//! `brdf_solve::irls` (bisquare, default tuning and acceleration) on each
//! under two conventions: statsmodels' (its scale, its deviance test) and
//! MATLAB 2004's (leverage-adjusted MAD scale, the coefficient test).
//!
//! ```text
//! irls_peer [--out DIR] [--curet all|none|N[,N..]] [--no-synthetic] [--min-seconds S]
//! ```
//!
//! Writes `DIR/designs/` (the export) and `DIR/rust.jsonl`: one JSON object
//! per design and convention with `name`, `rows`, `cols`, `convention`,
//! `stopping`, `iterations`, `converged`, `termination`, `seconds` (median
//! wall time of one fit), `runs`, `coefficients`. Each fit is repeated at
//! least 3 times and until about `S` seconds (default 0.2) have passed.
//! Data from `BRDF_DATA`; DIR defaults to `$CARGO_TARGET_DIR/peers/irls` or
//! `target/peers/irls`.

use std::io::Write;
use std::path::{Path, PathBuf};

use brdf_benches::irls_designs::{self, Design};
use brdf_benches::peers::PeerError;
use brdf_solve::{IrlsOptions, ScaleConvention, StoppingTest, irls};

struct Args {
    out: PathBuf,
    curet: Option<Vec<u32>>,
    use_curet: bool,
    synthetic: bool,
    min_seconds: f64,
}

fn value(it: &mut impl Iterator<Item = String>, flag: &str) -> Result<String, PeerError> {
    it.next()
        .ok_or_else(|| PeerError::Usage(format!("{flag} needs a value")))
}

fn parse_args() -> Result<Args, PeerError> {
    let mut a = Args {
        out: std::env::var_os("CARGO_TARGET_DIR")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("target"))
            .join("peers")
            .join("irls"),
        curet: None,
        use_curet: true,
        synthetic: true,
        min_seconds: 0.2,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        match flag.as_str() {
            "--out" => a.out = PathBuf::from(value(&mut it, "--out")?),
            "--curet" => match value(&mut it, "--curet")?.as_str() {
                "all" => (a.curet, a.use_curet) = (None, true),
                "none" => a.use_curet = false,
                list => {
                    let n: Result<Vec<u32>, _> = list.split(',').map(str::parse).collect();
                    a.curet = Some(n.map_err(|_| {
                        PeerError::Usage(format!(
                            "--curet `{list}`: all, none or sample numbers like 4,25"
                        ))
                    })?);
                }
            },
            "--no-synthetic" => a.synthetic = false,
            "--min-seconds" => {
                let v = value(&mut it, "--min-seconds")?;
                a.min_seconds = v
                    .parse()
                    .ok()
                    .filter(|s: &f64| s.is_finite() && *s >= 0.0)
                    .ok_or_else(|| {
                        PeerError::Usage(format!("--min-seconds `{v}`: a number >= 0"))
                    })?;
            }
            other => {
                return Err(PeerError::Usage(format!(
                    "unknown argument `{other}` (see the doc of irls_peer)"
                )));
            }
        }
    }
    Ok(a)
}

/// The conventions timed: (name, options).
fn conventions() -> [(&'static str, IrlsOptions); 2] {
    [
        (
            "statsmodels",
            IrlsOptions {
                scale: ScaleConvention::Statsmodels,
                stopping: StoppingTest::Deviance,
                ..IrlsOptions::default()
            },
        ),
        (
            "matlab2004",
            IrlsOptions {
                scale: ScaleConvention::Matlab2004,
                stopping: StoppingTest::Coefficients,
                ..IrlsOptions::default()
            },
        ),
    ]
}

/// Fit `d` under `options` at least 3 times and until `min_seconds` have
/// passed (at most 1000 runs); the JSON record with the median wall time.
fn time_one(
    d: &Design,
    convention: &str,
    options: &IrlsOptions,
    min_seconds: f64,
) -> Result<serde_json::Value, PeerError> {
    let mut times = Vec::new();
    let mut total = 0.0;
    let sol = loop {
        let t0 = std::time::Instant::now();
        let sol = irls(d.x.as_ref(), std::hint::black_box(&d.y), options)?;
        let dt = t0.elapsed().as_secs_f64();
        times.push(dt);
        total += dt;
        if (times.len() >= 3 && total >= min_seconds) || times.len() >= 1000 {
            break sol;
        }
    };
    times.sort_by(f64::total_cmp);
    let stopping = match options.stopping {
        StoppingTest::Coefficients => "coefficients",
        StoppingTest::Deviance => "deviance",
    };
    Ok(serde_json::json!({
        "name": d.name,
        "rows": d.x.nrows(),
        "cols": d.x.ncols(),
        "convention": convention,
        "stopping": stopping,
        "iterations": sol.iterations,
        "accelerated_steps": sol.accelerated_steps,
        "converged": sol.converged(),
        "termination": sol.termination.describe(),
        "seconds": times[times.len() / 2],
        "runs": times.len(),
        "coefficients": sol.coef,
    }))
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> PeerError {
    let path = path.display().to_string();
    move |source| PeerError::Io { path, source }
}

fn main() {
    if let Err(e) = run() {
        eprintln!("irls_peer: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), PeerError> {
    let args = parse_args()?;
    let mut designs = Vec::new();
    if args.use_curet {
        let data = PathBuf::from(
            std::env::var_os("BRDF_DATA")
                .ok_or_else(|| PeerError::Usage("set BRDF_DATA to the data folder".into()))?,
        );
        designs = irls_designs::curet_designs(&data, args.curet.as_deref())?;
        if let Some(want) = &args.curet
            && designs.len() != want.len()
        {
            return Err(PeerError::Missing(format!(
                "isotropic CUReT samples {want:?}: found {} of them",
                designs.len()
            )));
        }
    }
    if args.synthetic {
        designs.push(irls_designs::synthetic(900_000, 10));
    }
    let all: Vec<&Design> = designs.iter().collect();
    irls_designs::export(&all, &args.out.join("designs"))?;
    let path = args.out.join("rust.jsonl");
    let mut file = std::fs::File::create(&path).map_err(io_err(&path))?;
    let convs = conventions();
    let bar = indicatif::ProgressBar::new((designs.len() * convs.len()) as u64);
    for d in &designs {
        for (name, options) in &convs {
            let rec = time_one(d, name, options, args.min_seconds)?;
            let line = format!(
                "{:>20} {:>11}: {:>2} iterations, {:.3e} s  {}",
                d.name,
                name,
                rec["iterations"],
                rec["seconds"].as_f64().unwrap_or(f64::NAN),
                rec["termination"].as_str().unwrap_or("?")
            );
            // A hidden bar (stderr not a terminal) prints nothing itself.
            if bar.is_hidden() {
                eprintln!("{line}");
            } else {
                bar.println(line);
            }
            writeln!(file, "{rec}").map_err(io_err(&path))?;
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    Ok(())
}
