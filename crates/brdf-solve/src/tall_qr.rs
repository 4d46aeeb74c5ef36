//! The triangular factor of a tall, skinny matrix (millions of rows, a
//! handful of columns): the kernel under every least-squares step of the
//! fitting solvers.
//!
//! A least-squares problem `min ||A x - b||` with `m >> n` needs only the
//! `R` of `[A | b] = Q [R  Q^T b; 0  rho]`: the normal-equation-free
//! solution, the residual norm `rho` and every damped variant
//! `[R; sqrt(lambda) D]` follow from that `(n+1) x (n+1)` triangle, so the
//! tall matrix is factored once per Jacobian and never stored as `Q`.
//!
//! Two ways to the triangle, chosen per call:
//!
//! - [`gram_triangle`]: the normal equations, `A^T A = R^T R` by Cholesky
//!   and `Q^T B = R^-T A^T B`, one streaming pass over `A` (a Gram
//!   product, no Householder sweep, no copy). Their accuracy degrades with
//!   the square of the condition number, so they are guarded: the Gram
//!   matrix is scaled to unit diagonal and the factor is used only when
//!   its smallest Cholesky pivot shows `cond(A D^-1) <~ 1e3` (at most six
//!   of the sixteen digits lost); otherwise the caller falls back to QR.
//! - [`r_factor`]: faer's Householder QR, run sequentially on row blocks
//!   that rayon factors in parallel, whose stacked triangles are factored
//!   again (the TSQR reduction of Demmel et al. 2012).
//!
//! Both run sequential faer kernels inside parallel row blocks (summed or
//! reduced in block order, so the result is the same for any number of
//! threads): faer's own thread pool would meet at a barrier inside every
//! narrow panel, which on a busy machine costs more than the arithmetic.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::matmul::matmul;
use faer::linalg::qr::no_pivoting::factor::{
    qr_in_place, qr_in_place_scratch, recommended_block_size,
};
use faer::{Accum, Mat, MatMut, MatRef, Par, Side};

/// Rows per block of the parallel reduction.
const BLOCK_ROWS: usize = 1 << 15;

/// The upper-triangular `k x k` factor `R` of the `m x k` matrix `a`
/// (`A = Q R`, `k = min(m, a.ncols())` rows). `a` is overwritten.
pub fn r_factor(a: MatMut<'_, f64>) -> Mat<f64> {
    let (m, k) = (a.nrows(), a.ncols());
    if m <= 2 * BLOCK_ROWS || k == 0 {
        return r_factor_seq(a);
    }
    let blocks = m.div_ceil(BLOCK_ROWS);
    let mut rs: Vec<Mat<f64>> = Vec::with_capacity(blocks);
    let mut rest = a;
    let mut parts = Vec::with_capacity(blocks);
    while rest.nrows() > 0 {
        let take = rest.nrows().min(BLOCK_ROWS);
        let (top, bottom) = rest.split_at_row_mut(take);
        parts.push(top);
        rest = bottom;
    }
    #[cfg(feature = "rayon")]
    {
        use rayon::prelude::*;
        rs.par_extend(parts.into_par_iter().map(r_factor_seq));
    }
    #[cfg(not(feature = "rayon"))]
    rs.extend(parts.into_iter().map(r_factor_seq));
    let rows: usize = rs.iter().map(|r| r.nrows()).sum();
    let mut stacked = Mat::zeros(rows, k);
    let mut at = 0;
    for r in &rs {
        stacked
            .as_mut()
            .submatrix_mut(at, 0, r.nrows(), k)
            .copy_from(r.as_ref());
        at += r.nrows();
    }
    r_factor_seq(stacked.as_mut())
}

/// [`r_factor`] without the parallel reduction.
fn r_factor_seq(mut a: MatMut<'_, f64>) -> Mat<f64> {
    let (m, k) = (a.nrows(), a.ncols());
    let size = m.min(k);
    if size == 0 {
        return Mat::zeros(size, k);
    }
    let bs = recommended_block_size::<f64>(m, k);
    let mut coeff = Mat::<f64>::zeros(bs, size);
    let mut mem = MemBuffer::new(qr_in_place_scratch::<f64>(
        m,
        k,
        bs,
        Par::Seq,
        Default::default(),
    ));
    qr_in_place(
        a.as_mut(),
        coeff.as_mut(),
        Par::Seq,
        MemStack::new(&mut mem),
        Default::default(),
    );
    Mat::from_fn(size, k, |i, j| if j >= i { a[(i, j)] } else { 0.0 })
}

/// Smallest squared Cholesky pivot of the unit-diagonal Gram matrix at
/// which the normal equations are trusted (about `1 / cond(A D^-1)^2`).
const GRAM_MIN_PIVOT2: f64 = 1e-6;

/// `R` (`k x k`, upper triangular, positive diagonal) and `Q^T B`
/// (`k x c`) of `A = Q R` (`A` is `m x k`, `B` is `m x c`, any strides)
/// from the normal equations, or `None` when they are not accurate enough
/// (a zero or non-finite column, a failed or ill-conditioned Cholesky
/// factorisation: see the module doc), so the caller uses QR instead.
pub fn gram_triangle(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Option<(Mat<f64>, Mat<f64>)> {
    gram_triangle_weighted(a, b, None)
}

/// [`gram_triangle`] of the row-weighted `W^(1/2) A` and `W^(1/2) B`
/// (`weights` `w_i >= 0`, one per row), without forming them: the weighted
/// least-squares step of IRLS. `None` also for a negative or non-finite
/// weight (the caller's QR path reports it).
pub fn gram_triangle_weighted(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    weights: Option<&[f64]>,
) -> Option<(Mat<f64>, Mat<f64>)> {
    let k = a.ncols();
    if k == 0 || a.nrows() < k || b.nrows() != a.nrows() {
        return None;
    }
    if let Some(w) = weights
        && (w.len() != a.nrows() || w.iter().any(|v| !(v.is_finite() && *v >= 0.0)))
    {
        return None;
    }
    let (g, h) = gram(a, b, weights);
    triangle_from_gram(g.as_ref(), h)
}

/// `R` and `Q^T B` from the normal equations `G = A^T A`, `H = A^T B`
/// already formed (by a problem that accumulates them in its own pass over
/// the data, never storing `A`), under the guard of [`gram_triangle`]:
/// `None` when they are not accurate enough.
pub fn triangle_from_gram(g: MatRef<'_, f64>, h: Mat<f64>) -> Option<(Mat<f64>, Mat<f64>)> {
    let k = g.nrows();
    if k == 0 || g.ncols() != k || h.nrows() != k {
        return None;
    }
    let d: Vec<f64> = (0..k).map(|i| g[(i, i)].sqrt()).collect();
    if d.iter().any(|v| !(v.is_finite() && *v > 0.0)) || !h.as_ref().is_all_finite() {
        return None;
    }
    let scaled = Mat::from_fn(k, k, |i, j| g[(i, j)] / (d[i] * d[j]));
    let llt = scaled.llt(Side::Lower).ok()?;
    let l = llt.L();
    if (0..k).any(|i| !(l[(i, i)] * l[(i, i)] >= GRAM_MIN_PIVOT2)) {
        return None;
    }
    // A^T A = D L L^T D, so R = L^T D.
    let r = Mat::from_fn(k, k, |i, j| if j >= i { l[(j, i)] * d[j] } else { 0.0 });
    let mut qtb = h;
    r.as_ref()
        .transpose()
        .solve_lower_triangular_in_place(qtb.as_mut());
    qtb.as_ref().is_all_finite().then_some((r, qtb))
}

/// [`triangle_from_gram`] that also takes exactly zero columns of `A`
/// (zero diagonal of `G`: a parameter the model at this point does not
/// depend on, such as a tint whose lobe is off): the other columns are
/// factored under the same guard and the zero ones get zero rows and
/// columns in `R` and zero rows in `Q^T B`, so `R^T R = A^T A` and
/// `R^T Q^T B = A^T B` still hold. `R` is then singular: for damped steps
/// (`[R; sqrt(lambda) D]`), as the Householder `R` of such an `A` is, not
/// for solving with `R` alone.
pub fn triangle_from_gram_with_zero_columns(
    g: MatRef<'_, f64>,
    h: Mat<f64>,
) -> Option<(Mat<f64>, Mat<f64>)> {
    let k = g.nrows();
    if g.ncols() != k || h.nrows() != k {
        return None;
    }
    let keep: Vec<usize> = (0..k).filter(|&i| g[(i, i)] != 0.0).collect();
    if keep.len() == k || keep.is_empty() {
        return triangle_from_gram(g, h);
    }
    let c = h.ncols();
    let gs = Mat::from_fn(keep.len(), keep.len(), |a, b| g[(keep[a], keep[b])]);
    let hs = Mat::from_fn(keep.len(), c, |a, j| h[(keep[a], j)]);
    let (rs, qs) = triangle_from_gram(gs.as_ref(), hs)?;
    let mut r = Mat::<f64>::zeros(k, k);
    let mut qtb = Mat::<f64>::zeros(k, c);
    for (a, &ia) in keep.iter().enumerate() {
        for (b, &ib) in keep.iter().enumerate() {
            r[(ia, ib)] = rs[(a, b)];
        }
        for j in 0..c {
            qtb[(ia, j)] = qs[(a, j)];
        }
    }
    Some((r, qtb))
}

/// `A^T W A` and `A^T W B` (`W = I` without weights), summed over row
/// blocks in block order (in parallel with rayon for tall matrices).
fn gram(a: MatRef<'_, f64>, b: MatRef<'_, f64>, w: Option<&[f64]>) -> (Mat<f64>, Mat<f64>) {
    let (m, k, c) = (a.nrows(), a.ncols(), b.ncols());
    let block = |start: usize| {
        let rows = BLOCK_ROWS.min(m - start);
        let (ab, bb) = (a.subrows(start, rows), b.subrows(start, rows));
        let mut g = Mat::<f64>::zeros(k, k);
        let mut h = Mat::<f64>::zeros(k, c);
        // W A of the block (one block-sized copy) when weighted.
        let wa = w.map(|w| {
            let wb = &w[start..start + rows];
            Mat::from_fn(rows, k, |i, j| wb[i] * ab[(i, j)])
        });
        let wa = wa.as_ref().map_or(ab, |x| x.as_ref());
        matmul(
            g.as_mut(),
            Accum::Replace,
            ab.transpose(),
            wa,
            1.0,
            Par::Seq,
        );
        matmul(
            h.as_mut(),
            Accum::Replace,
            wa.transpose(),
            bb,
            1.0,
            Par::Seq,
        );
        (g, h)
    };
    let starts: Vec<usize> = (0..m).step_by(BLOCK_ROWS).collect();
    #[cfg(feature = "rayon")]
    let parts: Vec<(Mat<f64>, Mat<f64>)> = {
        use rayon::prelude::*;
        if starts.len() > 2 {
            starts.par_iter().map(|s| block(*s)).collect()
        } else {
            starts.iter().map(|s| block(*s)).collect()
        }
    };
    #[cfg(not(feature = "rayon"))]
    let parts: Vec<(Mat<f64>, Mat<f64>)> = starts.iter().map(|s| block(*s)).collect();
    let mut it = parts.into_iter();
    let (mut g, mut h) = it
        .next()
        .unwrap_or_else(|| (Mat::zeros(k, k), Mat::zeros(k, c)));
    for (gp, hp) in it {
        g += gp;
        h += hp;
    }
    (g, h)
}
