//! Adaptive Gauss-Kronrod quadrature and the directional albedo of any BRDF.
//!
//! The 1-D rule is the 7-point Gauss / 15-point Kronrod pair (as in QUADPACK's
//! QAG): on each interval the Kronrod sum is the estimate and
//! `|K15 - G7|` the error estimate; the interval with the largest error is
//! bisected until the summed error estimate falls below
//! `max(abs_tol, rel_tol |I|)`. For integrands that are smooth on each final
//! interval the estimate is pessimistic by orders of magnitude (the Kronrod
//! value is far more accurate than the Gauss value it is compared with), which
//! is what lets the tests use it as a bound.
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
) -> (Vec<f64>, Vec<f64>) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let mut k = vec![0.0; dim];
    let mut g = vec![0.0; dim];
    for i in 0..8 {
        let nodes: &[f64] = if i == 7 { &[0.0] } else { &[-XGK[i], XGK[i]] };
        for &x in nodes {
            f(c + h * x, buf);
            for d in 0..dim {
                k[d] += WGK[i] * buf[d];
                if i % 2 == 1 {
                    g[d] += WG[i / 2] * buf[d];
                }
            }
        }
    }
    let val: Vec<f64> = k.iter().map(|x| x * h).collect();
    let err: Vec<f64> = k.iter().zip(&g).map(|(x, y)| ((x - y) * h).abs()).collect();
    (val, err)
}

/// Adaptive Gauss-Kronrod integral of a `dim`-valued integrand over `[a, b]`.
/// The integrand writes its values into the slice it is given.
pub fn integrate(
    mut f: impl FnMut(f64, &mut [f64]),
    a: f64,
    b: f64,
    dim: usize,
    opts: &QuadratureOptions,
) -> Integral {
    let mut buf = vec![0.0; dim];
    let mut evaluations = 15;
    let (v, e) = gk15(&mut f, a, b, dim, &mut buf);
    let mut intervals = vec![(a, b, v, e)];
    loop {
        let (total, err) = sum_intervals(&intervals, dim);
        let worst_ok = (0..dim).all(|d| err[d] <= opts.abs_tol.max(opts.rel_tol * total[d].abs()));
        if worst_ok || intervals.len() >= opts.max_intervals {
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
        let (v1, e1) = gk15(&mut f, lo, mid, dim, &mut buf);
        let (v2, e2) = gk15(&mut f, mid, hi, dim, &mut buf);
        evaluations += 30;
        intervals.push((lo, mid, v1, e1));
        intervals.push((mid, hi, v2, e2));
    }
}

type Interval = (f64, f64, Vec<f64>, Vec<f64>);

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
    use std::f64::consts::PI;
    let nc = brdf.channels();
    let mut evals = 0usize;
    let mut fbuf = vec![0.0; nc];
    let (pole, lo) = match frame {
        AlbedoFrame::Normal => (Frame::identity(), 0.0),
        AlbedoFrame::Mirror => (Frame::from_z(reflect_about_normal(l)), -1.0),
    };
    // The inner integral over phi starts at the mirror azimuth of L (Normal
    // frame) so a lobe's peak is an interior point, not split at an endpoint.
    let phi0 = match frame {
        AlbedoFrame::Normal => l.y.atan2(l.x) + PI,
        AlbedoFrame::Mirror => 0.0,
    };
    let outer = integrate(
        |mu, out: &mut [f64]| {
            let s = (1.0 - mu * mu).max(0.0).sqrt();
            let inner = integrate(
                |phi, o: &mut [f64]| {
                    let local = Vector3::new(s * phi.cos(), s * phi.sin(), mu);
                    let v = pole.from_local(&local);
                    if v.z <= 0.0 || l.z <= 0.0 {
                        o.iter_mut().for_each(|x| *x = 0.0);
                        return;
                    }
                    brdf.eval(l, &v, &mut fbuf);
                    for c in 0..nc {
                        o[c] = fbuf[c] * v.z;
                    }
                },
                phi0 - PI,
                phi0 + PI,
                nc,
                opts,
            );
            evals += inner.evaluations;
            for c in 0..nc {
                out[c] = inner.value[c];
                out[nc + c] = inner.error[c];
            }
        },
        lo,
        1.0,
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
