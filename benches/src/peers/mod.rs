//! The side-by-side peer comparison of the solvers: the problems, their export
//! for the Python side (`benches/peers/peers.py`), and every Rust solver of
//! the comparison behind one interface ([`Outcome`]).
//!
//! | module | what |
//! | --- | --- |
//! | [`problem`] | the peer problems (paper_white on the full MERL grid, CUReT 25) and their start |
//! | [`npy`] | `.npy` writer |
//! | [`export`] | a problem and the solvers' results to a folder |
//! | [`ours`] | this workspace's bounded solver and variable projection |
//! | [`lm_crate`] | the `levenberg-marquardt` crate on the same problem |
//! | [`varpro_crate`] | the `varpro` crate on the same problem |

pub mod export;
pub mod lm_crate;
pub mod npy;
pub mod ours;
pub mod problem;
pub mod varpro_crate;

pub use problem::PeerProblem;

/// What went wrong building, exporting or solving a peer problem.
#[derive(Debug, thiserror::Error)]
pub enum PeerError {
    /// Reading the data.
    #[error(transparent)]
    Data(#[from] brdf_io::IoError),
    /// A model parameter problem.
    #[error(transparent)]
    Param(#[from] brdf_core::ParamError),
    /// A solver refused.
    #[error(transparent)]
    Solve(#[from] brdf_solve::SolveError),
    /// File system.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// Something the data should hold is not there.
    #[error("missing: {0}")]
    Missing(String),
    /// Bad arguments.
    #[error("{0}")]
    Usage(String),
}

/// One solver's run on one problem.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// Solver name as in the report.
    pub solver: String,
    /// Final full parameter vector.
    pub params: Vec<f64>,
    /// Wall-clock seconds of one fit (median over the repeats).
    pub seconds: f64,
    /// Processor seconds of the whole process (all threads, user + system)
    /// per fit, the mean over the repeats: less sensitive than the wall
    /// clock to other work on a shared machine.
    pub cpu_seconds: f64,
    /// Repeats timed.
    pub repeats: usize,
    /// Residual evaluations (full passes over the samples) per fit.
    pub residual_evals: usize,
    /// Jacobian evaluations per fit (`None` when the solver does not say).
    pub jacobian_evals: Option<usize>,
    /// Passes over the samples per fit, where one pass gives both the
    /// residuals and the normal equations (the Rust solvers on large
    /// problems: `ModelProblem`'s blocked pass); `None`: residual plus
    /// Jacobian evaluations.
    pub passes: Option<usize>,
    /// Why it stopped.
    pub termination: String,
    /// Whether the final parameters lie in the box.
    pub inside_box: bool,
    /// The solver's own `0.5 ||r||^2` (the shared cost is recomputed in Python).
    pub own_cost: f64,
}

/// Processor time of this process so far (user + system, all threads), from
/// `/proc/self/stat` in clock ticks of 1/100 s (Linux's fixed `USER_HZ`);
/// `NaN` where that file cannot be read.
pub fn process_cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return f64::NAN;
    };
    // Fields after the parenthesised command name; utime and stime are
    // fields 14 and 15 of the whole line.
    let Some((_, rest)) = stat.rsplit_once(')') else {
        return f64::NAN;
    };
    let f: Vec<&str> = rest.split_whitespace().collect();
    match (
        f.get(11).and_then(|x| x.parse::<f64>().ok()),
        f.get(12).and_then(|x| x.parse::<f64>().ok()),
    ) {
        (Some(u), Some(s)) => (u + s) / 100.0,
        _ => f64::NAN,
    }
}

/// Time `f` once; if one fit takes under 0.2 s, repeat until about a second
/// has passed (at most 200 runs). Returns the median wall time, the mean
/// processor time, the number of runs and the last result.
pub type Timed<T> = (f64, f64, usize, T);

/// See [`Timed`].
pub fn timed<T>(mut f: impl FnMut() -> Result<T, PeerError>) -> Result<Timed<T>, PeerError> {
    let mut times = Vec::new();
    let mut total = 0.0;
    let cpu0 = process_cpu_seconds();
    loop {
        let t0 = std::time::Instant::now();
        let r = f()?;
        let dt = t0.elapsed().as_secs_f64();
        times.push(dt);
        total += dt;
        if dt >= 0.2 || total >= 1.0 || times.len() >= 200 {
            let cpu = (process_cpu_seconds() - cpu0) / times.len() as f64;
            times.sort_by(f64::total_cmp);
            return Ok((times[times.len() / 2], cpu, times.len(), r));
        }
    }
}
