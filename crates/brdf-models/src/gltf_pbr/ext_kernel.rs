//! The batch kernel of [`super::GltfPbrExt`] (glTF with the ior, specular
//! and clear-coat extensions) with hand-written derivatives; the dual
//! formula stays the single-point reference. Per sample the two GGX lobes
//! (base and coat) are evaluated once with their width derivatives, and
//! the chain rule runs through the pieces of the formula:
//!
//! - `f0_c = min(r^2 s_c, 1) k` with `r = (ior - 1)/(ior + 1)`, `s_c` the
//!   specular colour and `k` the specular factor (the clamp's side carries
//!   the derivatives, as the dual `min_c`);
//! - `F_c = f0_c (1 - w) + k w`, and `max_c F_c`, whose derivatives are the
//!   first channel reaching the maximum (as the dual `max`);
//! - `f_c = (1 - F_coat) ((1 - m) (F_c S + (1 - max F) C_c / pi) +
//!   m S (C_c + (1 - C_c) w)) + F_coat S_coat`, `F_coat = clearcoat (0.04 +
//!   0.96 (1 - N.V)^5)`.
//!
//! A dual evaluation carries all `2 nc + 6` derivatives through every
//! operation of the formula; here each is one product of a few factors,
//! which is what makes `gltf-ext` as cheap to fit as the core model.

use std::f64::consts::FRAC_1_PI;

use brdf_core::DirPairs;

use super::kernel::zero_pair;
use crate::dual_model::MAX_CHANNELS;
use crate::ggx::Masking;
use crate::ggx::chunk::{CHUNK, LobeChunk};
use crate::principled::schlick_weight;

/// The parameter-only factors of a batch: the specular colour's Fresnel
/// at normal incidence per channel and its derivatives.
struct Hoisted {
    metallic: f64,
    rough: f64,
    specular: f64,
    clearcoat: f64,
    cc_rough: f64,
    /// `f0_c` per channel.
    f0: [f64; MAX_CHANNELS],
    /// `d f0_c / d ior`, `d f0_c / d specular`, `d f0_c / d s_c`.
    df0: [[f64; 3]; MAX_CHANNELS],
}

impl Hoisted {
    fn new(p: &[f64], nc: usize) -> Self {
        let e = &p[nc + 2..];
        let (ior, specular) = (e[0], e[1]);
        let r = (ior - 1.0) / (ior + 1.0);
        let f0_ior = r * r;
        let df0_ior = 2.0 * r * 2.0 / ((ior + 1.0) * (ior + 1.0));
        let mut h = Hoisted {
            metallic: p[nc],
            rough: p[nc + 1],
            specular,
            clearcoat: e[2 + nc],
            cc_rough: e[3 + nc],
            f0: [0.0; MAX_CHANNELS],
            df0: [[0.0; 3]; MAX_CHANNELS],
        };
        for c in 0..nc {
            let t = f0_ior * e[2 + c];
            if t <= 1.0 {
                h.f0[c] = t * specular;
                h.df0[c] = [df0_ior * e[2 + c] * specular, t, f0_ior * specular];
            } else {
                h.f0[c] = specular;
                h.df0[c] = [0.0, 1.0, 0.0];
            }
        }
        h
    }
}

/// Values `out[c * n + j]` and, with `jac`, the Jacobian
/// `jac[(c * n + j) * (2 nc + 6) + k]` of `gltf-ext` at `p` (`base_color`
/// per channel, `metallic`, `roughness`, `ior`, `specular`,
/// `specular_color` per channel, `clearcoat`, `clearcoat_roughness`); 0
/// below the horizon.
pub(crate) fn batch(
    p: &[f64],
    nc: usize,
    pairs: &DirPairs,
    out: &mut [f64],
    jac: Option<&mut [f64]>,
) {
    let h = Hoisted::new(p, nc);
    let (alpha, cc_alpha) = (h.rough * h.rough, h.cc_rough * h.cc_rough);
    pulp::Arch::new().dispatch(Ext {
        h: &h,
        p,
        nc,
        pairs,
        out,
        jac,
        widths: (alpha, cc_alpha),
    });
}

/// The loops of [`batch`], inlined into `pulp`'s target-feature function
/// (the widest instruction set of the machine) so that the lobes' chunks
/// vectorise.
struct Ext<'a> {
    h: &'a Hoisted,
    p: &'a [f64],
    nc: usize,
    pairs: &'a DirPairs,
    out: &'a mut [f64],
    jac: Option<&'a mut [f64]>,
    /// The base and coat GGX widths.
    widths: (f64, f64),
}

impl pulp::WithSimd for Ext<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let Ext {
            h,
            p,
            nc,
            pairs,
            out,
            mut jac,
            widths: (alpha, cc_alpha),
        } = self;
        let (n, np) = (pairs.len(), 2 * nc + 6);
        // The two lobes for a chunk of pairs at a time (vectorised), then
        // the channels pair by pair.
        let (mut base, mut coat) = (LobeChunk::new(), LobeChunk::new());
        let mut start = 0;
        while start < n {
            let len = CHUNK.min(n - start);
            base.fill(pairs, (start, len), alpha, Masking::HeightCorrelated);
            coat.fill(pairs, (start, len), cc_alpha, Masking::HeightCorrelated);
            for i in 0..len {
                let j = start + i;
                if !base.above[i] {
                    zero_pair(out, jac.as_deref_mut(), (j, n, nc, np));
                    continue;
                }
                let lz = pairs.lz[j];
                let w = schlick_weight(base.vh[i]);
                let (s, ds) = (base.s[i], base.ds[i] * 2.0 * h.rough);
                let (sc, dsc) = (coat.s[i], coat.ds[i] * 2.0 * h.cc_rough);
                pair(
                    h,
                    p,
                    (s, ds, sc, dsc),
                    (w, lz),
                    (j, n, nc),
                    out,
                    jac.as_deref_mut(),
                );
            }
            start += len;
        }
    }
}

/// Pair `j`'s values and rows from its lobes (`s`, `dS/d roughness`,
/// the coat's `S` and `dS/d clearcoat_roughness`), its Schlick weight `w`
/// and the viewer's cosine `lz`.
#[inline(always)]
fn pair(
    h: &Hoisted,
    p: &[f64],
    (s, ds, sc, dsc): (f64, f64, f64, f64),
    (w, lz): (f64, f64),
    (j, n, nc): (usize, usize, usize),
    out: &mut [f64],
    mut jac: Option<&mut [f64]>,
) {
    let np = 2 * nc + 6;
    // The viewer's cosine: the first direction (renderers' order).
    let coat_w = 0.04 + 0.96 * schlick_weight(lz);
    let fc = h.clearcoat * coat_w;
    // F_c per channel and the first channel of the largest.
    let mut fd = [0.0; MAX_CHANNELS];
    let mut top = 0;
    for c in 0..nc {
        fd[c] = h.f0[c] + (h.specular - h.f0[c]) * w;
        if c > 0 && !(fd[top] >= fd[c]) {
            top = c;
        }
    }
    let fmax = fd[top];
    for c in 0..nc {
        let b = p[c];
        let dielectric = fd[c] * s + (1.0 - fmax) * b * FRAC_1_PI;
        let metal_f = b + (1.0 - b) * w;
        let material = (1.0 - h.metallic) * dielectric + h.metallic * s * metal_f;
        let i = c * n + j;
        out[i] = (1.0 - fc) * material + fc * sc;
        let Some(jac) = jac.as_deref_mut() else {
            continue;
        };
        let row = &mut jac[i * np..(i + 1) * np];
        row.fill(0.0);
        let keep = 1.0 - fc;
        let diel_w = keep * (1.0 - h.metallic);
        row[c] =
            keep * ((1.0 - h.metallic) * (1.0 - fmax) * FRAC_1_PI + h.metallic * s * (1.0 - w));
        row[nc] = keep * (s * metal_f - dielectric);
        row[nc + 1] = keep * ((1.0 - h.metallic) * fd[c] + h.metallic * metal_f) * ds;
        // F_c and max F move with ior, specular and the specular colour.
        let b_pi = b * FRAC_1_PI;
        let dfd = |k: usize, q: usize| -> f64 {
            let spec_w = if q == 1 { w } else { 0.0 };
            h.df0[k][q] * (1.0 - w) + spec_w
        };
        for q in 0..2 {
            row[nc + 2 + q] = diel_w * (dfd(c, q) * s - dfd(top, q) * b_pi);
        }
        row[nc + 4 + c] += diel_w * h.df0[c][2] * (1.0 - w) * s;
        row[nc + 4 + top] -= diel_w * h.df0[top][2] * (1.0 - w) * b_pi;
        row[2 * nc + 4] = coat_w * (sc - material);
        row[2 * nc + 5] = fc * dsc;
    }
}

#[cfg(test)]
mod tests {
    use crate::GltfPbrExt;
    use crate::principled::kernel::tests::{
        assert_batch_matches_duals, assert_chunks_give_the_bits_of_single_pairs,
    };

    /// The kernel against the dual formula: every branch of the clamp
    /// (`r^2 s_c` below and above 1: ior 3 with a specular colour of 2), a
    /// channel other than the first carrying the largest Fresnel, with and
    /// without the coat, at metallic 0, 1 and between.
    #[test]
    fn batch_kernel_matches_the_dual_formula() {
        let cases: [&[f64]; 5] = [
            // base (3), metallic, roughness, ior, specular, sc (3), clearcoat, cc roughness
            &[0.5, 0.5, 0.5, 0.0, 0.5, 1.5, 1.0, 1.0, 1.0, 1.0, 0.0, 0.1],
            &[0.2, 0.6, 0.9, 0.3, 0.2, 1.8, 0.7, 0.3, 1.6, 0.9, 0.5, 0.3],
            &[0.9, 0.1, 0.4, 1.0, 0.05, 2.5, 0.4, 2.0, 0.1, 1.2, 1.0, 0.02],
            &[0.1, 0.3, 0.7, 0.6, 1.0, 3.0, 1.0, 2.0, 2.0, 0.5, 0.2, 1.0],
            &[0.0, 1.0, 0.5, 0.0, 0.01, 1.0, 0.0, 0.0, 0.0, 0.0, 0.8, 0.5],
        ];
        for p in cases {
            let model = GltfPbrExt::new(3, p).expect("parameters in the box");
            assert_batch_matches_duals(&model, p);
            assert_chunks_give_the_bits_of_single_pairs(&model, p);
        }
        // One channel (grey).
        let p = [0.4, 0.2, 0.3, 2.0, 0.8, 1.4, 0.6, 0.4];
        let model = GltfPbrExt::new(1, &p).expect("parameters in the box");
        assert_batch_matches_duals(&model, &p);
    }
}
