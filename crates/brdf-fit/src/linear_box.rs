//! Linear least squares within a box `[0, upper]`: NNLS keeps the
//! coefficients non-negative but knows no upper bound, so a Lambert fit of
//! data with one huge value would give an albedo above its box (`kd <= 1`)
//! and the fit would be refused. Where NNLS exceeds an upper bound, the
//! problem is solved again as least squares with inequality constraints
//! (`x >= 0`, `-x >= -upper`; [`brdf_solve::lsi`](fn@brdf_solve::lsi)), so
//! the coefficient ends on its bound, where the report shows it.

use brdf_solve::SolveError;
use faer::{Mat, MatRef};

/// `x` (the NNLS solution of `min ||A x - b||`, `x >= 0`) if it respects
/// `upper`; otherwise the solution within `[0, upper]`. The flag says
/// whether the box solve was needed.
pub fn within_upper(
    a: MatRef<'_, f64>,
    b: &[f64],
    x: Vec<f64>,
    upper: &[f64],
) -> Result<(Vec<f64>, bool), SolveError> {
    if x.iter().zip(upper).all(|(x, u)| x <= u) {
        return Ok((x, false));
    }
    let n = x.len();
    let bounded: Vec<usize> = (0..n).filter(|&k| upper[k].is_finite()).collect();
    let rows = n + bounded.len();
    let g = Mat::from_fn(rows, n, |i, j| {
        if i < n {
            f64::from(u8::from(i == j))
        } else if bounded[i - n] == j {
            -1.0
        } else {
            0.0
        }
    });
    let h: Vec<f64> = (0..rows)
        .map(|i| if i < n { 0.0 } else { -upper[bounded[i - n]] })
        .collect();
    // Rounding-level excursions of the constrained solution are clamped.
    let clamp =
        |x: Vec<f64>| -> Vec<f64> { x.iter().zip(upper).map(|(v, u)| v.clamp(0.0, *u)).collect() };
    let lsi = brdf_solve::lsi(a, b, g.as_ref(), &h).map(clamp);
    // The LSI's reduction works on `x - x0` (x0 the unconstrained
    // solution): a bound many orders below x0 (data of 1e300 against
    // `kd <= 1`) is lost to cancellation. Fixing the violators at their
    // bound and solving the rest by NNLS is then the answer; the smaller
    // residual of the two wins.
    let fixed = fix_at_upper(a, b, x, upper)?;
    let best = match lsi {
        Ok(l) if residual(a, b, &l) < residual(a, b, &fixed) => l,
        _ => fixed,
    };
    Ok((best, true))
}

/// `||A x - b||`.
fn residual(a: MatRef<'_, f64>, b: &[f64], x: &[f64]) -> f64 {
    (0..a.nrows())
        .map(|i| {
            let r = (0..a.ncols()).map(|k| a[(i, k)] * x[k]).sum::<f64>() - b[i];
            r * r
        })
        .sum::<f64>()
        .sqrt()
}

/// Fix every coefficient above its bound at the bound, move its column to
/// the right-hand side, and solve the others by NNLS; repeat until none
/// exceeds its bound (at most once per coefficient).
fn fix_at_upper(
    a: MatRef<'_, f64>,
    b: &[f64],
    mut x: Vec<f64>,
    upper: &[f64],
) -> Result<Vec<f64>, SolveError> {
    let n = x.len();
    let mut at_upper = vec![false; n];
    for _ in 0..n {
        let over: Vec<usize> = (0..n)
            .filter(|&k| !at_upper[k] && x[k] > upper[k])
            .collect();
        if over.is_empty() {
            break;
        }
        for k in over {
            at_upper[k] = true;
        }
        let free: Vec<usize> = (0..n).filter(|&k| !at_upper[k]).collect();
        let rhs: Vec<f64> = (0..a.nrows())
            .map(|i| {
                b[i] - (0..n)
                    .filter(|&k| at_upper[k])
                    .map(|k| a[(i, k)] * upper[k])
                    .sum::<f64>()
            })
            .collect();
        for k in 0..n {
            if at_upper[k] {
                x[k] = upper[k];
            }
        }
        if free.is_empty() {
            break;
        }
        let af = Mat::from_fn(a.nrows(), free.len(), |i, j| a[(i, free[j])]);
        let s = brdf_solve::nnls(af.as_ref(), &rhs, 3 * free.len() + 10)?;
        for (j, &k) in free.iter().enumerate() {
            x[k] = s.x[j];
        }
    }
    Ok(x.iter().zip(upper).map(|(v, u)| v.clamp(0.0, *u)).collect())
}
