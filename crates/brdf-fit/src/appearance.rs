//! Fits that look like the material: image errors of a fit, and the fit
//! chosen by them.
//!
//! A lookdev user judges a fit by its render. For data that can be
//! evaluated at any direction pair (RGL `.bsdf`, MERL `.binary`), the fit
//! and the data are rendered by `brdf-render` on the judge sphere under
//! the standard light sets (`sky`: clear sky and sun; `studio`: a dim
//! surround and a square key light), and compared by HDR-FLIP, PSNR and
//! the CIEDE2000 difference of the mean sphere colours ([`ImageError`]).
//!
//! [`fit_for_appearance`] fits the candidates of a renderer model under
//! several objectives (Ngan's L2, log, Forés' cube root), keeps the one
//! with the least image error (mean FLIP over the light sets), and refines
//! it (and the other candidates: the objective has several basins) in the
//! image objective ([`crate::image_objective`]): Bieron and Peers
//! (2020) chose among BRDF-space fits by image error; the refinement fits
//! the pixels themselves. Lobes the data may not need (sheen, clear coat,
//! anisotropy, transmission) are first switched off (anisotropy is not
//! tried at all on isotropic data); a model with them is
//! kept only when its image error is lower by [`LOBE_MARGIN`] (nested
//! models), so no fit parks parameters on bounds to mimic a grazing tail.
//! Each lobe is tried twice: in the BRDF-space objective that won, and
//! after the refinement in the image objective, where a lobe must pay in
//! the render itself. Lobes that pay only together (paper_white's sheen
//! and clear coat) are tried together, in BRDF space under each objective.
//!
//! Each of these stages (the base candidates, the single lobes, the lobes
//! together, the refinements, the lobes in the image objective) fits its
//! candidates in parallel, then decides in their fixed order: the choice
//! and every candidate are the same for any thread count.
//!
//! What no fit of a renderer model can do is said too: every lobe of
//! `principled` and `gltf` is white or the base colour, so under the white
//! studio light all their colours lie in one plane of white and one colour.
//! [`ImageError::colour_plane`] gives how much of the data's render lies off
//! the closest such plane ([`DataColourPlane`], a lower bound on any such
//! fit's difference), and a fit of those models whose data lie further off
//! than [`COLOUR_PLANE_NOTE`] carries a note saying so
//! ([`colour_plane_note`]): the colour-shifting films, whose highlight and
//! rim are other hues than their body.
//!
//! Thresholds of the plain-words warnings ([`ImageError::warnings`]):
//! mean-colour CIEDE2000 above [`DELTA_E_WARN`] (a colour difference an
//! observer names at a glance; 2.3 is a just-noticeable difference) and
//! HDR-FLIP above [`FLIP_WARN`] (two renders of the same measurement with
//! different noise differ by 0.02-0.05; the films' default fits before
//! this module were at 0.3-0.6).

use std::sync::Arc;
use std::time::Instant;

use brdf_core::{Brdf, DirPairs, SampleSet};
use brdf_render::flip::FlipMap;
use brdf_render::{Image, LightSet, ShadingPoints};
use serde::Serialize;

use crate::image_objective::{ImageTarget, ImageTerms};
use crate::reference::Reference;
use crate::{Fit, FitError, FitReport, Objective};

/// Mean-colour CIEDE2000 above which a report warns.
pub const DELTA_E_WARN: f64 = 5.0;
/// HDR-FLIP above which a report warns.
pub const FLIP_WARN: f64 = 0.15;
/// Relative FLIP improvement an optional lobe must bring to be kept.
pub const LOBE_MARGIN: f64 = 0.05;
/// Objectives whose lobe-less candidate renders more than this many times
/// the best one's mean FLIP are not tried with every lobe on: on the films
/// (cc_ibiza_sunset, cc_iris_purple_gem, vch_golden_yellow) the Ngan and
/// log candidates render at 1.48-2.4 times the cube-root one's (32 px),
/// their many-lobe fits took up to 2.7 s each and none came near the
/// winner; on paper_white the Ngan candidate, at 1.25 times, is the one
/// whose lobes win.
pub const PAIR_REACH: f64 = 1.4;
/// Largest growth of Ngan's L2 an image-objective refinement may bring
/// (against the best BRDF-space candidate's). Measured: the rough clear
/// coat that renders vch_golden_yellow at sky FLIP 0.256 instead of 0.279
/// (32 px) raises Ngan's L2 1.57 times (the peak it misses is a few
/// samples; most of the sphere is the body it matches). The base
/// refinements of the five RGL files stay below 1.5.
pub const REFINE_L2_GROWTH: f64 = 2.0;
/// Image size of the image errors in reports (the judge's film).
pub const REPORT_SIZE: usize = 128;
/// Image size of the image objective and of the candidate ranking.
pub const FIT_SIZE: usize = 32;

/// The image errors of a fit under one light set.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct LightError {
    /// Light set name.
    pub light: String,
    /// Mean HDR-FLIP over the image (0: identical).
    pub flip: f64,
    /// PSNR (dB) after the data's exposure, clip, gamma 2.2.
    pub psnr: f64,
    /// CIEDE2000 between the mean sphere colours.
    pub delta_e: f64,
    /// Mean linear RGB of the data's sphere.
    pub mean_colour_data: [f64; 3],
    /// Mean linear RGB of the fit's sphere.
    pub mean_colour_fit: [f64; 3],
    /// Exposure `1 / p99` of the data's render.
    pub exposure: f64,
}

/// The image errors of a fit under the standard light sets.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct ImageError {
    /// Image size (pixels per side).
    pub size: usize,
    /// One entry per light set.
    pub lights: Vec<LightError>,
    /// The data's colours against the planes of white and one colour,
    /// under the first white light set ([`DataColourPlane`]); `None` when
    /// no light set is white or the data's render is black.
    pub colour_plane: Option<DataColourPlane>,
}

/// How far the data's render under a white light set lies from every
/// plane of white and one colour ([`brdf_render::colour_plane`]): no fit
/// of a model that colours every lobe white or by its one base colour
/// ([`is_single_colour_model`]) renders closer to it than `outside`.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct DataColourPlane {
    /// The white light set it was measured under.
    pub light: String,
    /// The closest plane's colour (linear RGB, largest channel 1).
    pub colour: [f64; 3],
    /// RMS distance of the data's sphere colours from that plane over
    /// their RMS (linear RGB): the least relative RMS difference any render
    /// of a single-colour model can have.
    pub outside: f64,
}

/// `outside` of [`DataColourPlane`] above which a fit of a single-colour
/// model carries a note that its colours cannot match. Measured
/// (`results/colour_planes.md`, 128 px, studio): paper_white 0.0005,
/// colodur_napoli 0.0016, vch_golden_yellow 0.0100, cc_iris_purple_gem
/// 0.0205, cc_ibiza_sunset 0.0360. Moving every pixel of the measurement's
/// own Mitsuba render (studio) to the nearest colour of the best plane (in
/// FLIP's linear opponent space) renders at HDR-FLIP 0.036 (golden yellow),
/// 0.180 (iris) and 0.156 (ibiza) against the unmoved render before any
/// error of shape: beyond 0.015 the colours alone cost a film most of what
/// its fits show (their default fits: 0.185, 0.230, 0.216).
pub const COLOUR_PLANE_NOTE: f64 = 0.015;

/// Whether every lobe of catalogue model `name` is coloured white or by its
/// one base colour (so its renders under white light keep to one plane of
/// colours): `principled` (diffuse, sheen, tinted and metallic Fresnel,
/// clear coat) and `gltf` (diffuse, dielectric and metal Fresnel). Not
/// `gltf-ext` (its specular colour is a second colour) nor the GGX family
/// (a diffuse and a specular colour per channel).
pub fn is_single_colour_model(name: &str) -> bool {
    matches!(name, "principled" | "gltf")
}

/// The note of a fit of single-colour model `model` whose data lie off
/// every colour plane by more than [`COLOUR_PLANE_NOTE`].
pub fn colour_plane_note(model: &str, e: &ImageError) -> Option<String> {
    let c = e.colour_plane.as_ref()?;
    if !is_single_colour_model(model) || c.outside <= COLOUR_PLANE_NOTE {
        return None;
    }
    Some(format!(
        "the data's hue changes across the sphere: under the {} light {:.1}% (RMS) of its rendered colour lies off every plane of white and one colour; each `{model}` lobe is white or the base colour, so every `{model}` render lies in such a plane and none comes closer; models with a second colour can",
        c.light,
        100.0 * c.outside
    ))
}

impl ImageError {
    /// Mean FLIP over the light sets (the ranking of candidates).
    pub fn mean_flip(&self) -> f64 {
        self.lights.iter().map(|l| l.flip).sum::<f64>() / self.lights.len().max(1) as f64
    }

    /// Largest HDR-FLIP over the light sets.
    pub fn max_flip(&self) -> f64 {
        self.lights.iter().map(|l| l.flip).fold(0.0, f64::max)
    }

    /// Largest mean-colour difference over the light sets.
    pub fn max_delta_e(&self) -> f64 {
        self.lights.iter().map(|l| l.delta_e).fold(0.0, f64::max)
    }

    /// Plain-words warnings when the fit will not look like the data.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        for l in &self.lights {
            if l.delta_e > DELTA_E_WARN {
                out.push(format!(
                    "under the {} light the fit's colour differs visibly from the data's (CIEDE2000 {:.1} > {DELTA_E_WARN}): data mean RGB {}, fit {}",
                    l.light,
                    l.delta_e,
                    rgb(l.mean_colour_data, l.exposure),
                    rgb(l.mean_colour_fit, l.exposure)
                ));
            }
            if l.flip > FLIP_WARN {
                out.push(format!(
                    "under the {} light the fit renders unlike the data (FLIP {:.3} > {FLIP_WARN})",
                    l.light, l.flip
                ));
            }
        }
        out
    }
}

fn rgb(c: [f64; 3], exposure: f64) -> String {
    format!(
        "({:.2}, {:.2}, {:.2})",
        c[0] * exposure,
        c[1] * exposure,
        c[2] * exposure
    )
}

/// The standard light sets of reports and of the image objective.
pub fn standard_lights() -> Vec<LightSet> {
    vec![LightSet::sky(), LightSet::studio()]
}

/// Renders data and fits under the standard light sets and compares them
/// (the data rendered once, [`crate::reference`]).
pub struct Judge {
    size: usize,
    points: Arc<Vec<(LightSet, ShadingPoints)>>,
    /// The data's renders, one per light set, when made once
    /// ([`Judge::with_data`]).
    reference: Vec<Reference>,
}

impl Judge {
    /// The judge at `size x size` pixels (backgrounds shown, as the
    /// reference renderer's images; the terms are computed once).
    pub fn new(size: usize) -> Self {
        let points = Arc::new(
            standard_lights()
                .into_iter()
                .map(|l| {
                    let sp = ShadingPoints::judge_with_background(&l, size);
                    (l, sp)
                })
                .collect(),
        );
        Judge {
            size,
            points,
            reference: Vec::new(),
        }
    }

    /// Pixels per side of the judge's images.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Light sets the judge renders under.
    pub fn lights(&self) -> usize {
        self.points.len()
    }

    /// The judge with `data` rendered once, for [`Judge::fit_errors`] of
    /// many fits of the same data.
    pub fn with_data(size: usize, data: &dyn Brdf) -> Result<Self, FitError> {
        Judge::new(size).rendering(data)
    }

    /// This judge's terms (shared, not copied) with `data` rendered on
    /// them: one set of terms serves every material of a batch.
    pub fn rendering(&self, data: &dyn Brdf) -> Result<Self, FitError> {
        let reference = self
            .points
            .iter()
            .map(|(_, sp)| Reference::new(sp, data).map_err(|e| FitError::Usage(e.to_string())))
            .collect::<Result<_, _>>()?;
        Ok(Judge {
            size: self.size,
            points: Arc::clone(&self.points),
            reference,
        })
    }

    /// The image errors of `fit` against `data`.
    pub fn errors(&self, data: &dyn Brdf, fit: &dyn Brdf) -> Result<ImageError, FitError> {
        let refs = self
            .points
            .iter()
            .map(|(_, sp)| Reference::new(sp, data).map_err(|e| FitError::Usage(e.to_string())))
            .collect::<Result<Vec<_>, _>>()?;
        self.errors_against(&refs, fit)
    }

    /// The image errors of `fit` against the data of [`Judge::with_data`].
    pub fn fit_errors(&self, fit: &dyn Brdf) -> Result<ImageError, FitError> {
        self.errors_against(&self.reference, fit)
    }

    /// The image errors of `fit` against the data of [`Judge::with_data`]
    /// and the renders they compare, one per light set: what a report
    /// shows beside its numbers (the fit rendered once for both).
    pub fn fit_renders(&self, fit: &dyn Brdf) -> Result<(ImageError, Vec<LightRenders>), FitError> {
        let (errors, compared) = self.compare(&self.reference, fit)?;
        let renders = self
            .points
            .iter()
            .zip(&self.reference)
            .zip(compared)
            .map(|(((light, _), r), (fit, flip))| LightRenders {
                light: light.name().to_string(),
                data: r.image().clone(),
                fit,
                flip,
                exposure: r.exposure(),
            })
            .collect();
        Ok((errors, renders))
    }

    fn errors_against(&self, refs: &[Reference], fit: &dyn Brdf) -> Result<ImageError, FitError> {
        Ok(self.compare(refs, fit)?.0)
    }

    /// The image errors of `fit` against the data's `refs`, and per light
    /// set the fit's render and its FLIP map.
    fn compare(
        &self,
        refs: &[Reference],
        fit: &dyn Brdf,
    ) -> Result<(ImageError, Vec<(Image, FlipMap)>), FitError> {
        if refs.len() != self.points.len() {
            return Err(FitError::Usage(
                "the judge has no renders of the data: build it with Judge::with_data".into(),
            ));
        }
        let mut lights = Vec::with_capacity(self.points.len());
        let mut compared = Vec::with_capacity(self.points.len());
        for ((light, sp), r) in self.points.iter().zip(refs) {
            let t = sp.render(fit);
            let (e, map) = r.compare(&t).map_err(|e| FitError::Usage(e.to_string()))?;
            compared.push((t, map));
            lights.push(LightError {
                light: light.name().to_string(),
                flip: e.flip,
                psnr: e.psnr,
                delta_e: e.delta_e_mean_colour,
                mean_colour_data: e.mean_colour_ref,
                mean_colour_fit: e.mean_colour_test,
                exposure: e.exposure,
            });
        }
        let colour_plane = self
            .points
            .iter()
            .zip(refs)
            .find(|((light, _), _)| light.is_white())
            .and_then(|((light, _), r)| {
                r.colour_plane().map(|c| DataColourPlane {
                    light: light.name().to_string(),
                    colour: c.colour,
                    outside: c.outside,
                })
            });
        let errors = ImageError {
            size: self.size,
            lights,
            colour_plane,
        };
        Ok((errors, compared))
    }
}

/// A light set's renders of the data and of a fit on the judge's film
/// (background included), as [`Judge`] compares them.
#[derive(Clone, Debug)]
pub struct LightRenders {
    /// Light set name.
    pub light: String,
    /// The data's render.
    pub data: Image,
    /// The fit's render.
    pub fit: Image,
    /// The HDR-FLIP map between them (its mean is the light's FLIP).
    pub flip: FlipMap,
    /// The exposure `1 / p99` of the data's sphere pixels.
    pub exposure: f64,
}

/// The shading terms of the standard light sets at `size` pixels (no
/// background: only the sphere is fitted), as image-objective terms.
pub fn image_terms(size: usize) -> Result<ImageTerms, FitError> {
    let mut pairs = DirPairs::with_capacity(0);
    let mut weight_rows: [Vec<f64>; 3] = Default::default();
    let mut pixel = Vec::new();
    let mut image_of_pixel = Vec::new();
    for (i, light) in standard_lights().iter().enumerate() {
        let sp = ShadingPoints::judge(light, size);
        for px in &sp.pixels {
            let q = image_of_pixel.len();
            image_of_pixel.push(i);
            for k in px.start..px.end {
                // The renderers' order, as ShadingPoints::render.
                pairs.push(&px.v_local, &sp.l_local[k]);
                for (c, row) in weight_rows.iter_mut().enumerate() {
                    row.push(sp.weight[k][c]);
                }
                pixel.push(q);
            }
        }
    }
    let [r, g, b] = weight_rows;
    ImageTerms::new(pairs, [r, g, b].concat(), 3, &pixel, image_of_pixel)
}

/// One candidate of [`fit_for_appearance`].
#[derive(Clone, Debug, Serialize)]
pub struct Candidate {
    /// Objective of the candidate's fit.
    pub objective: String,
    /// Optional lobes switched on (empty: the base model).
    pub lobes: Vec<String>,
    /// Ngan's L2 of the candidate.
    pub ngan_l2: f64,
    /// Its image errors (at [`FIT_SIZE`]).
    pub image: ImageError,
    /// Seconds of its fit.
    pub seconds: f64,
    /// Whether it was chosen.
    pub chosen: bool,
}

/// A model, its optional lobes, and each lobe's companions (in the lobes'
/// order).
type LobeRow = (
    &'static str,
    &'static [&'static str],
    &'static [&'static [&'static str]],
);

/// The optional lobes of each renderer model, in the order they are
/// tried, and beside each lobe its companions ([`lobe_companions`]): one
/// table, so a lobe and the parameters held with it cannot drift apart.
const OPTIONAL_LOBES: &[LobeRow] = &[
    (
        "principled",
        &["sheen", "clearcoat", "anisotropic"],
        &[&["sheen_tint"], &["clearcoat_gloss"], &[]],
    ),
    ("gltf-ext", &["clearcoat"], &[&["clearcoat_roughness"]]),
];

/// Optional lobes of a model: parameter prefixes that switch a lobe off
/// when held at 0.
pub fn optional_lobes(model: &str) -> &'static [&'static str] {
    OPTIONAL_LOBES
        .iter()
        .find(|(m, _, _)| *m == model)
        .map_or(&[], |(_, lobes, _)| *lobes)
}

/// The parameters of an optional lobe besides its strength (the lobe's own
/// name): they act only through the lobe, so while it is off they are held
/// at their defaults. Left free, such a parameter has no influence at all:
/// the solver then reported the fit as "NOT converged: stopped on a plateau
/// with a singular Jacobian" (4 of the 5 RGL files' default fits), and the
/// saved model carried whatever value a random start gave it.
pub fn lobe_companions(model: &str, lobe: &str) -> &'static [&'static str] {
    OPTIONAL_LOBES
        .iter()
        .find(|(m, _, _)| *m == model)
        .and_then(|(_, lobes, companions)| {
            let k = lobes.iter().position(|l| *l == lobe)?;
            companions.get(k).copied()
        })
        .unwrap_or(&[])
}

/// Whether `data` is isotropic: its values do not change when both
/// directions of a pair turn about the normal (64 fixed pairs, each turned by
/// a fixed angle, relative agreement `1e-6`). Anisotropy is a lobe such data
/// cannot need, so [`fit_for_appearance`] does not try it there.
pub fn is_isotropic(data: &dyn Brdf) -> bool {
    let nc = data.channels().max(1);
    let (mut a, mut b) = (vec![0.0; nc], vec![0.0; nc]);
    // A fixed low-discrepancy set of pairs in the upper hemisphere.
    let dir = |u: f64, w: f64| {
        let z = 0.05 + 0.95 * u;
        let r = (1.0 - z * z).sqrt();
        let phi = 2.0 * std::f64::consts::PI * w;
        brdf_core::nalgebra::Vector3::new(r * phi.cos(), r * phi.sin(), z)
    };
    let frac = |x: f64| x - x.floor();
    (0..64).all(|i| {
        let t = i as f64;
        let l = dir(frac(0.5 + t * 0.618_033_988_7), frac(t * 0.754_877_666_2));
        let v = dir(frac(t * 0.569_840_290_9), frac(0.3 + t * 0.414_213_562_4));
        let turn = brdf_core::nalgebra::Rotation3::from_axis_angle(
            &brdf_core::nalgebra::Vector3::z_axis(),
            0.7 + 2.1 * frac(t * 0.324_717_957_2),
        );
        data.eval(&l, &v, &mut a);
        data.eval(&(turn * l), &(turn * v), &mut b);
        a.iter()
            .zip(&b)
            .all(|(x, y)| (x - y).abs() <= 1e-6 * x.abs().max(y.abs()) + 1e-12)
    })
}

/// Objectives tried by [`fit_for_appearance`].
pub const CANDIDATE_OBJECTIVES: [Objective; 3] =
    [Objective::Ngan, Objective::Log, Objective::CubeRoot];

/// One candidate fit and its image errors.
fn candidate(
    f: &Fit,
    objective: Objective,
    lobes: Vec<String>,
    samples: &SampleSet,
    judge: &Judge,
) -> Result<(FitReport, Candidate), FitError> {
    let t0 = Instant::now();
    let report = f.clone().objective(objective).run(samples)?;
    let image = judge.fit_errors(report.model.as_ref())?;
    let c = Candidate {
        objective: objective.name().to_string(),
        lobes,
        ngan_l2: report.summary.ngan_l2,
        image,
        seconds: t0.elapsed().as_secs_f64(),
        chosen: false,
    };
    Ok((report, c))
}

/// `fit` with every optional lobe but those in `on` held at 0, and its
/// [`lobe_companions`] at their defaults.
fn with_lobes(fit: &Fit, on: &[String]) -> Result<Fit, FitError> {
    let specs = fit.param_specs()?;
    let mut out = fit.clone();
    for lobe in optional_lobes(fit.model_name()) {
        if on.iter().any(|o| o == lobe) {
            continue;
        }
        out = out.narrow(lobe, 0.0, 0.0);
        for name in lobe_companions(fit.model_name(), lobe) {
            if let Some(s) = specs.iter().find(|s| s.name == *name) {
                out = out.narrow(name, s.default, s.default);
            }
        }
    }
    Ok(out)
}

/// Fit `fit`'s model to `samples` so that it looks like `data` (the same
/// measurement, evaluable at any direction pair): candidates under
/// [`CANDIDATE_OBJECTIVES`] with the optional lobes off; then, under the
/// winning objective, each optional lobe on, kept only when it lowers the
/// mean FLIP by [`LOBE_MARGIN`] (anisotropy only when the data are not
/// [`is_isotropic`]); then, when the data can need two or more lobes, every
/// such lobe on at once under each objective whose lobe-less candidate
/// renders within [`PAIR_REACH`] of the best (under the winning one only
/// when a single lobe lowered its FLIP), kept by the same margin; then
/// the winner and the other base candidates each
/// refined in the image objective, the refinement with the least image
/// error kept if it lowers the winner's; then, from the best so far, each
/// optional lobe still off switched on and refined in the image objective,
/// kept only when it lowers the mean FLIP by [`LOBE_MARGIN`]. A refinement
/// is kept only while Ngan's L2 stays within [`REFINE_L2_GROWTH`] times the
/// winning candidate's. Returns the chosen fit and every candidate.
pub fn fit_for_appearance(
    fit: &Fit,
    samples: &SampleSet,
    data: &dyn Brdf,
) -> Result<(FitReport, Vec<Candidate>), FitError> {
    fit_for_appearance_with(fit, samples, data, REFINE_L2_GROWTH)
}

/// [`fit_for_appearance`] with another limit on the growth of Ngan's L2
/// that the image refinement may bring (`f64::INFINITY`: judged by the
/// render alone, as a conversion between renderer models is).
pub fn fit_for_appearance_with(
    fit: &Fit,
    samples: &SampleSet,
    data: &dyn Brdf,
    refine_l2_growth: f64,
) -> Result<(FitReport, Vec<Candidate>), FitError> {
    let judge = Judge::with_data(FIT_SIZE, data)?;
    let base = with_lobes(fit, &[])?;
    let mut candidates: Vec<Candidate> = Vec::new();
    let mut best: Option<(FitReport, usize)> = None;
    let mut base_params: Vec<(Vec<f64>, usize)> = Vec::new();
    // Every stage fits its candidates in parallel and then decides in
    // their fixed order, so the choice is the same for any thread count.
    let fits = in_parallel(&CANDIDATE_OBJECTIVES, |o| {
        candidate(&base, *o, Vec::new(), samples, &judge)
    })?;
    for (r, c) in fits {
        base_params.push((r.model.params().to_vec(), candidates.len()));
        candidates.push(c);
        let k = candidates.len() - 1;
        if best
            .as_ref()
            .is_none_or(|(_, b)| flip(&candidates, k) < flip(&candidates, *b))
        {
            best = Some((r, k));
        }
    }
    let (mut report, mut k) = best.ok_or_else(|| FitError::Usage("no candidate fit".into()))?;
    let objective = Objective::parse(&candidates[k].objective)?;
    let isotropic = is_isotropic(data);
    let (winner, mut single_gain) = (k, false);
    let singles: Vec<Vec<String>> = optional_lobes(fit.model_name())
        .iter()
        .filter(|on| !(isotropic && on.starts_with("anisotropic")))
        .map(|on| vec![on.to_string()])
        .collect();
    let fits = in_parallel(&singles, |on| {
        candidate(
            &with_lobes(fit, on)?,
            objective,
            on.clone(),
            samples,
            &judge,
        )
    })?;
    for (r, c) in fits {
        candidates.push(c);
        let j = candidates.len() - 1;
        single_gain |= flip(&candidates, j) < flip(&candidates, winner);
        if flip(&candidates, j) < flip(&candidates, k) * (1.0 - LOBE_MARGIN) {
            report = r;
            k = j;
        }
    }
    // Every lobe the data can need switched on at once, under each
    // objective: the single-lobe trials above are nested under the winning
    // objective only, and miss a fit that needs two lobes together (on
    // paper_white the Ngan fit with sheen and clear coat renders at 32 px
    // FLIP 0.052 / 0.036 against the best single lobe's 0.056 / 0.039).
    // Under the winning objective they are tried only when a single lobe
    // lowered its FLIP at all: on the films no lobe did, and their
    // cube-root fit with both on (up to 3.7 s) came out no better.
    let all: Vec<String> = singles.concat();
    if all.len() > 1 {
        let best_base = base_params
            .iter()
            .map(|(_, j)| flip(&candidates, *j))
            .fold(f64::INFINITY, f64::min);
        let pairs: Vec<Objective> = CANDIDATE_OBJECTIVES
            .into_iter()
            .zip(&base_params)
            .filter(|(o, (_, b))| {
                flip(&candidates, *b) <= PAIR_REACH * best_base && (*o != objective || single_gain)
            })
            .map(|(o, _)| o)
            .collect();
        let with_all = with_lobes(fit, &all)?;
        let fits = in_parallel(&pairs, |o| {
            candidate(&with_all, *o, all.clone(), samples, &judge)
        })?;
        for (r, c) in fits {
            candidates.push(c);
            let j = candidates.len() - 1;
            if flip(&candidates, j) < flip(&candidates, k) * (1.0 - LOBE_MARGIN) {
                report = r;
                k = j;
            }
        }
    }
    candidates[k].chosen = true;
    // Refine in the image objective from the winner and from every other
    // base candidate (the image objective has several basins: on
    // cc_iris_purple_gem the Ngan start's basin renders at mean FLIP 0.326,
    // the winner's at 0.343); keep the least image error.
    let lobes = candidates[k].lobes.clone();
    let mut starts = vec![(report.model.params().to_vec(), lobes.clone())];
    for (p, j) in &base_params {
        if *j != k {
            starts.push((p.clone(), Vec::new()));
        }
    }
    // The data's pixels are rendered once, for every start.
    let target = ImageTarget::new(
        image_terms(FIT_SIZE)?,
        data,
        report.model.channels(),
        Vec::new(),
    );
    // The refinement sees the BRDF only through the sphere's pixels; it is
    // kept only if it also stays a fit of the data (Ngan's L2 at most
    // REFINE_L2_GROWTH times the winner's), so it cannot trade the
    // unrendered directions for a lower image error.
    let refiner = Refiner {
        fit,
        target: &target,
        samples,
        judge: &judge,
        max_l2: refine_l2_growth * candidates[k].ngan_l2,
    };
    let mut choice = Choice { report, k };
    for (refined, c) in in_parallel(&starts, |(p, on)| refiner.refine(p, on))? {
        refiner.offer(refined, c, 1.0, &mut candidates, &mut choice);
    }
    // The optional lobes, tried in the image objective (nested models): from
    // the best fit so far, each lobe switched on at the middle of its box and
    // refined, kept when it lowers the mean FLIP by LOBE_MARGIN and stays a
    // fit of the data. In BRDF space a lobe mimics a grazing tail the render
    // hardly shows; here it must pay in the render (on vch_golden_yellow a
    // rough clear coat does: the GGX fit converted to principled, which
    // found it, rendered at sky FLIP 0.251 against the lobe-less 0.291).
    let base = choice.report.model.params().to_vec();
    let on_already = candidates[choice.k].lobes.clone();
    let specs = choice.report.model.param_specs().to_vec();
    let trials: Vec<(Vec<f64>, Vec<String>)> = singles
        .iter()
        .filter(|on| !on_already.contains(&on[0]))
        .map(|on| {
            let mut start = base.clone();
            for (p, s) in start.iter_mut().zip(specs.iter()) {
                if s.name.starts_with(on[0].as_str()) {
                    *p = 0.5 * (s.lower + s.upper);
                }
            }
            (start, [on_already.clone(), on.clone()].concat())
        })
        .collect();
    for (refined, c) in in_parallel(&trials, |(p, on)| refiner.refine(p, on))? {
        refiner.offer(refined, c, 1.0 - LOBE_MARGIN, &mut candidates, &mut choice);
    }
    if fit.polishes_on_flip() {
        refiner.polish(&mut candidates, &mut choice)?;
    }
    Ok((choice.report, candidates))
}

/// The chosen fit of [`fit_for_appearance_with`] and its index among the
/// candidates.
struct Choice {
    report: FitReport,
    k: usize,
}

/// Refinements in the image objective of one appearance fit.
struct Refiner<'a> {
    fit: &'a Fit,
    /// The data's pixels (the start is set per refinement).
    target: &'a ImageTarget,
    samples: &'a SampleSet,
    judge: &'a Judge,
    /// Largest Ngan's L2 a refinement may have and still be chosen.
    max_l2: f64,
}

impl Refiner<'_> {
    /// `self.fit` with `lobes` on, refined in the image objective from
    /// `start`: the fit and its candidate row.
    fn refine(&self, start: &[f64], lobes: &[String]) -> Result<(FitReport, Candidate), FitError> {
        let target = ImageTarget {
            start: start.to_vec(),
            ..self.target.clone()
        };
        let refine = with_lobes(self.fit, lobes)?.image_target(Arc::new(target));
        candidate(
            &refine,
            Objective::Image,
            lobes.to_vec(),
            self.samples,
            self.judge,
        )
    }

    /// The choice moved by [`crate::flip_polish`] to a lower mean FLIP,
    /// added to `candidates` (objective `flip`) and chosen when it stays a
    /// fit of the data (Ngan's L2 within `max_l2`).
    fn polish(&self, candidates: &mut Vec<Candidate>, choice: &mut Choice) -> Result<(), FitError> {
        let t0 = Instant::now();
        let start = &candidates[choice.k];
        let fit = with_lobes(self.fit, &start.lobes)?;
        let Some(polished) = crate::flip_polish::polish(
            &fit,
            &choice.report,
            &start.image,
            self.target,
            self.judge,
            self.samples,
        )?
        else {
            return Ok(());
        };
        let c = Candidate {
            objective: "flip".to_string(),
            lobes: start.lobes.clone(),
            ngan_l2: polished.summary.ngan_l2,
            image: self.judge.fit_errors(polished.model.as_ref())?,
            seconds: t0.elapsed().as_secs_f64(),
            chosen: false,
        };
        self.offer(polished, c, 1.0, candidates, choice);
        Ok(())
    }

    /// Add `c` (the candidate of `report`) to `candidates` and make it the
    /// choice when its Ngan's L2 is within `max_l2` and its mean FLIP below
    /// `gain` times the choice's.
    fn offer(
        &self,
        report: FitReport,
        c: Candidate,
        gain: f64,
        candidates: &mut Vec<Candidate>,
        choice: &mut Choice,
    ) {
        let keeps_data = c.ngan_l2 <= self.max_l2;
        candidates.push(c);
        let j = candidates.len() - 1;
        if keeps_data && flip(candidates, j) < gain * flip(candidates, choice.k) {
            candidates[choice.k].chosen = false;
            candidates[j].chosen = true;
            *choice = Choice { report, k: j };
        }
    }
}

/// `fit` of every item, in parallel, in the items' order (the first error
/// wins, as in a loop).
fn in_parallel<T: Sync, R: Send>(
    items: &[T],
    fit: impl Fn(&T) -> Result<R, FitError> + Sync + Send,
) -> Result<Vec<R>, FitError> {
    use rayon::prelude::*;
    items.par_iter().map(fit).collect()
}

fn flip(candidates: &[Candidate], k: usize) -> f64 {
    candidates[k].image.mean_flip()
}

/// Whether a catalogue model is one a renderer offers (principled, glTF,
/// the GGX family): these are fitted for appearance by default.
pub fn is_renderer_model(name: &str) -> bool {
    matches!(name, "principled" | "gltf" | "gltf-ext") || name.starts_with("ggx")
}

/// Why a data set gets no image error.
pub const SCATTERED_NOTE: &str = "no image error: the data are scattered samples (CUReT, Cornell, CSV) that cannot be evaluated at the direction pairs of a rendered sphere; RGL `.bsdf` and MERL `.binary` data can";

/// A fit as front ends run it: chosen by image error when `for_appearance`
/// and the data can be rendered (`dense`, the same measurement as
/// `samples`), else `fit` itself; then its image errors at
/// [`REPORT_SIZE`] pixels and their warnings attached, or the note that
/// none can be formed.
pub fn fit_judged(
    fit: &Fit,
    samples: &SampleSet,
    dense: Option<&dyn Brdf>,
    for_appearance: bool,
) -> Result<FitReport, FitError> {
    let Some(data) = dense else {
        let mut report = fit.run(samples)?;
        report.image_note = Some(SCATTERED_NOTE.to_string());
        return Ok(report);
    };
    // The report's judge (its cells and the data's renders) does not
    // depend on the fit: built beside it, on another thread when there is
    // one.
    let (report, judge) = rayon::join(
        || fit_rendered(fit, samples, data, for_appearance),
        || Judge::with_data(REPORT_SIZE, data),
    );
    let report = report?;
    with_image_errors(report, &judge?)
}

/// [`fit_judged`] on data that can be rendered, judged by `judge` (the
/// report-size judge holding the data's renders, [`Judge::with_data`] or
/// [`Judge::rendering`]) when several fits of the same data are judged.
pub fn fit_judged_on(
    fit: &Fit,
    samples: &SampleSet,
    data: &dyn Brdf,
    for_appearance: bool,
    judge: &Judge,
) -> Result<FitReport, FitError> {
    with_image_errors(fit_rendered(fit, samples, data, for_appearance)?, judge)
}

/// The fit of [`fit_judged`] on data that can be rendered, before its
/// image errors.
pub(crate) fn fit_rendered(
    fit: &Fit,
    samples: &SampleSet,
    data: &dyn Brdf,
    for_appearance: bool,
) -> Result<FitReport, FitError> {
    if for_appearance {
        let (mut report, candidates) = fit_for_appearance(fit, samples, data)?;
        report.candidates = candidates;
        Ok(report)
    } else if fit.needs_image_target() {
        fit_in_image_objective(fit, samples, data)
    } else {
        fit.run(samples)
    }
}

/// `report` with its image errors by `judge` and their warnings attached.
pub(crate) fn with_image_errors(
    mut report: FitReport,
    judge: &Judge,
) -> Result<FitReport, FitError> {
    let errors = judge.fit_errors(report.model.as_ref())?;
    report.notes.extend(errors.warnings());
    report
        .notes
        .extend(colour_plane_note(report.model.name(), &errors));
    report.image_error = Some(errors);
    Ok(report)
}

/// A fit in the image objective alone (a front end's `--metric image`):
/// `fit` under Ngan's L2, then refined in the image objective at
/// [`FIT_SIZE`] pixels from there (the objective needs a start; its
/// basins trap a cold one). Unlike [`fit_for_appearance`] nothing checks
/// that the result still fits the data's unrendered directions: the
/// render is the whole objective.
pub fn fit_in_image_objective(
    fit: &Fit,
    samples: &SampleSet,
    data: &dyn Brdf,
) -> Result<FitReport, FitError> {
    let start = fit.clone().objective(Objective::Ngan).run(samples)?;
    let target = ImageTarget::new(
        image_terms(FIT_SIZE)?,
        data,
        start.model.channels(),
        start.model.params().to_vec(),
    );
    fit.clone()
        .objective(Objective::Image)
        .image_target(Arc::new(target))
        .run(samples)
}

/// The renderer models `brdf select --by-image` chooses among.
pub const RENDERER_MODELS: [&str; 4] = ["principled", "gltf", "gltf-ext", "ggx"];

/// One model of [`select_by_image`]: its appearance fit and image errors.
#[derive(Clone, Debug, Serialize)]
pub struct ImageChoice {
    /// Catalogue name.
    pub model: String,
    /// Objective of the chosen candidate of this model.
    pub objective: String,
    /// Optional lobes it kept.
    pub lobes: Vec<String>,
    /// Its image errors at [`REPORT_SIZE`] pixels.
    pub image: ImageError,
    /// Ngan's L2.
    pub ngan_l2: f64,
    /// Parameters.
    pub parameters: usize,
    /// Seconds of the model's appearance fit.
    pub seconds: f64,
}

/// Selection by image error (Bieron and Peers 2020): every model of
/// `models` fitted for appearance to `samples` (each fit ended by the
/// search on its render's FLIP when `polish`, [`Fit::polish_on_flip`]),
/// judged against `data` at [`REPORT_SIZE`] pixels; the index of the least
/// mean FLIP is the choice.
pub fn select_by_image(
    models: &[&str],
    samples: &SampleSet,
    data: &dyn Brdf,
    polish: bool,
) -> Result<(Vec<ImageChoice>, usize), FitError> {
    // The data rendered once at the report size for every model; the
    // models fitted in parallel (rows in the order of `models`, each fit
    // the same for any number of threads).
    let judge = Judge::with_data(REPORT_SIZE, data)?;
    use rayon::prelude::*;
    let rows = models
        .par_iter()
        .map(|name| {
            let t0 = Instant::now();
            let fit = Fit::model(name)?.polish_on_flip(polish);
            let report = fit_judged_on(&fit, samples, data, true, &judge)?;
            let chosen = report.candidates.iter().find(|c| c.chosen);
            Ok(ImageChoice {
                model: report.summary.model.clone(),
                objective: chosen.map_or_else(String::new, |c| c.objective.clone()),
                lobes: chosen.map_or_else(Vec::new, |c| c.lobes.clone()),
                image: report.image_error.clone().ok_or_else(|| {
                    FitError::Usage(format!("`{}`: the fit has no image error", samples.name))
                })?,
                ngan_l2: report.summary.ngan_l2,
                parameters: report.summary.parameters.len(),
                seconds: t0.elapsed().as_secs_f64(),
            })
        })
        .collect::<Result<Vec<_>, FitError>>()?;
    let choice = (0..rows.len())
        .min_by(|a, b| {
            rows[*a]
                .image
                .mean_flip()
                .total_cmp(&rows[*b].image.mean_flip())
        })
        .ok_or_else(|| FitError::Usage("select by image: no model to fit".into()))?;
    Ok((rows, choice))
}

/// [`crate::select::select_fitted`] and, when the data can be rendered
/// (`dense`, the same measurement as `samples`), the chosen model's image
/// errors at [`REPORT_SIZE`] pixels; the judge's terms and the data's
/// renders do not depend on the choice, so they are made beside the
/// selection.
pub fn select_judged(
    samples: &SampleSet,
    dense: Option<&dyn Brdf>,
    tolerance: f64,
    opts: &crate::FitOptions,
    among: &crate::select::Among,
    search: crate::select::Search,
) -> Result<(crate::select::Selection, Option<ImageError>), FitError> {
    let select = || crate::select::select_fitted(samples, tolerance, opts, among, search);
    let judge = || dense.map(|d| Judge::with_data(REPORT_SIZE, d)).transpose();
    let (selected, judge) = rayon::join(select, judge);
    let selection = selected?;
    let image = match judge? {
        Some(j) => Some(j.fit_errors(selection.model.as_ref())?),
        None => None,
    };
    Ok((selection, image))
}

/// What a front end's `--metric` (or `metric=`) means for `model`:
/// whether to fit for appearance, and the objective of the fit (of the
/// candidates' first, for appearance). `auto` is the appearance fit for a
/// renderer model on data that can be rendered, else Ngan's L2.
pub fn metric_choice<'a>(metric: &'a str, model: &str, renderable: bool) -> (bool, &'a str) {
    match metric {
        "auto" if is_renderer_model(model) && renderable => (true, "ngan"),
        "auto" => (false, "ngan"),
        "appearance" => (true, "ngan"),
        m => (false, m),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use brdf_models::catalogue::{ModelConfig, build};

    /// Every lobe of the table has its companions beside it, and every
    /// name in it (lobe and companion) is a parameter of its model, with a
    /// lower bound of 0 for the lobe (held there to switch it off).
    #[test]
    fn the_lobe_table_names_parameters_of_its_models() {
        for (model, lobes, companions) in OPTIONAL_LOBES {
            assert_eq!(lobes.len(), companions.len(), "{model}");
            assert!(is_renderer_model(model), "{model}");
            let m = build(model, &ModelConfig::default()).expect("model");
            let specs = m.param_specs();
            let spec = |n: &str| specs.iter().find(|s| s.name == n);
            for (lobe, with) in lobes.iter().zip(companions.iter()) {
                let s = spec(lobe).unwrap_or_else(|| panic!("{model}: no `{lobe}`"));
                assert_eq!(s.lower, 0.0, "{model}: {lobe}");
                assert_eq!(optional_lobes(model), *lobes);
                assert_eq!(lobe_companions(model, lobe), *with);
                for c in *with {
                    assert!(spec(c).is_some(), "{model}: no `{c}`");
                }
            }
        }
        assert!(optional_lobes("lambert").is_empty());
        assert!(lobe_companions("principled", "metallic").is_empty());
    }
}
