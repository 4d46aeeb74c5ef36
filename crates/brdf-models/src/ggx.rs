//! GGX / Trowbridge-Reitz microfacet models (Walter, Marschner, Li &
//! Torrance 2007, "Microfacet models for refraction through rough
//! surfaces", EGSR; Trowbridge & Reitz 1975), isotropic and anisotropic,
//! with Smith masking-shadowing in its height-correlated form (Heitz 2014,
//! "Understanding the masking-shadowing function in microfacet-based
//! BRDFs", JCGT 3(2)) or the separable form, and a Schlick, exact
//! dielectric or exact conductor Fresnel term:
//!
//! `f = kd/pi + sum_k ks_k D(H) G(L, V) F(V.H) / (4 (N.L)(N.V))`,
//!
//! `D(H) = 1 / (pi ax ay (Hx^2/ax^2 + Hy^2/ay^2 + Hz^2)^2)`,
//! `Lambda(W) = (sqrt(1 + (ax^2 Wx^2 + ay^2 Wy^2)/Wz^2) - 1) / 2`,
//! height-correlated `G = 1 / (1 + Lambda(L) + Lambda(V))`,
//! separable `G = 1 / ((1 + Lambda(L)) (1 + Lambda(V)))`;
//! `F` is Schlick's `F0 + (1 - F0)(1 - V.H)^5`, the exact dielectric
//! reflectance for index `eta`, or the exact conductor reflectance for
//! `eta + i k` ([`brdf_core::fresnel_conductor`]). `alpha = ax = ay` for the
//! isotropic models; `ax` acts along the tangent `+x`.
//!
//! These are the specular lobes renderers use: pbrt-v4's
//! `TrowbridgeReitzDistribution` uses the height-correlated `G`, Mitsuba 3's
//! `roughconductor` (`distribution = "ggx"`) the separable one; the glTF
//! BRDF appendix the height-correlated one with Schlick's `F`. `alpha` is
//! the distribution's own width (Mitsuba's `alpha`), not the perceptual
//! roughness (`alpha = roughness^2` in glTF and Disney's model).
//!
//! | model | parameters after `kd`, `ks` (per channel, linear, `[0, 1]`) |
//! | --- | --- |
//! | `ggx`, `ggx-separable` (K lobes: `ks{k}`, `alpha{k}`, `f0_{k}`) | `alpha`, `f0` |
//! | `ggx-aniso`, `ggx-aniso-separable` | `ax`, `ay`, `f0` |
//! | `ggx-dielectric[-aniso][-separable]` | `alpha` (or `ax`, `ay`), `eta` |
//! | `ggx-conductor[-aniso][-separable]` | `alpha` (or `ax`, `ay`), `eta`, `k` |
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `ks` (per channel) | specular strength | `[0, 1]` | yes |
//! | `alpha`, `ax`, `ay` | GGX width | `(0, 1]` | no |
//! | `f0` | Schlick reflectance at normal incidence | `[0, 1]` | no |
//! | `eta` (dielectric) | relative index of refraction | `[1, 3]` | no |
//! | `eta` (conductor) | real part of the complex index | `[0.01, 5]` | no |
//! | `k` (conductor) | extinction coefficient | `[0, 10]` | no |
//!
//! Properties: reciprocal (`V.H = L.H`, `D` and `G` symmetric); non-negative;
//! finite above the horizon (at `alpha = 1e-6` `D(N) = 1/(pi alpha^2)`;
//! `G / (N.L)` stays bounded near the horizon since `Lambda` grows like
//! `1/N.L`). Energy: `G <= min(G1(L), G1(V))` and the GGX `D` is normalised
//! for the visible projected area, so each lobe's albedo is at most
//! `max F <= 1`; the model conserves energy for `kd + sum ks <= 1` (tested
//! in `tests/models/renderer_models.rs`).
//!
//! ```
//! use brdf_core::{Brdf, Parametric};
//! use brdf_models::GgxAniso;
//! use nalgebra::Vector3;
//! // kd, ks, ax, ay, f0
//! let m = GgxAniso::new(&[0.0], &[1.0], &[0.2, 0.4, 0.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // At the pole: D = 1/(pi ax ay), G = 1, F = F0: f = F0 / (4 pi ax ay).
//! let expect = 0.5 / (4.0 * std::f64::consts::PI * 0.2 * 0.4);
//! assert!((f[0] - expect).abs() < 1e-12);
//! ```

use std::f64::consts::PI;

use brdf_core::fresnel::{fresnel_dielectric_d_eta, schlick, schlick_d_f0};
use brdf_core::fresnel_conductor::{fresnel_conductor, fresnel_conductor_grad};
use brdf_core::{DirPairs, PairGeometry, ParamSpec};
use nalgebra::Vector3;

use crate::combinators::{DiffuseLobe, Lobe, MultiLobe};

pub(crate) mod chunk;

/// Form of the Smith masking-shadowing term.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Masking {
    /// `1 / (1 + Lambda(L) + Lambda(V))` (Heitz 2014).
    HeightCorrelated,
    /// `G1(L) G1(V)`, `G1 = 1 / (1 + Lambda)` (Walter et al. 2007).
    Separable,
}

/// `D(h)` of GGX for a unit half vector `h` and `(d ln D/d ax, d ln D/d ay)`.
#[inline(always)]
pub fn ggx_d(h: &Vector3<f64>, ax: f64, ay: f64) -> (f64, f64, f64) {
    let x2 = h.x * h.x / (ax * ax);
    let y2 = h.y * h.y / (ay * ay);
    let s = x2 + y2 + h.z * h.z;
    let d = 1.0 / (PI * ax * ay * s * s);
    (
        d,
        -1.0 / ax + 4.0 * x2 / (ax * s),
        -1.0 / ay + 4.0 * y2 / (ay * s),
    )
}

/// Smith's `Lambda(w)` for GGX and `(dLambda/d ax, dLambda/d ay)`, for `w`
/// above the horizon; `t / (2 (sqrt(1 + t) + 1))` avoids cancellation for
/// small `t = (ax^2 wx^2 + ay^2 wy^2) / wz^2`.
#[inline(always)]
pub fn smith_lambda(w: &Vector3<f64>, ax: f64, ay: f64) -> (f64, f64, f64) {
    let z2 = w.z * w.z;
    let t = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / z2;
    let r = (1.0 + t).sqrt();
    let lam = t / (2.0 * (r + 1.0));
    let dt = 1.0 / (4.0 * r);
    (
        lam,
        dt * 2.0 * ax * w.x * w.x / z2,
        dt * 2.0 * ay * w.y * w.y / z2,
    )
}

/// Smith `G(L, V)` in the given form and `(dG/d ax, dG/d ay)`.
#[inline(always)]
pub fn smith_g(
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    ax: f64,
    ay: f64,
    masking: Masking,
) -> (f64, f64, f64) {
    let (ll, lx, ly) = smith_lambda(l, ax, ay);
    let (lv, vx, vy) = smith_lambda(v, ax, ay);
    match masking {
        Masking::HeightCorrelated => {
            let g = 1.0 / (1.0 + ll + lv);
            (g, -g * g * (lx + vx), -g * g * (ly + vy))
        }
        Masking::Separable => {
            let (gl, gv) = (1.0 / (1.0 + ll), 1.0 / (1.0 + lv));
            let g = gl * gv;
            (g, -g * (lx * gl + vx * gv), -g * (ly * gl + vy * gv))
        }
    }
}

/// The Fresnel-free specular lobe `D G / (4 N.L N.V)` at one direction pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GgxSpecular {
    /// `D G / (4 N.L N.V)`.
    pub value: f64,
    /// Its derivative in `ax`.
    pub d_ax: f64,
    /// Its derivative in `ay`.
    pub d_ay: f64,
    /// `V.H`, the Fresnel cosine.
    pub vh: f64,
    /// The unit half vector.
    pub h: Vector3<f64>,
}

/// `D G / (4 N.L N.V)` for `L`, `V` above the horizon; `None` if `L + V = 0`.
#[inline]
pub fn ggx_specular(
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    ax: f64,
    ay: f64,
    masking: Masking,
) -> Option<GgxSpecular> {
    let len = (l + v).norm();
    if !(len > 0.0) {
        return None;
    }
    Some(ggx_specular_unchecked(l, v, ax, ay, masking))
}

/// [`ggx_specular`] without the test of `L + V = 0` (not a number there):
/// a batch computes it branch-free for every pair and keeps the valid
/// ones, with the same operations, so the same bits.
#[inline(always)]
pub(crate) fn ggx_specular_unchecked(
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    ax: f64,
    ay: f64,
    masking: Masking,
) -> GgxSpecular {
    let s = l + v;
    let h = s / s.norm();
    let (d, dlx, dly) = ggx_d(&h, ax, ay);
    let (g, gx, gy) = smith_g(l, v, ax, ay, masking);
    let value = d * g / (4.0 * l.z * v.z);
    let (d_ax, d_ay) = if g > 0.0 {
        (value * (dlx + gx / g), value * (dly + gy / g))
    } else {
        (0.0, 0.0)
    };
    GgxSpecular {
        value,
        d_ax,
        d_ay,
        vh: v.dot(&h).clamp(0.0, 1.0),
        h,
    }
}

/// A Fresnel term with its own parameters (one to two).
pub trait GgxFresnel {
    /// Number of parameters.
    const NQ: usize;
    /// Their descriptions.
    fn specs() -> Vec<ParamSpec>;
    /// `F(cos)` at parameters `q`, derivatives into `dq[..NQ]`.
    fn eval(q: &[f64], cos: f64, dq: &mut [f64; 2]) -> f64;
    /// `F(cos)` alone, the same to the bit as [`GgxFresnel::eval`]'s (what
    /// trial points and renders call).
    fn value(q: &[f64], cos: f64) -> f64 {
        Self::eval(q, cos, &mut [0.0; 2])
    }
}

/// Schlick's `F0 + (1 - F0)(1 - c)^5`, parameter `f0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SchlickF0;

impl GgxFresnel for SchlickF0 {
    const NQ: usize = 1;
    fn specs() -> Vec<ParamSpec> {
        vec![ParamSpec::new(
            "f0",
            "Fresnel reflectance at normal incidence",
            0.0,
            1.0,
            0.04,
            false,
        )]
    }
    #[inline(always)]
    fn eval(q: &[f64], cos: f64, dq: &mut [f64; 2]) -> f64 {
        dq[0] = schlick_d_f0(cos);
        schlick(q[0], cos)
    }
}

/// Exact dielectric reflectance, parameter `eta`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric;

impl GgxFresnel for Dielectric {
    const NQ: usize = 1;
    fn specs() -> Vec<ParamSpec> {
        vec![ParamSpec::new(
            "eta",
            "relative index of refraction",
            1.0,
            3.0,
            1.5,
            false,
        )]
    }
    #[inline(always)]
    fn eval(q: &[f64], cos: f64, dq: &mut [f64; 2]) -> f64 {
        let (f, d) = fresnel_dielectric_d_eta(cos, q[0]);
        dq[0] = d;
        f
    }
}

/// Exact conductor reflectance, parameters `eta`, `k`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor;

impl GgxFresnel for Conductor {
    const NQ: usize = 2;
    fn specs() -> Vec<ParamSpec> {
        vec![
            ParamSpec::new(
                "eta",
                "real part of the complex index",
                0.01,
                5.0,
                0.2,
                false,
            ),
            ParamSpec::new("k", "extinction coefficient", 0.0, 10.0, 3.0, false),
        ]
    }
    #[inline(always)]
    fn eval(q: &[f64], cos: f64, dq: &mut [f64; 2]) -> f64 {
        let (f, de, dk) = fresnel_conductor_grad(cos, q[0], q[1]);
        dq[0] = de;
        dq[1] = dk;
        f
    }
    #[inline(always)]
    fn value(q: &[f64], cos: f64) -> f64 {
        fresnel_conductor(cos, q[0], q[1])
    }
}

fn width_specs(aniso: bool) -> Vec<ParamSpec> {
    let w = |name: &str, meaning: &str| {
        ParamSpec::new(name, meaning, 0.0, 1.0, 0.2, false).open_below()
    };
    if aniso {
        vec![
            w("ax", "GGX width along the tangent"),
            w("ay", "GGX width along the bitangent"),
        ]
    } else {
        vec![w("alpha", "GGX width")]
    }
}

/// The lobe `D G F / (4 N.L N.V)` with parameters `[alpha | ax, ay, F...]`.
#[inline]
pub(crate) fn ggx_shape<F: GgxFresnel>(
    q: &[f64],
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    dq: Option<&mut [f64]>,
    aniso: bool,
    masking: Masking,
) -> f64 {
    if !((l + v).norm() > 0.0) {
        if let Some(dq) = dq {
            dq.fill(0.0);
        }
        return 0.0;
    }
    ggx_shape_unchecked::<F>(q, l, v, dq, aniso, masking)
}

/// [`ggx_shape`] where `L + V` is not 0 (see [`ggx_specular_unchecked`]).
#[inline(always)]
fn ggx_shape_unchecked<F: GgxFresnel>(
    q: &[f64],
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    dq: Option<&mut [f64]>,
    aniso: bool,
    masking: Masking,
) -> f64 {
    let (ax, ay, nr) = if aniso {
        (q[0], q[1], 2)
    } else {
        (q[0], q[0], 1)
    };
    let sp = ggx_specular_unchecked(l, v, ax, ay, masking);
    let Some(dq) = dq else {
        return sp.value * F::value(&q[nr..], sp.vh);
    };
    let mut df = [0.0; 2];
    let f = F::eval(&q[nr..], sp.vh, &mut df);
    if aniso {
        dq[0] = sp.d_ax * f;
        dq[1] = sp.d_ay * f;
    } else {
        dq[0] = (sp.d_ax + sp.d_ay) * f;
    }
    for k in 0..F::NQ {
        dq[nr + k] = sp.value * df[k];
    }
    sp.value * f
}

/// The lobe of [`ggx_shape`] at every pair (0 and zero derivatives where
/// the pair is invalid), what the fits call: branch-free over chunks of
/// pairs, inside `pulp`'s dispatch, so that the loop vectorises for the
/// widest instruction set of the machine (`ANISO` and height-correlated
/// masking `HC` are constants of the lobe). Lanes round as the scalar code
/// (never fused): the same bits as [`ggx_shape`] pair by pair (tested).
#[inline(always)]
pub(crate) fn ggx_shape_batch<F: GgxFresnel, const ANISO: bool, const HC: bool>(
    q: &[f64],
    pairs: &DirPairs,
    geom: &PairGeometry,
    s: &mut [f64],
    ds: Option<&mut [f64]>,
) {
    pulp::Arch::new().dispatch(ShapeBatch::<F, ANISO, HC> {
        q,
        pairs,
        valid: &geom.valid,
        s,
        ds,
        fresnel: std::marker::PhantomData,
    });
}

/// Pairs per chunk of [`ggx_shape_batch`].
const CHUNK: usize = 64;

/// The loops of [`ggx_shape_batch`].
struct ShapeBatch<'a, F, const ANISO: bool, const HC: bool> {
    q: &'a [f64],
    pairs: &'a DirPairs,
    valid: &'a [bool],
    s: &'a mut [f64],
    ds: Option<&'a mut [f64]>,
    fresnel: std::marker::PhantomData<F>,
}

impl<F: GgxFresnel, const ANISO: bool, const HC: bool> pulp::WithSimd
    for ShapeBatch<'_, F, ANISO, HC>
{
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let ShapeBatch {
            q,
            pairs,
            valid,
            s,
            ds,
            ..
        } = self;
        let masking = if HC {
            Masking::HeightCorrelated
        } else {
            Masking::Separable
        };
        // The lobe's parameters: its widths, then the Fresnel law's.
        let nq = if ANISO { 2 } else { 1 } + F::NQ;
        // The parameters in an array of known length, so reading them
        // needs no bounds check in the loop.
        let mut qa = [0.0; 4];
        qa[..nq].copy_from_slice(&q[..nq]);
        let n = pairs.len();
        let mut ds = ds;
        // The value and up to 4 derivatives of a chunk, column by column.
        let mut buf = [[0.0; CHUNK]; 5];
        let mut start = 0;
        while start < n {
            let len = CHUNK.min(n - start);
            let r = start..start + len;
            let pc = pairs.chunk(start, len);
            let ok = &valid[r.clone()];
            if ds.is_some() {
                for i in 0..len {
                    let (l, v) = pc.at(i);
                    let mut dq = [0.0; 4];
                    let x =
                        ggx_shape_unchecked::<F>(&qa, &l, &v, Some(&mut dq[..nq]), ANISO, masking);
                    buf[0][i] = if ok[i] { x } else { 0.0 };
                    for u in 0..nq {
                        buf[1 + u][i] = if ok[i] { dq[u] } else { 0.0 };
                    }
                }
            } else {
                for i in 0..len {
                    let (l, v) = pc.at(i);
                    let x = ggx_shape_unchecked::<F>(&qa, &l, &v, None, ANISO, masking);
                    buf[0][i] = if ok[i] { x } else { 0.0 };
                }
            }
            s[r.clone()].copy_from_slice(&buf[0][..len]);
            if let Some(ds) = ds.as_deref_mut() {
                for u in 0..nq {
                    ds[u * n + start..u * n + start + len].copy_from_slice(&buf[1 + u][..len]);
                }
            }
            start += len;
        }
    }
}

macro_rules! ggx_lobe {
    ($lobe:ident, $name:literal, $fresnel:ty, $aniso:expr, $masking:expr, $doc:literal) => {
        #[doc = $doc]
        #[derive(Clone, Debug, PartialEq)]
        pub struct $lobe;
        impl Lobe for $lobe {
            const NAME: &'static str = $name;
            const BATCH_IS_EXACT: bool = true;
            fn specs() -> Vec<ParamSpec> {
                let mut s = width_specs($aniso);
                s.extend(<$fresnel>::specs());
                s
            }
            fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
                ggx_shape::<$fresnel>(q, l, v, dq, $aniso, $masking)
            }
            fn shape_batch(
                q: &[f64],
                pairs: &DirPairs,
                geom: &PairGeometry,
                s: &mut [f64],
                ds: Option<&mut [f64]>,
            ) {
                ggx_shape_batch::<
                    $fresnel,
                    { $aniso },
                    { matches!($masking, Masking::HeightCorrelated) },
                >(q, pairs, geom, s, ds)
            }
        }
    };
}

use Masking::{HeightCorrelated as Hc, Separable as Sep};

ggx_lobe!(
    GgxLobe,
    "ggx",
    SchlickF0,
    false,
    Hc,
    "Isotropic GGX, height-correlated Smith, Schlick `F`."
);
ggx_lobe!(
    GgxSeparableLobe,
    "ggx-separable",
    SchlickF0,
    false,
    Sep,
    "Isotropic GGX, separable Smith, Schlick `F`."
);
ggx_lobe!(
    GgxAnisoLobe,
    "ggx-aniso",
    SchlickF0,
    true,
    Hc,
    "Anisotropic GGX, height-correlated Smith, Schlick `F`."
);
ggx_lobe!(
    GgxAnisoSeparableLobe,
    "ggx-aniso-separable",
    SchlickF0,
    true,
    Sep,
    "Anisotropic GGX, separable Smith, Schlick `F`."
);
ggx_lobe!(
    GgxDielectricLobe,
    "ggx-dielectric",
    Dielectric,
    false,
    Hc,
    "Isotropic GGX, height-correlated Smith, exact dielectric `F`."
);
ggx_lobe!(
    GgxDielectricSeparableLobe,
    "ggx-dielectric-separable",
    Dielectric,
    false,
    Sep,
    "Isotropic GGX, separable Smith, exact dielectric `F`."
);
ggx_lobe!(
    GgxDielectricAnisoLobe,
    "ggx-dielectric-aniso",
    Dielectric,
    true,
    Hc,
    "Anisotropic GGX, height-correlated Smith, exact dielectric `F`."
);
ggx_lobe!(
    GgxDielectricAnisoSeparableLobe,
    "ggx-dielectric-aniso-separable",
    Dielectric,
    true,
    Sep,
    "Anisotropic GGX, separable Smith, exact dielectric `F`."
);
ggx_lobe!(
    GgxConductorLobe,
    "ggx-conductor",
    Conductor,
    false,
    Hc,
    "Isotropic GGX, height-correlated Smith, exact conductor `F`."
);
ggx_lobe!(
    GgxConductorSeparableLobe,
    "ggx-conductor-separable",
    Conductor,
    false,
    Sep,
    "Isotropic GGX, separable Smith, exact conductor `F`."
);
ggx_lobe!(
    GgxConductorAnisoLobe,
    "ggx-conductor-aniso",
    Conductor,
    true,
    Hc,
    "Anisotropic GGX, height-correlated Smith, exact conductor `F`."
);
ggx_lobe!(
    GgxConductorAnisoSeparableLobe,
    "ggx-conductor-aniso-separable",
    Conductor,
    true,
    Sep,
    "Anisotropic GGX, separable Smith, exact conductor `F`."
);

/// Lambert plus `K` isotropic GGX lobes (height-correlated Smith, Schlick).
pub type Ggx = MultiLobe<GgxLobe>;
/// Lambert plus `K` isotropic GGX lobes (separable Smith, Schlick).
pub type GgxSeparable = MultiLobe<GgxSeparableLobe>;
/// Lambert plus an anisotropic GGX lobe (height-correlated, Schlick).
pub type GgxAniso = DiffuseLobe<GgxAnisoLobe>;
/// Lambert plus an anisotropic GGX lobe (separable, Schlick).
pub type GgxAnisoSeparable = DiffuseLobe<GgxAnisoSeparableLobe>;
/// Lambert plus an isotropic GGX lobe with dielectric `F` (height-correlated).
pub type GgxDielectric = DiffuseLobe<GgxDielectricLobe>;
/// Lambert plus an isotropic GGX lobe with dielectric `F` (separable).
pub type GgxDielectricSeparable = DiffuseLobe<GgxDielectricSeparableLobe>;
/// Lambert plus an anisotropic GGX lobe with dielectric `F` (height-correlated).
pub type GgxDielectricAniso = DiffuseLobe<GgxDielectricAnisoLobe>;
/// Lambert plus an anisotropic GGX lobe with dielectric `F` (separable).
pub type GgxDielectricAnisoSeparable = DiffuseLobe<GgxDielectricAnisoSeparableLobe>;
/// Lambert plus an isotropic GGX lobe with conductor `F` (height-correlated).
pub type GgxConductor = DiffuseLobe<GgxConductorLobe>;
/// Lambert plus an isotropic GGX lobe with conductor `F` (separable).
pub type GgxConductorSeparable = DiffuseLobe<GgxConductorSeparableLobe>;
/// Lambert plus an anisotropic GGX lobe with conductor `F` (height-correlated).
pub type GgxConductorAniso = DiffuseLobe<GgxConductorAnisoLobe>;
/// Lambert plus an anisotropic GGX lobe with conductor `F` (separable).
pub type GgxConductorAnisoSeparable = DiffuseLobe<GgxConductorAnisoSeparableLobe>;

#[cfg(test)]
mod tests {
    use super::*;

    /// `S::shape_batch` (the vectorised chunks) gives [`Lobe::shape`]'s
    /// value and derivatives pair by pair, to the bit, over pairs on both
    /// sides of the horizon and random points of the lobe's box.
    fn assert_batch_bits<S: Lobe>(state: &mut u64) {
        let mut uniform = || {
            *state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (*state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut pairs = DirPairs::with_capacity(200);
        for _ in 0..200 {
            let mut dir = || {
                let z = (1.6 * uniform() - 0.3).clamp(-1.0, 1.0);
                let r = (1.0 - z * z).sqrt();
                let phi = std::f64::consts::TAU * uniform();
                Vector3::new(r * phi.cos(), r * phi.sin(), z)
            };
            let (l, v) = (dir(), dir());
            pairs.push(&l, &v);
        }
        let geom = PairGeometry::new(&pairs);
        let specs = S::specs();
        let (n, nq) = (pairs.len(), specs.len());
        for _ in 0..10 {
            let q: Vec<f64> = specs
                .iter()
                .map(|s| s.lower + (s.upper - s.lower) * uniform())
                .collect();
            let (mut s, mut ds) = (vec![f64::NAN; n], vec![f64::NAN; nq * n]);
            S::shape_batch(&q, &pairs, &geom, &mut s, Some(&mut ds));
            let mut only = vec![f64::NAN; n];
            S::shape_batch(&q, &pairs, &geom, &mut only, None);
            for j in 0..n {
                let mut dq = vec![0.0; nq];
                let (x, y) = if geom.valid[j] {
                    let l = pairs.l(j);
                    let v = pairs.v(j);
                    (
                        S::shape(&q, &l, &v, Some(&mut dq)),
                        S::shape(&q, &l, &v, None),
                    )
                } else {
                    (0.0, 0.0)
                };
                assert_eq!(s[j].to_bits(), x.to_bits(), "{} pair {j}", S::NAME);
                assert_eq!(only[j].to_bits(), y.to_bits(), "{} value only", S::NAME);
                for u in 0..nq {
                    assert_eq!(ds[u * n + j].to_bits(), dq[u].to_bits(), "{} d{u}", S::NAME);
                }
            }
        }
    }

    /// Renders of the GGX models (one lobe, two lobes) take the batch
    /// kernel and give what `eval` gives pair by pair.
    #[test]
    fn renders_give_the_bits_of_single_pairs() {
        use crate::combinators::assert_renders_as_pair_by_pair;
        use brdf_core::Parametric;
        let mut pairs = DirPairs::with_capacity(0);
        let dir = |t: f64, f: f64| Vector3::new(t.sin() * f.cos(), t.sin() * f.sin(), t.cos());
        for i in 0..40 {
            // Every fifth pair with one direction below the horizon.
            let below = if i % 5 == 0 { 1.7 } else { 0.0 };
            pairs.push(
                &dir(0.04 * i as f64 + below, 0.3 * i as f64),
                &dir(1.5 - 0.035 * i as f64, 2.0),
            );
        }
        pairs.push(&Vector3::z(), &Vector3::z());
        let one = GgxAniso::new(&[0.2, 0.3], &[0.7, 0.1], &[0.25, 0.1, 0.3]).expect("ggx");
        assert_renders_as_pair_by_pair(&one, &pairs);
        let mut two = Ggx::new(2, 2).expect("two lobes");
        two.set_params(&[0.2, 0.3, 0.5, 0.4, 0.3, 0.8, 0.2, 0.1, 0.05, 0.6])
            .expect("params");
        assert_renders_as_pair_by_pair(&two, &pairs);
    }

    #[test]
    fn batches_give_the_bits_of_single_pairs() {
        let mut state = 0x6667_u64;
        assert_batch_bits::<GgxLobe>(&mut state);
        assert_batch_bits::<GgxSeparableLobe>(&mut state);
        assert_batch_bits::<GgxAnisoLobe>(&mut state);
        assert_batch_bits::<GgxAnisoSeparableLobe>(&mut state);
        assert_batch_bits::<GgxDielectricLobe>(&mut state);
        assert_batch_bits::<GgxDielectricSeparableLobe>(&mut state);
        assert_batch_bits::<GgxDielectricAnisoLobe>(&mut state);
        assert_batch_bits::<GgxDielectricAnisoSeparableLobe>(&mut state);
        assert_batch_bits::<GgxConductorLobe>(&mut state);
        assert_batch_bits::<GgxConductorSeparableLobe>(&mut state);
        assert_batch_bits::<GgxConductorAnisoLobe>(&mut state);
        assert_batch_bits::<GgxConductorAnisoSeparableLobe>(&mut state);
    }
}
