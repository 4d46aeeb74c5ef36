//! Robust regression by iteratively reweighted least squares, as MATLAB's
//! `robustfit` (used by Kurt 2007), with the scale conventions of
//! `fitting.md` selectable by name:
//!
//! 1. `b` = ordinary least squares (column-pivoted QR, [`crate::lstsq`]).
//! 2. Leverages `h` = diagonal of the hat matrix of the unweighted design,
//!    capped at `0.9999`, computed once from its QR (not for statsmodels).
//! 3. Loop: `r = y - X b`; `r_adj = r / sqrt(1 - h)`; scale `s`;
//!    `u = r_adj / (tune s)`; `w = psi_weight(u)`; `b` = weighted least
//!    squares with `w`. Stop when every
//!    `|b - b_old| <= sqrt(eps) max(|b|, |b_old|)` or after the cap (default 50).
//!
//! Scale conventions ([`ScaleConvention`]); `a` = `|r_adj|` sorted with the
//! `p - 1` smallest dropped (`p` = number of coefficients):
//! - `Matlab2004`: MAD about the median of `a`, `median(|a - median(a)|) /
//!   0.6745`; if zero, `0.5 mean(|r_adj|)`;
//! - `Matlab2011`: about zero, `median(a) / 0.6745`, floored at
//!   `1e-6 std(y)`;
//! - `Statsmodels`: `median(|r|) / 0.6744897...` (`Phi^-1(3/4)`, statsmodels'
//!   constant; MATLAB's is the rounded `0.6745`) without leverage adjustment, as
//!   statsmodels `RLM` with `scale_est='mad'` computes it (its
//!   `_estimate_scale` calls `scale.mad(resid, center=0)`; fitting.md's
//!   `median(|r - median(r)|)` is the `mad` function's default centring,
//!   which `RLM` does not use).
//!
//! Convergence. The plain loop (`acceleration: false`) is MATLAB's
//! fixed-point iteration `b <- G(b)`; it converges linearly and on Kurt's
//! polynomial designs often slowly (40-200 iterations at MATLAB's test). By
//! default, once the rows beyond the weight's kink and the rows defining the
//! median scale have stayed the same for two iterations (so that `G` is
//! smooth there), the point at which `G` is next evaluated is proposed by
//! Anderson acceleration (type II, the last [`IrlsOptions::anderson_memory`]
//! steps, history cleared when that pattern changes; Walker & Ni 2011). A
//! proposal is tried only if it has the same pattern, and kept only if the
//! fixed-point step it leads to, `||D X (G(b') - b')||` (`D` the leverage
//! adjustment), is no larger than the step at the point `b` it was
//! extrapolated from; otherwise the loop continues from the plain step
//! `G(b)` (a safeguard on the fixed-point residual, as in Zhang, O'Donoghue
//! & Boyd 2020). An earlier safeguard, on the robust objective at the
//! current scale, rejected almost every proposal while the scale still
//! drifted (CUReT 7 and 22 in statsmodels' convention then hit the cap):
//! the fixed point of the joint update of `b` and the scale is not the
//! minimiser at the current scale. A fixed point of the accelerated loop is
//! a fixed point of `G`, and the stopping test is always applied to a plain
//! step `G(b)` against `b`, so the returned `coef` is the weighted
//! least-squares solution for the returned `weights`, as MATLAB's is. The
//! stopping test
//! is MATLAB's on the coefficients by default, or statsmodels' on the
//! deviance (absolute change `<= 1e-8`, [`StoppingTest`]). Starting from a
//! Huber pass instead of least squares was tried and rejected: on 13 of the
//! 46 CUReT designs where MATLAB's loop converges it leads the bisquare
//! iteration to another fixed point (so does unrestricted acceleration).
//! On some designs (CUReT 4, 7, 19, 20, 22, 50 with the 2004 scale)
//! MATLAB's plain loop reaches no fixed point: it ends in a 2-cycle of the
//! median scale, and the solution says `IterationCap`; the accelerated loop
//! finds one on 7 and 20 (the coefficient test holds there: `G(b) = b` to
//! `sqrt(eps)`), and says `IterationCap` on the others.
//!
//! A zero scale (an exact fit of all but a few points) never divides by
//! zero: the conventions' fallbacks apply, and if the scale is still zero
//! (at most `16 eps max |y|`, the rounding noise of an exact fit) the fit
//! is exact and IRLS stops with the current `b`.

use std::collections::VecDeque;

use faer::{Mat, MatRef};

use crate::linear::leverages;
use crate::robust_weights::RobustWeight;
use crate::small_qr::SmallQr;
use crate::{LstsqMethod, SolveError, lstsq, tall_qr};

/// Rows from which the weighted steps use the guarded normal equations.
const GRAM_MIN_ROWS: usize = 50_000;

/// How the residual scale is estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ScaleConvention {
    /// `robustfit` of the 2004 era (closest to Kurt's fits) (default).
    #[default]
    Matlab2004,
    /// `robustfit` 2011 and later.
    Matlab2011,
    /// statsmodels `RLM` (no leverage adjustment).
    Statsmodels,
}

impl ScaleConvention {
    /// Name as used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            ScaleConvention::Matlab2004 => "matlab2004",
            ScaleConvention::Matlab2011 => "matlab2011",
            ScaleConvention::Statsmodels => "statsmodels",
        }
    }
}

/// Which test ends the iteration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum StoppingTest {
    /// MATLAB `robustfit`: every `|b - b_old| <= tol max(|b|, |b_old|)`,
    /// `tol` (default `sqrt(eps)`).
    #[default]
    Coefficients,
    /// statsmodels `RLM` (`conv='dev'`): `|D - D_old| <= tol` [1e-8], with
    /// the deviance `D = sum tune^2 rho(r_adj / (tune s))`.
    Deviance,
}

/// Why [`irls`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum IrlsTermination {
    /// MATLAB's coefficient test held.
    CoefficientTest,
    /// statsmodels' deviance test held.
    DevianceTest,
    /// The scale vanished: the weighted points are fitted exactly.
    ExactFit,
    /// The iteration cap was reached without the test holding.
    IterationCap,
    /// A weighted solution recurred ([`IrlsOptions::stop_on_cycle`]): the
    /// reweighting cycles among a few points and no cap would end it.
    Cycle,
}

impl IrlsTermination {
    /// One line for reports.
    pub fn describe(self) -> &'static str {
        match self {
            IrlsTermination::CoefficientTest => {
                "converged: coefficient change below tolerance (MATLAB test)"
            }
            IrlsTermination::DevianceTest => {
                "converged: deviance change below tolerance (statsmodels test)"
            }
            IrlsTermination::ExactFit => "converged: zero residual scale (exact fit)",
            IrlsTermination::IterationCap => "NOT converged: iteration cap reached",
            IrlsTermination::Cycle => {
                "NOT converged: the reweighting cycles (a weighted solution recurred)"
            }
        }
    }

    /// Whether the stopping test held (or the fit is exact).
    pub fn is_converged(self) -> bool {
        !matches!(self, IrlsTermination::IterationCap | IrlsTermination::Cycle)
    }
}

/// Weighted solutions remembered by the cycle test.
const CYCLE_MEMORY: usize = 8;

/// The last [`CYCLE_MEMORY`] weighted solutions `G(b)`, for
/// [`IrlsOptions::stop_on_cycle`].
struct Recent(std::collections::VecDeque<Vec<f64>>);

impl Recent {
    /// Whether `g` equals (by the coefficient test at `tol`) a solution
    /// before the latest one, then remember it. The latest is skipped: two
    /// equal solutions in a row are a stall the stopping test settles, not
    /// a cycle.
    fn recurs(&mut self, g: &[f64], tol: f64) -> bool {
        let older = self.0.len().saturating_sub(1);
        let found = self.0.iter().take(older).any(|o| agree(g, o, tol));
        // The oldest solution's buffer holds the newest once full.
        let mut slot = if self.0.len() == CYCLE_MEMORY {
            self.0.pop_front().unwrap_or_default()
        } else {
            Vec::with_capacity(g.len())
        };
        slot.clear();
        slot.extend_from_slice(g);
        self.0.push_back(slot);
        found
    }
}

/// Options of [`irls`].
#[derive(Clone, Debug, PartialEq)]
pub struct IrlsOptions {
    /// Weight function (default bisquare).
    pub weight: RobustWeight,
    /// Tuning constant; `None` uses the weight function's default.
    pub tune: Option<f64>,
    /// Scale convention (default Matlab2004).
    pub scale: ScaleConvention,
    /// Iteration cap (default 50).
    pub max_iterations: usize,
    /// Stopping test [coefficients, MATLAB's].
    pub stopping: StoppingTest,
    /// Tolerance of the stopping test; `None`: `sqrt(eps)` for the
    /// coefficient test, `1e-8` for the deviance test.
    pub tolerance: Option<f64>,
    /// Safeguarded Anderson acceleration (default true); `false` is MATLAB's loop.
    pub acceleration: bool,
    /// Steps remembered by the acceleration (default 5).
    pub anderson_memory: usize,
    /// Stop with [`IrlsTermination::Cycle`] when a weighted solution
    /// recurs among the last few (default false: MATLAB's loop runs to its
    /// cap).
    pub stop_on_cycle: bool,
}

impl Default for IrlsOptions {
    fn default() -> Self {
        Self {
            weight: RobustWeight::Bisquare,
            tune: None,
            scale: ScaleConvention::Matlab2004,
            max_iterations: 50,
            stopping: StoppingTest::Coefficients,
            tolerance: None,
            acceleration: true,
            anderson_memory: 5,
            stop_on_cycle: false,
        }
    }
}

/// Result of [`irls`].
#[derive(Clone, Debug)]
pub struct IrlsSolution {
    /// Coefficients (the weighted least-squares solution for `weights`).
    pub coef: Vec<f64>,
    /// Final robust weights, one per observation.
    pub weights: Vec<f64>,
    /// Reweighting iterations done (weighted least-squares solves after the
    /// ordinary one).
    pub iterations: usize,
    /// Why the iteration stopped.
    pub termination: IrlsTermination,
    /// Iterations whose next point came from the acceleration.
    pub accelerated_steps: usize,
    /// The final scale estimate.
    pub scale: f64,
    /// The convention used.
    pub convention: ScaleConvention,
}

impl IrlsSolution {
    /// Whether a stopping test held ([`IrlsTermination::is_converged`]);
    /// false where the cap was reached or the reweighting cycled.
    pub fn converged(&self) -> bool {
        self.termination.is_converged()
    }
}

fn std_dev(y: &[f64]) -> f64 {
    let n = y.len() as f64;
    let m = y.iter().sum::<f64>() / n;
    (y.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0).max(1.0)).sqrt()
}

/// The scale of residuals `r` (already leverage-adjusted where the
/// convention asks) for `p` coefficients.
pub fn robust_scale(r: &[f64], p: usize, y: &[f64], convention: ScaleConvention) -> f64 {
    scale_with(r, p, std_dev(y), convention, &mut Vec::new()).0
}

/// statsmodels' MAD normaliser, the normal quantile `Phi^-1(3/4)`
/// (`scale.mad`'s default `c`); MATLAB divides by `0.6745`.
const GAUSSIAN_3_4: f64 = 0.674_489_750_196_081_7;

/// Median of `(value, row)` pairs by selection (reorders `v`), with the
/// rows of the one or two middle elements (`usize::MAX` when empty).
fn median_rows(v: &mut [(f64, usize)]) -> (f64, [usize; 2]) {
    let n = v.len();
    if n == 0 {
        return (0.0, [usize::MAX; 2]);
    }
    let by_value = |a: &(f64, usize), b: &(f64, usize)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
    let (left, mid, _) = v.select_nth_unstable_by(n / 2, by_value);
    let hi = *mid;
    if n % 2 == 1 {
        return (hi.0, [hi.1, hi.1]);
    }
    let lo = left.iter().copied().max_by(by_value).unwrap_or(hi);
    (0.5 * (lo.0 + hi.0), [lo.1, hi.1])
}

/// [`robust_scale`] with `std(y)` given and a reusable buffer; also the
/// rows that define it (the middle elements of its medians), which stay
/// the same while the scale is a smooth function of the coefficients.
fn scale_with(
    r: &[f64],
    p: usize,
    std_y: f64,
    convention: ScaleConvention,
    buf: &mut Vec<(f64, usize)>,
) -> (f64, [usize; 4]) {
    buf.clear();
    buf.extend(r.iter().enumerate().map(|(i, v)| (v.abs(), i)));
    if convention == ScaleConvention::Statsmodels {
        let (m, rows) = median_rows(buf);
        return (m / GAUSSIAN_3_4, [rows[0], rows[1], usize::MAX, usize::MAX]);
    }
    let drop = p.saturating_sub(1).min(buf.len().saturating_sub(1));
    if drop > 0 {
        buf.select_nth_unstable_by(drop - 1, |a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    }
    let kept = &mut buf[drop..];
    let (med, rows) = median_rows(kept);
    if convention == ScaleConvention::Matlab2011 {
        let s = (med / 0.6745).max(1e-6 * std_y);
        return (s, [rows[0], rows[1], usize::MAX, usize::MAX]);
    }
    for v in kept.iter_mut() {
        v.0 = (v.0 - med).abs();
    }
    let (dev, dev_rows) = median_rows(kept);
    let s = dev / 0.6745;
    let all = [rows[0], rows[1], dev_rows[0], dev_rows[1]];
    if s > 0.0 {
        (s, all)
    } else {
        (
            0.5 * r.iter().map(|v| v.abs()).sum::<f64>() / r.len() as f64,
            all,
        )
    }
}

/// Which rows are beyond the weight function's kink (`|u| >= pi` for
/// Andrews, `|u| >= 1` for the others) and which rows define the scale:
/// while it stays the same, the reweighting map is smooth and may be
/// accelerated.
#[derive(Clone, Debug, PartialEq)]
struct Pattern {
    beyond: Vec<bool>,
    scale_rows: [usize; 4],
}

/// The fixed data of one robust fit.
struct Problem<'a> {
    x: MatRef<'a, f64>,
    y: &'a [f64],
    ym: Mat<f64>,
    /// `1 / sqrt(1 - h)` per row (1 for statsmodels).
    adj: Vec<f64>,
    std_y: f64,
    /// A scale at or below this is rounding noise of an exact fit
    /// (`16 eps max |y|`): treated as zero.
    zero_scale: f64,
    tune: f64,
    options: &'a IrlsOptions,
}

/// A point of the iteration: coefficients, their leverage-adjusted
/// residuals, the scale of those and the pattern of the rows at it.
struct Point {
    b: Vec<f64>,
    r: Vec<f64>,
    s: f64,
    pat: Pattern,
}

impl Point {
    fn new(m: usize, p: usize) -> Self {
        Self {
            b: vec![0.0; p],
            r: vec![0.0; m],
            s: 0.0,
            pat: Pattern {
                beyond: vec![false; m],
                scale_rows: [usize::MAX; 4],
            },
        }
    }
}

/// Buffers reused by every iteration.
struct Work {
    pairs: Vec<(f64, usize)>,
    qr: SmallQr,
}

impl Problem<'_> {
    /// Leverage-adjusted residuals `(y - X b) / sqrt(1 - h)`.
    fn residuals(&self, b: &[f64], r: &mut [f64]) {
        r.copy_from_slice(self.y);
        for (k, bk) in b.iter().enumerate() {
            let col = self.x.col(k);
            for (i, ri) in r.iter_mut().enumerate() {
                *ri -= bk * col[i];
            }
        }
        for (ri, a) in r.iter_mut().zip(&self.adj) {
            *ri *= a;
        }
    }

    /// Residuals, scale and pattern of the point at `pt.b`.
    fn evaluate(&self, pt: &mut Point, buf: &mut Vec<(f64, usize)>) {
        self.residuals(&pt.b, &mut pt.r);
        let (s, scale_rows) =
            scale_with(&pt.r, self.x.ncols(), self.std_y, self.options.scale, buf);
        let kink = if self.options.weight == RobustWeight::Andrews {
            std::f64::consts::PI
        } else {
            1.0
        };
        let c = kink * self.tune * s;
        pt.pat.beyond.clear();
        pt.pat.beyond.extend(pt.r.iter().map(|v| v.abs() >= c));
        pt.pat.scale_rows = scale_rows;
        pt.s = s;
    }

    /// The (weighted) least-squares coefficients into `b`: on tall designs
    /// by the guarded normal equations where they are accurate (one pass,
    /// no weighted copy of the design), else by Householder QR
    /// (faer's, in [`SmallQr`] on reused buffers; a rank-deficient problem through
    /// [`lstsq`], which re-solves it by SVD). Small designs always take QR:
    /// it costs little there, and its accuracy keeps coefficient tests far
    /// below MATLAB's `sqrt(eps)` reachable (the normal equations' `eps
    /// cond^2` would not).
    fn solve(&self, w: Option<&[f64]>, work: &mut Work, b: &mut [f64]) -> Result<(), SolveError> {
        let tall = self.x.nrows() >= GRAM_MIN_ROWS;
        let gram = tall
            .then(|| tall_qr::gram_triangle_weighted(self.x, self.ym.as_ref(), w))
            .flatten();
        if let Some((r, mut z)) = gram {
            r.as_ref().solve_upper_triangular_in_place(z.as_mut());
            if (0..b.len()).all(|k| z[(k, 0)].is_finite()) {
                b.iter_mut().enumerate().for_each(|(k, v)| *v = z[(k, 0)]);
                return Ok(());
            }
        }
        if !tall {
            work.qr.factor(self.x, w, true);
            if work.qr.solve(self.y, b) {
                return Ok(());
            }
        }
        let s = lstsq(self.x, self.ym.as_ref(), w, LstsqMethod::PivotedQr)?;
        b.iter_mut().enumerate().for_each(|(k, v)| *v = s.x[(k, 0)]);
        Ok(())
    }

    /// statsmodels' deviance as `RLM.deviance` computes it: `sum tune^2
    /// rho(e / (tune v))` of the unadjusted residuals `e`, with `v` the
    /// weighted least-squares variance `sum w e^2 / (m - p)` of the fit
    /// (not the robust scale), `w` the weights of that fit.
    fn deviance(&self, r: &[f64], w: &[f64]) -> f64 {
        let (m, p) = (self.x.nrows(), self.x.ncols());
        let e = |i: usize| r[i] / self.adj[i];
        let v = (0..m).map(|i| w[i] * e(i) * e(i)).sum::<f64>() / (m - p).max(1) as f64;
        if !(v > 0.0) {
            return 0.0;
        }
        let c = 1.0 / (self.tune * v);
        let rho = self.options.weight;
        self.tune * self.tune * (0..m).map(|i| rho.rho(e(i) * c)).sum::<f64>()
    }
}

/// Type-II Anderson acceleration of the fixed-point map `G` from the last
/// `memory` differences of `G(b)` and of `f = G(b) - b`.
struct Anderson {
    memory: usize,
    last: Option<(Vec<f64>, Vec<f64>)>,
    dg: VecDeque<Vec<f64>>,
    df: VecDeque<Vec<f64>>,
    qr: SmallQr,
}

impl Anderson {
    fn reset(&mut self) {
        self.last = None;
        self.dg.clear();
        self.df.clear();
    }

    fn new(memory: usize) -> Self {
        Self {
            memory,
            last: None,
            dg: VecDeque::new(),
            df: VecDeque::new(),
            qr: SmallQr::new(),
        }
    }

    /// Record `G(b) = g` and propose the next point
    /// `g - dG gamma`, `gamma = argmin ||f - dF gamma||`, into `next`.
    fn propose(&mut self, b: &[f64], g: &[f64], next: &mut [f64]) -> Result<bool, SolveError> {
        let f: Vec<f64> = g.iter().zip(b).map(|(g, b)| g - b).collect();
        if let Some((g0, f0)) = self.last.take() {
            self.dg
                .push_back(g.iter().zip(&g0).map(|(a, b)| a - b).collect());
            self.df
                .push_back(f.iter().zip(&f0).map(|(a, b)| a - b).collect());
            if self.df.len() > self.memory {
                self.dg.pop_front();
                self.df.pop_front();
            }
        }
        self.last = Some((g.to_vec(), f.clone()));
        if self.df.is_empty() {
            return Ok(false);
        }
        let (p, k) = (f.len(), self.df.len());
        let a = Mat::from_fn(p, k, |i, j| self.df[j][i]);
        let mut gamma = vec![0.0; k];
        self.qr.factor(a.as_ref(), None, true);
        if p < k || !self.qr.solve(&f, &mut gamma) {
            let rhs = Mat::from_fn(p, 1, |i, _| f[i]);
            let s = lstsq(a.as_ref(), rhs.as_ref(), None, LstsqMethod::PivotedQr)?;
            gamma
                .iter_mut()
                .enumerate()
                .for_each(|(j, v)| *v = s.x[(j, 0)]);
        }
        for (i, v) in next.iter_mut().enumerate() {
            *v = g[i] - (0..k).map(|j| self.dg[j][i] * gamma[j]).sum::<f64>();
        }
        Ok(next.iter().all(|v| v.is_finite()))
    }
}

fn check_inputs(
    x: MatRef<'_, f64>,
    y: &[f64],
    options: &IrlsOptions,
) -> Result<(f64, f64), SolveError> {
    let (m, p) = (x.nrows(), x.ncols());
    if y.len() != m {
        return Err(SolveError::Dimension {
            what: "rows of X vs length of y",
            left: m,
            right: y.len(),
        });
    }
    // The small-design QR does not check its input (faer's path does).
    let bad_y = y.iter().enumerate().find(|(_, v)| !v.is_finite());
    let bad_x = || (0..p).find_map(|j| (0..m).find(|&i| !x[(i, j)].is_finite()).map(|i| (i, j)));
    if let Some((row, &value)) = bad_y {
        return Err(SolveError::NonFinite {
            what: "y",
            row,
            col: 0,
            value,
        });
    }
    if let Some((row, col)) = bad_x() {
        let value = x[(row, col)];
        return Err(SolveError::NonFinite {
            what: "X",
            row,
            col,
            value,
        });
    }
    if m < p {
        return Err(SolveError::Dimension {
            what: "fewer observations than coefficients",
            left: m,
            right: p,
        });
    }
    let tune = options.tune.unwrap_or(options.weight.default_tune());
    if !(tune > 0.0 && tune.is_finite()) {
        return Err(SolveError::InvalidOption {
            name: "tune",
            value: tune,
            reason: "the tuning constant must be finite and > 0",
        });
    }
    let tol = options.tolerance.unwrap_or(match options.stopping {
        StoppingTest::Coefficients => f64::EPSILON.sqrt(),
        StoppingTest::Deviance => 1e-8,
    });
    if !(tol >= 0.0 && tol.is_finite()) {
        return Err(SolveError::InvalidOption {
            name: "tolerance",
            value: tol,
            reason: "the stopping tolerance must be finite and >= 0",
        });
    }
    Ok((tune, tol))
}

/// Robust fit of `y ~ X b`.
pub fn irls(
    x: MatRef<'_, f64>,
    y: &[f64],
    options: &IrlsOptions,
) -> Result<IrlsSolution, SolveError> {
    let (tune, tol) = check_inputs(x, y, options)?;
    let (m, p) = (x.nrows(), x.ncols());
    let mut work = Work {
        pairs: Vec::with_capacity(m),
        qr: SmallQr::new(),
    };
    let adj: Vec<f64> = if options.scale == ScaleConvention::Statsmodels {
        vec![1.0; m]
    } else {
        let h = if m >= GRAM_MIN_ROWS {
            leverages(x)?
        } else {
            work.qr.factor(x, None, false);
            match work.qr.leverages() {
                Some(h) => h,
                None => leverages(x)?,
            }
        };
        h.into_iter()
            .map(|h| 1.0 / (1.0 - h.min(0.9999)).sqrt())
            .collect()
    };
    let prob = Problem {
        x,
        y,
        ym: Mat::from_fn(m, 1, |i, _| y[i]),
        adj,
        std_y: std_dev(y),
        zero_scale: 16.0 * f64::EPSILON * y.iter().fold(0.0_f64, |a, v| a.max(v.abs())),
        tune,
        options,
    };
    let mut start = Point::new(m, p);
    prob.solve(None, &mut work, &mut start.b)?;
    iterate(&prob, start, tol, work)
}

/// Consecutive iterations with an unchanged [`Pattern`] before the
/// acceleration is used (fewer lets it jump between smooth pieces and
/// reach another fixed point than MATLAB's loop on CUReT designs).
const STABLE_ITERATIONS: usize = 2;

/// The robust weights of the point `pt` into `w`.
fn reweight(prob: &Problem<'_>, pt: &Point, w: &mut [f64]) -> Result<(), SolveError> {
    let c = 1.0 / (prob.tune * pt.s);
    for (wi, ri) in w.iter_mut().zip(&pt.r) {
        *wi = prob.options.weight.weight(ri * c);
    }
    if w.iter().all(|v| *v == 0.0) {
        return Err(SolveError::InvalidOption {
            name: "tune",
            value: prob.tune,
            reason: "every observation got weight zero",
        });
    }
    Ok(())
}

/// The stopping test on the weighted least-squares solution `g = G(b)`
/// (`dev`: its deviance, for the deviance test).
fn stop_test(
    stopping: StoppingTest,
    tol: f64,
    g: &[f64],
    b: &[f64],
    dev: f64,
    dev_old: f64,
) -> Option<IrlsTermination> {
    match stopping {
        StoppingTest::Coefficients => agree(g, b, tol).then_some(IrlsTermination::CoefficientTest),
        StoppingTest::Deviance => {
            ((dev - dev_old).abs() <= tol).then_some(IrlsTermination::DevianceTest)
        }
    }
}

/// MATLAB's coefficient test: every `|g - b| <= tol max(|g|, |b|)`.
fn agree(g: &[f64], b: &[f64], tol: f64) -> bool {
    g.iter()
        .zip(b)
        .all(|(n, o)| (n - o).abs() <= tol * n.abs().max(o.abs()))
}

/// `||a - b||`: for residuals at `b` and at `G(b)`, the size of the
/// fixed-point step in the adjusted residuals, `||D X (G(b) - b)||`.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// The plain step kept while an extrapolated point is on trial: the point
/// `G(b)` the loop falls back to, its deviance, and the step size at `b`.
struct Fallback {
    point: Point,
    deviance: f64,
    step: f64,
}

/// The reweighting loop from the ordinary least-squares solution in `cur.b`.
fn iterate(
    prob: &Problem<'_>,
    cur: Point,
    tol: f64,
    mut work: Work,
) -> Result<IrlsSolution, SolveError> {
    let opts = prob.options;
    let mut state = Reweighting::start(prob, cur, &mut work);
    for it in 1..=opts.max_iterations {
        if let Some(t) = state.iteration(prob, tol, &mut work)? {
            return Ok(state.solution(opts, it, t));
        }
    }
    let t = IrlsTermination::IterationCap;
    Ok(state.solution(opts, opts.max_iterations, t))
}

/// The state the reweighting loop carries from one iteration to the next.
/// The points are buffers swapped between the roles, so an iteration
/// allocates nothing for them.
struct Reweighting {
    /// The point `b` the next plain step starts from.
    cur: Point,
    /// The plain step `G(b)` of the current iteration.
    next: Point,
    /// The accelerated proposal.
    cand: Point,
    /// A point buffer free for the next trial's [`Fallback`].
    spare: Option<Point>,
    /// The plain step kept while an accelerated point is on trial.
    trial: Option<Fallback>,
    /// The robust weights of the latest weighted solve (1 before the first).
    w: Vec<f64>,
    /// The acceleration (`None`: MATLAB's plain loop).
    anderson: Option<Anderson>,
    /// Iterations whose next point came from the acceleration.
    accelerated: usize,
    /// Consecutive iterations with an unchanged [`Pattern`].
    same: usize,
    /// The deviance test's previous value: the deviance of the latest
    /// plain step kept.
    dev_old: f64,
    /// The latest plain step `G(b)`: what the cap returns, being the
    /// weighted least-squares solution for the returned weights.
    last_g: Vec<f64>,
    /// The scale the latest weights were computed with.
    s_w: f64,
    /// The cycle test's memory, for [`IrlsOptions::stop_on_cycle`].
    recent: Option<Recent>,
}

impl Reweighting {
    /// The loop's state at the ordinary least-squares solution `cur.b`,
    /// with weights 1.
    fn start(prob: &Problem<'_>, mut cur: Point, work: &mut Work) -> Self {
        let (opts, m, p) = (prob.options, prob.y.len(), prob.x.ncols());
        prob.evaluate(&mut cur, &mut work.pairs);
        let w = vec![1.0; m];
        let dev_old = prob.deviance(&cur.r, &w);
        Self {
            next: Point::new(m, p),
            cand: Point::new(m, p),
            spare: None,
            trial: None,
            w,
            anderson: (opts.acceleration && opts.anderson_memory > 0)
                .then(|| Anderson::new(opts.anderson_memory)),
            accelerated: 0,
            same: 0,
            dev_old,
            last_g: cur.b.clone(),
            s_w: cur.s,
            recent: opts
                .stop_on_cycle
                .then(|| Recent(std::collections::VecDeque::with_capacity(CYCLE_MEMORY))),
            cur,
        }
    }

    /// One iteration: the plain step from the current point, the stopping
    /// tests on it, then the choice of the next point. Returns the
    /// termination when the loop ends here.
    fn iteration(
        &mut self,
        prob: &Problem<'_>,
        tol: f64,
        work: &mut Work,
    ) -> Result<Option<IrlsTermination>, SolveError> {
        if !(self.cur.s > prob.zero_scale) {
            // An exact fit of the weighted points (up to rounding): nothing
            // to reweight; the weights that produced it are kept.
            return Ok(Some(IrlsTermination::ExactFit));
        }
        let dev = self.plain_step(prob, work)?;
        if let Some(t) = self.stopped(prob.options, tol, dev) {
            return Ok(Some(t));
        }
        let step = distance(&self.next.r, &self.cur.r);
        if self.reject_trial(step) {
            return Ok(None);
        }
        self.advance(prob, work, dev, step)?;
        Ok(None)
    }

    /// The weights at the current point and the weighted least-squares
    /// solution `G(b)` into `next`. Returns its deviance when the deviance
    /// test needs it (0 for the coefficient test, which would waste a pass
    /// over the rows on it).
    fn plain_step(&mut self, prob: &Problem<'_>, work: &mut Work) -> Result<f64, SolveError> {
        reweight(prob, &self.cur, &mut self.w)?;
        self.s_w = self.cur.s;
        prob.solve(Some(&self.w), work, &mut self.next.b)?;
        prob.evaluate(&mut self.next, &mut work.pairs);
        self.last_g.copy_from_slice(&self.next.b);
        Ok(match prob.options.stopping {
            StoppingTest::Deviance => prob.deviance(&self.next.r, &self.w),
            StoppingTest::Coefficients => 0.0,
        })
    }

    /// The stopping test on the plain step, then the cycle test (which
    /// also remembers the step).
    fn stopped(&mut self, opts: &IrlsOptions, tol: f64, dev: f64) -> Option<IrlsTermination> {
        let (g, b) = (&self.next.b, &self.cur.b);
        if let Some(t) = stop_test(opts.stopping, tol, g, b, dev, self.dev_old) {
            return Some(t);
        }
        if let Some(r) = self.recent.as_mut()
            && r.recurs(g, tol)
        {
            return Some(IrlsTermination::Cycle);
        }
        None
    }

    /// Judge the accelerated point on trial, if any, by the size of its
    /// plain step. When it moves more than the point it was extrapolated
    /// from, it is dropped and the loop continues from that point's plain
    /// step, with the acceleration's history cleared (returns true: the
    /// iteration ends there).
    fn reject_trial(&mut self, step: f64) -> bool {
        let Some(fb) = self.trial.take() else {
            return false;
        };
        if step > fb.step {
            self.spare = Some(std::mem::replace(&mut self.cur, fb.point));
            self.dev_old = fb.deviance;
            self.accelerated -= 1;
            self.same = 0;
            if let Some(a) = self.anderson.as_mut() {
                a.reset();
            }
            return true;
        }
        self.spare = Some(fb.point);
        false
    }

    /// Move to the next point: the Anderson proposal once the pattern has
    /// been stable for [`STABLE_ITERATIONS`] and only if the proposal keeps
    /// it (the plain step then waits as its [`Fallback`]), else the plain
    /// step.
    fn advance(
        &mut self,
        prob: &Problem<'_>,
        work: &mut Work,
        dev: f64,
        step: f64,
    ) -> Result<(), SolveError> {
        let (m, p) = (prob.y.len(), prob.x.ncols());
        self.dev_old = dev;
        self.same = if self.next.pat == self.cur.pat {
            self.same + 1
        } else {
            0
        };
        let proposed = match self.anderson.as_mut() {
            Some(a) => {
                if self.same == 0 {
                    a.reset();
                }
                a.propose(&self.cur.b, &self.next.b, &mut self.cand.b)?
                    && self.same >= STABLE_ITERATIONS
            }
            None => false,
        };
        // Only a point on the same smooth piece (same pattern) is tried.
        let accept = proposed && {
            prob.evaluate(&mut self.cand, &mut work.pairs);
            self.cand.pat == self.cur.pat
        };
        if accept {
            let spare = self.spare.take().unwrap_or_else(|| Point::new(m, p));
            let plain = std::mem::replace(&mut self.next, spare);
            self.trial = Some(Fallback {
                point: plain,
                deviance: dev,
                step,
            });
            std::mem::swap(&mut self.cur, &mut self.cand);
            self.accelerated += 1;
        } else {
            std::mem::swap(&mut self.cur, &mut self.next);
        }
        Ok(())
    }

    /// The solution when the loop ended with `termination` at iteration
    /// `it`. A plain step that passed a test is returned with the scale its
    /// weights came from; an exact fit is found before iteration `it`
    /// solves anything, so that iteration does not count, and its current
    /// point is returned; at the cap the latest plain step is returned.
    fn solution(self, opts: &IrlsOptions, it: usize, termination: IrlsTermination) -> IrlsSolution {
        let (coef, iterations, scale) = match termination {
            IrlsTermination::ExactFit => (self.cur.b, it - 1, 0.0),
            IrlsTermination::IterationCap => (self.last_g, it, self.s_w),
            _ => (self.next.b, it, self.cur.s),
        };
        IrlsSolution {
            coef,
            weights: self.w,
            iterations,
            termination,
            accelerated_steps: self.accelerated,
            scale,
            convention: opts.scale,
        }
    }
}
