//! Column-pivoted Householder QR of small dense least-squares problems
//! (hundreds of rows, a few dozen columns) on buffers reused from call to
//! call: the inner solve of IRLS (one weighted fit per iteration), of its
//! Anderson acceleration and of NNLS (one per change of its passive set).
//!
//! It computes what [`crate::lstsq`] with [`crate::LstsqMethod::PivotedQr`]
//! computes on a full-rank problem (rows weighted by `sqrt(w)`, columns
//! scaled to unit norm, column-pivoted QR, rank counted as the `|R_kk| >
//! max(m, n) eps |R_00|`, LAPACK's `xGELSY` convention), but unblocked and
//! without allocating: at these sizes faer's blocked, pivoted factorisation
//! spends most of its time in set-up and in its scaled column norms (a
//! profile of IRLS on the CUReT polynomial designs: 60% of the time in
//! `norm_l2`). A rank-deficient problem is not solved here: the caller falls
//! back to [`crate::lstsq`], which re-solves it by SVD.
//!
//! The trailing column norms that choose the pivots are recomputed at every
//! step (not downdated), so no cancellation can pick a wrong pivot; at these
//! sizes that costs less than the factorisation itself.

use faer::MatRef;

/// Workspace of [`SmallQr::factor`]: the factored matrix and its reflectors.
#[derive(Debug, Default)]
pub(crate) struct SmallQr {
    m: usize,
    n: usize,
    /// `R` above the diagonal, the reflectors' tails below (column-major).
    a: Vec<f64>,
    tau: Vec<f64>,
    /// Column `k` of the factored matrix is column `perm[k]` of the input.
    perm: Vec<usize>,
    /// Column scales (the input column's weighted norm, 1 for zero columns).
    scale: Vec<f64>,
    /// Square roots of the row weights.
    sw: Vec<f64>,
    /// Right-hand side buffer.
    rhs: Vec<f64>,
    rank: usize,
}

impl SmallQr {
    /// An empty workspace.
    pub(crate) fn new() -> Self {
        Self::default()
    }

    /// Factor `diag(sqrt(w)) A` (every row weight 1 when `w` is `None`),
    /// with its columns scaled to unit norm when `scale_columns`. Returns
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
        self.sw.clear();
        match w {
            Some(w) => self.sw.extend(w.iter().map(|v| v.sqrt())),
            None => self.sw.resize(m, 1.0),
        }
        self.a.clear();
        self.a.reserve(m * n);
        self.scale.clear();
        for j in 0..n {
            let start = self.a.len();
            let col = a.col(cols.map_or(j, |c| c[j]));
            self.a
                .extend(self.sw.iter().enumerate().map(|(i, s)| s * col[i]));
            let s = norm(&self.a[start..]);
            let s = if scale_columns && s > 0.0 { s } else { 1.0 };
            if s != 1.0 {
                self.a[start..].iter_mut().for_each(|v| *v /= s);
            }
            self.scale.push(s);
        }
        self.perm.clear();
        self.perm.extend(0..n);
        self.tau.clear();
        let k_max = m.min(n);
        let mut r00 = 0.0;
        let tol = m.max(n) as f64 * f64::EPSILON;
        self.rank = 0;
        for k in 0..k_max {
            self.pivot(k);
            let beta = self.reflect(k);
            if k == 0 {
                r00 = beta.abs();
            }
            if beta.abs() > tol * r00 {
                self.rank += 1;
            }
        }
        self.rank
    }

    /// Swap the column of largest trailing norm (rows `k..`) into place `k`.
    fn pivot(&mut self, k: usize) {
        let m = self.m;
        let mut best = (k, -1.0);
        for j in k..self.n {
            let t = norm(&self.a[j * m + k..(j + 1) * m]);
            if t > best.1 {
                best = (j, t);
            }
        }
        let p = best.0;
        if p != k {
            for i in 0..m {
                self.a.swap(k * m + i, p * m + i);
            }
            self.perm.swap(k, p);
            self.scale.swap(k, p);
        }
    }

    /// The Householder reflector that zeroes column `k` below the diagonal,
    /// applied to the trailing columns; returns `R_kk`.
    fn reflect(&mut self, k: usize) -> f64 {
        let (m, n) = (self.m, self.n);
        let (head, tail) = self.a.split_at_mut((k + 1) * m);
        let col = &mut head[k * m + k..];
        let alpha = col[0];
        let xnorm = norm(&col[1..]);
        if xnorm == 0.0 {
            self.tau.push(0.0);
            return alpha;
        }
        let beta = -alpha.signum() * alpha.hypot(xnorm);
        let tau = (beta - alpha) / beta;
        let inv = 1.0 / (alpha - beta);
        col[1..].iter_mut().for_each(|v| *v *= inv);
        col[0] = beta;
        self.tau.push(tau);
        let v = &col[1..];
        for j in k + 1..n {
            let c = &mut tail[(j - k - 1) * m + k..(j - k) * m];
            let d = tau * (c[0] + dot(v, &c[1..]));
            c[0] -= d;
            axpy(-d, v, &mut c[1..]);
        }
        beta
    }

    /// Apply `Q^T` to `v` (length `m`) in place.
    fn apply_qt(&self, v: &mut [f64]) {
        let m = self.m;
        for (k, &tau) in self.tau.iter().enumerate() {
            if tau == 0.0 {
                continue;
            }
            let refl = &self.a[k * m + k + 1..(k + 1) * m];
            let d = tau * (v[k] + dot(refl, &v[k + 1..]));
            v[k] -= d;
            axpy(-d, refl, &mut v[k + 1..]);
        }
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
        self.apply_qt(&mut rhs);
        // Back substitution R z = (Q^T b)[..n], in place in rhs.
        for k in (0..n).rev() {
            let mut t = rhs[k];
            for j in k + 1..n {
                t -= self.a[j * m + k] * rhs[j];
            }
            rhs[k] = t / self.a[k * m + k];
        }
        let ok = rhs[..n].iter().all(|v| v.is_finite());
        if ok {
            for k in 0..n {
                x[self.perm[k]] = rhs[k] / self.scale[k];
            }
        }
        self.rhs = rhs;
        ok
    }

    /// The leverages `h_i = ||Q_i||^2` over the first `rank` columns of `Q`
    /// (the diagonal of the hat matrix of the factored matrix's column
    /// space, as [`crate::linear::leverages`] defines them).
    pub(crate) fn leverages(&self) -> Vec<f64> {
        let m = self.m;
        let mut h = vec![0.0; m];
        let mut e = vec![0.0; m];
        for j in 0..self.rank {
            // Column j of Q = H_0 ... H_{k-1} e_j.
            e.fill(0.0);
            e[j] = 1.0;
            for k in (0..self.tau.len()).rev() {
                let tau = self.tau[k];
                if tau == 0.0 {
                    continue;
                }
                let refl = &self.a[k * m + k + 1..(k + 1) * m];
                let d = tau * (e[k] + dot(refl, &e[k + 1..]));
                e[k] -= d;
                axpy(-d, refl, &mut e[k + 1..]);
            }
            h.iter_mut().zip(&e).for_each(|(h, q)| *h += q * q);
        }
        h
    }
}

/// `a . b` with eight partial sums: a single running sum is a chain the
/// compiler may not reorder, so it would neither vectorise nor pipeline
/// (the dot products are most of the factorisation's time).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    ((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7])) + tail
}

fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    y.iter_mut().zip(x).for_each(|(y, x)| *y += alpha * x);
}

fn norm(v: &[f64]) -> f64 {
    dot(v, v).sqrt()
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

    /// Leverages of a straight-line design by hand: `h_i = 1/n + (t_i -
    /// mean)^2 / sum (t - mean)^2`; for t = 0..4: 1/4 + (t - 1.5)^2 / 5.
    #[test]
    fn leverages_of_a_line_by_hand() {
        let a = Mat::from_fn(4, 2, |i, j| if j == 0 { 1.0 } else { i as f64 });
        let mut qr = SmallQr::new();
        qr.factor(a.as_ref(), None, false);
        let h = qr.leverages();
        for (i, h) in h.iter().enumerate() {
            let want = 0.25 + (i as f64 - 1.5).powi(2) / 5.0;
            assert!((h - want).abs() < 1e-14, "row {i}: {h} vs {want}");
        }
    }
}
