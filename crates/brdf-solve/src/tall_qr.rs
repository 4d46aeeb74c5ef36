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
//! The factorisation is faer's Householder QR, run sequentially on row
//! blocks that rayon factors in parallel, whose stacked triangles are
//! factored again (the TSQR reduction of Demmel et al. 2012). Sequential
//! kernels inside parallel blocks: faer's own thread pool would meet at a
//! barrier inside every narrow panel, which on a busy machine costs more
//! than the arithmetic.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::qr::no_pivoting::factor::{
    qr_in_place, qr_in_place_scratch, recommended_block_size,
};
use faer::{Mat, MatMut, Par};

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
