//! The batch kernel of [`ColouredLobes`], what fits and renders call on
//! many direction pairs: the pairs go in chunks, and each stage (the
//! pairs' geometry, a lobe's shape at its width, one channel's Fresnel
//! and weight) is a branch-free loop over the chunk, so that it
//! vectorises (`pulp` compiles the loops for the widest instruction set
//! of the machine; profiled, this kernel was the largest cost of a `brdf
//! fit --for` run).
//!
//! Every lane is added, multiplied, divided and square-rooted as the
//! per-pair kernel ([`ColouredLobes`]'s `eval_at`, which single points
//! still use) does it, in the same order, never fused: the batch gives
//! that kernel's values and derivatives to the bit (tested), so a fit
//! follows the same path whichever it calls.

use std::f64::consts::FRAC_1_PI;

use brdf_core::DirPairs;
use brdf_core::fresnel::fresnel_dielectric_d_eta;
use brdf_core::fresnel_conductor::{fresnel_conductor, fresnel_conductor_grad};

use super::geometry::LobeGeometry;
use super::layout::{LobeFresnel, LobeLayout, weighted};
use crate::dual_model::MAX_CHANNELS;
use crate::ggx::Masking;

/// Pairs evaluated together.
const CHUNK: usize = 64;

/// One chunk's working arrays (structure of arrays), reused by every
/// chunk of a batch.
struct Chunk {
    above: [bool; CHUNK],
    cos_h2: [f64; CHUNK],
    tan2_i: [f64; CHUNK],
    tan2_o: [f64; CHUNK],
    cos_d: [f64; CHUNK],
    inv_4_cos: [f64; CHUNK],
    cos_first: [f64; CHUNK],
    /// A lobe's shape `S` and `dS/d alpha`, and its compensation excess
    /// `k` and `dk/d alpha`.
    s: [f64; CHUNK],
    ds: [f64; CHUNK],
    k: [f64; CHUNK],
    dk: [f64; CHUNK],
    /// One channel's derivatives of a lobe: in its first and second
    /// colour parameter, and in its width.
    g1: [f64; CHUNK],
    g2: [f64; CHUNK],
    ga: [f64; CHUNK],
    /// Each channel's value so far.
    value: [[f64; CHUNK]; MAX_CHANNELS],
}

impl Chunk {
    fn new() -> Box<Self> {
        let z = [0.0; CHUNK];
        Box::new(Chunk {
            above: [false; CHUNK],
            cos_h2: z,
            tan2_i: z,
            tan2_o: z,
            cos_d: z,
            inv_4_cos: z,
            cos_first: z,
            s: z,
            ds: z,
            k: z,
            dk: z,
            g1: z,
            g2: z,
            ga: z,
            value: [z; MAX_CHANNELS],
        })
    }

    /// The geometry of pairs `start..start + len`, below the horizon too
    /// (never read there).
    #[inline(always)]
    fn geometry(&mut self, pairs: &DirPairs, start: usize, len: usize) {
        let pc = pairs.chunk(start, len);
        for i in 0..len {
            let (l, v) = pc.at(i);
            let g = LobeGeometry::unchecked(&l, &v);
            self.above[i] = l.z > 0.0 && v.z > 0.0;
            self.cos_h2[i] = g.cos_h2;
            self.tan2_i[i] = g.tan2_i;
            self.tan2_o[i] = g.tan2_o;
            self.cos_d[i] = g.cos_d;
            self.inv_4_cos[i] = g.inv_4_cos;
            self.cos_first[i] = g.cos_first;
        }
    }

    #[inline(always)]
    fn at(&self, i: usize) -> LobeGeometry {
        LobeGeometry {
            cos_h2: self.cos_h2[i],
            tan2_i: self.tan2_i[i],
            tan2_o: self.tan2_o[i],
            cos_d: self.cos_d[i],
            inv_4_cos: self.inv_4_cos[i],
            cos_first: self.cos_first[i],
        }
    }

    /// A lobe of width `alpha` at every pair of the chunk.
    #[inline(always)]
    fn shape(&mut self, alpha: f64, masking: Masking, compensated: bool, len: usize) {
        for i in 0..len {
            let g = self.at(i);
            (self.s[i], self.ds[i]) = g.lobe(alpha, masking);
            (self.k[i], self.dk[i]) =
                super::compensation::excess_if(compensated, g.cos_first, alpha);
        }
    }

    /// Channel `c`'s term of the current lobe, its Fresnel law `fresnel`
    /// (cosine to `F` and its derivatives in the lobe's two colour
    /// parameters), added to the channel's value; with `GRAD` its
    /// derivatives into `g1`, `g2`, `ga`.
    #[inline(always)]
    fn add_term<const GRAD: bool>(
        &mut self,
        c: usize,
        len: usize,
        fresnel: impl Fn(f64) -> (f64, f64, f64),
    ) {
        let value = &mut self.value[c];
        for i in 0..len {
            let (f, d1, d2) = fresnel(self.cos_d[i]);
            let (w, dw_df, dw_da) = weighted(f, (self.k[i], self.dk[i]));
            let s = self.s[i];
            value[i] += w * s;
            if GRAD {
                self.g1[i] = d1 * dw_df * s;
                self.g2[i] = d2 * dw_df * s;
                self.ga[i] = w * self.ds[i] + dw_da * s;
            }
        }
    }
}

impl Chunk {
    /// The white coat's term at every pair (into `g1`; the shape of its
    /// width in `s`), its derivatives in the coat's index (`g2`) and width
    /// (`ga`): the same for every channel.
    #[inline(always)]
    fn coat(&mut self, ior: f64, len: usize) {
        for i in 0..len {
            let (f, df) = fresnel_dielectric_d_eta(self.cos_d[i], ior);
            let (w, dw_df, dw_da) = weighted(f, (self.k[i], self.dk[i]));
            let s = self.s[i];
            self.g1[i] = w * s;
            self.g2[i] = df * dw_df * s;
            self.ga[i] = w * self.ds[i] + dw_da * s;
        }
    }
}

/// The batch of one call: values `out[c * n + j]` and, with `jac`, the
/// Jacobian `jac[(c * n + j) * np + k]`, 0 below the horizon.
pub(super) struct Batch<'a> {
    pub(super) view: View<'a>,
    pub(super) p: &'a [f64],
    pub(super) pairs: &'a DirPairs,
    pub(super) out: &'a mut [f64],
    pub(super) jac: Option<&'a mut [f64]>,
}

impl pulp::WithSimd for Batch<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(mut self, _simd: S) {
        let mut chunk = Chunk::new();
        let n = self.pairs.len();
        let mut start = 0;
        while start < n {
            let len = CHUNK.min(n - start);
            chunk.geometry(self.pairs, start, len);
            match self.jac {
                Some(ref mut jac) => self.view.chunk::<true>(
                    self.p,
                    &mut chunk,
                    (start, len, n),
                    self.out,
                    Some(jac),
                ),
                None => {
                    self.view
                        .chunk::<false>(self.p, &mut chunk, (start, len, n), self.out, None)
                }
            }
            start += len;
        }
    }
}

/// What the batch reads of a [`super::ColouredLobes`]: its channels,
/// parameter count and lobes.
pub(super) struct View<'a> {
    pub(super) channels: usize,
    pub(super) np: usize,
    pub(super) masking: Masking,
    pub(super) lobes: &'a [LobeLayout],
    pub(super) coat: Option<usize>,
    pub(super) compensated: bool,
}

impl View<'_> {
    /// The chunk `start..start + len` of `n` pairs (`chunk` holds its
    /// geometry) into `out` and, with `GRAD`, `jac`.
    #[inline(always)]
    fn chunk<const GRAD: bool>(
        &self,
        p: &[f64],
        chunk: &mut Chunk,
        (start, len, n): (usize, usize, usize),
        out: &mut [f64],
        mut jac: Option<&mut [f64]>,
    ) {
        // Never more than a chunk (said so the loops need no bounds checks).
        let len = len.min(CHUNK);
        let (nc, np) = (self.channels, self.np);
        let row = |c: usize, i: usize| (c * n + start + i) * np;
        if let Some(jac) = jac.as_deref_mut() {
            for i in 0..len {
                for c in 0..nc {
                    let r = row(c, i);
                    jac[r..r + np].fill(0.0);
                    if chunk.above[i] {
                        jac[r + c] = FRAC_1_PI;
                    }
                }
            }
        }
        for c in 0..nc {
            let kd = p[c] * FRAC_1_PI;
            chunk.value[c][..len].fill(kd);
        }
        for lobe in self.lobes {
            let alpha = p[lobe.alpha];
            chunk.shape(alpha, self.masking, self.compensated, len);
            let (a, b) = (lobe.start, lobe.start + nc);
            for c in 0..nc {
                match lobe.fresnel {
                    LobeFresnel::None => {
                        let ks = p[a + c];
                        chunk.add_term::<GRAD>(c, len, |_| (ks, 1.0, 0.0));
                    }
                    LobeFresnel::F82Tint => {
                        let (f0, tint) = (p[a + c], p[b + c]);
                        chunk.add_term::<GRAD>(c, len, |mu| {
                            super::fresnel_laws::f82_tint(f0, tint, mu)
                        });
                    }
                    LobeFresnel::Conductor if GRAD => {
                        let (eta, k) = (p[a + c], p[b + c]);
                        chunk.add_term::<GRAD>(c, len, |mu| fresnel_conductor_grad(mu, eta, k));
                    }
                    LobeFresnel::Conductor => {
                        let (eta, k) = (p[a + c], p[b + c]);
                        chunk.add_term::<GRAD>(c, len, |mu| {
                            (fresnel_conductor(mu, eta, k), 0.0, 0.0)
                        });
                    }
                }
                if let Some(jac) = jac.as_deref_mut() {
                    let two = lobe.fresnel != LobeFresnel::None;
                    for i in 0..len {
                        if chunk.above[i] {
                            let r = row(c, i);
                            jac[r + a + c] = chunk.g1[i];
                            if two {
                                jac[r + b + c] = chunk.g2[i];
                            }
                            jac[r + lobe.alpha] = chunk.ga[i];
                        }
                    }
                }
            }
        }
        if let Some(at) = self.coat {
            chunk.shape(p[at + 1], self.masking, self.compensated, len);
            chunk.coat(p[at], len);
            for c in 0..nc {
                let value = &mut chunk.value[c];
                for i in 0..len {
                    value[i] += chunk.g1[i];
                }
            }
            if let Some(jac) = jac {
                for i in 0..len {
                    for c in 0..nc {
                        if chunk.above[i] {
                            let r = row(c, i);
                            jac[r + at] = chunk.g2[i];
                            jac[r + at + 1] = chunk.ga[i];
                        }
                    }
                }
            }
        }
        for c in 0..nc {
            for i in 0..len {
                out[c * n + start + i] = if chunk.above[i] {
                    chunk.value[c][i]
                } else {
                    0.0
                };
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use brdf_core::{DirPairs, Parametric};
    use nalgebra::Vector3;

    use super::*;
    use crate::coloured_lobes::ColouredLobes;

    /// Pairs over the whole sphere of both directions (below the horizon
    /// too), more than a chunk of them.
    fn pairs(state: &mut u64) -> DirPairs {
        let mut uniform = || {
            *state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (*state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut pairs = DirPairs::with_capacity(300);
        for _ in 0..300 {
            let mut dir = || {
                let z = 2.0 * uniform() - 0.4;
                let z = z.clamp(-1.0, 1.0);
                let r = (1.0 - z * z).sqrt();
                let phi = std::f64::consts::TAU * uniform();
                Vector3::new(r * phi.cos(), r * phi.sin(), z)
            };
            let (l, v) = (dir(), dir());
            pairs.push(&l, &v);
        }
        pairs
    }

    /// The batch (values alone, and values with derivatives) gives the
    /// per-pair kernel's values and derivatives to the bit, for every
    /// Fresnel law, both maskings, with and without the coat and the
    /// compensation, one and three channels, at random points of the box.
    #[test]
    fn batch_gives_the_bits_of_the_per_pair_kernel() {
        use LobeFresnel::{Conductor, F82Tint, None as Plain};
        let mut state = 0xc0_10de_u64;
        let all = pairs(&mut state);
        let n = all.len();
        let laws: [&[LobeFresnel]; 3] = [&[Plain], &[F82Tint, Plain], &[Conductor, Plain, F82Tint]];
        for masking in [Masking::Separable, Masking::HeightCorrelated] {
            for fresnels in laws {
                for (coat, compensated) in [(false, false), (true, false), (true, true)] {
                    for nc in [1, 3] {
                        let mut m = ColouredLobes::custom("test", masking, fresnels, coat, nc)
                            .expect("a valid layout");
                        if compensated {
                            m = m.compensated();
                        }
                        let np = m.n_params();
                        let p: Vec<f64> = m
                            .param_specs()
                            .iter()
                            .map(|s| {
                                state = state
                                    .wrapping_mul(6_364_136_223_846_793_005)
                                    .wrapping_add(1_442_695_040_888_963_407);
                                let u = (state >> 11) as f64 / (1u64 << 53) as f64;
                                s.lower + (s.upper - s.lower) * u
                            })
                            .collect();
                        let (mut out, mut jac) = (vec![0.0; nc * n], vec![f64::NAN; nc * n * np]);
                        m.eval_grad_batch_at(&p, &all, &mut out, &mut jac);
                        let mut values = vec![f64::NAN; nc * n];
                        m.eval_batch_at(&p, &all, &mut values);
                        let (mut f, mut g, mut v1) =
                            (vec![0.0; nc], vec![0.0; nc * np], vec![0.0; nc]);
                        for j in 0..n {
                            m.eval_grad_at(&p, &all.l(j), &all.v(j), &mut f, &mut g);
                            m.eval_at(&p, &all.l(j), &all.v(j), &mut v1);
                            for c in 0..nc {
                                let i = c * n + j;
                                assert_eq!(
                                    out[i].to_bits(),
                                    f[c].to_bits(),
                                    "{fresnels:?} pair {j}"
                                );
                                assert_eq!(values[i].to_bits(), v1[c].to_bits(), "value only");
                                for k in 0..np {
                                    let (a, b) = (jac[i * np + k], g[c * np + k]);
                                    assert_eq!(
                                        a.to_bits(),
                                        b.to_bits(),
                                        "{fresnels:?} d/dp{k} pair {j}"
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
    }
}
