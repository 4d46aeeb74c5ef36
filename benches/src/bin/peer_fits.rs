//! `peer_fits`: build the peer problems, export them for the
//! Python side (`benches/peers/peers.py`) and fit them with every Rust
//! solver of the comparison (ours: bounded, variable projection + polish;
//! the `levenberg-marquardt` and `varpro` crates), writing each solver's
//! final parameters, time and passes next to the export.
//!
//! ```text
//! peer_fits [--out DIR] [--only NAME[,NAME..]] [--solvers S[,S..]] [--models M[,M..]] [--no-export]
//! ```
//!
//! Problems: `paper_white_grey_MODEL`, `paper_white_rgb_MODEL`,
//! `curet25_MODEL` (MODEL `as` or `ct`); solvers `bounded`, `varpro`,
//! `lm-crate`, `varpro-crate`; models `ashikhmin-shirley` (default),
//! `cook-torrance`. Data from `BRDF_DATA`; DIR defaults to
//! `$CARGO_TARGET_DIR/peers` or `target/peers`.

use std::path::PathBuf;

use brdf_benches::peers::{
    Outcome, PeerError, PeerProblem, export, lm_crate, ours, problem, varpro_crate,
};

struct Args {
    out: PathBuf,
    only: Option<Vec<String>>,
    solvers: Vec<String>,
    models: Vec<String>,
    export: bool,
}

fn list(v: Option<String>, flag: &str) -> Result<Vec<String>, PeerError> {
    let v = v.ok_or_else(|| PeerError::Usage(format!("{flag} needs a value")))?;
    Ok(v.split(',').map(str::to_string).collect())
}

fn parse_args() -> Result<Args, PeerError> {
    let default_out = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target"))
        .join("peers");
    let mut a = Args {
        out: default_out,
        only: None,
        solvers: ["bounded", "varpro", "lm-crate", "varpro-crate"]
            .map(String::from)
            .to_vec(),
        models: vec!["ashikhmin-shirley".into()],
        export: true,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        match flag.as_str() {
            "--out" => {
                a.out = it
                    .next()
                    .map(PathBuf::from)
                    .ok_or_else(|| PeerError::Usage("--out needs a folder".into()))?
            }
            "--only" => a.only = Some(list(it.next(), "--only")?),
            "--solvers" => a.solvers = list(it.next(), "--solvers")?,
            "--models" => a.models = list(it.next(), "--models")?,
            "--no-export" => a.export = false,
            other => {
                return Err(PeerError::Usage(format!(
                    "unknown argument `{other}` (see the doc of peer_fits)"
                )));
            }
        }
    }
    Ok(a)
}

fn run_solver(name: &str, prob: &PeerProblem) -> Result<Outcome, PeerError> {
    match name {
        "bounded" => ours::bounded(prob),
        "varpro" => ours::varpro_polish(prob),
        "lm-crate" => lm_crate::fit(prob),
        "varpro-crate" => varpro_crate::fit(prob),
        other => Err(PeerError::Usage(format!(
            "unknown solver `{other}`: bounded, varpro, lm-crate, varpro-crate"
        ))),
    }
}

type Builder = Box<dyn Fn() -> Result<PeerProblem, PeerError>>;

fn main() {
    if let Err(e) = run() {
        eprintln!("peer_fits: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), PeerError> {
    let args = parse_args()?;
    let data = PathBuf::from(
        std::env::var_os("BRDF_DATA")
            .ok_or_else(|| PeerError::Usage("set BRDF_DATA to the data folder".into()))?,
    );
    std::fs::create_dir_all(&args.out).map_err(|source| PeerError::Io {
        path: args.out.display().to_string(),
        source,
    })?;
    let mut builders: Vec<(String, Builder)> = Vec::new();
    for m in &args.models {
        let short = match m.as_str() {
            "ashikhmin-shirley" => "as",
            "cook-torrance" => "ct",
            other => {
                return Err(PeerError::Usage(format!(
                    "model `{other}`: ashikhmin-shirley or cook-torrance"
                )));
            }
        };
        for (kind, nc) in [("grey", 1), ("rgb", 3)] {
            let (d, o, m) = (data.clone(), args.out.clone(), m.clone());
            builders.push((
                format!("paper_white_{kind}_{short}"),
                Box::new(move || problem::paper_white(&d, &o, nc, &m)),
            ));
        }
        let (d, m) = (data.clone(), m.clone());
        builders.push((
            format!("curet25_{short}"),
            Box::new(move || problem::curet(&d, 25, &m)),
        ));
    }
    for (name, build) in &builders {
        if let Some(only) = &args.only
            && !only.contains(name)
        {
            continue;
        }
        let prob = build()?;
        println!(
            "{}: {} samples of {} ({} channels), start {:?}",
            prob.name,
            prob.len(),
            prob.samples_present,
            prob.channels(),
            prob.start
        );
        if args.export {
            export::problem(&args.out, &prob)?;
        }
        let mut outcomes = Vec::new();
        for s in &args.solvers {
            let o = run_solver(s, &prob)?;
            println!(
                "  {:<42} {:>9.4} s (CPU {:>8.4} s)  x{:<3} res {:>4} jac {:>4}  cost {:.10e}  box {}  {}",
                o.solver,
                o.seconds,
                o.cpu_seconds,
                o.repeats,
                o.residual_evals,
                o.jacobian_evals.map_or("-".into(), |j| j.to_string()),
                o.own_cost,
                o.inside_box,
                o.termination
            );
            outcomes.push(o);
        }
        if args.export {
            export::results(&args.out, &prob, &outcomes)?;
        }
    }
    Ok(())
}
