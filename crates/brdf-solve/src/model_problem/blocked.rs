//! The blocked pass of a [`ModelProblem`] over many rows: the residuals
//! and, when asked, the normal equations of `[J | r]` accumulated block by
//! block, so the Jacobian is never stored (on the full MERL grid, writing
//! and re-reading a row-major `J` of 0.9M x 4 entries cost as much as the
//! model itself).
//!
//! The samples are cut once into blocks of [`BLOCK`] rows, each with its
//! own copy of the pairs and of their half-vector geometry, small enough
//! that the basis, its derivatives and the block's Jacobian stay in cache.
//! Blocks are grouped into tasks of [`TASK_BLOCKS`] that rayon runs in
//! parallel; a task sums its Gram matrices in block order and the tasks'
//! sums are added in task order, so the result is the same for any number
//! of threads. For a model with a channel-shared basis each channel's Gram
//! matrix covers only that channel's coefficients and the non-linear
//! parameters (no zero blocks) and is scattered into the full one.

use brdf_core::{DirPairs, PairGeometry, SharedBasis};

use super::ModelProblem;

/// Rows per kernel call.
const BLOCK: usize = 1024;
/// Blocks per parallel task.
const TASK_BLOCKS: usize = 32;
/// Samples from which a problem is cut into blocks; below, one pass over
/// whole arrays costs less than the bookkeeping.
pub(super) const MIN_SAMPLES: usize = 8 * BLOCK;

/// One block of samples: its first row, its pairs and their geometry.
pub(super) struct Block {
    start: usize,
    pairs: DirPairs,
    geom: Option<PairGeometry>,
}

/// `pairs` cut into blocks, with their geometry when the model reads it.
pub(super) fn blocks(pairs: &DirPairs, with_geometry: bool) -> Vec<Block> {
    (0..pairs.len())
        .step_by(BLOCK)
        .map(|start| {
            let pairs = pairs.range(start, BLOCK.min(pairs.len() - start));
            let geom = with_geometry.then(|| PairGeometry::new(&pairs));
            Block { start, pairs, geom }
        })
        .collect()
}

/// Buffers of one task, reused by its blocks.
#[derive(Default)]
struct Work {
    phi: Vec<f64>,
    dphi: Vec<f64>,
    a: Vec<f64>,
    val: Vec<f64>,
    jac: Vec<f64>,
    /// Per-row derivative factors under a row transform.
    factor: Vec<f64>,
}

/// `acc += A^T A` for the column-major `rows x w` matrix in `a` (`w` a
/// handful, `rows` one block): the upper triangle as dot products of the
/// block's columns, which stay in cache, mirrored. A general matrix
/// product would pack and pad the few columns to its kernel's width.
/// Column `i` is dotted with four columns at once (each load of it serves
/// four products), inside `pulp`'s dispatch so the partial sums fill the
/// widest vectors; each product sums as [`dot`] does, so the bits do not
/// depend on the vector width or the grouping.
fn add_gram(acc: &mut [f64], a: &[f64], rows: usize, w: usize) {
    pulp::Arch::new().dispatch(Gram { acc, a, rows, w });
}

/// The arguments of [`add_gram`].
struct Gram<'a> {
    acc: &'a mut [f64],
    a: &'a [f64],
    rows: usize,
    w: usize,
}

impl pulp::WithSimd for Gram<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let Gram { acc, a, rows, w } = self;
        let col = |k: usize| &a[k * rows..(k + 1) * rows];
        let mut add = |i: usize, j: usize, d: f64| {
            acc[i * w + j] += d;
            if j != i {
                acc[j * w + i] += d;
            }
        };
        for i in 0..w {
            let ci = col(i);
            let mut j = i;
            while j + 4 <= w {
                let d = dot4(ci, [col(j), col(j + 1), col(j + 2), col(j + 3)]);
                for (t, dt) in d.into_iter().enumerate() {
                    add(i, j + t, dt);
                }
                j += 4;
            }
            for j in j..w {
                add(i, j, dot(ci, col(j)));
            }
        }
    }
}

/// `x . y` with four partial sums, so the loop vectorises.
#[inline(always)]
fn dot(x: &[f64], y: &[f64]) -> f64 {
    let mut s = [0.0; 4];
    let (xc, yc) = (x.chunks_exact(4), y.chunks_exact(4));
    let tail: f64 = xc
        .remainder()
        .iter()
        .zip(yc.remainder())
        .map(|(a, b)| a * b)
        .sum();
    for (a, b) in xc.zip(yc) {
        for k in 0..4 {
            s[k] += a[k] * b[k];
        }
    }
    (s[0] + s[1]) + (s[2] + s[3]) + tail
}

/// [`dot`] of `x` with four columns at once, each summed as `dot` sums it.
#[inline(always)]
fn dot4(x: &[f64], ys: [&[f64]; 4]) -> [f64; 4] {
    let n = x.len() / 4 * 4;
    let mut s = [[0.0; 4]; 4];
    let (x4, ys4) = (&x[..n], ys.map(|y| &y[..n]));
    for c in (0..n).step_by(4) {
        let a = &x4[c..c + 4];
        for (st, y) in s.iter_mut().zip(&ys4) {
            let b = &y[c..c + 4];
            for k in 0..4 {
                st[k] += a[k] * b[k];
            }
        }
    }
    std::array::from_fn(|t| {
        let tail: f64 = x[n..].iter().zip(&ys[t][n..]).map(|(a, b)| a * b).sum();
        let st = s[t];
        (st[0] + st[1]) + (st[2] + st[3]) + tail
    })
}

/// `a[k * m + i] = jac[i * np + k] * scale[i % len]` for the `m` rows of
/// the row-major `jac` (`m` a multiple of `len = scale.len()`), in tiles of
/// [`TILE`] rows: each tile's rows are read once, contiguously, and each
/// column is written as a contiguous run, where a row-by-row loop wrote
/// every entry `m` apart (the transpose cost a sixth of a principled fit).
fn scaled_transpose(jac: &[f64], scale: &[f64], np: usize, a: &mut [f64]) {
    let (m, len) = (jac.len() / np.max(1), scale.len());
    for i0 in (0..m).step_by(TILE) {
        let rows = TILE.min(m - i0);
        let mut st = [0.0; TILE];
        for (t, v) in st[..rows].iter_mut().enumerate() {
            *v = scale[(i0 + t) % len];
        }
        let tile = &jac[i0 * np..(i0 + rows) * np];
        for k in 0..np {
            let col = &mut a[k * m + i0..k * m + i0 + rows];
            for ((v, row), s) in col.iter_mut().zip(tile.chunks_exact(np)).zip(&st) {
                *v = row[k] * s;
            }
        }
    }
}

/// Rows per tile of [`scaled_transpose`].
const TILE: usize = 16;

impl ModelProblem<'_> {
    /// The parameter index of every column of each accumulation group (a
    /// channel of a shared-basis model, else the whole problem), the
    /// residual column last (index `n_params`).
    fn groups(&self) -> Vec<Vec<usize>> {
        let np = self.model.n_params();
        match self.shared() {
            Some((b, _)) => {
                let l = b.basis_len();
                (0..self.model.channels())
                    .map(|c| {
                        let mut idx = self.coefficients[c * l..(c + 1) * l].to_vec();
                        idx.extend(&self.nonlinear);
                        idx.push(np);
                        idx
                    })
                    .collect()
            }
            None => vec![(0..=np).collect()],
        }
    }

    /// The residuals into `out` and, when `gram` is given, the row-major
    /// Gram matrix of `[J | r]` into it (as
    /// [`crate::LeastSquaresProblem::residuals_and_gram`]).
    pub(super) fn blocked_pass(&self, p: &[f64], out: &mut [f64], gram: Option<&mut [f64]>) {
        let n = self.pairs.len();
        let groups = self.groups();
        let w = groups[0].len();
        let acc_len = if gram.is_some() {
            groups.len() * w * w
        } else {
            0
        };
        // Each task's rows of every channel.
        let tasks: Vec<&[Block]> = self.blocks.chunks(TASK_BLOCKS).collect();
        let mut outs: Vec<Vec<&mut [f64]>> = tasks.iter().map(|_| Vec::new()).collect();
        for channel in out.chunks_mut(n) {
            for (t, piece) in channel.chunks_mut(TASK_BLOCKS * BLOCK).enumerate() {
                outs[t].push(piece);
            }
        }
        let run = |(blocks, mut outs): (&[Block], Vec<&mut [f64]>)| {
            let mut acc = vec![0.0; acc_len];
            let mut work = Work::default();
            let first = blocks.first().map_or(0, |b| b.start);
            for b in blocks {
                let (off, len) = (b.start - first, b.pairs.len());
                let mut rows: Vec<&mut [f64]> =
                    outs.iter_mut().map(|o| &mut o[off..off + len]).collect();
                let acc = (acc_len > 0).then_some(acc.as_mut_slice());
                match self.shared() {
                    Some((basis, _)) => self.shared_block(*basis, p, b, &mut rows, acc, &mut work),
                    None => self.general_block(p, b, &mut rows, acc, &mut work),
                }
            }
            acc
        };
        let jobs: Vec<_> = tasks.into_iter().zip(outs).collect();
        #[cfg(feature = "rayon")]
        let parts: Vec<Vec<f64>> = {
            use rayon::prelude::*;
            jobs.into_par_iter().map(run).collect()
        };
        #[cfg(not(feature = "rayon"))]
        let parts: Vec<Vec<f64>> = jobs.into_iter().map(run).collect();
        if let Some(gram) = gram {
            let wg = self.model.n_params() + 1;
            gram.fill(0.0);
            for part in &parts {
                for (g, idx) in groups.iter().enumerate() {
                    let acc = &part[g * w * w..(g + 1) * w * w];
                    for (a, &ia) in idx.iter().enumerate() {
                        for (b, &ib) in idx.iter().enumerate() {
                            gram[ia * wg + ib] += acc[a * w + b];
                        }
                    }
                }
            }
        }
    }

    /// One block of a shared-basis model: per channel, the residual rows
    /// and (with `acc`) that channel's Gram matrix over its coefficients,
    /// the non-linear parameters and the residual.
    fn shared_block(
        &self,
        basis: &dyn SharedBasis,
        p: &[f64],
        blk: &Block,
        rows: &mut [&mut [f64]],
        acc: Option<&mut [f64]>,
        work: &mut Work,
    ) {
        let (n, len) = (self.pairs.len(), blk.pairs.len());
        let (l, nq) = (basis.basis_len(), self.nonlinear.len());
        let w = l + nq + 1;
        let Some(geom) = &blk.geom else { return };
        work.phi.resize(l * len, 0.0);
        let phi = &mut work.phi[..l * len];
        let dphi = match acc {
            Some(_) => {
                work.dphi.resize(l * nq * len, 0.0);
                Some(&mut work.dphi[..l * nq * len])
            }
            None => None,
        };
        let with_gram = dphi.is_some();
        basis.basis_batch(p, &blk.pairs, geom, phi, dphi);
        let scale = &self.scale[blk.start..blk.start + len];
        let mut acc = acc;
        for (c, r) in rows.iter_mut().enumerate() {
            let ks = &self.coefficients[c * l..(c + 1) * l];
            let y = &self.targets[c * n + blk.start..c * n + blk.start + len];
            // Column by column over the block (the same sums per row as
            // a row loop, in the same order), so the loops vectorise.
            r.fill(0.0);
            for (t, &k) in ks.iter().enumerate() {
                let x = p[k];
                for (v, f) in r.iter_mut().zip(&phi[t * len..(t + 1) * len]) {
                    *v += x * f;
                }
            }
            for ((v, s), yj) in r.iter_mut().zip(scale).zip(y) {
                *v = *v * s - yj;
            }
            let Some(acc) = acc.as_deref_mut() else {
                continue;
            };
            debug_assert!(with_gram);
            work.a.resize(w * len, 0.0);
            let (a, dphi) = (&mut work.a[..w * len], &work.dphi[..l * nq * len]);
            for t in 0..l {
                let col = &mut a[t * len..(t + 1) * len];
                for ((v, f), s) in col.iter_mut().zip(&phi[t * len..(t + 1) * len]).zip(scale) {
                    *v = f * s;
                }
            }
            for u in 0..nq {
                let col = &mut a[(l + u) * len..(l + u + 1) * len];
                col.fill(0.0);
                for (t, &k) in ks.iter().enumerate() {
                    let d = &dphi[(t * nq + u) * len..(t * nq + u + 1) * len];
                    for ((v, s), dj) in col.iter_mut().zip(scale).zip(d) {
                        *v += p[k] * s * dj;
                    }
                }
            }
            a[(w - 1) * len..].copy_from_slice(r);
            add_gram(&mut acc[c * w * w..(c + 1) * w * w], a, len, w);
        }
    }

    /// One block of any model: the residual rows and (with `acc`) the Gram
    /// matrix of every parameter and the residual, from the model's batch
    /// gradient.
    fn general_block(
        &self,
        p: &[f64],
        blk: &Block,
        rows: &mut [&mut [f64]],
        acc: Option<&mut [f64]>,
        work: &mut Work,
    ) {
        let (n, len, np) = (self.pairs.len(), blk.pairs.len(), p.len());
        let m = rows.len() * len;
        work.val.resize(m, 0.0);
        let val = &mut work.val[..m];
        if acc.is_some() {
            work.jac.resize(m * np, 0.0);
            let jac = &mut work.jac[..m * np];
            self.model.eval_grad_batch_at(p, &blk.pairs, val, jac);
        } else {
            self.model.eval_batch_at(p, &blk.pairs, val);
        }
        let scale = &self.scale[blk.start..blk.start + len];
        if let Some(t) = self.transform {
            // Transformed rows: the residual and the row's derivative
            // factor from the model value.
            work.factor.resize(m, 0.0);
            for (c, r) in rows.iter_mut().enumerate() {
                for j in 0..len {
                    let (v, d) = t.apply(c * n + blk.start + j, val[c * len + j]);
                    r[j] = v;
                    work.factor[c * len + j] = d;
                }
            }
        } else {
            for (c, r) in rows.iter_mut().enumerate() {
                let y = &self.targets[c * n + blk.start..c * n + blk.start + len];
                for j in 0..len {
                    r[j] = val[c * len + j] * scale[j] - y[j];
                }
            }
        }
        let Some(acc) = acc else { return };
        let w = np + 1;
        work.a.resize(w * m, 0.0);
        let (a, jac) = (&mut work.a[..w * m], &work.jac[..m * np]);
        let factor = if self.transform.is_some() {
            &work.factor[..m]
        } else {
            scale
        };
        scaled_transpose(jac, factor, np, a);
        for (c, r) in rows.iter().enumerate() {
            a[np * m + c * len..np * m + (c + 1) * len].copy_from_slice(r);
        }
        add_gram(acc, a, m, w);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four columns at a time, in the dispatch's vectors, give each entry
    /// the bits of its own [`dot`] (rows with and without a tail).
    #[test]
    fn the_grouped_gram_is_the_dot_of_every_pair_bit_for_bit() {
        for (rows, w) in [(1024, 9), (1027, 6), (3, 5), (64, 1)] {
            let a: Vec<f64> = (0..rows * w)
                .map(|k| ((k * 7919 % 1013) as f64 / 101.0 - 4.0) * 1.000_000_1f64.powi(k as i32))
                .collect();
            let mut acc = vec![0.5; w * w];
            add_gram(&mut acc, &a, rows, w);
            for i in 0..w {
                for j in 0..w {
                    let d = dot(&a[i * rows..(i + 1) * rows], &a[j * rows..(j + 1) * rows]);
                    assert_eq!(
                        acc[i * w + j].to_bits(),
                        (0.5 + d).to_bits(),
                        "{rows} x {w}: {i}, {j}"
                    );
                }
            }
        }
    }
}
