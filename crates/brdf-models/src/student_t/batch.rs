//! The STD lobe over many pairs at once, with the same bits as
//! [`StdLobe::shape`](super::StdLobe) pair by pair.
//!
//! Nearly all of an STD evaluation is Smith's `Lambda`: the incomplete
//! beta function's continued fraction (half of a fit's processor time,
//! profiled on paper_white) and the logarithms around it. Per pair the
//! fraction is a chain of dependent divisions, so one pair at a time the
//! processor waits on each. Here the `Lambda`s of a chunk of pairs (of `L`
//! and `V`, at `gamma` and, for the derivative, at `gamma` plus and minus
//! its step) are gathered, their fractions run [`LANES`] at a time in
//! vector lanes, each lane with the scalar code's operations in its order
//! (no fused multiply-add) and frozen once it has converged, and the
//! factors that depend on `gamma` alone are taken once per batch
//! ([`LambdaAt`]). A direction repeated from the pair before (the view of
//! every term of a rendered pixel, the incident direction along a
//! measurement's grid) has its `Lambda`s evaluated once.

use brdf_core::DirPairs;
use nalgebra::Vector3;

use super::{
    BetaTail, CF_MAX_TERMS, LambdaAt, LambdaStart, cf_guard, cot_over_alpha, gamma_step,
    half_vector, lambda_derivatives, lambdas_at, lobe_value,
};

/// Pairs per chunk: its `Lambda`s (up to six per pair) stay in cache.
const CHUNK: usize = 64;
/// Continued fractions run side by side: two AVX2 vectors, so that the
/// dependent divisions of one overlap those of the other.
const LANES: usize = 8;

/// `s[j]` and, when given, `ds[u * n + j]` of the STD lobe at `q` for
/// every pair (0 where `valid[j]` is false), as
/// [`per_pair`](crate::combinators::per_pair) over
/// [`StdLobe::shape`](super::StdLobe) writes them.
pub(super) fn shape_batch(
    q: &[f64],
    pairs: &DirPairs,
    valid: &[bool],
    s: &mut [f64],
    ds: Option<&mut [f64]>,
) {
    pulp::Arch::new().dispatch(Batch {
        q,
        pairs,
        valid,
        s,
        ds,
    });
}

/// The arguments of [`shape_batch`], run inside `pulp`'s dispatch so the
/// lanes of the continued fraction vectorise.
struct Batch<'a> {
    q: &'a [f64],
    pairs: &'a DirPairs,
    valid: &'a [bool],
    s: &'a mut [f64],
    ds: Option<&'a mut [f64]>,
}

impl pulp::WithSimd for Batch<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let Batch {
            q,
            pairs,
            valid,
            s,
            mut ds,
        } = self;
        let n = pairs.len();
        let grad = ds.is_some();
        let at = lambdas_at(q[1], grad);
        let mut lambdas = Lambdas::default();
        let mut dq = [0.0; 3];
        let mut start = 0;
        while start < n {
            let len = CHUNK.min(n - start);
            let pc = pairs.chunk(start, len);
            lambdas.gather(q[0], &at, grad, &valid[start..start + len], |i| pc.at(i));
            lambdas.evaluate(&at);
            for i in 0..len {
                let j = start + i;
                dq.fill(0.0);
                let (l, v) = pc.at(i);
                let value = match (valid[j], half_vector(&l, &v)) {
                    (true, Some(h)) => {
                        let ll = lambdas.of(2 * i, q[0], &at);
                        let lv = lambdas.of(2 * i + 1, q[0], &at);
                        lobe_value(q, &l, &v, &h, ll, lv, grad.then_some(&mut dq[..]))
                    }
                    _ => 0.0,
                };
                s[j] = value;
                if let Some(ds) = ds.as_deref_mut() {
                    for (u, d) in dq.iter().enumerate() {
                        ds[u * n + j] = *d;
                    }
                }
            }
            start += len;
        }
    }
}

/// The `Lambda`s of a chunk: for each direction (`L` then `V` of every
/// pair) its first entry among the evaluations, or none at the pole or
/// for a pair not evaluated; each entry one `a` at one of the three
/// [`LambdaAt`].
#[derive(Default)]
struct Lambdas {
    first: Vec<Option<usize>>,
    /// Entries per direction: 3 with the derivative in `gamma`, else 1.
    per_direction: usize,
    which: Vec<usize>,
    starts: Vec<LambdaStart>,
    results: Vec<(f64, f64)>,
}

impl Lambdas {
    /// The entries of a chunk's pairs (`pair(i)` gives `(L, V)` of pair
    /// `i`, `valid[i]` whether it is evaluated).
    fn gather(
        &mut self,
        alpha: f64,
        at: &[LambdaAt; 3],
        grad: bool,
        valid: &[bool],
        pair: impl Fn(usize) -> (Vector3<f64>, Vector3<f64>),
    ) {
        self.first.clear();
        self.which.clear();
        self.starts.clear();
        self.per_direction = if grad && gamma_step(at[0].gamma) > 0.0 {
            3
        } else {
            1
        };
        // The last direction of each role (`L`, `V`) with its entries:
        // consecutive pairs often share one (every term of a pixel its
        // view; a measurement's grid its incident direction), and its
        // `Lambda`s are then read again rather than evaluated again.
        let mut last: [Option<([u64; 3], usize)>; 2] = [None, None];
        for (i, ok) in valid.iter().enumerate() {
            let (l, v) = pair(i);
            let evaluated = *ok && half_vector(&l, &v).is_some();
            for (role, w) in [l, v].iter().enumerate() {
                let a = cot_over_alpha(w, alpha).filter(|_| evaluated);
                let Some(a) = a else {
                    self.first.push(None);
                    continue;
                };
                let bits = [w.x.to_bits(), w.y.to_bits(), w.z.to_bits()];
                if let Some((_, e)) = last[role].filter(|(b, _)| *b == bits) {
                    self.first.push(Some(e));
                    continue;
                }
                let e = self.starts.len();
                self.first.push(Some(e));
                last[role] = Some((bits, e));
                for (k, lambda) in at.iter().enumerate().take(self.per_direction) {
                    self.which.push(k);
                    self.starts.push(lambda.start(a));
                }
            }
        }
    }

    /// Every entry's `(Lambda, tail)`: the continued fractions in lanes
    /// (inlined into the dispatch, where the lanes are the widest vectors).
    #[inline(always)]
    fn evaluate(&mut self, at: &[LambdaAt; 3]) {
        let m = self.starts.len();
        let mut i_x = vec![0.0; m];
        for (group, out) in self.starts.chunks(LANES).zip(i_x.chunks_mut(LANES)) {
            let mut args = [(1.0, 1.0, 0.0); LANES];
            let mut live = [false; LANES];
            for (k, s) in group.iter().enumerate() {
                match s.tail {
                    BetaTail::Known(v) => out[k] = v,
                    BetaTail::Fraction(f) => {
                        args[k] = (f.a, f.b, f.x);
                        live[k] = true;
                    }
                }
            }
            let cf = beta_cf_lanes(&args, live);
            for (k, s) in group.iter().enumerate() {
                if let BetaTail::Fraction(f) = s.tail {
                    out[k] = f.finish(cf[k]);
                }
            }
        }
        self.results.clear();
        self.results.extend(
            self.starts
                .iter()
                .zip(&self.which)
                .zip(&i_x)
                .map(|((s, k), i)| at[*k].finish(s, *i)),
        );
    }

    /// `(Lambda, dLambda/d alpha, dLambda/d gamma)` of direction `d`.
    fn of(&self, d: usize, alpha: f64, at: &[LambdaAt; 3]) -> (f64, f64, f64) {
        let Some(e) = self.first[d] else {
            return (0.0, 0.0, 0.0);
        };
        let (lam, tail) = self.results[e];
        let ends =
            (self.per_direction == 3).then(|| (self.results[e + 1].0, self.results[e + 2].0));
        lambda_derivatives(lam, tail, alpha, at[0].gamma, ends)
    }
}

/// The continued fraction of the incomplete beta function (modified
/// Lentz) for [`LANES`] argument triples `(a, b, x)` at once, each lane as
/// [`beta_cf`](super::beta_cf) computes it; lanes not `live` are left at
/// their first value.
#[inline(always)]
fn beta_cf_lanes(args: &[(f64, f64, f64); LANES], live: [bool; LANES]) -> [f64; LANES] {
    let guard = cf_guard;
    let a: [f64; LANES] = std::array::from_fn(|k| args[k].0);
    let b: [f64; LANES] = std::array::from_fn(|k| args[k].1);
    let x: [f64; LANES] = std::array::from_fn(|k| args[k].2);
    let qab: [f64; LANES] = std::array::from_fn(|k| a[k] + b[k]);
    let qap: [f64; LANES] = std::array::from_fn(|k| a[k] + 1.0);
    let qam: [f64; LANES] = std::array::from_fn(|k| a[k] - 1.0);
    let mut c = [1.0; LANES];
    let mut d: [f64; LANES] = std::array::from_fn(|k| 1.0 / guard(1.0 - qab[k] * x[k] / qap[k]));
    let mut h = d;
    let mut going = live;
    for m in 1..=CF_MAX_TERMS {
        if !going.iter().any(|g| *g) {
            break;
        }
        let m = m as f64;
        let m2 = 2.0 * m;
        for k in 0..LANES {
            let aa = m * (b[k] - m) * x[k] / ((qam[k] + m2) * (a[k] + m2));
            let d1 = 1.0 / guard(1.0 + aa * d[k]);
            let c1 = guard(1.0 + aa / c[k]);
            let h1 = h[k] * (d1 * c1);
            let aa = -(a[k] + m) * (qab[k] + m) * x[k] / ((a[k] + m2) * (qap[k] + m2));
            let d2 = 1.0 / guard(1.0 + aa * d1);
            let c2 = guard(1.0 + aa / c1);
            let del = d2 * c2;
            let h2 = h1 * del;
            // A lane that has converged keeps its value, as the scalar
            // loop's `break` does.
            h[k] = if going[k] { h2 } else { h[k] };
            d[k] = d2;
            c[k] = c2;
            going[k] = going[k] && !((del - 1.0).abs() < 1e-16);
        }
    }
    h
}

#[cfg(test)]
mod tests {
    use super::super::{StdLobe, beta_cf};
    use super::*;
    use crate::combinators::{Lobe, per_pair};
    use brdf_core::PairGeometry;

    /// Pairs over the hemisphere, the pole and grazing directions included.
    fn pairs() -> DirPairs {
        let mut p = DirPairs::with_capacity(0);
        let dir = |t: f64, f: f64| Vector3::new(t.sin() * f.cos(), t.sin() * f.sin(), t.cos());
        for i in 0..23 {
            for j in 0..11 {
                let ti = 1.55 * i as f64 / 22.0;
                let to = 1.56 * j as f64 / 10.0;
                p.push(&dir(ti, 0.3 * i as f64), &dir(to, 2.9 - 0.4 * j as f64));
            }
        }
        // One view for many lights, as the terms of a rendered pixel.
        for k in 0..40 {
            p.push(&dir(1.5 * k as f64 / 40.0, k as f64), &dir(0.7, 1.0));
        }
        p.push(&Vector3::z(), &Vector3::z());
        p
    }

    #[test]
    fn the_lanes_give_the_scalar_fraction_bit_for_bit() {
        let triples: Vec<(f64, f64, f64)> = (0..37)
            .map(|i| {
                let t = i as f64 / 36.0;
                if i % 2 == 0 {
                    (0.55 + 30.0 * t, 0.5, 0.02 + 0.9 * t * t)
                } else {
                    (0.5, 0.6 + 12.0 * t, 0.97 - 0.9 * t)
                }
            })
            .collect();
        for group in triples.chunks(LANES) {
            let mut args = [(1.0, 1.0, 0.0); LANES];
            let mut live = [false; LANES];
            for (k, t) in group.iter().enumerate() {
                args[k] = *t;
                live[k] = true;
            }
            let cf = beta_cf_lanes(&args, live);
            for (k, (a, b, x)) in group.iter().enumerate() {
                assert_eq!(
                    cf[k].to_bits(),
                    beta_cf(*a, *b, *x).to_bits(),
                    "{a} {b} {x}"
                );
            }
        }
    }

    #[test]
    fn the_batch_gives_the_per_pair_lobe_bit_for_bit() {
        let p = pairs();
        let geom = PairGeometry::new(&p);
        let n = p.len();
        for q in [
            [0.3, 2.0, 0.04],
            [0.07, 1.6, 0.5],
            [0.8, 35.0, 0.9],
            [0.2, 1.5, 0.1],
        ] {
            for grad in [false, true] {
                let (mut s0, mut s1) = (vec![0.0; n], vec![0.0; n]);
                let (mut d0, mut d1) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
                let (g0, g1) = if grad {
                    (Some(&mut d0[..]), Some(&mut d1[..]))
                } else {
                    (None, None)
                };
                per_pair(&q, &p, &geom, &mut s0, g0, StdLobe::shape);
                StdLobe::shape_batch(&q, &p, &geom, &mut s1, g1);
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&s0), bits(&s1), "values at {q:?}");
                assert_eq!(bits(&d0), bits(&d1), "derivatives at {q:?}");
                assert!(s1.iter().any(|x| *x > 0.0));
            }
        }
    }

    /// Renders take the batch kernel (`eval_pairs`) and give what `eval`
    /// gives pair by pair, below the horizon included.
    #[test]
    fn the_model_renders_what_it_evaluates_pair_by_pair() {
        let mut p = pairs();
        p.push(&Vector3::new(0.6, 0.0, -0.8), &Vector3::z());
        let std = crate::Std::new(&[0.2, 0.3], &[0.7, 0.1], &[0.25, 3.0, 0.3]).expect("std");
        crate::combinators::assert_renders_as_pair_by_pair(&std, &p);
    }
}
