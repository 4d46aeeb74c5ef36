//! An isotropic GGX lobe over a chunk of direction pairs, the part of the
//! glTF kernels with the square roots and divisions: a branch-free loop
//! (structure of arrays) that vectorises when the caller runs inside `pulp`'s dispatch
//! (its target-feature function, the widest instruction set of the
//! machine). Lanes round as [`super::ggx_specular`] does (never fused), so
//! the kernels built on it keep their bits (tested there).

use brdf_core::DirPairs;

use super::{Masking, ggx_specular_unchecked};

/// Pairs per chunk.
pub(crate) const CHUNK: usize = 64;

/// One lobe width's values over a chunk.
pub(crate) struct LobeChunk {
    /// Both directions above the horizon (the lobe is read only there).
    pub(crate) above: [bool; CHUNK],
    /// `D G / (4 N.L N.V)`.
    pub(crate) s: [f64; CHUNK],
    /// Its derivative in the width, `d/d ax + d/d ay` at `ax = ay`.
    pub(crate) ds: [f64; CHUNK],
    /// `|V.H|`, the Fresnel cosine.
    pub(crate) vh: [f64; CHUNK],
}

impl LobeChunk {
    pub(crate) fn new() -> Box<Self> {
        Box::new(LobeChunk {
            above: [false; CHUNK],
            s: [0.0; CHUNK],
            ds: [0.0; CHUNK],
            vh: [0.0; CHUNK],
        })
    }

    /// The lobe of width `alpha` at pairs `start..start + len` (`len <=`
    /// [`CHUNK`]), below the horizon too (never read there).
    #[inline(always)]
    pub(crate) fn fill(
        &mut self,
        pairs: &DirPairs,
        (start, len): (usize, usize),
        alpha: f64,
        masking: Masking,
    ) {
        let len = len.min(CHUNK);
        let pc = pairs.chunk(start, len);
        for i in 0..len {
            let (l, v) = pc.at(i);
            let g = ggx_specular_unchecked(&l, &v, alpha, alpha, masking);
            self.above[i] = l.z > 0.0 && v.z > 0.0;
            self.s[i] = g.value;
            self.ds[i] = g.d_ax + g.d_ay;
            self.vh[i] = v.dot(&g.h).abs();
        }
    }
}
