//! The glTF material with `KHR_materials_iridescence` (Khronos, the
//! extension's README, "Iridescence BRDF" and "Implementation Notes"): the
//! `gltf-ext` material whose Fresnel terms are mixed, by `iridescence`,
//! with a thin film's reflectance as glTF approximates it, so that a thin
//! film fitted to a measurement reaches glTF viewers.
//!
//! With `S`, `w = (1 - |V.H|)^5`, `C` and `m` as in [`crate::gltf_pbr`],
//! `b0_c = min(((ior - 1)/(ior + 1))^2 specular_color_c, 1)`,
//! `fr_c = b0_c + (1 - b0_c) w`, `I(f0)` the film's reflectance over a base
//! of normal reflectance `f0` (below) at `cos theta_1 = V.H`:
//!
//! `a_c = (1 - t) specular fr_c + t I(specular b0)_c`, `t = iridescence`,
//! `dielectric_c = (1 - max_k a_k) C_c / pi + a_c S`,
//! `metal_c = S ((1 - t) (C_c + (1 - C_c) w) + t I(C)_c)`,
//! `material = (1 - m) dielectric + m metal`, and the clear coat as
//! `gltf-ext`'s (the extension ignores the interface between coat and film).
//!
//! The film's reflectance `I` is the extension's: Schlick reflectances at
//! both interfaces (`R12` from the film index `n`, `R23` at the refracted
//! angle from the base index `(1 + sqrt f0)/(1 - sqrt f0)`, `f0 + 1e-4`),
//! phases 0 or `pi` by which index is larger, and Belcour & Barla's
//! Fourier-domain sum of the DC term and two orders with Gaussian fits of
//! the colour-matching functions, taken to linear Rec. 709 and floored at
//! 0. One channel reads the film's luminance (Rec. 709 weights).
//!
//! | parameter | meaning | box | default | linear |
//! | --- | --- | --- | --- | --- |
//! | `gltf-ext`'s | | | | |
//! | `iridescence` | `iridescenceFactor` | `[0, 1]` | 1 | no |
//! | `iridescence_ior` | `iridescenceIor` | `[1, 3]` | 1.3 | no |
//! | `iridescence_thickness` | `iridescenceThicknessMaximum`, nm | `[0, 1500]` | 400 | no |
//!
//! Without a thickness texture glTF's film is `iridescenceThicknessMaximum`
//! thick everywhere. The extension leaves the angle at which `I` is taken
//! to the implementation; this model takes `V.H`, the angle of the core
//! material's Fresnel that `I` is mixed with (Khronos' sample viewer takes
//! `N.V` per pixel). Not reciprocal with a clear coat (as `gltf-ext`).
//!
//! A single pair evaluates the film exactly. A batch (a fit's residuals, a
//! render) reads both films from a Catmull-Rom table over `V.H` of
//! [`INTERVALS`] steps, built once per parameter vector with the films'
//! exact derivatives at its nodes: within 3e-5 of the exact value on the
//! test pairs (`tests/models/gltf_iridescence.rs`), its Jacobian the derivative
//! of the interpolant, and a fit's time no longer spent evaluating the
//! film at every sample.

use std::f64::consts::{FRAC_1_PI, PI};

use brdf_core::{DirPairs, ParamSpec, Parametric, SampleSet};
use nalgebra::Vector3;

use super::GltfExtFormula;
use crate::dual::Dual;
use crate::dual_model::{DualFormula, DualModel, MAX_CHANNELS};
use crate::ggx::Masking;
use crate::principled::{ggx_dual, schlick_weight};

/// Thickest film the box allows, in nm (as the thin-film models').
pub const THICKNESS_MAX: f64 = 1500.0;

/// `XYZ_TO_REC709` of the extension, row by row.
const XYZ_TO_REC709: [[f64; 3]; 3] = [
    [3.2404542, -1.5371385, -0.4985314],
    [-0.9692660, 1.8760108, 0.0415560],
    [0.0556434, -0.2040259, 1.0572252],
];

fn cos<const N: usize>(x: Dual<N>) -> Dual<N> {
    x.chain(x.v.cos(), -x.v.sin())
}

fn exp<const N: usize>(x: Dual<N>) -> Dual<N> {
    let e = x.v.exp();
    x.chain(e, e)
}

/// Schlick's `f0 + (1 - f0)(1 - c)^5`.
fn schlick<const N: usize>(f0: Dual<N>, c: Dual<N>) -> Dual<N> {
    let m = (c * -1.0 + 1.0).max_c(0.0);
    let m2 = m * m;
    f0 + (f0 * -1.0 + 1.0) * (m2 * m2 * m)
}

/// The extension's `evalSensitivity`: linear Rec. 709 response at optical
/// path difference `opd` (nm) with per-channel phase shifts.
fn sensitivity<const N: usize>(opd: Dual<N>, shift: [f64; 3]) -> [Dual<N>; 3] {
    const VAL: [f64; 3] = [5.4856e-13, 4.4201e-13, 5.2481e-13];
    const POS: [f64; 3] = [1.6810e+06, 1.7953e+06, 2.2084e+06];
    const VAR: [f64; 3] = [4.3278e+09, 9.3046e+09, 6.6121e+09];
    let phase = opd * (2.0 * PI * 1e-9);
    let gauss = |val: f64, pos: f64, var: f64, s: f64| {
        cos(phase * pos + s) * exp(phase.sq() * -var) * (val * (2.0 * PI * var).sqrt())
    };
    let mut xyz = [Dual::c(0.0); 3];
    for k in 0..3 {
        xyz[k] = gauss(VAL[k], POS[k], VAR[k], shift[k]);
    }
    xyz[0] = xyz[0] + gauss(9.7470e-14, 2.2399e+06, 4.5282e+09, shift[0]);
    let xyz = xyz.map(|x| x / 1.0685e-7);
    XYZ_TO_REC709.map(|r| xyz[0] * r[0] + xyz[1] * r[1] + xyz[2] * r[2])
}

/// The extension's `iridescent_fresnel` (outside index 1) over a base of
/// normal reflectance `f0` (per Rec. 709 channel) at `cos1`.
fn film<const N: usize>(n: Dual<N>, d: Dual<N>, f0: [Dual<N>; 3], cos1: f64) -> [Dual<N>; 3] {
    let one = Dual::c(1.0);
    let r0 = ((n - 1.0) / (n + 1.0)).sq();
    let r12 = schlick(r0, Dual::c(cos1));
    let t121 = one - r12;
    let cos2_sq = one - (one / n).sq() * (1.0 - cos1 * cos1);
    if cos2_sq.v < 0.0 {
        return [one; 3];
    }
    let cos2 = cos2_sq.sqrt();
    // phi21 = pi - phi12, phi12 = 0 for a film denser than the outside.
    let phi21 = if n.v < 1.0 { 0.0 } else { PI };
    let mut r23 = [Dual::c(0.0); 3];
    let mut shift = [0.0; 3];
    for k in 0..3 {
        let s = (f0[k] + 1e-4).sqrt();
        let base = (one + s) / (one - s);
        r23[k] = schlick(((base - n) / (base + n)).sq(), cos2);
        shift[k] = phi21 + if base.v < n.v { PI } else { 0.0 };
    }
    let opd = n * d * cos2 * 2.0;
    let s1 = sensitivity(opd, shift);
    let s2 = sensitivity(opd * 2.0, shift.map(|x| 2.0 * x));
    let mut out = [Dual::c(0.0); 3];
    for k in 0..3 {
        let mut r123 = r12 * r23[k];
        r123 = if r123.v < 1e-5 {
            Dual::c(1e-5)
        } else if r123.v > 0.9999 {
            Dual::c(0.9999)
        } else {
            r123
        };
        let r = r123.sqrt();
        let rs = t121.sq() * r23[k] / (one - r123);
        let c1 = (rs - t121) * r;
        let c2 = c1 * r;
        out[k] = (r12 + rs + c1 * s1[k] * 2.0 + c2 * s2[k] * 2.0).max_c(0.0);
    }
    out
}

/// The film's reflectance in `nc` channels: Rec. 709 for three, the
/// luminance for one (its base reflectance repeated).
fn film_channels<const N: usize>(
    n: Dual<N>,
    d: Dual<N>,
    f0: &[Dual<N>],
    nc: usize,
    cos1: f64,
    out: &mut [Dual<N>],
) {
    if nc == 3 {
        out[..3].copy_from_slice(&film(n, d, [f0[0], f0[1], f0[2]], cos1));
    } else {
        let rgb = film(n, d, [f0[0]; 3], cos1);
        out[0] = rgb[0] * 0.2126 + rgb[1] * 0.7152 + rgb[2] * 0.0722;
    }
}

/// Derivative slots of the film's own duals: the film index, the
/// thickness and three base reflectances.
const FILM_VARS: usize = 5;

/// [`film_channels`] with the derivatives in the model's parameters taken
/// through the film's five inputs: the film is evaluated over duals of
/// [`FILM_VARS`] slots (a third of the model's), its partials then chained
/// into each input's derivatives, which is what dominates a fit's time.
fn film_chained<const N: usize>(
    n: Dual<N>,
    d: Dual<N>,
    f0: &[Dual<N>],
    nc: usize,
    cos1: f64,
    out: &mut [Dual<N>],
) {
    if N == 0 {
        film_channels(n, d, f0, nc, cos1, out);
        return;
    }
    let var = |x: Dual<N>, i: usize| Dual::<FILM_VARS>::var(x.v, i, FILM_VARS);
    let mut f0_local = [Dual::<FILM_VARS>::c(0.0); 3];
    for (k, f) in f0.iter().take(nc).enumerate() {
        f0_local[k] = var(*f, 2 + k);
    }
    let mut local = [Dual::<FILM_VARS>::c(0.0); 3];
    film_channels(var(n, 0), var(d, 1), &f0_local[..nc], nc, cos1, &mut local);
    for c in 0..nc {
        let o = local[c];
        let mut r = Dual::c(o.v) + (n - n.v) * o.d[0] + (d - d.v) * o.d[1];
        for (k, f) in f0.iter().take(nc).enumerate() {
            r = r + (*f - f.v) * o.d[2 + k];
        }
        out[c] = r;
    }
}

/// The glTF material with `KHR_materials_iridescence`.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfIridescenceFormula;

impl DualFormula for GltfIridescenceFormula {
    const NAME: &'static str = "gltf-iridescence";

    fn specs(nc: usize) -> Vec<ParamSpec> {
        let mut s = GltfExtFormula::specs(nc);
        s.extend([
            ParamSpec::new(
                "iridescence",
                "iridescenceFactor (KHR_materials_iridescence)",
                0.0,
                1.0,
                1.0,
                false,
            ),
            ParamSpec::new("iridescence_ior", "iridescenceIor", 1.0, 3.0, 1.3, false),
            ParamSpec::new(
                "iridescence_thickness",
                "iridescenceThicknessMaximum, nm",
                0.0,
                THICKNESS_MAX,
                400.0,
                false,
            ),
        ]);
        s
    }

    fn eval<const N: usize>(
        p: &[Dual<N>],
        nc: usize,
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [Dual<N>],
    ) {
        let inputs = FilmInputs::new(p, nc);
        let mu = v.dot(&(l + v).normalize()).abs();
        let (film_d, film_m) = inputs.films(p, nc, mu);
        shade(p, nc, l, v, &inputs, (&film_d, &film_m), out);
    }

    fn batch(
        p: &[f64],
        nc: usize,
        pairs: &DirPairs,
        out: &mut [f64],
        jac: Option<&mut [f64]>,
    ) -> bool {
        match jac {
            None => batch_with::<0>(p, nc, pairs, out, None),
            Some(j) if p.len() <= 16 => batch_with::<16>(p, nc, pairs, out, Some(j)),
            Some(j) => batch_with::<{ crate::dual::MAX_DERIV }>(p, nc, pairs, out, Some(j)),
        }
        true
    }

    fn reciprocal() -> bool {
        false
    }
}

/// What the film needs of the parameters: its index and thickness and the
/// dielectric's base reflectance per channel (`specular b0`), with `b0`
/// itself (the core Fresnel's).
struct FilmInputs<const N: usize> {
    n: Dual<N>,
    d: Dual<N>,
    b0: [Dual<N>; MAX_CHANNELS],
    sb0: [Dual<N>; MAX_CHANNELS],
}

impl<const N: usize> FilmInputs<N> {
    fn new(p: &[Dual<N>], nc: usize) -> Self {
        let e = &p[nc + 2..];
        let (ior, specular, sc) = (e[0], e[1], &e[2..2 + nc]);
        let f0_ior = ((ior - 1.0) / (ior + 1.0)).sq();
        let zero = Dual::c(0.0);
        let (mut b0, mut sb0) = ([zero; MAX_CHANNELS], [zero; MAX_CHANNELS]);
        for c in 0..nc {
            b0[c] = (f0_ior * sc[c]).min_c(1.0);
            sb0[c] = b0[c] * specular;
        }
        FilmInputs {
            n: e[5 + nc],
            d: e[6 + nc],
            b0,
            sb0,
        }
    }

    /// The films over the dielectric's base and over the metal's (the base
    /// colour, `p[..nc]`) at `mu = V.H`, exactly.
    fn films(&self, p: &[Dual<N>], nc: usize, mu: f64) -> ([Dual<N>; 3], [Dual<N>; 3]) {
        let zero = Dual::c(0.0);
        let (mut fd, mut fm) = ([zero; 3], [zero; 3]);
        film_chained(self.n, self.d, &self.sb0[..nc], nc, mu, &mut fd);
        film_chained(self.n, self.d, &p[..nc], nc, mu, &mut fm);
        (fd, fm)
    }
}

/// The material at one pair given the film's reflectance over the
/// dielectric's and over the metal's base (`films`, per channel).
fn shade<const N: usize>(
    p: &[Dual<N>],
    nc: usize,
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    inputs: &FilmInputs<N>,
    (film_d, film_m): (&[Dual<N>; 3], &[Dual<N>; 3]),
    out: &mut [Dual<N>],
) {
    let base = &p[..nc];
    let (metallic, rough) = (p[nc], p[nc + 1]);
    let e = &p[nc + 2..];
    let specular = e[1];
    let (cc, cc_rough, t) = (e[2 + nc], e[3 + nc], e[4 + nc]);
    let h = (l + v).normalize();
    let w = schlick_weight(v.dot(&h).abs());
    let alpha = rough.sq();
    let spec = ggx_dual(l, v, alpha, alpha, Masking::HeightCorrelated);
    let zero = Dual::c(0.0);
    let mut a = [zero; MAX_CHANNELS];
    let mut amax = Dual::c(f64::NEG_INFINITY);
    for c in 0..nc {
        let b0 = inputs.b0[c];
        let fr = b0 + (b0 * -1.0 + 1.0) * w;
        a[c] = t.lerp(specular * fr, film_d[c]);
        amax = amax.max(a[c]);
    }
    let a_coat = cc_rough.sq();
    // The viewer's cosine: the first direction (renderers' order).
    let fc = cc * (0.04 + 0.96 * schlick_weight(l.z));
    let coat = ggx_dual(l, v, a_coat, a_coat, Masking::HeightCorrelated);
    for c in 0..nc {
        let dielectric = (1.0 - amax) * base[c] * FRAC_1_PI + a[c] * spec;
        let conductor = base[c] + (1.0 - base[c]) * w;
        let metal = spec * t.lerp(conductor, film_m[c]);
        let material = (1.0 - metallic) * dielectric + metallic * metal;
        out[c] = (1.0 - fc) * material + fc * coat;
    }
}

/// Steps of `V.H` in a batch's film table.
pub const INTERVALS: usize = 256;

/// The two films (over the dielectric's and the metal's base) at the
/// nodes `i / INTERVALS` of `V.H`, for one parameter vector.
struct FilmTable<const N: usize> {
    nodes: Vec<([Dual<N>; 3], [Dual<N>; 3])>,
}

impl<const N: usize> FilmTable<N> {
    fn new(p: &[Dual<N>], nc: usize, inputs: &FilmInputs<N>) -> Self {
        let nodes = (0..=INTERVALS)
            .map(|i| inputs.films(p, nc, i as f64 / INTERVALS as f64))
            .collect();
        FilmTable { nodes }
    }

    /// Node `i` for `i` in `-1..=INTERVALS + 1`, the ends extended by the
    /// quadratic through the three nearest nodes.
    fn node(&self, i: isize, nc: usize) -> ([Dual<N>; 3], [Dual<N>; 3]) {
        let n = INTERVALS as isize;
        let (a, b, c) = match i {
            -1 => (0, 1, 2),
            _ if i > n => (INTERVALS, INTERVALS - 1, INTERVALS - 2),
            _ => return self.nodes[i as usize],
        };
        let (a, b, c) = (&self.nodes[a], &self.nodes[b], &self.nodes[c]);
        let mut out = a.to_owned();
        for k in 0..nc {
            out.0[k] = a.0[k] * 3.0 - b.0[k] * 3.0 + c.0[k];
            out.1[k] = a.1[k] * 3.0 - b.1[k] * 3.0 + c.1[k];
        }
        out
    }

    /// The Catmull-Rom interpolant of both films at `mu`, floored at 0 as
    /// the film itself.
    fn at(&self, mu: f64, nc: usize) -> ([Dual<N>; 3], [Dual<N>; 3]) {
        let x = mu.clamp(0.0, 1.0) * INTERVALS as f64;
        let i = (x as usize).min(INTERVALS - 1);
        let w = crate::thin_film::table::catmull_rom(x - i as f64);
        let i = i as isize;
        let nodes = [
            self.node(i - 1, nc),
            self.node(i, nc),
            self.node(i + 1, nc),
            self.node(i + 2, nc),
        ];
        let zero = Dual::c(0.0);
        let (mut fd, mut fm) = ([zero; 3], [zero; 3]);
        for c in 0..nc {
            for (k, node) in nodes.iter().enumerate() {
                fd[c] = fd[c] + node.0[c] * w[k];
                fm[c] = fm[c] + node.1[c] * w[k];
            }
            fd[c] = fd[c].max_c(0.0);
            fm[c] = fm[c].max_c(0.0);
        }
        (fd, fm)
    }
}

/// A batch (fits, renders): the films read from a [`FilmTable`] built once
/// for the parameters, the rest of the formula per pair, over duals of `N`
/// derivative slots (0: values only).
fn batch_with<const N: usize>(
    p: &[f64],
    nc: usize,
    pairs: &DirPairs,
    out: &mut [f64],
    mut jac: Option<&mut [f64]>,
) {
    let np = p.len();
    let mut q = [Dual::<N>::c(0.0); crate::dual::MAX_DERIV];
    crate::dual::seed(p, N > 0, &mut q[..np]);
    let q = &q[..np];
    let inputs = FilmInputs::new(q, nc);
    let table = FilmTable::new(q, nc, &inputs);
    let n = pairs.len();
    let mut o = [Dual::<N>::c(0.0); MAX_CHANNELS];
    for j in 0..n {
        let (l, v) = (pairs.l(j), pairs.v(j));
        let above = l.z > 0.0 && v.z > 0.0;
        if above {
            let mu = v.dot(&(l + v).normalize()).abs();
            let films = table.at(mu, nc);
            shade(q, nc, &l, &v, &inputs, (&films.0, &films.1), &mut o);
        }
        for c in 0..nc {
            out[c * n + j] = if above { o[c].v } else { 0.0 };
            if let Some(jac) = jac.as_deref_mut() {
                let row = &mut jac[(c * n + j) * np..(c * n + j + 1) * np];
                row.fill(0.0);
                if above {
                    let k = o[c].n.min(np).min(N);
                    row[..k].copy_from_slice(&o[c].d[..k]);
                }
            }
        }
    }
}

/// The glTF material with `KHR_materials_iridescence` as a model.
pub type GltfIridescence = DualModel<GltfIridescenceFormula>;

/// Samples the start screen reads at most (every k-th of the data).
const SCREEN_SAMPLES: usize = 2000;
/// Starts returned by [`screened_starts`].
const STARTS: usize = 4;

/// Fit starts for the thickness, whose fringes (about 150 nm apart) are
/// each a local optimum: the model's defaults with the film at every
/// 50 nm from 100 to 1000 nm and indices 1.3, 1.6 and 2.0, screened by the
/// `cos_i`-weighted squared error on at most 2000 samples;
/// the best four, at least 100 nm apart at one index.
pub fn screened_starts(model: &dyn Parametric, data: &SampleSet) -> Vec<Vec<f64>> {
    let (nc, np) = (model.channels(), model.n_params());
    if data.channels() != nc || data.is_empty() || np < 3 {
        return Vec::new();
    }
    let every = data.len().div_ceil(SCREEN_SAMPLES).max(1);
    let all = data.pairs();
    let mut pairs = DirPairs::with_capacity(data.len() / every + 1);
    let mut rows = Vec::new();
    for j in (0..data.len()).step_by(every) {
        pairs.push(&all.l(j), &all.v(j));
        rows.push(j);
    }
    let n = pairs.len();
    let mut f = vec![0.0; nc * n];
    let mut scored = Vec::new();
    for ior in [1.3, 1.6, 2.0] {
        for k in 2..=20 {
            let mut p = model.params().to_vec();
            p[np - 2] = ior;
            p[np - 1] = 50.0 * k as f64;
            model.eval_batch_at(&p, &pairs, &mut f);
            let mut cost = 0.0;
            for (i, &j) in rows.iter().enumerate() {
                let w = all.l(j).z.max(0.0);
                for c in 0..nc {
                    let r = f[c * n + i] - data.channel(c)[j];
                    cost += w * r * r;
                }
            }
            scored.push((cost, p));
        }
    }
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut chosen: Vec<Vec<f64>> = Vec::with_capacity(STARTS);
    for (cost, p) in scored {
        let near = chosen
            .iter()
            .any(|c| c[np - 2] == p[np - 2] && (c[np - 1] - p[np - 1]).abs() < 100.0);
        if cost.is_finite() && !near {
            chosen.push(p);
        }
        if chosen.len() == STARTS {
            break;
        }
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;

    fn film_at(n: f64, d: f64, f0: f64, cos1: f64) -> [f64; 3] {
        film::<0>(Dual::c(n), Dual::c(d), [Dual::c(f0); 3], cos1).map(|x| x.v)
    }

    #[test]
    fn a_film_of_no_thickness_stays_in_range() {
        // At d = 0 the sensitivities are evaluated at phase 0 with shifts 0
        // or pi: the value is finite, in [0, 1], and the same in all
        // channels up to the fits' imbalance.
        let f = film_at(1.5, 0.0, 0.04, 0.8);
        assert!(f.iter().all(|x| (0.0..=1.0).contains(x)), "{f:?}");
    }

    #[test]
    fn colour_turns_with_thickness_and_fades_at_large_thickness() {
        let hue = |c: [f64; 3]| (c[0] - c[2]) / (c[0] + c[1] + c[2]);
        let a = film_at(1.6, 250.0, 0.04, 1.0);
        let b = film_at(1.6, 350.0, 0.04, 1.0);
        assert!((hue(a) - hue(b)).abs() > 0.05, "{a:?} {b:?}");
        // Thick films average out: the colour tends to grey.
        let c = film_at(1.6, 1500.0, 0.04, 1.0);
        assert!(hue(c).abs() < hue(a).abs().max(hue(b).abs()), "{c:?}");
    }

    #[test]
    fn no_iridescence_is_the_gltf_ext_material() {
        // iridescence = 0: the extension leaves gltf-ext's BRDF.
        let mut p = vec![0.3, 0.2, 0.1, 0.2, 0.4, 1.45, 0.8, 1.0, 0.9, 0.7, 0.3, 0.2];
        let ext = crate::GltfPbrExt::new(3, &p).unwrap();
        p.extend([0.0, 1.7, 300.0]);
        let iri = GltfIridescence::new(3, &p).unwrap();
        let l = Vector3::new(0.3, 0.1, 0.9).normalize();
        let v = Vector3::new(-0.4, 0.2, 0.8).normalize();
        let (mut a, mut b) = ([0.0; 3], [0.0; 3]);
        use brdf_core::Brdf;
        ext.eval(&l, &v, &mut a);
        iri.eval(&l, &v, &mut b);
        for c in 0..3 {
            assert!((a[c] - b[c]).abs() <= 1e-14 * a[c], "{a:?} {b:?}");
        }
    }
}
