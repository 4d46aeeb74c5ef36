//! Householder QR of small dense least-squares problems (hundreds of rows,
//! a few dozen columns) on buffers reused from call to call: the inner
//! solve of IRLS (one weighted fit per iteration), of its Anderson
//! acceleration and of NNLS (one per change of its passive set).
//!
//! The rows are weighted by `sqrt(w)` and the columns scaled to a common
//! norm (as [`crate::lstsq`] does, to a power of two here: see
//! [`COLUMN_NORM`]), then faer's unpivoted QR factors the copy in place
//! (its unblocked kernel at these sizes: see [`UNBLOCKED_MAX_ENTRIES`])
//! and faer's Householder and triangular kernels apply `Q^T` and solve
//! `R`; the matrix, the reflector factors and faer's scratch memory are
//! kept between calls, so a call allocates nothing once the buffers have
//! grown to the problem's size. faer's column-pivoted QR is not used: in
//! a profile of IRLS on the CUReT polynomial designs (189 x 15) it spent
//! 60% of the time in the `norm_l2` of its column norms.
//!
//! Without pivoting the rank check is a count: on equal-norm columns a
//! column is dependent on the ones before it when its `|R_kk|` is at most
//! `max(m, n) eps max_j |R_jj|` (LAPACK's `xGELSY` tolerance). faer itself
//! skips a column whose `|R_kk|` is below `16 (m - k) eps` of the column's
//! norm (its rank is then below `min(m, n)`), which also counts as rank
//! deficiency. A rank-deficient problem is not solved here: the caller
//! falls back to [`crate::lstsq`], which re-solves it by SVD.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::householder::{
    apply_block_householder_sequence_on_the_left_in_place_scratch,
    apply_block_householder_sequence_on_the_left_in_place_with_conj,
    apply_block_householder_sequence_transpose_on_the_left_in_place_scratch,
};
use faer::linalg::qr::no_pivoting::factor::{
    qr_in_place, qr_in_place_scratch, recommended_block_size,
};
use faer::linalg::qr::no_pivoting::solve::solve_lstsq_in_place_with_conj;
use faer::{Conj, MatMut, MatRef, Par};

/// The norm of a scaled column: a power of two, so the scaling is exact
/// and the factorisation the same as on unit-norm columns times it, only
/// faster. Why not 1: faer's `norm_l2` (which its Householder reflectors
/// call on every column) accumulates the squares of `x sqrt(MIN_POSITIVE)`,
/// subnormal for every `|x| < 1`, and each subnormal result costs a
/// microcode assist; on unit-norm columns nearly every entry is below 1
/// (on the CUReT IRLS designs, with faer's blocked kernel, the reflectors'
/// norms were then half of the whole IRLS time). At
/// `2^64` only entries below `2^-64` of their column's norm are, and the
/// squares (at most `2^128` a column) stay far from overflow.
const COLUMN_NORM: f64 = 18_446_744_073_709_551_616.0;

/// Largest problem (entries of `A`, 512 KiB) factored by faer's unblocked
/// kernel (one reflector at a time, `block_size == 1`). Measured on the
/// CUReT IRLS designs (189 x 15): faer's recommended block of 8 took 1.6
/// times as long as the unblocked kernel, whose panel is the whole matrix
/// and stays in cache anyway; larger problems keep faer's recommendation,
/// where blocking saves passes over memory.
const UNBLOCKED_MAX_ENTRIES: usize = 1 << 16;

/// The Householder block size of an `m x n` factorisation.
fn block_size(m: usize, n: usize) -> usize {
    if m * n <= UNBLOCKED_MAX_ENTRIES {
        1
    } else {
        recommended_block_size::<f64>(m, n)
    }
}

/// Workspace of [`SmallQr::factor`]: the factored matrix and its reflectors.
pub(crate) struct SmallQr {
    m: usize,
    n: usize,
    /// `R` on and above the diagonal, the reflectors below (column-major).
    a: Vec<f64>,
    /// faer's block reflector factors (`block x min(m, n)`, column-major).
    coeff: Vec<f64>,
    block: usize,
    /// Column scales (the input column's weighted norm over
    /// [`COLUMN_NORM`], 1 for zero columns or unscaled problems).
    scale: Vec<f64>,
    /// Square roots of the row weights.
    sw: Vec<f64>,
    /// Right-hand side buffer.
    rhs: Vec<f64>,
    /// faer's scratch memory, grown when a problem needs more.
    mem: MemBuffer,
    rank: usize,
}

impl Default for SmallQr {
    fn default() -> Self {
        Self {
            m: 0,
            n: 0,
            a: Vec::new(),
            coeff: Vec::new(),
            block: 1,
            scale: Vec::new(),
            sw: Vec::new(),
            rhs: Vec::new(),
            mem: MemBuffer::new(StackReq::EMPTY),
            rank: 0,
        }
    }
}

impl SmallQr {
    /// An empty workspace.
    pub(crate) fn new() -> Self {
        Self::default()
    }

    /// Factor `diag(sqrt(w)) A` (every row weight 1 when `w` is `None`),
    /// with its columns scaled to a common norm when `scale_columns`. Returns
    /// the numerical rank. `w` must be finite and `>= 0`, `A` finite.
    pub(crate) fn factor(
        &mut self,
        a: MatRef<'_, f64>,
        w: Option<&[f64]>,
        scale_columns: bool,
    ) -> usize {
        self.factor_selected(a, None, w, scale_columns)
    }

    /// [`SmallQr::factor`] of the columns `cols` of `A` only (unweighted);
    /// the solution of [`SmallQr::solve`] is then indexed like `cols`.
    pub(crate) fn factor_columns(
        &mut self,
        a: MatRef<'_, f64>,
        cols: &[usize],
        scale_columns: bool,
    ) -> usize {
        self.factor_selected(a, Some(cols), None, scale_columns)
    }

    fn factor_selected(
        &mut self,
        a: MatRef<'_, f64>,
        cols: Option<&[usize]>,
        w: Option<&[f64]>,
        scale_columns: bool,
    ) -> usize {
        let m = a.nrows();
        let n = cols.map_or(a.ncols(), <[usize]>::len);
        (self.m, self.n) = (m, n);
        self.load(a, cols, w, scale_columns);
        let size = m.min(n);
        self.rank = 0;
        if size == 0 {
            return 0;
        }
        self.block = block_size(m, n);
        self.coeff.clear();
        self.coeff.resize(self.block * size, 0.0);
        self.reserve_scratch();
        let info = qr_in_place(
            MatMut::from_column_major_slice_mut(&mut self.a, m, n),
            MatMut::from_column_major_slice_mut(&mut self.coeff, self.block, size),
            Par::Seq,
            MemStack::new(&mut self.mem),
            Default::default(),
        );
        self.rank = if info.rank < size {
            info.rank
        } else {
            self.count_rank()
        };
        self.rank
    }

    /// Copy `diag(sqrt(w)) A` (columns `cols`) into `a`, each column
    /// divided by its norm when `scale_columns`.
    fn load(
        &mut self,
        a: MatRef<'_, f64>,
        cols: Option<&[usize]>,
        w: Option<&[f64]>,
        scale_columns: bool,
    ) {
        let m = a.nrows();
        self.sw.clear();
        match w {
            Some(w) => self.sw.extend(w.iter().map(|v| v.sqrt())),
            None => self.sw.resize(m, 1.0),
        }
        self.a.clear();
        self.a.reserve(m * self.n);
        self.scale.clear();
        for j in 0..self.n {
            let start = self.a.len();
            let col = a.col(cols.map_or(j, |c| c[j]));
            self.a
                .extend(self.sw.iter().enumerate().map(|(i, s)| s * col[i]));
            let s = column_norm(MatRef::from_column_major_slice(&self.a[start..], m, 1));
            let s = if scale_columns && s > 0.0 {
                s / COLUMN_NORM
            } else {
                1.0
            };
            if s != 1.0 {
                self.a[start..].iter_mut().for_each(|v| *v /= s);
            }
            self.scale.push(s);
        }
    }

    /// Grow faer's scratch memory to what the factorisation, `Q^T b` and
    /// `Q [I; 0]` (the leverages) need at the current size.
    fn reserve_scratch(&mut self) {
        let (m, n, bs) = (self.m, self.n, self.block);
        let req = qr_in_place_scratch::<f64>(m, n, bs, Par::Seq, Default::default())
            .or(
                apply_block_householder_sequence_transpose_on_the_left_in_place_scratch::<f64>(
                    m, bs, 1,
                ),
            )
            .or(apply_block_householder_sequence_on_the_left_in_place_scratch::<f64>(m, bs, n));
        if !MemStack::new(&mut self.mem).can_hold(req) {
            self.mem = MemBuffer::new(req);
        }
    }

    /// The number of `|R_kk|` above `max(m, n) eps max_j |R_jj|`.
    fn count_rank(&self) -> usize {
        let (m, n) = (self.m, self.n);
        let diag = |k: usize| self.a[k * m + k].abs();
        let size = m.min(n);
        let largest = (0..size).map(diag).fold(0.0, f64::max);
        let tol = m.max(n) as f64 * f64::EPSILON * largest;
        (0..size).filter(|&k| diag(k) > tol).count()
    }

    /// The factored matrix (`R` above the reflectors) and faer's reflector
    /// factors as faer's kernels take them, with the scratch memory.
    fn factors(&mut self) -> (MatRef<'_, f64>, MatRef<'_, f64>, &mut MemStack) {
        let size = self.m.min(self.n);
        (
            MatRef::from_column_major_slice(&self.a, self.m, self.n),
            MatRef::from_column_major_slice(&self.coeff, self.block, size),
            MemStack::new(&mut self.mem),
        )
    }

    /// The least-squares solution `x` of the factored problem for `b`
    /// (weighted like the rows); false (and `x` untouched) when the
    /// factored matrix is rank-deficient or the solution not finite.
    pub(crate) fn solve(&mut self, b: &[f64], x: &mut [f64]) -> bool {
        let (m, n) = (self.m, self.n);
        if self.rank < n || m < n {
            return false;
        }
        let mut rhs = std::mem::take(&mut self.rhs);
        rhs.clear();
        rhs.extend(b.iter().zip(&self.sw).map(|(b, s)| b * s));
        let (qr, coeff, stack) = self.factors();
        // Q^T b, then R z = (Q^T b)[..n], in place in rhs.
        solve_lstsq_in_place_with_conj(
            qr,
            coeff,
            qr,
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut rhs, m, 1),
            Par::Seq,
            stack,
        );
        let ok = rhs[..n].iter().all(|v| v.is_finite());
        if ok {
            for k in 0..n {
                x[k] = rhs[k] / self.scale[k];
            }
        }
        self.rhs = rhs;
        ok
    }

    /// The leverages `h_i = ||Q_i||^2` over the `n` columns of the thin `Q`
    /// (the diagonal of the hat matrix of the factored matrix's column
    /// space, as [`crate::linear::leverages`] defines them); `None` when
    /// the factored matrix is rank-deficient (those columns of an unpivoted
    /// `Q` need not span its column space), for the caller to use
    /// [`crate::linear::leverages`].
    pub(crate) fn leverages(&mut self) -> Option<Vec<f64>> {
        let (m, n) = (self.m, self.n);
        if self.rank < n || m < n {
            return None;
        }
        // The thin Q = Q [I; 0], by faer's Householder kernel.
        let mut q = vec![0.0; m * n];
        (0..n).for_each(|j| q[j * m + j] = 1.0);
        let (qr, coeff, stack) = self.factors();
        apply_block_householder_sequence_on_the_left_in_place_with_conj(
            qr,
            coeff,
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut q, m, n),
            Par::Seq,
            stack,
        );
        let mut h = vec![0.0; m];
        for col in q.chunks_exact(m) {
            h.iter_mut().zip(col).for_each(|(h, q)| *h += q * q);
        }
        Some(h)
    }
}

/// The Euclidean norm of a column as the root of its plain sum of squares
/// when that sum is a normal number, faer's scaled `norm_l2` otherwise (an
/// overflow or underflow of the squares). Why not always `norm_l2`: its
/// accumulator of small values squares `x sqrt(MIN_POSITIVE)`, which is
/// subnormal for every `|x| < 1`, and each subnormal result costs a
/// microcode assist: on the CUReT designs that made the column norms a
/// third of the whole IRLS time.
fn column_norm(col: MatRef<'_, f64>) -> f64 {
    let s2 = col.squared_norm_l2();
    if s2.is_normal() {
        s2.sqrt()
    } else {
        col.norm_l2()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    /// A 6 x 3 problem with a known exact solution plus a residual
    /// orthogonal to the columns (hand-built: the columns are orthogonal
    /// to `(1, -1, 1, -1, 1, -1)`), so the least-squares solution is the
    /// exact one whatever the weights that keep that orthogonality.
    #[test]
    fn solves_a_problem_with_known_solution() {
        // Columns: 1, i, i^2 on rows i = 0..6; x = (1, -2, 0.5).
        let a = Mat::from_fn(6, 3, |i, j| (i as f64).powi(j as i32));
        let exact = [1.0, -2.0, 0.5];
        let b: Vec<f64> = (0..6)
            .map(|i| (0..3).map(|j| a[(i, j)] * exact[j]).sum::<f64>())
            .collect();
        let mut qr = SmallQr::new();
        assert_eq!(qr.factor(a.as_ref(), None, true), 3);
        let mut x = [0.0; 3];
        assert!(qr.solve(&b, &mut x));
        for (x, e) in x.iter().zip(exact) {
            assert!((x - e).abs() < 1e-12, "{x} vs {e}");
        }
    }

    /// A consistent 6000 x 12 weighted problem (past
    /// [`UNBLOCKED_MAX_ENTRIES`], so faer's blocked kernels run): whatever
    /// the weights, the least-squares solution is the exact one.
    #[test]
    fn solves_a_blocked_weighted_problem_with_known_solution() {
        let (m, n) = (6000, 12);
        assert!(block_size(m, n) > 1);
        let t = |i: usize| std::f64::consts::PI * i as f64 / (m - 1) as f64;
        let a = Mat::from_fn(m, n, |i, j| (j as f64 * t(i)).cos() * (1.0 + j as f64));
        let exact: Vec<f64> = (0..n).map(|j| 1.0 - 0.25 * j as f64).collect();
        let b: Vec<f64> = (0..m)
            .map(|i| (0..n).map(|j| a[(i, j)] * exact[j]).sum::<f64>())
            .collect();
        let w: Vec<f64> = (0..m).map(|i| 0.5 + (i % 7) as f64).collect();
        let mut qr = SmallQr::new();
        assert_eq!(qr.factor(a.as_ref(), Some(&w), true), n);
        let mut x = vec![0.0; n];
        assert!(qr.solve(&b, &mut x));
        for (x, e) in x.iter().zip(&exact) {
            assert!((x - e).abs() < 1e-12, "{x} vs {e}");
        }
    }

    /// The leverages of a CUReT-size design against the normal
    /// equations' `h_i = a_i^T (A^T A)^-1 a_i` (faer's Cholesky, another
    /// algorithm); they sum to the rank, the trace of the projection.
    #[test]
    fn leverages_match_the_normal_equations() {
        let (m, n) = (150, 10);
        let a = Mat::from_fn(m, n, |i, j| {
            let t = i as f64 / (m - 1) as f64;
            (std::f64::consts::PI * j as f64 * t).cos() * (1.0 + j as f64)
        });
        let mut qr = SmallQr::new();
        assert_eq!(qr.factor(a.as_ref(), None, false), n);
        let h = qr.leverages().expect("a full-rank design");
        let gram = a.transpose() * &a;
        let llt = gram
            .llt(faer::Side::Lower)
            .expect("a positive definite Gram matrix");
        let g_inv_at = faer::linalg::solvers::Solve::solve(&llt, a.transpose());
        for (i, h) in h.iter().enumerate() {
            let want: f64 = (0..n).map(|k| a[(i, k)] * g_inv_at[(k, i)]).sum();
            assert!((h - want).abs() < 1e-12, "row {i}: {h} vs {want}");
        }
        let sum: f64 = h.iter().sum();
        assert!((sum - n as f64).abs() < 1e-12, "{sum}");
    }

    /// Weighted least squares of a constant: the weighted mean (by hand:
    /// weights (1, 3), values (2, 6) -> (2 + 18) / 4 = 5); a zero weight
    /// drops its row.
    #[test]
    fn weighted_mean_by_hand() {
        let a = Mat::from_fn(3, 1, |_, _| 1.0);
        let mut qr = SmallQr::new();
        qr.factor(a.as_ref(), Some(&[1.0, 3.0, 0.0]), true);
        let mut x = [0.0];
        assert!(qr.solve(&[2.0, 6.0, 100.0], &mut x));
        assert!((x[0] - 5.0).abs() < 1e-14, "{}", x[0]);
    }

    /// A duplicated column is rank-deficient: no solution from here.
    #[test]
    fn rank_deficiency_is_refused() {
        let a = Mat::from_fn(5, 3, |i, j| if j == 2 { 1.0 } else { (i + j) as f64 });
        // Column 1 = column 0 + column 2.
        let mut qr = SmallQr::new();
        assert_eq!(qr.factor(a.as_ref(), None, true), 2);
        let mut x = [7.0; 3];
        assert!(!qr.solve(&[1.0; 5], &mut x));
        assert_eq!(x, [7.0; 3]);
    }

    /// A rank-deficient design has no leverages from the unpivoted `Q`
    /// (the caller takes them from the pivoted QR of `linear`).
    #[test]
    fn no_leverages_of_a_rank_deficient_design() {
        let a = Mat::from_fn(4, 3, |i, j| {
            if j == 2 {
                2.0 * i as f64
            } else {
                (i * j) as f64 + 1.0
            }
        });
        // Column 2 = 2 * column 1 - 2 * column 0.
        let mut qr = SmallQr::new();
        assert_eq!(qr.factor(a.as_ref(), None, false), 2);
        assert!(qr.leverages().is_none());
    }

    /// Leverages of a straight-line design by hand: `h_i = 1/n + (t_i -
    /// mean)^2 / sum (t - mean)^2`; for t = 0..4: 1/4 + (t - 1.5)^2 / 5.
    #[test]
    fn leverages_of_a_line_by_hand() {
        let a = Mat::from_fn(4, 2, |i, j| if j == 0 { 1.0 } else { i as f64 });
        let mut qr = SmallQr::new();
        qr.factor(a.as_ref(), None, false);
        let h = qr.leverages().expect("a full-rank design");
        for (i, h) in h.iter().enumerate() {
            let want = 0.25 + (i as f64 - 1.5).powi(2) / 5.0;
            assert!((h - want).abs() < 1e-14, "row {i}: {h} vs {want}");
        }
    }
}
