//! The thin-film model itself: its parameter layout and the per-pair kernel
//! shared by values and derivatives.

use std::f64::consts::FRAC_1_PI;

use brdf_core::fresnel::fresnel_dielectric_d_eta;
use brdf_core::params::per_channel_specs;
use brdf_core::{DirPairs, ParamError, ParamSpec, Parametric};
use nalgebra::Vector3;

use super::table::{FilmFormula, FilmTable, TableCache};
use crate::coloured_lobes::ALPHA_MIN;
use crate::coloured_lobes::compensation;
use crate::coloured_lobes::geometry::LobeGeometry;
use crate::ggx::Masking;

/// Thickest film the box allows, in nm: interference colours fade into
/// white beyond about a micrometre, and fringes repeat about every 150 nm.
pub const THICKNESS_MAX: f64 = 1500.0;

/// Lambert plus one GGX lobe whose Fresnel is a thin film's over a
/// dielectric base, plus an optional white dielectric coat lobe (see the
/// module documentation of [`crate::thin_film`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ThinFilm {
    name: &'static str,
    channels: usize,
    coat: bool,
    renderer: FilmRenderer,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
    tables: TableCache,
}

/// The renderer whose evaluation of the film lobe the model is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilmRenderer {
    /// Cycles: the spectral Airy reflectance, single-scattering GGX.
    Cycles,
    /// MaterialX: its two-order series ([`super::materialx_airy`]) and its
    /// GGX energy compensation on the film lobe and the coat
    /// ([`crate::coloured_lobes::compensation`]).
    MaterialX,
}

/// Where the parameters after the diffuse colour sit, counted from the
/// channel count `nc`.
struct Layout;

impl Layout {
    const WEIGHT: usize = 0;
    const ALPHA: usize = 1;
    const THICKNESS: usize = 2;
    const FILM_IOR: usize = 3;
    const BASE_IOR: usize = 4;
    const COAT_IOR: usize = 5;
    const COAT_ALPHA: usize = 6;
}

fn spec(
    name: &str,
    meaning: &str,
    lower: f64,
    upper: f64,
    default: f64,
    linear: bool,
) -> ParamSpec {
    ParamSpec::new(name, meaning, lower, upper, default, linear)
}

impl ThinFilm {
    /// A model named `name` with `channels` colour channels (1 or 3) and the
    /// coat lobe if `coat`, at its default parameters.
    pub fn new(name: &'static str, channels: usize, coat: bool) -> Result<Self, ParamError> {
        if channels != 1 && channels != 3 {
            return Err(ParamError::Config {
                model: name.to_string(),
                reason: format!("takes 1 (luminance) or 3 (RGB) channels, not {channels}"),
            });
        }
        let mut specs = per_channel_specs("kd", "diffuse albedo", channels, 0.0, 1.0, 0.3);
        specs.extend([
            spec("w", "weight of the film lobe", 0.0, 1.0, 1.0, true),
            spec(
                "alpha",
                "GGX width of the film lobe",
                ALPHA_MIN,
                1.0,
                0.1,
                false,
            ),
            spec(
                "film_d",
                "film thickness in nm",
                0.0,
                THICKNESS_MAX,
                250.0,
                false,
            ),
            spec(
                "film_ior",
                "index of refraction of the film",
                1.05,
                5.0,
                1.6,
                false,
            ),
            spec(
                "base_ior",
                "index of refraction of the base",
                1.05,
                5.0,
                1.5,
                false,
            ),
        ]);
        if coat {
            specs.extend([
                spec(
                    "coat_ior",
                    "index of refraction of the coat",
                    1.2,
                    2.0,
                    1.5,
                    false,
                ),
                spec(
                    "coat_alpha",
                    "GGX width of the coat",
                    ALPHA_MIN,
                    1.0,
                    0.05,
                    false,
                ),
            ]);
        }
        let params = specs.iter().map(|s| s.default).collect();
        Ok(ThinFilm {
            name,
            channels,
            coat,
            renderer: FilmRenderer::Cycles,
            specs,
            params,
            tables: TableCache::default(),
        })
    }

    /// The model as `renderer` evaluates it.
    pub fn for_renderer(mut self, renderer: FilmRenderer) -> Self {
        self.renderer = renderer;
        self
    }

    /// The renderer whose film the model is.
    pub fn renderer(&self) -> FilmRenderer {
        self.renderer
    }

    /// The model with parameters `p` (checked against the box).
    pub fn with_params(mut self, p: &[f64]) -> Result<Self, ParamError> {
        self.set_params(p)?;
        Ok(self)
    }

    /// Whether the model has the dielectric coat lobe.
    pub fn has_coat(&self) -> bool {
        self.coat
    }

    /// Index of the film lobe's weight `w`; `alpha`, `film_d`, `film_ior`,
    /// `base_ior` (and `coat_ior`, `coat_alpha`) follow in that order.
    pub fn weight_index(&self) -> usize {
        self.channels
    }

    /// The film's table at parameters `p` (built once per parameter
    /// vector and shared).
    fn table(&self, p: &[f64]) -> std::sync::Arc<FilmTable> {
        let at = |k: usize| self.channels + k;
        self.tables.get(
            p[at(Layout::THICKNESS)],
            p[at(Layout::FILM_IOR)],
            p[at(Layout::BASE_IOR)],
            self.channels,
            match self.renderer {
                FilmRenderer::Cycles => FilmFormula::Spectral,
                FilmRenderer::MaterialX => FilmFormula::MaterialX,
            },
        )
    }

    /// The lobes' widths and the coat's index, read once per batch.
    fn widths(&self, p: &[f64]) -> Widths {
        let at = |k: usize| self.channels + k;
        let coat = |k: usize| if self.coat { p[at(k)] } else { 0.0 };
        Widths {
            alpha: p[at(Layout::ALPHA)],
            coat_alpha: coat(Layout::COAT_ALPHA),
            coat_ior: coat(Layout::COAT_IOR),
            coat: self.coat,
            compensated: self.renderer == FilmRenderer::MaterialX,
        }
    }

    /// The per-pair kernel, with `table` the film's at `p`: channel `c`'s
    /// value into `out[c * os]` and, with `grad = Some((g, gs))`, its
    /// gradient into `g[c * gs..c * gs + np]`. 0 (and a zero gradient)
    /// below the horizon.
    #[inline]
    fn kernel(
        &self,
        p: &[f64],
        table: &FilmTable,
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: (&mut [f64], usize),
        grad: Option<(&mut [f64], usize)>,
    ) {
        let terms = LobeGeometry::new(l, v).map(|geo| self.widths(p).terms(&geo));
        self.combine(p, table, terms.as_ref(), out, grad);
    }

    /// The film's colour at the pair's `cos_d` and the pair's `terms`
    /// (`None` below the horizon) combined into each channel's value and
    /// gradient (as [`ThinFilm::kernel`] says).
    #[inline(always)]
    fn combine(
        &self,
        p: &[f64],
        table: &FilmTable,
        terms: Option<&Terms>,
        (out, os): (&mut [f64], usize),
        mut grad: Option<(&mut [f64], usize)>,
    ) {
        let (nc, np) = (self.channels, self.specs.len());
        if let Some((g, gs)) = grad.as_mut() {
            for c in 0..nc {
                g[c * *gs..c * *gs + np].fill(0.0);
            }
        }
        let Some(t) = terms else {
            for c in 0..nc {
                out[c * os] = 0.0;
            }
            return;
        };
        let at = |k: usize| nc + k;
        let w = p[at(Layout::WEIGHT)];
        let (s, ds, k, dk) = (t.s, t.ds, t.k, t.dk);
        let film = table.at(t.cos_d);
        for c in 0..nc {
            // MaterialX's compensation turns the film's colour A into
            // A (1 + A k); without it k = 0.
            let a = film.value[c];
            let ac = a * (1.0 + a * k);
            let mut value = p[c] * FRAC_1_PI + w * ac * s;
            if self.coat {
                value += t.cw * t.cs;
            }
            out[c * os] = value;
            let Some((g, gs)) = grad.as_mut() else {
                continue;
            };
            let row = &mut g[c * *gs..c * *gs + np];
            row[c] = FRAC_1_PI;
            row[at(Layout::WEIGHT)] = ac * s;
            row[at(Layout::ALPHA)] = w * ac * ds + w * a * a * dk * s;
            let dac = 1.0 + 2.0 * a * k;
            for (j, da) in film.grad[c].iter().enumerate() {
                row[at(Layout::THICKNESS + j)] = w * s * da * dac;
            }
            if self.coat {
                row[at(Layout::COAT_IOR)] = t.dcw * t.cs;
                row[at(Layout::COAT_ALPHA)] = t.d_alpha;
            }
        }
    }
}

/// The parameters the per-pair terms need, read once per batch.
#[derive(Clone, Copy)]
struct Widths {
    alpha: f64,
    coat_alpha: f64,
    coat_ior: f64,
    coat: bool,
    compensated: bool,
}

/// What one pair contributes before the film's colour: the Fresnel cosine,
/// the film lobe's shape `S`, `dS/d alpha`, its compensation excess `k`,
/// `dk/d alpha`; the coat's weight `F (1 + F k)`, its index derivative,
/// its shape and its width derivative (0 without a coat).
#[derive(Clone, Copy, Default)]
struct Terms {
    cos_d: f64,
    s: f64,
    ds: f64,
    k: f64,
    dk: f64,
    cw: f64,
    dcw: f64,
    cs: f64,
    d_alpha: f64,
}

impl Widths {
    /// MaterialX's `(k, dk/d alpha)` for a lobe of width `alpha` at this
    /// pair, `(0, 0)` for Cycles.
    #[inline(always)]
    fn excess(&self, geo: &LobeGeometry, alpha: f64) -> (f64, f64) {
        compensation::excess_if(self.compensated, geo.cos_first, alpha)
    }

    /// The pair's [`Terms`] (branch-free, so a batch vectorises it).
    #[inline(always)]
    fn terms(&self, geo: &LobeGeometry) -> Terms {
        let (s, ds) = geo.lobe(self.alpha, Masking::HeightCorrelated);
        let (k, dk) = self.excess(geo, self.alpha);
        let mut t = Terms {
            cos_d: geo.cos_d,
            s,
            ds,
            k,
            dk,
            ..Terms::default()
        };
        if self.coat {
            let (cs, cds) = geo.lobe(self.coat_alpha, Masking::HeightCorrelated);
            let (f, df) = fresnel_dielectric_d_eta(geo.cos_d, self.coat_ior);
            // The coat's weight F (1 + F k) and its derivatives (as the
            // film's).
            let (ck, cdk) = self.excess(geo, self.coat_alpha);
            let cw = f * (1.0 + f * ck);
            t.cw = cw;
            t.dcw = df * (1.0 + 2.0 * f * ck);
            t.cs = cs;
            t.d_alpha = cds * cw + cs * f * f * cdk;
        }
        t
    }
}

/// Pairs per chunk of the batch.
const CHUNK: usize = 64;

/// [`Terms`] of a chunk, field by field (so the loop that fills them
/// vectorises), and whether the pair is above the horizon.
struct TermsChunk {
    above: [bool; CHUNK],
    f: [[f64; CHUNK]; 9],
}

impl TermsChunk {
    fn new() -> Box<Self> {
        Box::new(TermsChunk {
            above: [false; CHUNK],
            f: [[0.0; CHUNK]; 9],
        })
    }

    #[inline(always)]
    fn set(&mut self, i: usize, above: bool, t: Terms) {
        self.above[i] = above;
        let v = [t.cos_d, t.s, t.ds, t.k, t.dk, t.cw, t.dcw, t.cs, t.d_alpha];
        for (f, x) in self.f.iter_mut().zip(v) {
            f[i] = x;
        }
    }

    #[inline(always)]
    fn at(&self, i: usize) -> Terms {
        let f = |k: usize| self.f[k][i];
        Terms {
            cos_d: f(0),
            s: f(1),
            ds: f(2),
            k: f(3),
            dk: f(4),
            cw: f(5),
            dcw: f(6),
            cs: f(7),
            d_alpha: f(8),
        }
    }
}

/// The batch of one call (values, and with `jac` derivatives, in the
/// batch layout): each chunk's [`Terms`] computed together, inlined into
/// `pulp`'s target-feature function so that the loop vectorises (the
/// square roots and divisions of the lobes and the coat's Fresnel; lanes
/// round as the scalar code, never fused: the per-pair kernel's bits,
/// tested); the film's table and the channels then pair by pair.
struct Batch<'a> {
    model: &'a ThinFilm,
    p: &'a [f64],
    pairs: &'a DirPairs,
    out: &'a mut [f64],
    jac: Option<&'a mut [f64]>,
}

impl pulp::WithSimd for Batch<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let Batch {
            model,
            p,
            pairs,
            out,
            mut jac,
        } = self;
        let (n, np) = (pairs.len(), model.specs.len());
        let (table, widths) = (model.table(p), model.widths(p));
        let mut terms = TermsChunk::new();
        let mut start = 0;
        while start < n {
            let len = CHUNK.min(n - start);
            let pc = pairs.chunk(start, len);
            for i in 0..len {
                let (l, v) = pc.at(i);
                terms.set(
                    i,
                    l.z > 0.0 && v.z > 0.0,
                    widths.terms(&LobeGeometry::unchecked(&l, &v)),
                );
            }
            for i in 0..len {
                let j = start + i;
                let t = terms.above[i].then(|| terms.at(i));
                let t = t.as_ref();
                let grad = jac.as_deref_mut().map(|g| (&mut g[j * np..], n * np));
                model.combine(p, &table, t, (&mut out[j..], n), grad);
            }
            start += len;
        }
    }
}

brdf_core::impl_brdf_via_params!(ThinFilm);

impl Parametric for ThinFilm {
    fn name(&self) -> &str {
        self.name
    }

    brdf_core::param_accessors!();

    fn is_reciprocal(&self) -> bool {
        // MaterialX's compensation depends on the first direction alone.
        self.renderer == FilmRenderer::Cycles
    }

    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.kernel(p, &self.table(p), l, v, (out, 1), None);
    }

    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        let np = self.specs.len();
        self.kernel(p, &self.table(p), l, v, (out, 1), Some((grad, np)));
    }

    fn eval_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64]) {
        pulp::Arch::new().dispatch(Batch {
            model: self,
            p,
            pairs,
            out,
            jac: None,
        });
    }

    fn eval_grad_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64], jac: &mut [f64]) {
        // Layout: out[c * n + j], jac[(c * n + j) * np + k].
        pulp::Arch::new().dispatch(Batch {
            model: self,
            p,
            pairs,
            out,
            jac: Some(jac),
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The batch (its terms computed chunk by chunk, vectorised) gives the
    /// per-pair kernel's values and derivatives to the bit, for both
    /// renderers' films, with and without the coat, one and three
    /// channels, at random points of the box and pairs on both sides of
    /// the horizon.
    #[test]
    fn batch_gives_the_bits_of_the_per_pair_kernel() {
        let mut state = 0xf11f_u64;
        let mut uniform = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut pairs = DirPairs::with_capacity(150);
        for _ in 0..150 {
            let mut dir = || {
                let z = (1.6 * uniform() - 0.3).clamp(-1.0, 1.0);
                let r = (1.0 - z * z).sqrt();
                let phi = std::f64::consts::TAU * uniform();
                Vector3::new(r * phi.cos(), r * phi.sin(), z)
            };
            let (l, v) = (dir(), dir());
            pairs.push(&l, &v);
        }
        let n = pairs.len();
        for renderer in [FilmRenderer::Cycles, FilmRenderer::MaterialX] {
            for (nc, coat) in [(1, false), (3, false), (3, true)] {
                let m = ThinFilm::new("test", nc, coat)
                    .expect("a valid layout")
                    .for_renderer(renderer);
                let p: Vec<f64> = m
                    .param_specs()
                    .iter()
                    .map(|s| s.lower + (s.upper - s.lower) * uniform())
                    .collect();
                let np = p.len();
                let (mut out, mut jac) = (vec![0.0; nc * n], vec![f64::NAN; nc * n * np]);
                m.eval_grad_batch_at(&p, &pairs, &mut out, &mut jac);
                let mut values = vec![f64::NAN; nc * n];
                m.eval_batch_at(&p, &pairs, &mut values);
                let (mut f, mut g) = (vec![0.0; nc], vec![0.0; nc * np]);
                for j in 0..n {
                    m.eval_grad_at(&p, &pairs.l(j), &pairs.v(j), &mut f, &mut g);
                    for c in 0..nc {
                        let i = c * n + j;
                        assert_eq!(out[i].to_bits(), f[c].to_bits(), "pair {j}");
                        assert_eq!(values[i].to_bits(), f[c].to_bits(), "value only");
                        for k in 0..np {
                            let (a, b) = (jac[i * np + k], g[c * np + k]);
                            assert_eq!(a.to_bits(), b.to_bits(), "d/dp{k} pair {j}");
                        }
                    }
                }
            }
        }
    }
}
