//! The batch kernel of the core [`super::GltfPbr`] model with hand-written
//! derivatives (the dual formula stays the single-point reference).
//!
//! With the core model's constants (`ior = 1.5`, `specular = 1`,
//! `specular_color = 1`, no coat) `F_d = f0 + (1 - f0) w` is the same on
//! every channel and free of parameters, so per sample only the GGX lobe
//! `S(alpha)` and its width derivative are evaluated, and
//! `f_c = (1 - m) (F_d S + (1 - F_d) C_c / pi) + m S (C_c + (1 - C_c) w)`
//! is differentiated in closed form: `C_c` touches only channel `c`.

use std::f64::consts::FRAC_1_PI;

use brdf_core::DirPairs;

use crate::ggx::Masking;
use crate::ggx::chunk::{CHUNK, LobeChunk};
use crate::principled::schlick_weight;

/// Values `out[c * n + j]` and, with `jac`, the Jacobian
/// `jac[(c * n + j) * (nc + 2) + k]` of the core glTF model at `p`
/// (`base_color` per channel, `metallic`, `roughness`); 0 below the horizon.
pub(crate) fn batch(
    p: &[f64],
    nc: usize,
    pairs: &DirPairs,
    out: &mut [f64],
    jac: Option<&mut [f64]>,
) {
    let (n, np) = (pairs.len(), nc + 2);
    let (m, rough) = (p[nc], p[nc + 1]);
    let alpha = rough * rough;
    // As the dual formula: ((ior - 1)/(ior + 1))^2 at ior = 1.5, clamped to 1.
    let r: f64 = (1.5 - 1.0) / (1.5 + 1.0);
    let f0 = (r * r).min(1.0);
    pulp::Arch::new().dispatch(Core {
        p,
        nc,
        pairs,
        out,
        jac,
        consts: (n, np, m, rough, alpha, f0),
    });
}

/// The loops of [`batch`], inlined into `pulp`'s target-feature function
/// (the widest instruction set of the machine) so that the lobe's chunk
/// vectorises.
struct Core<'a> {
    p: &'a [f64],
    nc: usize,
    pairs: &'a DirPairs,
    out: &'a mut [f64],
    jac: Option<&'a mut [f64]>,
    /// `n`, `np`, metallic, roughness, `alpha`, `f0`.
    consts: (usize, usize, f64, f64, f64, f64),
}

impl pulp::WithSimd for Core<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let Core {
            p,
            nc,
            pairs,
            out,
            mut jac,
            consts: (n, np, m, rough, alpha, f0),
        } = self;
        // The lobe for a chunk of pairs at a time (vectorised), then the
        // channels pair by pair.
        let mut lobe = LobeChunk::new();
        let mut start = 0;
        while start < n {
            let len = CHUNK.min(n - start);
            lobe.fill(pairs, (start, len), alpha, Masking::HeightCorrelated);
            for i in 0..len {
                let j = start + i;
                if !lobe.above[i] {
                    zero_pair(out, jac.as_deref_mut(), (j, n, nc, np));
                    continue;
                }
                let w = schlick_weight(lobe.vh[i]);
                let fd = f0 + (1.0 - f0) * w;
                let s = lobe.s[i];
                // d S / d roughness through alpha = roughness^2 (both widths).
                let ds = lobe.ds[i] * 2.0 * rough;
                for c in 0..nc {
                    let b = p[c];
                    let dielectric = fd * s + (1.0 - fd) * b * FRAC_1_PI;
                    let metal_f = b + (1.0 - b) * w;
                    let k = c * n + j;
                    out[k] = (1.0 - m) * dielectric + m * s * metal_f;
                    let Some(jac) = jac.as_deref_mut() else {
                        continue;
                    };
                    let row = &mut jac[k * np..(k + 1) * np];
                    row[..nc].fill(0.0);
                    row[c] = (1.0 - m) * (1.0 - fd) * FRAC_1_PI + m * s * (1.0 - w);
                    row[nc] = s * metal_f - dielectric;
                    row[nc + 1] = ((1.0 - m) * fd + m * metal_f) * ds;
                }
            }
            start += len;
        }
    }
}

/// Pair `j` of `n` (below the horizon) as 0 with zero derivatives on
/// every channel of `nc`, `np` parameters a row.
pub(super) fn zero_pair(
    out: &mut [f64],
    jac: Option<&mut [f64]>,
    (j, n, nc, np): (usize, usize, usize, usize),
) {
    for c in 0..nc {
        out[c * n + j] = 0.0;
    }
    if let Some(jac) = jac {
        for c in 0..nc {
            jac[(c * n + j) * np..(c * n + j + 1) * np].fill(0.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::GltfPbr;
    use crate::principled::kernel::tests::{
        assert_batch_matches_duals, assert_chunks_give_the_bits_of_single_pairs,
    };

    #[test]
    fn batch_kernel_matches_the_dual_formula() {
        let colours: [&[f64]; 3] = [&[0.8], &[0.2, 0.5, 0.9], &[0.0, 1.0, 0.3]];
        for base in colours {
            for s in [[0.0, 0.5], [0.4, 0.05], [1.0, 1.0], [0.7, 0.001]] {
                let p: Vec<f64> = base.iter().chain(&s).copied().collect();
                let model = GltfPbr::new(base.len(), &p).expect("parameters in the box");
                assert_batch_matches_duals(&model, &p);
                assert_chunks_give_the_bits_of_single_pairs(&model, &p);
            }
        }
    }
}
