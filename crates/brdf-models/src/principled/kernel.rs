//! The batch kernel of [`super::Principled`] with hand-written derivatives.
//!
//! The dual-number formula ([`super::PrincipledFormula`]) stays the
//! reference for single points; in a fit the same formula is evaluated
//! millions of times, and forward-mode duals carry every one of the
//! `nc + 9` derivatives through every operation, most of which touch only
//! one or two parameters. Here:
//!
//! - the parameter-only factors (luminance, tints, `eta(specular)`,
//!   `R0`, the GGX widths and their derivatives, the clear coat's GTR1
//!   width) are computed once per call ([`Hoisted`]), not per sample;
//! - per sample only the direction-dependent terms are evaluated (the GGX
//!   lobe and its two width derivatives, the dielectric Fresnel and its
//!   `eta` derivative, the diffuse, sheen and clear-coat factors);
//! - the value is linear in most parameters given those terms, so each
//!   derivative is a short closed form (see `channel_row`);
//! - quotients share their reciprocals (one division for the masking term
//!   and both its width derivatives, two for the dielectric Fresnel and its
//!   `eta` derivative), and the values-only path (`batch_value`, what the
//!   solvers' trial points and the renders call) forms no derivative factor
//!   at all (criterion `renderer_kernels/principled` measures both);
//! - the samples go in chunks of [`CHUNK`]: first every sample's direction
//!   terms, field by field, then each channel's values and derivatives,
//!   branch-free over the chunk, so that both loops vectorise
//!   (`pulp` compiles them for the widest instruction set of the machine).
//!   Lanes are added, multiplied, divided and square-rooted as the scalar
//!   code is, never fused, so the values are the same bits on any machine
//!   (tested against single pairs); the vector loops made the kernel about
//!   twice as fast, the default `principled` fit a third.
//!
//! The formulas are the ones of the dual formula, with the same clamps
//! (`max(1e-12, specular)`, `max(0.001, width)`, the `F_dielectric > 0`
//! mask, tint 1 where the luminance is 0) and derivative 0 on the clamped
//! side, so values and derivatives agree with it to rounding (tested).

use std::f64::consts::{FRAC_1_PI, PI};

use brdf_core::DirPairs;
use nalgebra::Vector3;

use super::schlick_weight;
use crate::dual_model::MAX_CHANNELS;

/// Number of scalar parameters after the per-channel base colour.
const NS: usize = 9;

/// Factors of the parameters alone, computed once per batch.
#[derive(Clone, Copy)]
struct Hoisted {
    nc: usize,
    base: [f64; MAX_CHANNELS],
    /// `C_c / lum` (1 where `lum = 0`).
    tint: [f64; MAX_CHANNELS],
    /// `d lum / d C_k` and `1 / lum` (0 where `lum = 0`: the tint is then
    /// the constant 1).
    dlum: [f64; MAX_CHANNELS],
    inv_lum: f64,
    /// `d tint_c / d C_k` ([`Hoisted::dtint_of`]) as `dtint[c][k]`.
    dtint: [[f64; MAX_CHANNELS]; MAX_CHANNELS],
    metallic: f64,
    spec_tint: f64,
    rough: f64,
    sheen: f64,
    sheen_tint: f64,
    cc: f64,
    /// `eta(specular)`, `1/eta^2`, `1/eta^3`, `d eta / d specular`, `R0`,
    /// `d R0 / d specular`.
    eta: f64,
    inv_eta2: f64,
    inv_eta3: f64,
    deta: f64,
    r0: f64,
    dr0: f64,
    /// GGX widths and their derivatives in roughness and anisotropy.
    ax: f64,
    ay: f64,
    dax_dr: f64,
    day_dr: f64,
    dax_da: f64,
    day_da: f64,
    /// Width factors of the GGX lobe: `ax^2`, `ay^2`, `1/ax^2`, `1/ay^2`,
    /// `1/ax`, `1/ay`, `1/(pi ax ay)`.
    ax2: f64,
    ay2: f64,
    inv_ax2: f64,
    inv_ay2: f64,
    inv_ax: f64,
    inv_ay: f64,
    inv_pi_axay: f64,
    /// Clear-coat GTR1 = `(a_c^2 - 1) / (pi ln a_c^2 q)`,
    /// `q = 1 + (a_c^2 - 1) (N.H)^2`: `a_c^2 - 1`, `(a_c^2 - 1)/(pi ln a_c^2)`,
    /// `d ln GTR1 / d a_c^2 + (N.H)^2 / q` and `d a_c^2 / d clearcoat_gloss`.
    a2m1: f64,
    gtr1_num: f64,
    dln_gtr1: f64,
    da2_dgloss: f64,
}

impl Hoisted {
    fn new(p: &[f64], nc: usize) -> Self {
        let s = &p[nc..nc + NS];
        let mut base = [0.0; MAX_CHANNELS];
        base[..nc].copy_from_slice(&p[..nc]);
        let mut dlum = [0.0; MAX_CHANNELS];
        let lum = match nc {
            1 => base[0],
            3 => base[0] * 0.212671 + base[1] * 0.715160 + base[2] * 0.072169,
            _ => base[..nc].iter().sum::<f64>() / nc as f64,
        };
        match nc {
            1 => dlum[0] = 1.0,
            3 => dlum[..3].copy_from_slice(&[0.212671, 0.715160, 0.072169]),
            _ => dlum[..nc].fill(1.0 / nc as f64),
        }
        let inv_lum = if lum > 0.0 { 1.0 / lum } else { 0.0 };
        let mut tint = [1.0; MAX_CHANNELS];
        if lum > 0.0 {
            (0..nc).for_each(|c| tint[c] = base[c] / lum);
        }
        let (spec, rough, aniso) = (s[1], s[3], s[4]);
        // As the dual formula: sqrt kept away from 0 (derivative 0 below).
        let (sc, dsc) = if spec >= 1e-12 {
            (spec, 1.0)
        } else {
            (1e-12, 0.0)
        };
        let r = (sc * 0.08).sqrt();
        let dr = dsc * 0.04 / r;
        let eta = (1.0 + r) / (1.0 - r);
        let deta = 2.0 / ((1.0 - r) * (1.0 - r)) * dr;
        let r2 = rough * rough;
        let aspect = (1.0 - aniso * 0.9).sqrt();
        let dasp = if aspect > 0.0 { -0.45 / aspect } else { 0.0 };
        let (ax, ay) = (r2 / aspect, r2 * aspect);
        let (kx, ky) = (
            f64::from(u8::from(ax >= 0.001)),
            f64::from(u8::from(ay >= 0.001)),
        );
        let a_c = 0.1 + (0.001 - 0.1) * s[8];
        let a2 = a_c * a_c;
        let mut h = Hoisted {
            nc,
            base,
            tint,
            dlum,
            inv_lum,
            dtint: [[0.0; MAX_CHANNELS]; MAX_CHANNELS],
            metallic: s[0],
            spec_tint: s[2],
            rough,
            sheen: s[5],
            sheen_tint: s[6],
            cc: s[7],
            eta,
            inv_eta2: 1.0 / (eta * eta),
            inv_eta3: 1.0 / (eta * eta * eta),
            deta,
            r0: r * r,
            dr0: 2.0 * r * dr,
            ax: ax.max(0.001),
            ay: ay.max(0.001),
            dax_dr: kx * 2.0 * rough / aspect,
            day_dr: ky * 2.0 * rough * aspect,
            dax_da: -kx * r2 * dasp / (aspect * aspect),
            day_da: ky * r2 * dasp,
            ax2: ax.max(0.001) * ax.max(0.001),
            ay2: ay.max(0.001) * ay.max(0.001),
            inv_ax2: 1.0 / (ax.max(0.001) * ax.max(0.001)),
            inv_ay2: 1.0 / (ay.max(0.001) * ay.max(0.001)),
            inv_ax: 1.0 / ax.max(0.001),
            inv_ay: 1.0 / ay.max(0.001),
            inv_pi_axay: 1.0 / (PI * ax.max(0.001) * ay.max(0.001)),
            a2m1: a2 - 1.0,
            gtr1_num: (a2 - 1.0) / (PI * a2.ln()),
            dln_gtr1: 1.0 / (a2 - 1.0) - 1.0 / (a2 * a2.ln()),
            da2_dgloss: 2.0 * a_c * (0.001 - 0.1),
        };
        for c in 0..nc {
            for k in 0..nc {
                h.dtint[c][k] = h.dtint_of(c, k);
            }
        }
        h
    }

    /// `d tint_c / d C_k`.
    fn dtint_of(&self, c: usize, k: usize) -> f64 {
        let own = if c == k { self.inv_lum } else { 0.0 };
        own - self.base[c] * self.dlum[k] * self.inv_lum * self.inv_lum
    }
}

/// The direction-dependent terms of one sample.
struct Terms {
    /// Schlick weight of `V.H`.
    w: f64,
    /// The GGX lobe (0 under the Fresnel mask) and its width derivatives.
    s: f64,
    ds_ax: f64,
    ds_ay: f64,
    /// Dielectric Fresnel and its `eta` derivative.
    fdl: f64,
    dfdl: f64,
    /// `(1 - m)`-free diffuse factor and its roughness derivative.
    dg: f64,
    ddg: f64,
    /// Clear-coat factor (without `clearcoat`) and its gloss derivative.
    k: f64,
    dk: f64,
}

/// The separable-Smith GGX lobe `D G / (4 N.L N.V)` at the hoisted widths,
/// its width derivatives, the half vector, and the clear coat's
/// `G1(L) G1(V)` at `alpha = 0.25` (as [`crate::ggx::ggx_specular`] and
/// `separable_g1`, with the divisions shared: `1 + Lambda = (1 + r)/2`,
/// `r = sqrt(1 + t)`, so `G1 = 2 / (1 + r)`, and one reciprocal of
/// `N.L N.V` gives both `1/(N.W)^2` and the lobe's `1/(4 N.L N.V)`).
struct Lobe {
    h: [f64; 3],
    value: f64,
    d_ax: f64,
    d_ay: f64,
    g_cc: f64,
}

#[inline(always)]
fn lobe<const GRAD: bool>(k: &Hoisted, l: &Vector3<f64>, v: &Vector3<f64>) -> Lobe {
    let s = l + v;
    let inv_len = 1.0 / s.norm();
    let h = [s.x * inv_len, s.y * inv_len, s.z * inv_len];
    let x2 = h[0] * h[0] * k.inv_ax2;
    let y2 = h[1] * h[1] * k.inv_ay2;
    let inv_s = 1.0 / (x2 + y2 + h[2] * h[2]);
    let d = k.inv_pi_axay * inv_s * inv_s;
    let q = 1.0 / (l.z * v.z);
    let (il2, iv2) = (q * q * v.z * v.z, q * q * l.z * l.z);
    let (lx2, ly2, vx2, vy2) = (l.x * l.x, l.y * l.y, v.x * v.x, v.y * v.y);
    let rl = (1.0 + (k.ax2 * lx2 + k.ay2 * ly2) * il2).sqrt();
    let rv = (1.0 + (k.ax2 * vx2 + k.ay2 * vy2) * iv2).sqrt();
    let (al, av) = (1.0 + rl, 1.0 + rv);
    let rcl = (1.0 + 0.0625 * (lx2 + ly2) * il2).sqrt();
    let rcv = (1.0 + 0.0625 * (vx2 + vy2) * iv2).sqrt();
    let g_cc = 4.0 / ((1.0 + rcl) * (1.0 + rcv));
    // One division for G and both G1 dLambda/dt = 2/(1 + r) * 1/(4 r):
    // `t = 1/(rl (1 + rl) rv (1 + rv))`; dt/dax = 2 ax wx^2 / wz^2.
    let t = 1.0 / (rl * al * rv * av);
    let g = 4.0 * rl * rv * t;
    let value = d * g * 0.25 * q;
    if !GRAD {
        return Lobe {
            h,
            value,
            d_ax: 0.0,
            d_ay: 0.0,
            g_cc,
        };
    }
    let (cl, cv) = (0.5 * rv * av * t, 0.5 * rl * al * t);
    let dlx = -k.inv_ax + 4.0 * x2 * k.inv_ax * inv_s;
    let dly = -k.inv_ay + 4.0 * y2 * k.inv_ay * inv_s;
    let gx = 2.0 * k.ax * (cl * lx2 * il2 + cv * vx2 * iv2);
    let gy = 2.0 * k.ay * (cl * ly2 * il2 + cv * vy2 * iv2);
    Lobe {
        h,
        value,
        d_ax: value * (dlx - gx),
        d_ay: value * (dly - gy),
        g_cc,
    }
}

/// The exact dielectric Fresnel reflectance at `cos_d` for the hoisted
/// `eta` and, with `GRAD`, its `eta` derivative (as
/// `brdf_core::fresnel::fresnel_dielectric_d_eta`, with the powers of `eta` hoisted and the
/// quotients sharing their reciprocals).
#[inline(always)]
fn fresnel<const GRAD: bool>(k: &Hoisted, cos_d: f64) -> (f64, f64) {
    let ci = cos_d.clamp(0.0, 1.0);
    let sin2 = (1.0 - ci * ci).max(0.0);
    let s2t = sin2 * k.inv_eta2;
    // Total internal reflection (`s2t >= 1`) is selected at the end rather
    // than returned early, so a chunk of samples vectorises; where it
    // does not occur the operations, and so the bits, are the same.
    let tir = s2t >= 1.0;
    let ct = (1.0 - s2t).sqrt();
    let u = k.eta * ct;
    let a = 1.0 / (ci + u);
    let rs = (ci - u) * a;
    let (n, dd) = (k.eta * ci - ct, k.eta * ci + ct);
    let b = 1.0 / dd;
    let rp = n * b;
    let value = if tir { 1.0 } else { 0.5 * (rs * rs + rp * rp) };
    if !GRAD {
        return (value, 0.0);
    }
    let dct = if ct > 0.0 {
        sin2 * k.inv_eta3 / ct
    } else {
        0.0
    };
    let du = ct + k.eta * dct;
    let drs = -2.0 * ci * du * a * a;
    let drp = ((ci - dct) * dd - n * (ci + dct)) * b * b;
    (value, if tir { 0.0 } else { rs * drs + rp * drp })
}

impl Terms {
    #[inline(always)]
    fn new<const GRAD: bool>(k: &Hoisted, l: &Vector3<f64>, v: &Vector3<f64>) -> Self {
        let g = lobe::<GRAD>(k, l, v);
        let cos_d = (v.x * g.h[0] + v.y * g.h[1] + v.z * g.h[2]).clamp(0.0, 1.0);
        let w = schlick_weight(cos_d);
        let (fdl, dfdl) = fresnel::<GRAD>(k, cos_d);
        let (s, ds_ax, ds_ay) = if fdl > 0.0 {
            (g.value, g.d_ax, g.d_ay)
        } else {
            (0.0, 0.0, 0.0)
        };
        let (wl, wv) = (schlick_weight(l.z), schlick_weight(v.z));
        let f_diff = (1.0 - 0.5 * wl) * (1.0 - 0.5 * wv);
        let c2 = 2.0 * cos_d * cos_d;
        let rr = k.rough * c2;
        let dg = FRAC_1_PI * (f_diff + rr * (wl + wv + wl * wv * (rr - 1.0)));
        let nh2 = g.h[2] * g.h[2];
        let iq = 1.0 / (1.0 + k.a2m1 * nh2);
        let gtr1 = k.gtr1_num * iq;
        let coat = 0.25 * (0.04 + 0.96 * w) * g.g_cc;
        let (ddg, dk) = if GRAD {
            let dgtr1 = gtr1 * (k.dln_gtr1 - nh2 * iq);
            (
                FRAC_1_PI * c2 * (wl + wv + wl * wv * (2.0 * rr - 1.0)),
                coat * dgtr1 * k.da2_dgloss,
            )
        } else {
            (0.0, 0.0)
        };
        Terms {
            w,
            s,
            ds_ax,
            ds_ay,
            fdl,
            dfdl,
            dg,
            ddg,
            k: coat * gtr1,
            dk,
        }
    }
}

/// Value of channel `c` and, with `row`, its derivatives (`nc + 9`, `nc`
/// the model's channels: a constant where the caller knows it, so the
/// loop over the colour derivatives unrolls).
#[inline(always)]
fn channel_row(h: &Hoisted, t: &Terms, c: usize, nc: usize, row: Option<&mut [f64]>) -> f64 {
    let (m, st, w) = (h.metallic, h.spec_tint, t.w);
    let (b, ct) = (h.base[c], h.tint[c]);
    let f0t = ct * h.r0;
    let metal_f = b + (1.0 - b) * w;
    let tint_f = f0t + (1.0 - f0t) * w;
    let f = (1.0 - m) * (1.0 - st) * t.fdl + m * metal_f + (1.0 - m) * st * tint_f;
    let c_sheen = 1.0 + h.sheen_tint * (ct - 1.0);
    let sheen_w = h.sheen * (1.0 - m) * w;
    let value = f * t.s + (1.0 - m) * t.dg * b + sheen_w * c_sheen + h.cc * t.k;
    let Some(row) = row else { return value };
    // Through the tint: R0 tint in the dielectric lobe, and the sheen tint.
    let via_tint = (1.0 - m) * st * h.r0 * (1.0 - w) * t.s + sheen_w * h.sheen_tint;
    let own = m * (1.0 - w) * t.s + (1.0 - m) * t.dg;
    for (k, r) in row[..nc].iter_mut().enumerate() {
        *r = via_tint * h.dtint[c][k] + if k == c { own } else { 0.0 };
    }
    let d = &mut row[nc..nc + NS];
    d[0] = (metal_f - (1.0 - st) * t.fdl - st * tint_f) * t.s - t.dg * b - h.sheen * w * c_sheen;
    d[1] = (1.0 - m) * ((1.0 - st) * t.dfdl * h.deta + st * ct * (1.0 - w) * h.dr0) * t.s;
    d[2] = (1.0 - m) * (tint_f - t.fdl) * t.s;
    d[3] = f * (t.ds_ax * h.dax_dr + t.ds_ay * h.day_dr) + (1.0 - m) * b * t.ddg;
    d[4] = f * (t.ds_ax * h.dax_da + t.ds_ay * h.day_da);
    d[5] = (1.0 - m) * w * c_sheen;
    d[6] = sheen_w * (ct - 1.0);
    d[7] = t.k;
    d[8] = h.cc * t.dk;
    value
}

/// Values `out[c * n + j]` and, with `jac`, the Jacobian
/// `jac[(c * n + j) * (nc + 9) + k]` of the principled model at `p` on
/// every pair; 0 (and zero derivatives) below the horizon.
pub(crate) fn batch(
    p: &[f64],
    nc: usize,
    pairs: &DirPairs,
    out: &mut [f64],
    jac: Option<&mut [f64]>,
) {
    let h = Hoisted::new(p, nc);
    pulp::Arch::new().dispatch(Kernel {
        h: &h,
        pairs,
        out,
        jac,
    });
}

/// Samples whose direction terms are computed together, field by field,
/// so that the loop over them vectorises (the terms are most of the
/// kernel's divisions and square roots).
const CHUNK: usize = 64;

/// [`Terms`] of up to [`CHUNK`] samples (structure of arrays) and whether
/// both directions are above the horizon.
struct TermChunk {
    above: [bool; CHUNK],
    w: [f64; CHUNK],
    s: [f64; CHUNK],
    ds_ax: [f64; CHUNK],
    ds_ay: [f64; CHUNK],
    fdl: [f64; CHUNK],
    dfdl: [f64; CHUNK],
    dg: [f64; CHUNK],
    ddg: [f64; CHUNK],
    k: [f64; CHUNK],
    dk: [f64; CHUNK],
}

impl TermChunk {
    fn new() -> Self {
        let z = [0.0; CHUNK];
        TermChunk {
            above: [false; CHUNK],
            w: z,
            s: z,
            ds_ax: z,
            ds_ay: z,
            fdl: z,
            dfdl: z,
            dg: z,
            ddg: z,
            k: z,
            dk: z,
        }
    }

    /// The terms of pairs `start..start + len` (`len <= CHUNK`), computed
    /// for every pair, those below the horizon too (branch-free, so the
    /// loop vectorises; their terms are never read).
    #[inline(always)]
    fn fill<const GRAD: bool>(&mut self, h: &Hoisted, pairs: &DirPairs, start: usize, len: usize) {
        let pc = pairs.chunk(start, len);
        let above = &mut self.above[..len];
        let (w, s, ds_ax, ds_ay) = (
            &mut self.w[..len],
            &mut self.s[..len],
            &mut self.ds_ax[..len],
            &mut self.ds_ay[..len],
        );
        let (fdl, dfdl, dg, ddg) = (
            &mut self.fdl[..len],
            &mut self.dfdl[..len],
            &mut self.dg[..len],
            &mut self.ddg[..len],
        );
        let (k, dk) = (&mut self.k[..len], &mut self.dk[..len]);
        // A local copy: its fields stay in registers across the stores
        // below (through a reference they are reloaded, and the loop
        // does not vectorise).
        let h = *h;
        let h = &h;
        for i in 0..len {
            let (l, v) = pc.at(i);
            let t = Terms::new::<GRAD>(h, &l, &v);
            above[i] = l.z > 0.0 && v.z > 0.0;
            w[i] = t.w;
            s[i] = t.s;
            ds_ax[i] = t.ds_ax;
            ds_ay[i] = t.ds_ay;
            fdl[i] = t.fdl;
            dfdl[i] = t.dfdl;
            dg[i] = t.dg;
            ddg[i] = t.ddg;
            k[i] = t.k;
            dk[i] = t.dk;
        }
    }

    /// The terms of sample `i` of the chunk.
    #[inline(always)]
    fn at(&self, i: usize) -> Terms {
        Terms {
            w: self.w[i],
            s: self.s[i],
            ds_ax: self.ds_ax[i],
            ds_ay: self.ds_ay[i],
            fdl: self.fdl[i],
            dfdl: self.dfdl[i],
            dg: self.dg[i],
            ddg: self.ddg[i],
            k: self.k[i],
            dk: self.dk[i],
        }
    }
}

/// The batch over chunks, inlined into `pulp`'s target-feature function
/// so that [`TermChunk::fill`] vectorises for the widest instruction set
/// of the machine. Only additions, multiplications, divisions and square
/// roots are vectorised (never fused), so every lane rounds as the scalar
/// code does: the values are the same bits on any machine (tested).
struct Kernel<'a> {
    h: &'a Hoisted,
    pairs: &'a DirPairs,
    out: &'a mut [f64],
    jac: Option<&'a mut [f64]>,
}

impl pulp::WithSimd for Kernel<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let Kernel {
            h,
            pairs,
            out,
            mut jac,
        } = self;
        let (n, nc) = (pairs.len(), h.nc);
        let mut chunk = TermChunk::new();
        let mut rows = RowChunk::new();
        let mut start = 0;
        while start < n {
            let len = CHUNK.min(n - start);
            match jac {
                None => {
                    chunk.fill::<false>(h, pairs, start, len);
                    for i in 0..len {
                        let j = start + i;
                        if chunk.above[i] {
                            let t = chunk.at(i);
                            for c in 0..nc {
                                out[c * n + j] = channel_row(h, &t, c, nc, None);
                            }
                        } else {
                            (0..nc).for_each(|c| out[c * n + j] = 0.0);
                        }
                    }
                }
                Some(ref mut jac) => {
                    chunk.fill::<true>(h, pairs, start, len);
                    match nc {
                        1 => rows.fill::<1>(h, &chunk, (start, len), n, (out, jac)),
                        3 => rows.fill::<3>(h, &chunk, (start, len), n, (out, jac)),
                        _ => grad_chunk_any(h, &chunk, (start, len), n, (out, jac)),
                    }
                }
            }
            start += len;
        }
    }
}

/// Most parameters of any channel count.
const MAX_NP: usize = MAX_CHANNELS + NS;

/// One channel's values and Jacobian rows over a chunk (structure of
/// arrays: `d[k][i]`), made once per batch and reused by every chunk.
struct RowChunk {
    value: [f64; CHUNK],
    d: [[f64; CHUNK]; MAX_NP],
}

impl RowChunk {
    fn new() -> Self {
        RowChunk {
            value: [0.0; CHUNK],
            d: [[0.0; CHUNK]; MAX_NP],
        }
    }

    /// Values and Jacobian rows of the chunk's samples `start..start +
    /// len` (of `n`) for `NC` channels: each channel's rows are computed
    /// over the chunk (so the loop vectorises), then written to their
    /// rows of `jac`.
    #[inline(always)]
    fn fill<const NC: usize>(
        &mut self,
        h: &Hoisted,
        t: &TermChunk,
        (start, len): (usize, usize),
        n: usize,
        (out, jac): (&mut [f64], &mut [f64]),
    ) {
        let np = NC + NS;
        // Never more than a chunk (said so the loops need no bounds checks).
        let len = len.min(CHUNK);
        let hc = *h;
        let (value, d) = (&mut self.value, &mut self.d);
        for c in 0..NC {
            for i in 0..len {
                let mut row = [0.0; MAX_NP];
                let v = channel_row(&hc, &t.at(i), c, NC, Some(&mut row[..np]));
                // Below the horizon the model is 0 with zero derivatives.
                let above = t.above[i];
                value[i] = if above { v } else { 0.0 };
                for k in 0..np {
                    d[k][i] = if above { row[k] } else { 0.0 };
                }
            }
            for i in 0..len {
                let r = c * n + start + i;
                out[r] = value[i];
                let row = &mut jac[r * np..(r + 1) * np];
                for k in 0..np {
                    row[k] = d[k][i];
                }
            }
        }
    }
}

/// [`RowChunk::fill`] for a channel count known only at run time.
#[inline(always)]
fn grad_chunk_any(
    h: &Hoisted,
    t: &TermChunk,
    (start, len): (usize, usize),
    n: usize,
    (out, jac): (&mut [f64], &mut [f64]),
) {
    let nc = h.nc;
    let np = nc + NS;
    for i in 0..len {
        let j = start + i;
        let terms = t.above[i].then(|| t.at(i));
        for c in 0..nc {
            let r = c * n + j;
            let row = &mut jac[r * np..(r + 1) * np];
            out[r] = match &terms {
                Some(terms) => channel_row(h, terms, c, nc, Some(row)),
                None => {
                    row.fill(0.0);
                    0.0
                }
            };
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use brdf_core::{DirPairs, Parametric};
    use nalgebra::Vector3;

    use crate::Principled;

    /// Direction pairs over the upper hemisphere (pole, grazing, mirror and
    /// retro-reflection included) and two below it.
    pub(crate) fn pairs() -> DirPairs {
        let mut pairs = DirPairs::with_capacity(400);
        let dir = |t: f64, p: f64| Vector3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
        let thetas = [0.0, 0.3, 0.8, 1.2, 1.5, std::f64::consts::FRAC_PI_2 - 1e-6];
        for &ti in &thetas {
            for &to in &thetas {
                for k in 0..6 {
                    let phi = k as f64 * 1.1;
                    pairs.push(&dir(ti, 0.4), &dir(to, 0.4 + phi));
                }
            }
        }
        pairs.push(&dir(2.0, 0.0), &dir(0.5, 1.0));
        pairs.push(&dir(0.5, 0.0), &dir(1.7, 1.0));
        pairs
    }

    /// The batch kernel against the dual formula at every pair.
    pub(crate) fn assert_batch_matches_duals(model: &dyn Parametric, p: &[f64]) {
        assert_batch_matches_duals_on(
            model,
            p,
            &pairs(),
            |f| 1e-11 * (1.0 + f.abs()),
            |f, b| 1e-10 * (1.0 + f.abs() + b.abs()),
        );
    }

    /// The batch kernel (values alone, and values with derivatives)
    /// against the dual formula at `pairs`: the value `f` within
    /// `value_tol(f)`, a derivative `b` within `deriv_tol(f, b)`; the values
    /// of both paths identical.
    fn assert_batch_matches_duals_on(
        model: &dyn Parametric,
        p: &[f64],
        pairs: &DirPairs,
        value_tol: impl Fn(f64) -> f64,
        deriv_tol: impl Fn(f64, f64) -> f64,
    ) {
        let (n, nc, np) = (pairs.len(), model.channels(), p.len());
        let mut out = vec![0.0; nc * n];
        let mut jac = vec![f64::NAN; nc * n * np];
        model.eval_grad_batch_at(p, pairs, &mut out, &mut jac);
        let mut only = vec![0.0; nc * n];
        model.eval_batch_at(p, pairs, &mut only);
        let (mut f, mut g) = (vec![0.0; nc], vec![0.0; nc * np]);
        for j in 0..n {
            model.eval_grad_at(p, &pairs.l(j), &pairs.v(j), &mut f, &mut g);
            for c in 0..nc {
                let i = c * n + j;
                assert!(
                    (out[i] - f[c]).abs() <= value_tol(f[c]),
                    "value {p:?} pair {j}: {} vs {}",
                    out[i],
                    f[c]
                );
                assert_eq!(out[i], only[i], "value without derivatives");
                for k in 0..np {
                    let (a, b) = (jac[i * np + k], g[c * np + k]);
                    assert!(
                        (a - b).abs() <= deriv_tol(f[c], b),
                        "d/dp{k} {p:?} pair {j} ch {c}: {a} vs {b}"
                    );
                }
            }
        }
    }

    /// A deterministic uniform sequence on `[0, 1)` (64-bit LCG, high bits).
    fn uniform(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    /// At random parameters in the box and random direction pairs above
    /// the horizon, the batch kernel equals the dual-number reference
    /// formula: values to 1e-12 relative, derivatives to 1e-10 of the
    /// value's and the derivative's size.
    #[test]
    fn batch_kernel_equals_the_reference_at_random_points() {
        let mut state = 0x5eed_u64;
        let dir = |u: f64, w: f64| {
            let z = 0.02 + 0.98 * u;
            let r = (1.0 - z * z).sqrt();
            let phi = 2.0 * std::f64::consts::PI * w;
            Vector3::new(r * phi.cos(), r * phi.sin(), z)
        };
        for nc in [1, 3] {
            for _ in 0..40 {
                let p: Vec<f64> = (0..nc + 9)
                    .map(|k| {
                        let u = uniform(&mut state);
                        // specular's box is open at 0
                        if k == nc + 1 {
                            1e-3 + u * (1.0 - 1e-3)
                        } else {
                            u
                        }
                    })
                    .collect();
                let model = Principled::new(nc, &p).expect("parameters in the box");
                let mut pairs = DirPairs::with_capacity(64);
                for _ in 0..64 {
                    let l = dir(uniform(&mut state), uniform(&mut state));
                    let v = dir(uniform(&mut state), uniform(&mut state));
                    pairs.push(&l, &v);
                }
                assert_batch_matches_duals_on(
                    &model,
                    &p,
                    &pairs,
                    |f| 1e-12 * f.abs(),
                    |f, b| 1e-10 * (f.abs() + b.abs()),
                );
            }
        }
    }

    #[test]
    fn batch_kernel_matches_the_dual_formula() {
        let cases: [[f64; 9]; 5] = [
            [0.0, 0.5, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0],
            [0.3, 0.7, 0.4, 0.35, 0.6, 0.5, 0.3, 0.8, 0.4],
            [1.0, 1.0, 1.0, 0.02, 0.0, 1.0, 1.0, 1.0, 1.0],
            [0.1, 1e-14, 0.9, 0.9, 1.0, 0.2, 0.7, 0.1, 0.9],
            [0.6, 0.2, 0.1, 0.1, 0.95, 0.0, 0.0, 0.5, 0.0],
        ];
        let colours: [&[f64]; 4] = [&[0.8], &[0.2, 0.5, 0.9], &[0.0, 0.0, 0.0], &[0.3, 0.0]];
        for base in colours {
            let nc = base.len();
            for s in &cases {
                let p: Vec<f64> = base.iter().chain(s).copied().collect();
                let model = Principled::new(nc, &p).expect("parameters in the box");
                assert_batch_matches_duals(&model, &p);
            }
        }
    }

    /// The batch over [`pairs`] (full chunks, where the vectorised loops
    /// run over several lanes) equals, to the bit, the batch of each pair
    /// alone (a chunk of one, the loops' scalar remainder): values alone,
    /// and values with derivatives.
    pub(crate) fn assert_chunks_give_the_bits_of_single_pairs(model: &dyn Parametric, p: &[f64]) {
        let all = pairs();
        let (n, nc, np) = (all.len(), model.channels(), p.len());
        let (mut out, mut jac) = (vec![0.0; nc * n], vec![f64::NAN; nc * n * np]);
        model.eval_grad_batch_at(p, &all, &mut out, &mut jac);
        let mut values = vec![0.0; nc * n];
        model.eval_batch_at(p, &all, &mut values);
        let (mut o1, mut j1) = (vec![0.0; nc], vec![0.0; nc * np]);
        let mut single = DirPairs::with_capacity(1);
        for j in 0..n {
            single.clear();
            single.push(&all.l(j), &all.v(j));
            model.eval_grad_batch_at(p, &single, &mut o1, &mut j1);
            for c in 0..nc {
                let i = c * n + j;
                assert_eq!(out[i].to_bits(), o1[c].to_bits(), "value, pair {j}");
                assert_eq!(values[i].to_bits(), o1[c].to_bits(), "value only");
                for k in 0..np {
                    let (a, b) = (jac[i * np + k], j1[c * np + k]);
                    assert_eq!(a.to_bits(), b.to_bits(), "d/dp{k}, pair {j}");
                }
            }
        }
    }

    /// The vectorised chunks round as scalar code does, for one, two (the
    /// path for any channel count) and three channels.
    #[test]
    fn chunks_give_the_bits_of_single_pairs() {
        let mut state = 0xb175_u64;
        for nc in [1, 2, 3] {
            for _ in 0..8 {
                let p: Vec<f64> = (0..nc + 9).map(|_| uniform(&mut state)).collect();
                let model = Principled::new(nc, &p).expect("parameters in the box");
                assert_chunks_give_the_bits_of_single_pairs(&model, &p);
            }
        }
    }
}
