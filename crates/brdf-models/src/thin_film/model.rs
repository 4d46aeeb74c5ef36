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

    /// MaterialX's `(k, dk/d alpha)` for a lobe of width `alpha` at this
    /// pair, `(0, 0)` for Cycles.
    #[inline]
    fn excess(&self, geo: &LobeGeometry, alpha: f64) -> (f64, f64) {
        match self.renderer {
            FilmRenderer::Cycles => (0.0, 0.0),
            FilmRenderer::MaterialX => compensation::excess(geo.cos_first, alpha),
        }
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
        (out, os): (&mut [f64], usize),
        mut grad: Option<(&mut [f64], usize)>,
    ) {
        let (nc, np) = (self.channels, self.specs.len());
        if let Some((g, gs)) = grad.as_mut() {
            for c in 0..nc {
                g[c * *gs..c * *gs + np].fill(0.0);
            }
        }
        let Some(geo) = LobeGeometry::new(l, v) else {
            for c in 0..nc {
                out[c * os] = 0.0;
            }
            return;
        };
        let at = |k: usize| nc + k;
        let w = p[at(Layout::WEIGHT)];
        let alpha = p[at(Layout::ALPHA)];
        let (s, ds) = geo.lobe(alpha, Masking::HeightCorrelated);
        let (k, dk) = self.excess(&geo, alpha);
        let film = table.at(geo.cos_d);
        let coat = self.coat.then(|| {
            let coat_alpha = p[at(Layout::COAT_ALPHA)];
            let (cs, cds) = geo.lobe(coat_alpha, Masking::HeightCorrelated);
            let (f, df) = fresnel_dielectric_d_eta(geo.cos_d, p[at(Layout::COAT_IOR)]);
            // The coat's weight F (1 + F k) and its derivatives (as the
            // film's below).
            let (ck, cdk) = self.excess(&geo, coat_alpha);
            let cw = f * (1.0 + f * ck);
            (
                cw,
                df * (1.0 + 2.0 * f * ck),
                cs,
                cds * cw + cs * f * f * cdk,
            )
        });
        for c in 0..nc {
            // MaterialX's compensation turns the film's colour A into
            // A (1 + A k); without it k = 0.
            let a = film.value[c];
            let ac = a * (1.0 + a * k);
            let mut value = p[c] * FRAC_1_PI + w * ac * s;
            if let Some((cw, _, cs, _)) = coat {
                value += cw * cs;
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
            if let Some((_, dcw, cs, d_alpha)) = coat {
                row[at(Layout::COAT_IOR)] = dcw * cs;
                row[at(Layout::COAT_ALPHA)] = d_alpha;
            }
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
        let (n, table) = (pairs.len(), self.table(p));
        for j in 0..n {
            self.kernel(
                p,
                &table,
                &pairs.l(j),
                &pairs.v(j),
                (&mut out[j..], n),
                None,
            );
        }
    }

    fn eval_grad_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64], jac: &mut [f64]) {
        // Layout: out[c * n + j], jac[(c * n + j) * np + k].
        let (n, np, table) = (pairs.len(), self.specs.len(), self.table(p));
        for j in 0..n {
            self.kernel(
                p,
                &table,
                &pairs.l(j),
                &pairs.v(j),
                (&mut out[j..], n),
                Some((&mut jac[j * np..], n * np)),
            );
        }
    }
}
