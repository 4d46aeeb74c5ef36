//! Adaptive Gauss-Kronrod quadrature and the directional albedo of any BRDF.
//!
//! The 1-D rule is the 7-point Gauss / 15-point Kronrod pair (as in QUADPACK's
//! QAG): on each interval the Kronrod sum is the estimate and
//! `|K15 - G7|` the error estimate; the interval with the largest error is
//! bisected until the summed error estimate falls below
//! `max(abs_tol, rel_tol |I|)`. The estimate is QUADPACK's scaled
//! `|K15 - G7|`. For integrands that are smooth on each initial interval it is
//! pessimistic by orders of magnitude (the Kronrod value is far more accurate
//! than the Gauss value it is compared with), which is what lets the tests use
//! it as a bound; kinks, jumps and sharp peaks must be break points
//! ([`integrate_with_breaks`], [`integrate_around_peak`]), as
//! [`directional_albedo`] does for the horizon and the mirror direction.
//!
//! The directional albedo `a(L) = int_{H^2} f(L, V) cos theta_o dV` is a nested
//! integral in `mu = cos theta_o` and `phi_o`; the error of the inner integrals
//! is integrated along with the values, so the reported error covers both
//! levels.

use nalgebra::Vector3;

use crate::trig::reflect_about_normal;
use crate::{Brdf, Frame};

const XGK: [f64; 8] = [
    0.991_455_371_120_812_639_206_854_697_526_329,
    0.949_107_912_342_758_524_526_189_684_047_851,
    0.864_864_423_359_769_072_789_712_788_640_926,
    0.741_531_185_599_394_439_863_864_773_280_788,
    0.586_087_235_467_691_130_294_144_845_693_013,
    0.405_845_151_377_397_166_906_606_412_076_961,
    0.207_784_955_007_898_467_600_689_403_773_245,
    0.0,
];
const WGK: [f64; 8] = [
    0.022_935_322_010_529_224_963_732_008_058_970,
    0.063_092_092_629_978_553_290_700_663_189_204,
    0.104_790_010_322_250_183_839_876_322_541_518,
    0.140_653_259_715_525_918_745_189_590_510_238,
    0.169_004_726_639_267_902_826_583_426_598_550,
    0.190_350_578_064_785_409_913_256_402_421_014,
    0.204_432_940_075_298_892_414_161_999_234_649,
    0.209_482_141_084_727_828_012_999_174_891_714,
];
/// Gauss weights for the nodes `XGK[1], XGK[3], XGK[5], XGK[7]`.
const WG: [f64; 4] = [
    0.129_484_966_168_869_693_270_611_432_679_082,
    0.279_705_391_489_276_667_901_467_771_423_780,
    0.381_830_050_505_118_944_950_369_775_488_975,
    0.417_959_183_673_469_387_755_102_040_816_327,
];

/// Tolerances and limits of the adaptive rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadratureOptions {
    /// Absolute tolerance on the summed error estimate.
    pub abs_tol: f64,
    /// Relative tolerance on the summed error estimate.
    pub rel_tol: f64,
    /// Most intervals kept before giving up (the result then carries its
    /// larger error estimate; it is never silently accepted).
    pub max_intervals: usize,
}

impl Default for QuadratureOptions {
    fn default() -> Self {
        QuadratureOptions {
            abs_tol: 1e-10,
            rel_tol: 1e-8,
            max_intervals: 200,
        }
    }
}

/// A vector-valued integral with its error estimate per component.
#[derive(Clone, Debug, PartialEq)]
pub struct Integral {
    /// The estimate.
    pub value: Vec<f64>,
    /// The error estimate per component.
    pub error: Vec<f64>,
    /// Integrand evaluations used.
    pub evaluations: usize,
}

fn gk15(
    f: &mut impl FnMut(f64, &mut [f64]),
    a: f64,
    b: f64,
    dim: usize,
    buf: &mut [f64],
    vals: &mut Vec<f64>,
) -> (Vec<f64>, Vec<f64>) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let mut k = vec![0.0; dim];
    let mut g = vec![0.0; dim];
    let mut kabs = vec![0.0; dim];
    vals.clear();
    for i in 0..8 {
        let nodes: &[f64] = if i == 7 { &[0.0] } else { &[-XGK[i], XGK[i]] };
        for &x in nodes {
            f(c + h * x, buf);
            for d in 0..dim {
                k[d] += WGK[i] * buf[d];
                kabs[d] += WGK[i] * buf[d].abs();
                if i % 2 == 1 {
                    g[d] += WG[i / 2] * buf[d];
                }
            }
            vals.extend_from_slice(&buf[..dim]);
        }
    }
    // QUADPACK's error scaling (Piessens et al. 1983, QK15): the raw
    // |K15 - G7| is scaled by (200 |K - G| / resasc)^1.5, which is
    // conservative when the interval is not yet resolved (e.g. a kink inside
    // it), and floored at 50 eps |K|abs for rounding.
    let mut err = vec![0.0; dim];
    for d in 0..dim {
        let mean = 0.5 * k[d];
        let mut asc = 0.0;
        let mut idx = 0;
        for i in 0..8 {
            let count = if i == 7 { 1 } else { 2 };
            for _ in 0..count {
                asc += WGK[i] * (vals[idx * dim + d] - mean).abs();
                idx += 1;
            }
        }
        let resasc = asc * h.abs();
        let raw = ((k[d] - g[d]) * h).abs();
        let mut e = raw;
        if resasc != 0.0 && raw != 0.0 {
            e = resasc * (200.0 * raw / resasc).powf(1.5).min(1.0);
        }
        let resabs = kabs[d] * h.abs();
        e = e.max(50.0 * f64::EPSILON * resabs);
        err[d] = e;
    }
    let val: Vec<f64> = k.iter().map(|x| x * h).collect();
    (val, err)
}

/// Adaptive Gauss-Kronrod integral of a `dim`-valued integrand over `[a, b]`.
/// The integrand writes its values into the slice it is given.
pub fn integrate(
    f: impl FnMut(f64, &mut [f64]),
    a: f64,
    b: f64,
    dim: usize,
    opts: &QuadratureOptions,
) -> Integral {
    integrate_with_breaks(f, &[a, b], dim, opts)
}

/// As [`integrate`], over `[breaks[0], breaks[last]]` starting from the
/// intervals between the given (increasing) break points. Break points at
/// kinks, discontinuities or near a sharp peak keep the adaptive rule from
/// missing them (a peak that falls between all 15 initial nodes would give a
/// zero error estimate).
pub fn integrate_with_breaks(
    mut f: impl FnMut(f64, &mut [f64]),
    breaks: &[f64],
    dim: usize,
    opts: &QuadratureOptions,
) -> Integral {
    let mut buf = vec![0.0; dim];
    let mut vals = Vec::with_capacity(15 * dim);
    let mut evaluations = 0;
    let mut intervals: Vec<Interval> = Vec::new();
    for w in breaks.windows(2) {
        if w[1] > w[0] {
            let (v, e) = gk15(&mut f, w[0], w[1], dim, &mut buf, &mut vals);
            evaluations += 15;
            intervals.push((w[0], w[1], v, e));
        }
    }
    loop {
        let (total, err) = sum_intervals(&intervals, dim);
        if meets_tolerance(&total, &err, opts)
            || intervals.is_empty()
            || intervals.len() >= opts.max_intervals
        {
            return Integral {
                value: total,
                error: err,
                evaluations,
            };
        }
        let idx = (0..intervals.len())
            .max_by(|&i, &j| {
                let ei = intervals[i].3.iter().cloned().fold(0.0, f64::max);
                let ej = intervals[j].3.iter().cloned().fold(0.0, f64::max);
                ei.total_cmp(&ej)
            })
            .unwrap_or(0);
        let (lo, hi, _, _) = intervals.swap_remove(idx);
        let mid = 0.5 * (lo + hi);
        let (v1, e1) = gk15(&mut f, lo, mid, dim, &mut buf, &mut vals);
        let (v2, e2) = gk15(&mut f, mid, hi, dim, &mut buf, &mut vals);
        evaluations += 30;
        intervals.push((lo, mid, v1, e1));
        intervals.push((mid, hi, v2, e2));
    }
}

type Interval = (f64, f64, Vec<f64>, Vec<f64>);

/// Whether every component's error estimate is within `max(abs_tol,
/// rel_tol |value|)`.
fn meets_tolerance(value: &[f64], error: &[f64], opts: &QuadratureOptions) -> bool {
    value
        .iter()
        .zip(error)
        .all(|(v, e)| *e <= opts.abs_tol.max(opts.rel_tol * v.abs()))
}

/// Break points that catch a peak at `c` in `[c - half, c + half]`:
/// the ends, `c`, and `c +- half 10^-k` for `k = 1..=PEAK_DECADES`.
fn peak_breaks(c: f64, half: f64) -> Vec<f64> {
    let mut breaks = vec![c - half];
    breaks.extend((1..=PEAK_DECADES).map(|k| c - half * 10f64.powi(-k)));
    breaks.push(c);
    breaks.extend((1..=PEAK_DECADES).rev().map(|k| c + half * 10f64.powi(-k)));
    breaks.push(c + half);
    breaks
}

/// Decades of [`peak_breaks`]: with `half = pi` the innermost intervals are
/// `3e-7` wide, below the angular width `n^(-1/2) = 1e-6` of a lobe of
/// exponent `1e12`, the sharpest the outer break points of
/// [`directional_albedo`] catch.
const PEAK_DECADES: i32 = 7;

/// [`integrate`] over `[c - half, c + half]` for an integrand whose only
/// sharp feature is a peak at `c`. One Gauss-Kronrod pass over the whole
/// range samples `c` itself (its middle node); a smooth integrand meets the
/// tolerance there. Otherwise plain bisection would cut at `c`, leaving the
/// peak on interval ends where no node samples it (a zero integral with a
/// zero error estimate), so the integral is redone from break points that close in geometrically on `c`.
pub fn integrate_around_peak(
    mut f: impl FnMut(f64, &mut [f64]),
    c: f64,
    half: f64,
    dim: usize,
    opts: &QuadratureOptions,
) -> Integral {
    let one_pass = QuadratureOptions {
        max_intervals: 1,
        ..*opts
    };
    let first = integrate(&mut f, c - half, c + half, dim, &one_pass);
    if meets_tolerance(&first.value, &first.error, opts) {
        return first;
    }
    let mut r = integrate_with_breaks(&mut f, &peak_breaks(c, half), dim, opts);
    r.evaluations += first.evaluations;
    r
}

fn sum_intervals(intervals: &[Interval], dim: usize) -> (Vec<f64>, Vec<f64>) {
    let mut total = vec![0.0; dim];
    let mut err = vec![0.0; dim];
    for (_, _, v, e) in intervals {
        for d in 0..dim {
            total[d] += v[d];
            err[d] += e[d];
        }
    }
    (total, err)
}

/// Directional albedo per channel with an error estimate that covers both
/// integration levels.
#[derive(Clone, Debug, PartialEq)]
pub struct Albedo {
    /// `a_c(L)` per channel.
    pub value: Vec<f64>,
    /// Error estimate per channel.
    pub error: Vec<f64>,
    /// BRDF evaluations used.
    pub evaluations: usize,
}

/// How the outgoing hemisphere is parameterised for [`directional_albedo`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AlbedoFrame {
    /// `mu = cos theta_o` in `[0, 1]`, `phi_o` around the normal. Best for
    /// diffuse and broad lobes.
    Normal,
    /// Polar angle measured from the mirror direction of `L`, over the whole
    /// sphere (directions below the horizon contribute 0). Best for sharp
    /// lobes around the mirror direction, which then sit at the pole where
    /// the adaptive rule refines.
    Mirror,
}

/// `a(L) = int_{H^2} f(L, V) cos theta_o dV` for every channel, by nested
/// adaptive Gauss-Kronrod quadrature.
///
/// ```
/// # use brdf_core::{directional_albedo, AlbedoFrame, QuadratureOptions, Brdf};
/// # use nalgebra::Vector3;
/// struct Grey(f64);
/// impl Brdf for Grey {
///     fn channels(&self) -> usize { 1 }
///     fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
///         out[0] = if l.z > 0.0 && v.z > 0.0 { self.0 / std::f64::consts::PI } else { 0.0 };
///     }
/// }
/// let a = directional_albedo(&Grey(0.7), &Vector3::z(), AlbedoFrame::Normal, &QuadratureOptions::default());
/// assert!((a.value[0] - 0.7).abs() <= a.error[0] + 1e-14);
/// ```
pub fn directional_albedo(
    brdf: &(impl Brdf + ?Sized),
    l: &Vector3<f64>,
    frame: AlbedoFrame,
    opts: &QuadratureOptions,
) -> Albedo {
    let nc = brdf.channels();
    if l.z <= 0.0 {
        return Albedo {
            value: vec![0.0; nc],
            error: vec![0.0; nc],
            evaluations: 0,
        };
    }
    let mut evals = 0usize;
    let mut fbuf = vec![0.0; nc];
    let (breaks, pole, phi_center) = outer_breaks(l, frame);
    let outer = integrate_with_breaks(
        |mu, out: &mut [f64]| {
            let s = (1.0 - mu * mu).max(0.0).sqrt();
            let (center, half) = azimuth_range(frame, &pole, phi_center, mu, s);
            if half <= 0.0 {
                out.iter_mut().for_each(|x| *x = 0.0);
                return;
            }
            let ring = Ring {
                brdf,
                l,
                pole: &pole,
                mu,
                s,
            };
            let inner = ring.integrate(frame, center, half, &mut fbuf, opts);
            evals += inner.evaluations;
            out[..nc].copy_from_slice(&inner.value);
            out[nc..].copy_from_slice(&inner.error);
        },
        &breaks,
        2 * nc,
        opts,
    );
    Albedo {
        value: outer.value[..nc].to_vec(),
        error: (0..nc)
            .map(|c| outer.error[c] + outer.value[nc + c].abs() + outer.error[nc + c])
            .collect(),
        evaluations: evals,
    }
}

/// The break points of the outer variable of [`directional_albedo`] (sorted,
/// finite, within its range), the frame whose pole it measures the angle
/// from, and the azimuth of the mirror direction in that frame (used by the
/// Normal frame only). Geometric break points towards the pole of the outer
/// variable catch lobes of width down to 1e-12 in mu (exponents up to
/// ~1e12).
fn outer_breaks(l: &Vector3<f64>, frame: AlbedoFrame) -> (Vec<f64>, Frame, f64) {
    use std::f64::consts::PI;
    let mut breaks: Vec<f64> = Vec::new();
    let (pole, phi_center) = match frame {
        AlbedoFrame::Normal => {
            // mu = cos theta_o in [0, 1]; a lobe around the mirror direction
            // sits at mu_r = cos theta_i: break points close to it.
            let mu_r = l.z.min(1.0);
            breaks.push(0.0);
            for k in (1..=12).rev() {
                let d = 10f64.powi(-k);
                breaks.push(mu_r - d);
            }
            breaks.push(mu_r);
            for k in (1..=12).rev() {
                breaks.push(mu_r + 10f64.powi(-k));
            }
            breaks.push(1.0);
            (Frame::identity(), l.y.atan2(l.x) + PI)
        }
        AlbedoFrame::Mirror => {
            // mu' = cos of the angle to R in [-sin theta_r, 1]; below -sin
            // theta_r every direction is under the horizon, above sin theta_r
            // every direction is above it (a kink of the inner integral).
            let r = reflect_about_normal(l);
            let sin_r = (r.x * r.x + r.y * r.y).sqrt().min(1.0);
            breaks.push(-sin_r);
            breaks.push(sin_r);
            for k in 1..=12 {
                breaks.push(1.0 - 10f64.powi(-k));
            }
            breaks.push(1.0);
            (Frame::from_z(r), 0.0)
        }
    };
    breaks.retain(|b| b.is_finite());
    let lo = breaks[0];
    breaks.retain(|&b| b >= lo && b <= 1.0);
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    (breaks, pole, phi_center)
}

/// The azimuth range `(center, half width)` of the ring at `mu` (with
/// `s = sqrt(1 - mu^2)`) that lies above the horizon: `V.z = mu R.z + s A
/// cos(phi - phi0) > 0` with `A cos(phi0)`, `A sin(phi0)` the z-components
/// of the frame's tangents. Integrating only over it keeps the integrand
/// smooth (no jump at the horizon). In the Normal frame the whole ring is
/// above it, centred on the mirror direction's azimuth `phi_center`.
fn azimuth_range(frame: AlbedoFrame, pole: &Frame, phi_center: f64, mu: f64, s: f64) -> (f64, f64) {
    use std::f64::consts::PI;
    match frame {
        AlbedoFrame::Normal => (phi_center, PI),
        AlbedoFrame::Mirror => {
            let ax = pole.x.z;
            let ay = pole.y.z;
            let a = ax.hypot(ay);
            let phi0 = ay.atan2(ax);
            if a * s <= 0.0 {
                (phi0, if mu * pole.z.z > 0.0 { PI } else { 0.0 })
            } else {
                let c = (-mu * pole.z.z / (a * s)).clamp(-1.0, 1.0);
                (phi0, c.acos())
            }
        }
    }
}

/// The ring of outgoing directions at `mu = cos` of the angle to `pole.z`
/// (`s = sqrt(1 - mu^2)`), whose integral over the azimuth is the inner
/// integral of [`directional_albedo`].
struct Ring<'a, B: Brdf + ?Sized> {
    brdf: &'a B,
    l: &'a Vector3<f64>,
    pole: &'a Frame,
    mu: f64,
    s: f64,
}

impl<B: Brdf + ?Sized> Ring<'_, B> {
    /// `int f(L, V) cos theta_o dphi` over `[center - half, center + half]`
    /// per channel (`fbuf` holds one BRDF value per channel). In the Normal
    /// frame a lobe around the mirror direction is a peak in the azimuth at
    /// `center`; in the Mirror frame it is at the pole of the outer variable
    /// instead.
    fn integrate(
        &self,
        frame: AlbedoFrame,
        center: f64,
        half: f64,
        fbuf: &mut [f64],
        opts: &QuadratureOptions,
    ) -> Integral {
        let nc = fbuf.len();
        let integrand = |phi: f64, o: &mut [f64]| {
            let local = Vector3::new(self.s * phi.cos(), self.s * phi.sin(), self.mu);
            let v = self.pole.from_local(&local);
            if v.z <= 0.0 {
                o.iter_mut().for_each(|x| *x = 0.0);
                return;
            }
            self.brdf.eval(self.l, &v, fbuf);
            for c in 0..nc {
                o[c] = fbuf[c] * v.z;
            }
        };
        match frame {
            AlbedoFrame::Normal => integrate_around_peak(integrand, center, half, nc, opts),
            AlbedoFrame::Mirror => integrate(integrand, center - half, center + half, nc, opts),
        }
    }
}
