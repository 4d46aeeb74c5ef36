//! Ashikhmin-Shirley (Ashikhmin & Shirley 2000, "An anisotropic Phong BRDF
//! model", Journal of Graphics Tools 5(2)), isotropic and anisotropic, with
//! Lambert's diffuse term (as Kurt and Ngan fitted it) or the coupled one.
//!
//! Schlick Fresnel `F(c) = F0 + (1 - F0)(1 - c)^5`.
//!
//! iso specular: `ks (n+1)/(8 pi) (N.H)^n / ((V.H) max(N.L, N.V)) F(V.H)`
//!
//! aniso specular: `ks sqrt((nu+1)(nv+1))/(8 pi) (N.H)^(nu cos^2 phi_h + nv sin^2 phi_h) / ((V.H) max(N.L, N.V)) F(V.H)`
//!
//! diffuse: Lambert `kd/pi`, or coupled
//! `28 kd/(23 pi) (1 - F0) (1 - (1 - N.L/2)^5) (1 - (1 - N.V/2)^5)`.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `ks` (per channel) | specular strength | `[0, 1]` | yes |
//! | `n` (iso) / `nu`, `nv` (aniso) | exponents | `[0, 1e6]` | no |
//! | `f0` | Fresnel reflectance at normal incidence | `[0, 0.999]` | no |
//!
//! Properties: reciprocal (every factor is symmetric in `L`, `V`);
//! non-negative; finite above the horizon (`V.H >= sqrt((1 + L.V)/2) > 0`
//! and `max(N.L, N.V) >= 1e-6` within `1e-6` of the horizon). Energy:
//! `kd + ks <= 1` keeps the albedo at most 1 at every incidence, for both
//! diffuse forms, every exponent and `F0` (tested in `tests/models/energy.rs`).
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::AshikhminShirley;
//! use nalgebra::Vector3;
//! // kd = 0, ks = 1, n = 10, F0 = 0.5: at L = V = N, V.H = 1 and F = F0,
//! // so the lobe is (n+1)/(8 pi) F0.
//! let m = AshikhminShirley::new(&[0.0], &[1.0], &[10.0, 0.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! assert!((f[0] - 0.5 * 11.0 / (8.0 * std::f64::consts::PI)).abs() < 1e-12);
//! ```

use std::f64::consts::PI;

use brdf_core::fresnel::{schlick, schlick_d_f0};
use brdf_core::{DirPairs, PairGeometry, ParamSpec, vmath};
use nalgebra::Vector3;

use crate::combinators::{DiffuseLobe, Lobe, pow_clamped};
use crate::microfacet::HalfGeometry;

pub(crate) fn exponent(name: &str) -> ParamSpec {
    ParamSpec::new(name, "exponent", 0.0, 1e6, 20.0, false)
}

pub(crate) fn f0_spec() -> ParamSpec {
    ParamSpec::new(
        "f0",
        "Fresnel reflectance at normal incidence",
        0.0,
        0.999,
        0.04,
        false,
    )
}

/// The AS specular lobe with exponents `nu`, `nv` (equal when isotropic),
/// Fresnel on or off. Returns `S` and `(dS/dnu, dS/dnv, dS/dF0)`.
#[inline]
pub(crate) fn as_lobe(
    nu: f64,
    nv: f64,
    f0: Option<f64>,
    l: &Vector3<f64>,
    v: &Vector3<f64>,
) -> (f64, [f64; 3]) {
    let Some(g) = HalfGeometry::new(l, v) else {
        return (0.0, [0.0; 3]);
    };
    let c2 = g.cos2_phi_h;
    let e = nu * c2 + nv * (1.0 - c2);
    let (pw, dpw) = pow_clamped(g.nh, e);
    let norm = ((nu + 1.0) * (nv + 1.0)).sqrt() / (8.0 * PI);
    let denom = g.vh * g.nl.max(g.nv);
    let (fr, dfr) = match f0 {
        Some(f0) => (schlick(f0, g.vh), schlick_d_f0(g.vh)),
        None => (1.0, 0.0),
    };
    let base = norm / denom;
    let s = base * pw * fr;
    let dnu = s * 0.5 / (nu + 1.0) + base * dpw * c2 * fr;
    let dnv = s * 0.5 / (nv + 1.0) + base * dpw * (1.0 - c2) * fr;
    (s, [dnu, dnv, base * pw * dfr])
}

/// [`as_lobe`] for every pair of a sample set, over its precomputed
/// geometry (the fitting kernel: no per-pair half-vector, logarithm or
/// allocation). `ds` holds `dS/dnu, dS/dnv, dS/dF0` as `ds[u * n + j]`, or
/// for the isotropic lobe (`aniso` false) `dS/dn, dS/dF0`.
pub(crate) fn as_lobe_batch(
    (nu, nv, f0): (f64, f64, f64),
    aniso: bool,
    pairs: &DirPairs,
    geom: &PairGeometry,
    s: &mut [f64],
    ds: Option<&mut [f64]>,
) {
    // `pulp` compiles the kernel for the widest instruction set of the
    // machine (profiled, the scalar loop with a library `exp` was the
    // largest cost of a fit).
    pulp::Arch::new().dispatch(AsKernel {
        q: (nu, nv, f0),
        aniso,
        pairs,
        geom,
        s,
        ds,
    });
}

/// The batch kernel of [`as_lobe_batch`], inlined into `pulp`'s
/// target-feature function so that its loops vectorise.
struct AsKernel<'a> {
    q: (f64, f64, f64),
    aniso: bool,
    pairs: &'a DirPairs,
    geom: &'a PairGeometry,
    s: &'a mut [f64],
    ds: Option<&'a mut [f64]>,
}

impl pulp::WithSimd for AsKernel<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let AsKernel {
            q: (nu, nv, f0),
            aniso,
            pairs,
            geom,
            s,
            ds,
        } = self;
        let n = pairs.len();
        let norm = ((nu + 1.0) * (nv + 1.0)).sqrt() / (8.0 * PI);
        let (hu, hv) = (0.5 / (nu + 1.0), 0.5 / (nv + 1.0));
        // Every array cut to `n` so the loops need no bounds checks.
        let g = AsGeometry {
            ln_nh: &geom.ln_nh[..n],
            valid: &geom.valid[..n],
            cos2_phi_h: &geom.cos2_phi_h[..n],
            schlick5: &geom.schlick5[..n],
            inv_vh_max_cos: &geom.inv_vh_max_cos[..n],
        };
        let at = |j| as_lobe_at((nu, nv, f0), norm, &g, j);
        match ds {
            None => {
                for (j, sj) in s[..n].iter_mut().enumerate() {
                    let (bp, fr, _, _, _, ok) = at(j);
                    *sj = if ok { bp * fr } else { 0.0 };
                }
            }
            Some(ds) => {
                let (d0, rest) = ds.split_at_mut(n);
                let (d1, d2) = rest.split_at_mut(n);
                let s = &mut s[..n];
                let d2 = &mut d2[..if aniso { n } else { 0 }];
                for j in 0..n {
                    let (bp, fr, dfr, lnh, c2, ok) = at(j);
                    let v = bp * fr;
                    let dpw = v * lnh;
                    // Invalid pairs are 0 whatever the parameters (no
                    // 0 * inf from an extreme exponent).
                    let z = |x: f64| if ok { x } else { 0.0 };
                    let (v, dfr) = (z(v), z(bp * dfr));
                    let dnu = z(v * hu + dpw * c2);
                    let dnv = z(v * hv + dpw * (1.0 - c2));
                    s[j] = v;
                    if aniso {
                        d0[j] = dnu;
                        d1[j] = dnv;
                        d2[j] = dfr;
                    } else {
                        d0[j] = dnu + dnv;
                        d1[j] = dfr;
                    }
                }
            }
        }
    }
}

/// The arrays the kernel reads, all of one length.
struct AsGeometry<'a> {
    ln_nh: &'a [f64],
    valid: &'a [bool],
    cos2_phi_h: &'a [f64],
    schlick5: &'a [f64],
    inv_vh_max_cos: &'a [f64],
}

/// The lobe at pair `j` without its Fresnel factor, branch-free (the
/// caller selects 0 for an invalid pair, so the loops vectorise): `(base
/// (N.H)^e, F, dF/dF0, ln N.H, cos^2 phi_h, valid)`.
#[inline(always)]
fn as_lobe_at(
    (nu, nv, f0): (f64, f64, f64),
    norm: f64,
    g: &AsGeometry<'_>,
    j: usize,
) -> (f64, f64, f64, f64, f64, bool) {
    let lnh = g.ln_nh[j];
    let ok = g.valid[j] & (lnh > f64::NEG_INFINITY);
    let lnh = if ok { lnh } else { 0.0 };
    let c2 = g.cos2_phi_h[j];
    let pw = vmath::exp((nu * c2 + nv * (1.0 - c2)) * lnh);
    let base = norm * g.inv_vh_max_cos[j];
    let m5 = g.schlick5[j];
    (base * pw, f0 + (1.0 - f0) * m5, 1.0 - m5, lnh, c2, ok)
}

/// Coupled diffuse `28/(23 pi) (1 - F0) (1 - (1 - N.L/2)^5)(1 - (1 - N.V/2)^5)`
/// and its derivative with respect to `F0`.
#[inline]
pub(crate) fn coupled_diffuse(f0: f64, l: &Vector3<f64>, v: &Vector3<f64>) -> (f64, f64) {
    let a = 1.0 - (1.0 - 0.5 * l.z).powi(5);
    let b = 1.0 - (1.0 - 0.5 * v.z).powi(5);
    let k = 28.0 / (23.0 * PI) * a * b;
    (k * (1.0 - f0), -k)
}

macro_rules! as_model {
    ($lobe:ident, $model:ident, $name:literal, $aniso:expr, $coupled:expr, $doc:literal) => {
        #[doc = $doc]
        #[derive(Clone, Debug, PartialEq)]
        pub struct $lobe;
        impl Lobe for $lobe {
            const NAME: &'static str = $name;
            fn specs() -> Vec<ParamSpec> {
                if $aniso {
                    vec![exponent("nu"), exponent("nv"), f0_spec()]
                } else {
                    vec![exponent("n"), f0_spec()]
                }
            }
            fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
                let (nu, nv, f0) = if $aniso {
                    (q[0], q[1], q[2])
                } else {
                    (q[0], q[0], q[1])
                };
                let (s, d) = as_lobe(nu, nv, Some(f0), l, v);
                if let Some(dq) = dq {
                    if $aniso {
                        dq.copy_from_slice(&d);
                    } else {
                        dq[0] = d[0] + d[1];
                        dq[1] = d[2];
                    }
                }
                s
            }
            fn shape_batch(
                q: &[f64],
                pairs: &DirPairs,
                geom: &PairGeometry,
                s: &mut [f64],
                ds: Option<&mut [f64]>,
            ) {
                let par = if $aniso {
                    (q[0], q[1], q[2])
                } else {
                    (q[0], q[0], q[1])
                };
                as_lobe_batch(par, $aniso, pairs, geom, s, ds)
            }
            fn diffuse_batch(
                q: &[f64],
                pairs: &DirPairs,
                geom: &PairGeometry,
                d: &mut [f64],
                dd: Option<&mut [f64]>,
            ) {
                if $coupled {
                    return crate::combinators::per_pair(q, pairs, geom, d, dd, |q, l, v, dq| {
                        Self::diffuse(q, l, v, dq)
                    });
                }
                // Lambert: the constant 1/pi above the horizon.
                for (x, ok) in d.iter_mut().zip(&geom.valid) {
                    *x = if *ok {
                        std::f64::consts::FRAC_1_PI
                    } else {
                        0.0
                    };
                }
                if let Some(dd) = dd {
                    dd.fill(0.0);
                }
            }
            fn diffuse(
                q: &[f64],
                l: &Vector3<f64>,
                v: &Vector3<f64>,
                dq: Option<&mut [f64]>,
            ) -> f64 {
                if !$coupled {
                    return std::f64::consts::FRAC_1_PI;
                }
                let f0 = q[q.len() - 1];
                let (d, dd) = coupled_diffuse(f0, l, v);
                if let Some(dq) = dq {
                    dq[q.len() - 1] = dd;
                }
                d
            }
        }
        #[doc = $doc]
        pub type $model = DiffuseLobe<$lobe>;
    };
}

as_model!(
    AsLobe,
    AshikhminShirley,
    "ashikhmin-shirley",
    false,
    false,
    "Isotropic Ashikhmin-Shirley with Lambert diffuse: parameters `kd`, `ks` per channel, `n`, `f0`."
);
as_model!(
    AsAnisoLobe,
    AshikhminShirleyAniso,
    "ashikhmin-shirley-aniso",
    true,
    false,
    "Anisotropic Ashikhmin-Shirley with Lambert diffuse: `kd`, `ks` per channel, `nu`, `nv`, `f0`."
);
as_model!(
    AsCoupledLobe,
    AshikhminShirleyCoupled,
    "ashikhmin-shirley-coupled",
    false,
    true,
    "Isotropic Ashikhmin-Shirley with the coupled diffuse term: `kd`, `ks` per channel, `n`, `f0`."
);
as_model!(
    AsCoupledAnisoLobe,
    AshikhminShirleyCoupledAniso,
    "ashikhmin-shirley-coupled-aniso",
    true,
    true,
    "Anisotropic Ashikhmin-Shirley with the coupled diffuse term: `kd`, `ks` per channel, `nu`, `nv`, `f0`."
);
